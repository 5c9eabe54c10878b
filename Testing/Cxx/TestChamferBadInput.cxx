// Each bad input of vtkChamferVoxelDistance and vtkPolyDataVoxelizer gives the documented
// message, no crash, and no (or an empty) output.
// usage: TestChamferBadInput empty|nanspacing|noboundary|wrongsize|wrongtype|components|memory|
//                            voxelize-empty|voxelize-nan|voxelize-memory|voxelize-lines
#include "vtkChamferVoxelDistance.h"
#include "vtkPolyDataVoxelizer.h"

#include "vtkCellArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"
#include "vtkUnsignedCharArray.h"

#include "TestSupport.h"

#include <cmath>
#include <cstdio>
#include <string>

namespace
{

/// A 6^3 image whose Boundary mask has `values` values (all zero unless `set`).
vtkNew<vtkImageData> Image(vtkIdType values, bool set)
{
  vtkNew<vtkImageData> image;
  image->SetDimensions(6, 6, 6);
  vtkNew<vtkUnsignedCharArray> mask;
  mask->SetName("Boundary");
  mask->SetNumberOfTuples(values);
  mask->Fill(0);
  if (set)
  {
    mask->SetValue(values / 2, 1);
  }
  image->GetPointData()->AddArray(mask);
  return image;
}
} // namespace

int main(int argc, char* argv[])
{
  const std::string mode = argc > 1 ? argv[1] : "";
  vtkNew<vtkChamferVoxelDistance> chamfer;
  vtkNew<vtkPolyDataVoxelizer> voxelizer;
  vtkDistanceFieldAlgorithm* filter = chamfer;
  if (mode.rfind("voxelize-", 0) == 0)
  {
    filter = voxelizer;
  }
  vtkdf::testing::MessageRecorder recorder(filter);
  filter->SetResolution(16);
  filter->SetBackendToCPU();
  std::string expectError, expectWarning;
  bool expectOutput = false;
  if (mode == "empty" || mode == "voxelize-empty")
  {
    vtkNew<vtkPolyData> empty;
    filter->SetInputData(empty);
    expectWarning = "empty";
  }
  else if (mode == "nanspacing")
  {
    auto image = Image(216, true);
    image->SetSpacing(std::nan(""), 1, 1);
    filter->SetInputData(image);
    expectError = "The input image's grid is unusable: the grid spacing along x is not a finite";
  }
  else if (mode == "noboundary")
  {
    filter->SetInputData(Image(216, false));
    expectError = "no Boundary voxel is set";
  }
  else if (mode == "wrongsize")
  {
    filter->SetInputData(Image(100, true));
    expectError = "The Boundary array has 100 values for 216 samples";
  }
  else if (mode == "wrongtype")
  {
    vtkNew<vtkImageData> image;
    image->SetDimensions(6, 6, 6);
    vtkNew<vtkStringArray> names;
    names->SetName("Boundary");
    names->SetNumberOfValues(216);
    image->GetPointData()->AddArray(names);
    filter->SetInputData(image);
    expectError = "not a numeric array";
  }
  else if (mode == "components")
  {
    auto image = Image(216, true);
    image->GetPointData()->GetArray("Boundary")->SetNumberOfComponents(2);
    image->GetPointData()->GetArray("Boundary")->SetNumberOfTuples(216);
    filter->SetInputData(image);
    expectError = "has 2 components";
  }
  else if (mode == "memory" || mode == "voxelize-memory")
  {
    filter->SetInputData(vtkdf::testing::Triangle());
    filter->SetMemoryLimit(1000);
    expectError = "above MemoryLimit";
  }
  else if (mode == "voxelize-nan")
  {
    filter->SetInputData(vtkdf::testing::Triangle(std::nan("")));
    filter->ExplicitGridOn();
    expectError = "NaN";
  }
  else if (mode == "voxelize-lines")
  {
    vtkNew<vtkPolyData> mesh;
    mesh->DeepCopy(vtkdf::testing::Triangle());
    vtkNew<vtkCellArray> lines;
    const vtkIdType segment[2] = { 0, 1 };
    lines->InsertNextCell(2, segment);
    mesh->SetLines(lines);
    filter->SetInputData(mesh);
    expectWarning = "Vertex and line cells have no area to voxelize";
    expectOutput = true;
  }
  else
  {
    std::printf("unknown mode '%s'\n", mode.c_str());
    return 2;
  }
  filter->Update();
  const vtkIdType n = filter->GetOutput()->GetNumberOfPoints();
  return recorder.Expect(mode, n, expectError, expectWarning, expectOutput) ? 0 : 1;
}
