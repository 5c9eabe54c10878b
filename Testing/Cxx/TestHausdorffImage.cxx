// Regression image of vtkMeshHausdorffDistance: bunny_small (A, translucent) coloured by
// each vertex's distance to its decimation (B, vtkQuadricDecimation keeping a tenth of
// the triangles: blue near, white, red far), B's edges in grey, and the pair of points
// where the Hausdorff distance was found: a yellow ball on the mesh that holds it, a black
// segment to its closest point on the other. Compared with
// Testing/Data/Baseline/TestHausdorffImage.png. Also by numbers: the pixel at the ball is
// yellow, and the surface covers a fair share of the window.
//
// usage: TestHausdorffImage DATA_DIR -V BASELINE.png -T TMPDIR
#include "TestSupport.h"
#include "vtkMeshHausdorffDistance.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkLineSource.h"
#include "vtkLookupTable.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkQuadricDecimation.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSphereSource.h"
#include "vtkUnsignedCharArray.h"
#include "vtkXMLPolyDataReader.h"

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
  vtkNew<vtkQuadricDecimation> decimate;
  decimate->SetInputConnection(reader->GetOutputPort());
  decimate->SetTargetReduction(0.9);
  vtkNew<vtkMeshHausdorffDistance> hausdorff;
  hausdorff->SetInputConnection(reader->GetOutputPort());
  hausdorff->SetMeshBConnection(decimate->GetOutputPort());
  hausdorff->Update();
  vtkPolyData* fine = hausdorff->GetOutput(0);
  vtkPolyData* coarse = hausdorff->GetOutput(1);
  vtkDataArray* pair = fine->GetFieldData()->GetArray("HausdorffPoints");
  if (hausdorff->GetErrorCode() || !pair)
  {
    std::printf("FAIL: no Hausdorff distance\n");
    return 1;
  }
  double from[3], to[3];
  pair->GetTuple(0, from);
  pair->GetTuple(1, to);
  std::printf("Hausdorff distance %.9g in [%.9g, %.9g], found on %s\n",
    hausdorff->GetHausdorffDistance(),
    hausdorff->GetHausdorffBounds()[0],
    hausdorff->GetHausdorffBounds()[1],
    hausdorff->GetDistanceBToA() > hausdorff->GetDistanceAToB() ? "B" : "A");

  // Blue (near) through white to red (far), over A's vertex distances.
  vtkNew<vtkLookupTable> colours;
  colours->SetNumberOfTableValues(256);
  const double blue[3] = { 0.23, 0.30, 0.75 }, red[3] = { 0.71, 0.02, 0.15 };
  for (int i = 0; i < 256; ++i)
  {
    const double t = i / 255.0, s = std::fabs(2 * t - 1);
    const double* end = t < 0.5 ? blue : red;
    colours->SetTableValue(i, 1 + s * (end[0] - 1), 1 + s * (end[1] - 1), 1 + s * (end[2] - 1), 1);
  }
  vtkNew<vtkPolyDataMapper> fineMapper;
  fineMapper->SetInputData(fine);
  fineMapper->SetLookupTable(colours);
  fineMapper->SetScalarRange(fine->GetPointData()->GetArray("Distance")->GetRange());
  vtkNew<vtkActor> fineActor;
  fineActor->SetMapper(fineMapper);
  // See-through: the farthest point may lie under A's surface (on B, inside A).
  fineActor->GetProperty()->SetOpacity(0.45);

  vtkNew<vtkPolyDataMapper> coarseMapper;
  coarseMapper->SetInputData(coarse);
  coarseMapper->ScalarVisibilityOff();
  vtkNew<vtkActor> coarseActor;
  coarseActor->SetMapper(coarseMapper);
  coarseActor->GetProperty()->SetRepresentationToWireframe();
  coarseActor->GetProperty()->SetColor(0.35, 0.35, 0.35);
  coarseActor->GetProperty()->SetLineWidth(1);

  double bounds[6];
  fine->GetBounds(bounds);
  const double size = bounds[1] - bounds[0];
  vtkNew<vtkSphereSource> ball;
  ball->SetCenter(from);
  ball->SetRadius(0.03 * size);
  ball->SetThetaResolution(24);
  ball->SetPhiResolution(24);
  vtkNew<vtkPolyDataMapper> ballMapper;
  ballMapper->SetInputConnection(ball->GetOutputPort());
  vtkNew<vtkActor> ballActor;
  ballActor->SetMapper(ballMapper);
  ballActor->GetProperty()->SetColor(1, 0.85, 0);
  vtkNew<vtkLineSource> segment;
  segment->SetPoint1(from);
  segment->SetPoint2(to);
  vtkNew<vtkPolyDataMapper> segmentMapper;
  segmentMapper->SetInputConnection(segment->GetOutputPort());
  vtkNew<vtkActor> segmentActor;
  segmentActor->SetMapper(segmentMapper);
  segmentActor->GetProperty()->SetColor(0, 0, 0);
  segmentActor->GetProperty()->SetLineWidth(4);

  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(1, 1, 1);
  renderer->AddActor(fineActor);
  renderer->AddActor(coarseActor);
  renderer->AddActor(ballActor);
  renderer->AddActor(segmentActor);
  vtkNew<vtkRenderWindow> window;
  window->SetSize(400, 400);
  window->AddRenderer(renderer);
  // The bunny from its side (y is up), from the side of the ball.
  const double centre[3] = {
    0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3]), 0.5 * (bounds[4] + bounds[5])
  };
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetFocalPoint(centre);
  camera->SetPosition(centre[0], centre[1], centre[2] + (from[2] >= centre[2] ? 3 : -3) * size);
  camera->SetViewUp(0, 1, 0);
  renderer->ResetCamera();
  window->Render();

  // By numbers: the ball's pixel is yellow (behind at most A's translucent surface); the
  // surface covers a fair share of the window.
  vtkNew<vtkUnsignedCharArray> pixels;
  window->GetPixelData(0, 0, 399, 399, 1, pixels);
  renderer->SetWorldPoint(from[0], from[1], from[2], 1);
  renderer->WorldToDisplay();
  double d[3];
  renderer->GetDisplayPoint(d);
  const vtkIdType at = static_cast<int>(d[1] + 0.5) * 400 + static_cast<int>(d[0] + 0.5);
  double rgb[3];
  for (int a = 0; a < 3; ++a)
  {
    rgb[a] = pixels->GetComponent(at, a) / 255.0;
  }
  vtkIdType covered = 0;
  for (vtkIdType i = 0; i < 400 * 400; ++i)
  {
    covered += pixels->GetComponent(i, 0) < 250 || pixels->GetComponent(i, 1) < 250 ||
      pixels->GetComponent(i, 2) < 250;
  }
  std::printf("the ball's pixel %.2f %.2f %.2f; %.1f%% of the window covered\n",
    rgb[0],
    rgb[1],
    rgb[2],
    100.0 * covered / (400 * 400));
  CHECK(rgb[0] > rgb[2] + 0.2 && rgb[1] > rgb[2] + 0.2, "the ball's pixel is not yellow");
  CHECK(covered > 0.15 * 400 * 400, "the surface covers too little of the window");
  const int result = vtkRegressionTestImage(window);
  return result == vtkRegressionTester::PASSED && vtkdf::testing::Failures == 0 ? 0 : 1;
}
