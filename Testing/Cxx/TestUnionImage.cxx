// Regression image of vtkUnionClosestPoint: the four convex pieces of hubo_ankle_convex4
// translucent (the piece that holds the answer in orange), a query from inside (blue
// sphere), its closest point on the union's boundary (red sphere) and the segment between
// them (red). Compared with Testing/Data/Baseline/TestUnionImage.png. Also by numbers: the
// pixels at the projected query, segment midpoint and closest point have the colours of
// what is drawn there.
//
// usage: TestUnionImage DATA_DIR cpu|gpu -V BASELINE.png -T TMPDIR
#include "TestSupport.h"
#include "vtkUnionClosestPoint.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkLineSource.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataConnectivityFilter.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkUnsignedCharArray.h"
#include "vtkXMLPolyDataReader.h"

#include <cstdio>
#include <string>

namespace
{
vtkSmartPointer<vtkActor> Ball(const double centre[3], double radius, double r, double g, double b)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(centre[0], centre[1], centre[2]);
  sphere->SetRadius(radius);
  sphere->SetThetaResolution(24);
  sphere->SetPhiResolution(24);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(sphere->GetOutputPort());
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(r, g, b);
  return actor;
}
} // namespace

int main(int argc, char* argv[])
{
  if (!vtkdf::testing::HasArguments(argc, argv, 2, "DATA_DIR cpu|gpu -V BASELINE -T TMP"))
  {
    return 2;
  }
  const std::string dataDir = argv[1], backend = argv[2];
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName((dataDir + "/hubo_ankle_convex4.vtp").c_str());
  reader->Update();

  vtkNew<vtkUnionClosestPoint> query;
  query->SetInputConnection(reader->GetOutputPort());
  query->SetQueryPoint(0, 0.01, 0.01);
  query->SetBackend(
    backend == "gpu" ? vtkUnionClosestPoint::BACKEND_GPU : vtkUnionClosestPoint::BACKEND_CPU);
  query->Update();
  vtkPolyData* answer = query->GetOutput();
  if (answer->GetNumberOfPoints() != 2)
  {
    std::printf("FAIL: no answer\n");
    return 1;
  }
  double o[3], c[3];
  answer->GetPoint(0, o);
  answer->GetPoint(1, c);
  const int closestPiece =
    static_cast<int>(answer->GetPointData()->GetArray("ClosestPiece")->GetTuple1(0));
  std::printf("distance %.9f, piece %d (%s)\n",
    answer->GetPointData()->GetArray("Distance")->GetTuple1(0),
    closestPiece,
    backend.c_str());

  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(1, 1, 1);
  // The pieces, translucent; the one that holds the answer in orange. (Pieces in the
  // filter's order: connected components by their lowest cell id, as the connectivity
  // filter numbers its regions.)
  vtkNew<vtkPolyDataConnectivityFilter> regions;
  regions->SetInputConnection(reader->GetOutputPort());
  regions->SetExtractionModeToAllRegions();
  regions->ColorRegionsOn();
  regions->Update();
  for (int k = 0; k < regions->GetNumberOfExtractedRegions(); ++k)
  {
    vtkNew<vtkPolyDataConnectivityFilter> one;
    one->SetInputConnection(reader->GetOutputPort());
    one->SetExtractionModeToSpecifiedRegions();
    one->AddSpecifiedRegion(k);
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputConnection(one->GetOutputPort());
    mapper->ScalarVisibilityOff();
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    if (k == closestPiece)
    {
      actor->GetProperty()->SetColor(1.0, 0.65, 0.2);
    }
    else
    {
      actor->GetProperty()->SetColor(0.6, 0.7, 0.8);
    }
    actor->GetProperty()->SetOpacity(0.18);
    renderer->AddActor(actor);
  }
  const double diagonal = reader->GetOutput()->GetLength();
  renderer->AddActor(Ball(o, 0.012 * diagonal, 0.1, 0.2, 0.9));
  renderer->AddActor(Ball(c, 0.008 * diagonal, 0.9, 0.05, 0.05));
  vtkNew<vtkPolyDataMapper> segmentMapper;
  segmentMapper->SetInputData(answer);
  segmentMapper->ScalarVisibilityOff();
  vtkNew<vtkActor> segment;
  segment->SetMapper(segmentMapper);
  segment->GetProperty()->SetColor(0.9, 0.05, 0.05);
  segment->GetProperty()->SetLineWidth(5);
  renderer->AddActor(segment);

  vtkNew<vtkRenderWindow> window;
  window->SetSize(400, 400);
  window->AddRenderer(renderer);
  renderer->ResetCamera();
  // Look across the segment.
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetFocalPoint((o[0] + c[0]) / 2, (o[1] + c[1]) / 2, (o[2] + c[2]) / 2);
  camera->SetPosition((o[0] + c[0]) / 2 + diagonal,
    (o[1] + c[1]) / 2 + 0.4 * diagonal,
    (o[2] + c[2]) / 2 + 0.3 * diagonal);
  camera->SetViewUp(0, 0, 1);
  renderer->ResetCamera();
  camera->Zoom(1.3);
  window->Render();

  // By numbers: the colour at the projected query, midpoint and closest point.
  vtkNew<vtkUnsignedCharArray> pixels;
  window->GetPixelData(0, 0, 399, 399, 1, pixels);
  auto colourAt = [&](const double x[3], double rgb[3])
  {
    renderer->SetWorldPoint(x[0], x[1], x[2], 1);
    renderer->WorldToDisplay();
    double d[3];
    renderer->GetDisplayPoint(d);
    const int px = static_cast<int>(d[0] + 0.5), py = static_cast<int>(d[1] + 0.5);
    for (int a = 0; a < 3; ++a)
    {
      rgb[a] = pixels->GetComponent(py * 400 + px, a) / 255.0;
    }
  };
  const double middle[3] = { (o[0] + c[0]) / 2, (o[1] + c[1]) / 2, (o[2] + c[2]) / 2 };
  double atQuery[3], atMiddle[3], atClosest[3];
  colourAt(o, atQuery);
  colourAt(middle, atMiddle);
  colourAt(c, atClosest);
  std::printf("colours: query %.2f %.2f %.2f, midpoint %.2f %.2f %.2f, closest %.2f %.2f %.2f\n",
    atQuery[0],
    atQuery[1],
    atQuery[2],
    atMiddle[0],
    atMiddle[1],
    atMiddle[2],
    atClosest[0],
    atClosest[1],
    atClosest[2]);
  CHECK(atQuery[2] > atQuery[0] + 0.2 && atQuery[2] > atQuery[1] + 0.2,
    "the query's pixel is not blue");
  CHECK(atMiddle[0] > atMiddle[1] + 0.2 && atMiddle[0] > atMiddle[2] + 0.2,
    "the segment's midpoint pixel is not red");
  CHECK(atClosest[0] > atClosest[1] + 0.2 && atClosest[0] > atClosest[2] + 0.2,
    "the closest point's pixel is not red");
  const int result = vtkRegressionTestImage(window);
  return result == vtkRegressionTester::PASSED && vtkdf::testing::Failures == 0 ? 0 : 1;
}
