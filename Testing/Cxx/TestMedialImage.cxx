// Regression image of vtkMedialAxisFilter: the medial points of armadillo_52k (theta
// 75, inside, 64^3), as spheres coloured by Radius, inside the translucent surface.
// Compared with Testing/Data/Baseline/TestMedialImage.png. Also by numbers: the skeleton
// is connected (its largest 26-connected set of voxels holds at least 90% of them).
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

#include "vtkImageData.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

namespace
{
/// The share of the medial voxels in the largest 26-connected set of them.
double LargestComponentShare(vtkImageData* image)
{
  auto* medial = vtkUnsignedCharArray::SafeDownCast(image->GetPointData()->GetArray("Medial"));
  int n[3];
  image->GetDimensions(n);
  std::vector<char> left(
    medial->GetPointer(0), medial->GetPointer(0) + medial->GetNumberOfTuples());
  const int64_t total = std::count(left.begin(), left.end(), 1);
  int64_t largest = 0;
  std::vector<int64_t> stack;
  for (int64_t start = 0; start < static_cast<int64_t>(left.size()); ++start)
  {
    if (!left[start])
    {
      continue;
    }
    int64_t size = 0;
    left[start] = 0;
    stack.push_back(start);
    while (!stack.empty())
    {
      const int64_t v = stack.back();
      stack.pop_back();
      ++size;
      const int i = static_cast<int>(v % n[0]), j = static_cast<int>((v / n[0]) % n[1]),
                k = static_cast<int>(v / (int64_t(n[0]) * n[1]));
      for (int dz = -1; dz <= 1; ++dz)
      {
        for (int dy = -1; dy <= 1; ++dy)
        {
          for (int dx = -1; dx <= 1; ++dx)
          {
            const int a = i + dx, b = j + dy, c = k + dz;
            if (a < 0 || b < 0 || c < 0 || a >= n[0] || b >= n[1] || c >= n[2])
            {
              continue;
            }
            const int64_t u = a + int64_t(n[0]) * (b + int64_t(n[1]) * c);
            if (left[u])
            {
              left[u] = 0;
              stack.push_back(u);
            }
          }
        }
      }
    }
    largest = std::max(largest, size);
  }
  return total ? double(largest) / total : 0;
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
  reader->SetFileName((dataDir + "/armadillo_52k.vtp").c_str());

  vtkNew<vtkMedialAxisFilter> medial;
  medial->SetInputConnection(reader->GetOutputPort());
  medial->SetResolution(64);
  medial->SetSeparationAngle(75);
  medial->SetRegionToInside();
  vtkdf::testing::UseBackend(medial.GetPointer(), backend);
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
  const double connected = LargestComponentShare(medial->GetOutput());
  std::printf("the largest 26-connected set holds %.1f%% of the medial voxels\n", 100 * connected);
  if (!(connected >= 0.9))
  {
    std::printf("FAIL: the skeleton falls apart\n");
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
