// Regression image of vtkDistanceFieldProximity: bunny_small (A) and the cow (B), each
// scaled into a unit box, overlapping; both coloured by DistanceToOther (blue inside the
// other, white at contact, red outside), the contact normals of A's samples inside B as
// arrows seen through B (translucent), A's deepest point joined to B's surface in black.
// Compared with Testing/Data/Baseline/TestProximityImage.png. First by numbers: A alone,
// unlit, so at every vertex the z-buffer shows in front (visible) the pixel has the
// lookup table's colour of that vertex's DistanceToOther.
//
// usage: TestProximityImage DATA_DIR -V BASELINE.png -T TMPDIR
#include "TestSupport.h"
#include "UnitBoxMesh.h"
#include "vtkDistanceFieldProximity.h"

#include "vtkActor.h"
#include "vtkArrowSource.h"
#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkGlyph3D.h"
#include "vtkLookupTable.h"
#include "vtkMaskPoints.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"
#include "vtkTriangleFilter.h"
#include "vtkUnsignedCharArray.h"
#include "vtkXMLPolyDataReader.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

int main(int argc, char* argv[])
{
  if (!vtkdf::testing::HasArguments(argc, argv, 1, "DATA_DIR -V BASELINE -T TMP"))
  {
    return 2;
  }
  const std::string data = argv[1];
  const double atOrigin[3] = { 0, 0, 0 }, beside[3] = { 0.55, 0.05, 0.0 };
  auto a = vtkdf::testing::ReadUnitBoxMesh(data + "/bunny_small.vtp", 0, atOrigin);
  auto b = vtkdf::testing::ReadUnitBoxMesh(data + "/cow.vtp", 0.6, beside);
  vtkNew<vtkDistanceFieldProximity> proximity;
  proximity->SetModelAData(a);
  proximity->SetModelBData(b);
  proximity->SetResolution(48);
  proximity->Update();
  CHECK(proximity->GetErrorCode() == 0 && proximity->GetLastColliding(), "no collision found");
  std::printf("penetration AB %.6f BA %.6f, %lld contacts, %.4f s\n",
    proximity->GetLastPenetrationAB(),
    proximity->GetLastPenetrationBA(),
    static_cast<long long>(proximity->GetOutput(1)->GetNumberOfPoints()),
    proximity->GetLastSeconds());

  vtkNew<vtkLookupTable> lut;
  const double range = 0.08;
  lut->SetTableRange(-range, range);
  lut->SetNumberOfTableValues(256);
  for (int i = 0; i < 256; ++i)
  {
    // Blue (inside the other) through white (contact) to red (outside).
    const double t = i / 255.0;
    const double r = t < 0.5 ? 2 * t : 1.0, g = 1 - std::fabs(2 * t - 1),
                 bl = t < 0.5 ? 1.0 : 2 - 2 * t;
    lut->SetTableValue(i, 0.15 + 0.85 * r, 0.15 + 0.85 * g, 0.15 + 0.85 * bl);
  }
  lut->Build();

  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(1, 1, 1);
  vtkPolyData* models[2] = { proximity->GetOutput(2), proximity->GetOutput(3) };
  vtkSmartPointer<vtkActor> actors[2];
  for (int m = 0; m < 2; ++m)
  {
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(models[m]);
    mapper->SetScalarModeToUsePointFieldData();
    mapper->SelectColorArray("DistanceToOther");
    mapper->SetLookupTable(lut);
    mapper->UseLookupTableScalarRangeOn();
    actors[m] = vtkSmartPointer<vtkActor>::New();
    actors[m]->SetMapper(mapper);
    renderer->AddActor(actors[m]);
  }
  // The contact normals of A's samples inside B (Model 0), a few hundred of them.
  vtkNew<vtkPolyData> contactsA;
  {
    vtkPolyData* contacts = proximity->GetOutput(1);
    vtkNew<vtkPoints> points;
    vtkNew<vtkFloatArray> normals;
    normals->SetName("Normal");
    normals->SetNumberOfComponents(3);
    vtkDataArray* model = contacts->GetPointData()->GetArray("Model");
    vtkDataArray* normal = contacts->GetPointData()->GetArray("Normal");
    for (vtkIdType i = 0; i < contacts->GetNumberOfPoints(); ++i)
    {
      if (model->GetComponent(i, 0) == 0)
      {
        points->InsertNextPoint(contacts->GetPoint(i));
        normals->InsertNextTuple(normal->GetTuple3(i));
      }
    }
    contactsA->SetPoints(points);
    contactsA->GetPointData()->SetVectors(normals);
  }
  vtkNew<vtkMaskPoints> few;
  few->SetInputData(contactsA);
  few->SetOnRatio(std::max<vtkIdType>(1, contactsA->GetNumberOfPoints() / 300));
  few->SetRandomMode(false);
  few->GenerateVerticesOff();
  vtkNew<vtkArrowSource> arrow;
  vtkNew<vtkGlyph3D> glyphs;
  glyphs->SetInputConnection(few->GetOutputPort());
  glyphs->SetSourceConnection(arrow->GetOutputPort());
  glyphs->SetVectorModeToUseVector();
  glyphs->SetScaleModeToDataScalingOff();
  glyphs->SetScaleFactor(0.04);
  vtkNew<vtkPolyDataMapper> glyphMapper;
  glyphMapper->SetInputConnection(glyphs->GetOutputPort());
  glyphMapper->ScalarVisibilityOff();
  vtkNew<vtkActor> glyphActor;
  glyphActor->SetMapper(glyphMapper);
  glyphActor->GetProperty()->SetColor(0.1, 0.5, 0.1);
  glyphActor->VisibilityOff();
  renderer->AddActor(glyphActor);
  vtkNew<vtkPolyDataMapper> witnessMapper;
  witnessMapper->SetInputData(proximity->GetOutput(0));
  witnessMapper->ScalarVisibilityOff();
  vtkNew<vtkActor> witness;
  witness->SetMapper(witnessMapper);
  witness->GetProperty()->SetColor(0, 0, 0);
  witness->GetProperty()->SetLineWidth(4);
  witness->VisibilityOff();
  renderer->AddActor(witness);

  vtkNew<vtkRenderWindow> window;
  window->SetSize(400, 400);
  window->AddRenderer(renderer);
  vtkCamera* camera = renderer->GetActiveCamera();
  // From B's side: A's contact region shows through B.
  camera->SetPosition(2.0, 1.6, 1.0);
  camera->SetFocalPoint(0.4, 0, 0);
  camera->SetViewUp(0, 0, 1);
  renderer->ResetCamera();
  camera->Zoom(1.2);
  // First by numbers: A alone and unlit (its colours are the table's); the colour of
  // every visible vertex is its DistanceToOther's.
  actors[0]->GetProperty()->LightingOff();
  actors[1]->VisibilityOff();
  window->Render();
  vtkNew<vtkUnsignedCharArray> pixels;
  window->GetPixelData(0, 0, 399, 399, 1, pixels);
  vtkNew<vtkFloatArray> depth;
  window->GetZbufferData(0, 0, 399, 399, depth);
  int visible = 0, matching = 0;
  for (vtkPolyData* model : { models[0] })
  {
    vtkDataArray* distance = model->GetPointData()->GetArray("DistanceToOther");
    for (vtkIdType i = 0; i < model->GetNumberOfPoints(); ++i)
    {
      double x[3];
      model->GetPoint(i, x);
      renderer->SetWorldPoint(x[0], x[1], x[2], 1);
      renderer->WorldToDisplay();
      double d[3];
      renderer->GetDisplayPoint(d);
      const int px = static_cast<int>(std::floor(d[0])), py = static_cast<int>(std::floor(d[1]));
      if (px < 0 || py < 0 || px >= 400 || py >= 400 ||
        std::fabs(depth->GetValue(py * 400 + px) - d[2]) > 1e-3)
      {
        continue; // hidden, or off the picture
      }
      ++visible;
      double rgb[3];
      lut->GetColor(distance->GetComponent(i, 0), rgb);
      double error = 0;
      for (int c = 0; c < 3; ++c)
      {
        error = std::max(error, std::fabs(pixels->GetComponent(py * 400 + px, c) / 255.0 - rgb[c]));
      }
      matching += error < 0.12 ? 1 : 0;
    }
  }
  std::printf("%d visible vertices, %d with their DistanceToOther's colour\n", visible, matching);
  CHECK(visible >= 100, "too few visible vertices to check the colours");
  CHECK(matching >= 0.9 * visible, "the picture does not show DistanceToOther");

  // The picture: both lit, B translucent over A's contact normals and deepest point.
  actors[0]->GetProperty()->LightingOn();
  actors[1]->VisibilityOn();
  actors[1]->GetProperty()->SetOpacity(0.35);
  glyphActor->VisibilityOn();
  witness->VisibilityOn();
  window->Render();
  const int result = vtkRegressionTestImage(window);
  return result == vtkRegressionTester::PASSED && vtkdf::testing::Failures == 0 ? 0 : 1;
}
