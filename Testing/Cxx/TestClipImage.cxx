// Regression image of vtkClipByMeshDistance: a 32^3 grid of hexahedra around bunny_small
// clipped to the bunny's inside (the winding-number sign), then cut in half by a plane
// through its middle (VTK's clip) to show the cells within: coloured by Distance (deep
// blue at the bunny's core, white at its surface), the cells' edges in grey. Compared with
// Testing/Data/Baseline/TestClipImage.png. Also by numbers: every point of the clipped
// volume is inside (Distance <= 0), the cut face's pixels at the deepest point are the
// darkest blue of the map, and the volume covers a fair share of the window.
//
// usage: TestClipImage DATA_DIR -V BASELINE.png -T TMPDIR
#include "TestSupport.h"
#include "vtkClipByMeshDistance.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkDataSetMapper.h"
#include "vtkImageData.h"
#include "vtkLookupTable.h"
#include "vtkNew.h"
#include "vtkPlane.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkTableBasedClipDataSet.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnstructuredGrid.h"
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
  const std::string dataDir = argv[1];
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName((dataDir + "/bunny_small.vtp").c_str());
  reader->Update();
  double b[6];
  reader->GetOutput()->GetBounds(b);
  const double size = std::max({ b[1] - b[0], b[3] - b[2], b[5] - b[4] });
  const int n = 32;
  const double h = 1.1 * size / (n - 1);
  vtkNew<vtkImageData> grid;
  grid->SetDimensions(n, n, n);
  grid->SetSpacing(h, h, h);
  grid->SetOrigin(
    (b[0] + b[1] - 1.1 * size) / 2, (b[2] + b[3] - 1.1 * size) / 2, (b[4] + b[5] - 1.1 * size) / 2);

  vtkNew<vtkClipByMeshDistance> inside;
  inside->SetInputData(grid);
  inside->SetSurfaceConnection(reader->GetOutputPort());
  inside->Update();
  vtkUnstructuredGrid* volume = inside->GetOutput();
  vtkDataArray* distance = volume->GetPointData()->GetArray("Distance");
  if (inside->GetErrorCode() || !distance)
  {
    std::printf("FAIL: no clipped volume\n");
    return 1;
  }
  double range[2];
  distance->GetRange(range);
  std::printf("clipped volume: %lld cells, %lld points, Distance %.6g to %.6g\n",
    static_cast<long long>(volume->GetNumberOfCells()),
    static_cast<long long>(volume->GetNumberOfPoints()),
    range[0],
    range[1]);
  CHECK(range[1] <= 1e-12 * size, "a point of the clipped volume lies outside");

  // Half of it: the part behind the plane through the deepest point, facing the camera.
  vtkIdType deepest = 0;
  for (vtkIdType i = 0; i < distance->GetNumberOfTuples(); ++i)
  {
    deepest = distance->GetTuple1(i) < distance->GetTuple1(deepest) ? i : deepest;
  }
  double core[3];
  volume->GetPoint(deepest, core);
  vtkNew<vtkPlane> plane;
  plane->SetOrigin(core);
  plane->SetNormal(0, 0, 1);
  vtkNew<vtkTableBasedClipDataSet> half;
  half->SetInputConnection(inside->GetOutputPort());
  half->SetClipFunction(plane);
  half->InsideOutOn();
  half->Update();

  // Deep blue (the core) to white (the surface).
  vtkNew<vtkLookupTable> colours;
  colours->SetNumberOfTableValues(256);
  for (int i = 0; i < 256; ++i)
  {
    const double t = i / 255.0;
    colours->SetTableValue(i, 0.10 + 0.9 * t, 0.20 + 0.8 * t, 0.55 + 0.45 * t, 1);
  }
  vtkNew<vtkDataSetMapper> mapper;
  mapper->SetInputConnection(half->GetOutputPort());
  mapper->SetLookupTable(colours);
  mapper->SetScalarRange(range[0], 0);
  mapper->SetScalarModeToUsePointFieldData();
  mapper->SelectColorArray("Distance");
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->EdgeVisibilityOn();
  actor->GetProperty()->SetEdgeColor(0.55, 0.55, 0.6);
  actor->GetProperty()->SetAmbient(0.35);
  actor->GetProperty()->SetDiffuse(0.65);

  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(1, 1, 1);
  renderer->AddActor(actor);
  vtkNew<vtkRenderWindow> window;
  window->SetSize(400, 400);
  window->AddRenderer(renderer);
  // Looking at the cut face (z up to the camera) from the side, the bunny upright (y up).
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetFocalPoint(core);
  camera->SetPosition(core[0], core[1], core[2] + 3 * size);
  camera->SetViewUp(0, 1, 0);
  camera->Azimuth(30);
  camera->Elevation(15);
  camera->OrthogonalizeViewUp();
  renderer->ResetCamera();
  window->Render();

  // By numbers: the core's pixel is the darkest blue; the volume covers the window well.
  vtkNew<vtkUnsignedCharArray> pixels;
  window->GetPixelData(0, 0, 399, 399, 1, pixels);
  renderer->SetWorldPoint(core[0], core[1], core[2], 1);
  renderer->WorldToDisplay();
  double d[3];
  renderer->GetDisplayPoint(d);
  // The bluest pixel within 3 of it (one may be a cell's edge).
  double rgb[3] = { 1, 1, 1 };
  for (int dy = -3; dy <= 3; ++dy)
  {
    for (int dx = -3; dx <= 3; ++dx)
    {
      const int x = static_cast<int>(d[0] + 0.5) + dx, y = static_cast<int>(d[1] + 0.5) + dy;
      const vtkIdType at = std::min(399, std::max(0, y)) * 400 + std::min(399, std::max(0, x));
      if (pixels->GetComponent(at, 0) / 255.0 < rgb[0])
      {
        for (int a = 0; a < 3; ++a)
        {
          rgb[a] = pixels->GetComponent(at, a) / 255.0;
        }
      }
    }
  }
  vtkIdType covered = 0;
  for (vtkIdType i = 0; i < 400 * 400; ++i)
  {
    covered += pixels->GetComponent(i, 0) < 250 || pixels->GetComponent(i, 1) < 250 ||
      pixels->GetComponent(i, 2) < 250;
  }
  std::printf("the core's pixel %.2f %.2f %.2f; %.1f%% of the window covered\n",
    rgb[0],
    rgb[1],
    rgb[2],
    100.0 * covered / (400 * 400));
  CHECK(rgb[2] > rgb[0] + 0.2 && rgb[0] < 0.35, "the core's pixel is not deep blue");
  CHECK(covered > 0.15 * 400 * 400, "the volume covers too little of the window");
  const int result = vtkRegressionTestImage(window);
  return result == vtkRegressionTester::PASSED && vtkdf::testing::Failures == 0 ? 0 : 1;
}
