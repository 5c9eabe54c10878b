// Each bad input of vtkMedialAxisFilter gives the documented error, no crash, and
// empty outputs.
// usage: TestMedialBadInput noclosest|angle|unsigned|empty
#include "vtkMedialAxisFilter.h"

#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include "TestSupport.h"

#include <cstdio>
#include <string>

namespace
{
/// A 5^3 field: Distance = `sign` * (x + 1), and ClosestPoint unless `withClosest` is off.
vtkNew<vtkImageData> Field(double sign, bool withClosest)
{
  vtkNew<vtkImageData> image;
  image->SetDimensions(5, 5, 5);
  vtkNew<vtkFloatArray> distance, closest;
  distance->SetName("Distance");
  closest->SetName("ClosestPoint");
  closest->SetNumberOfComponents(3);
  for (vtkIdType v = 0; v < 125; ++v)
  {
    double x[3];
    image->GetPoint(v, x);
    distance->InsertNextValue(static_cast<float>(sign * (x[0] + 1)));
    closest->InsertNextTuple3(-1, x[1], x[2]);
  }
  image->GetPointData()->AddArray(distance);
  if (withClosest)
  {
    image->GetPointData()->AddArray(closest);
  }
  return image;
}
} // namespace

int main(int argc, char* argv[])
{
  const std::string mode = argc > 1 ? argv[1] : "";
  vtkNew<vtkMedialAxisFilter> filter;
  vtkdf::testing::MessageRecorder recorder(filter);
  filter->SetBackendToCPU();
  std::string expectError, expectWarning;
  if (mode == "noclosest")
  {
    filter->SetInputData(Field(-1, false));
    expectError = "no point-data array named ClosestPoint";
  }
  else if (mode == "nanspacing")
  {
    auto image = Field(-1, true);
    image->SetSpacing(1, std::nan(""), 1);
    filter->SetInputData(image);
    expectError = "The input image's grid is unusable: the grid spacing along y is not a finite";
  }
  else if (mode == "angle")
  {
    filter->SetInputData(Field(-1, true));
    filter->SetSeparationAngle(180);
    expectError = "SeparationAngle must lie in (0, 180)";
  }
  else if (mode == "unsigned")
  {
    filter->SetInputData(Field(1, true));
    filter->SetRegionToInside();
    expectError = "Region is Inside but the field is unsigned";
  }
  else if (mode == "empty")
  {
    vtkNew<vtkPolyData> empty;
    filter->SetInputData(empty);
    expectWarning = "empty";
  }
  else
  {
    std::printf("unknown mode '%s'\n", mode.c_str());
    return 2;
  }
  filter->Update();
  const vtkIdType n =
    filter->GetOutput()->GetNumberOfPoints() + filter->GetMedialPoints()->GetNumberOfPoints();
  return recorder.Expect(mode, n, expectError, expectWarning, false) ? 0 : 1;
}
