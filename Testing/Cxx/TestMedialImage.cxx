// Regression image of vtkMedialAxisFilter: the medial points of armadillo_52k (theta
// 75, inside, 64^3), as spheres coloured by Radius, inside the translucent surface.
// Compared with Testing/Data/Baseline/TestMedialImage.png.
//
// usage: TestMedialImage DATA_DIR cpu|gpu -V BASELINE.png -T TMPDIR
#include "TestSupport.h"
#include "vtkMedialAxisFilter.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkDataArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkXMLPolyDataReader.h"

#include <cstdio>
#include <string>

int main(int argc, char* argv[])
{
  if (!testsupport::HasArguments(argc, argv, 2, "DATA_DIR cpu|gpu -V BASELINE -T TMP"))
  {
    return 2;
  }
  const std::string dataDir = argv[1], backend = argv[2];
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName((dataDir + "/armadillo_52k.vtp").c_str());

  vtkNew<vtkMedialAxisFilter> medial;
  medial->SetInputConnection(reader->GetOutputPort());
  medial->SetResolution(64);
  medial->SetSeparationAngle(75);
  medial->SetRegionToInside();
  testsupport::UseBackend(medial.GetPointer(), backend);
  medial->Update();
  vtkPolyData* points = medial->GetMedialPoints();
  std::printf("%lld medial points (%s)\n",
    static_cast<long long>(points->GetNumberOfPoints()),
    medial->GetLastBackend());
  if (points->GetNumberOfPoints() == 0)
  {
    std::printf("FAIL: no medial point\n");
    return 1;
  }

  vtkNew<vtkPolyDataMapper> pointMapper;
  pointMapper->SetInputData(points);
  pointMapper->SetScalarModeToUsePointFieldData();
  pointMapper->SelectColorArray("Radius");
  pointMapper->SetScalarRange(points->GetPointData()->GetArray("Radius")->GetRange());
  pointMapper->ScalarVisibilityOn();
  vtkNew<vtkActor> pointActor;
  pointActor->SetMapper(pointMapper);
  pointActor->GetProperty()->SetRepresentationToPoints();
  pointActor->GetProperty()->SetPointSize(4);
  pointActor->GetProperty()->RenderPointsAsSpheresOn();

  vtkNew<vtkPolyDataMapper> surfaceMapper;
  surfaceMapper->SetInputConnection(reader->GetOutputPort());
  surfaceMapper->ScalarVisibilityOff();
  vtkNew<vtkActor> surface;
  surface->SetMapper(surfaceMapper);
  surface->GetProperty()->SetColor(0.8, 0.8, 0.75);
  surface->GetProperty()->SetOpacity(0.2);

  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(1, 1, 1);
  renderer->AddActor(pointActor);
  renderer->AddActor(surface);
  vtkNew<vtkRenderWindow> window;
  window->SetSize(400, 400);
  window->AddRenderer(renderer);
  renderer->ResetCamera();
  renderer->GetActiveCamera()->Azimuth(180);
  renderer->ResetCamera();
  window->Render();
  const int result = vtkRegressionTestImage(window);
  return result == vtkRegressionTester::PASSED ? 0 : 1;
}
