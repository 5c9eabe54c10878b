// Each bad input gives the documented message, no crash, and no (or an empty) field.
// usage: TestLinearFactorBadInput empty|nan|memory|overflow|cells|nogpu
#include "vtkLinearFactorDistanceField.h"

#include "vtkCellArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include "TestSupport.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

int main(int argc, char* argv[])
{
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode == "nogpu")
  {
    setenv("VTKDF_GL_PLATFORM", "none", 1); // no route: as on a machine without any GL
  }
  vtkNew<vtkLinearFactorDistanceField> filter;
  vtkdf::testing::MessageRecorder recorder(filter);
  filter->SetResolution(16);
  filter->SetBackendToCPU();
  std::string expectError, expectWarning;
  bool expectField = false;
  if (mode == "empty")
  {
    vtkNew<vtkPolyData> empty;
    filter->SetInputData(empty);
    expectWarning = "empty";
  }
  else if (mode == "nan")
  {
    filter->SetInputData(vtkdf::testing::Triangle(std::nan("")));
    filter->ExplicitGridOn(); // the default grid cannot be made from NaN bounds
    expectError = "NaN";
  }
  else if (mode == "memory")
  {
    filter->SetInputData(vtkdf::testing::Triangle());
    filter->SetMemoryLimit(1000);
    expectError = "above MemoryLimit";
  }
  else if (mode == "overflow")
  {
    filter->SetInputData(vtkdf::testing::Triangle());
    filter->ExplicitGridOn();
    filter->SetGridDimensions(2100000, 2100000, 2100000);
    expectError = "more than vtkIdType can index";
  }
  else if (mode == "cells")
  {
    vtkNew<vtkPolyData> mesh;
    mesh->DeepCopy(vtkdf::testing::Triangle());
    const vtkIdType two[2] = { 0, 1 };
    mesh->GetPolys()->InsertNextCell(2, two);
    filter->SetInputData(mesh);
    expectWarning = "1 polygons with fewer than 3 points";
    expectField = true;
  }
  else if (mode == "nogpu")
  {
    filter->SetInputData(vtkdf::testing::Triangle());
    filter->SetBackendToGPU();
    expectError = "Backend is GPU but no OpenGL 4.5 core context could be created";
  }
  else
  {
    std::printf("unknown mode '%s'\n", mode.c_str());
    return 2;
  }
  filter->Update();
  const vtkIdType n = filter->GetOutput()->GetNumberOfPoints();
  return recorder.Expect(mode, n, expectError, expectWarning, expectField) ? 0 : 1;
}
