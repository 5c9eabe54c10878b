#include "Subcommands.h"

#include "Files.h"
#include "Options.h"
#include "vtkClipByMeshDistance.h"
#include "vtkDistanceFieldEnums.h"

#include "vtkDataSet.h"
#include "vtkNew.h"
#include "vtkUnstructuredGrid.h"

#include <cstdio>
#include <string>

namespace vtkdf::cli
{

/// vtkdf clip MESH DATASET -o OUT.vtu [--value V] [--sign unsigned|pseudonormal|winding]
///   [--outside] [--timing]
int Clip(int argc, char* argv[])
{
  if (argc < 4)
  {
    return Usage("clip needs a mesh and the dataset to clip");
  }
  std::string output, sign = "winding";
  bool outside = false, timing = false;
  double value = 0;
  for (int a = 4; a < argc; ++a)
  {
    const std::string option = argv[a];
    const bool valued = a + 1 < argc;
    if (option == "--timing" || option == "--outside")
    {
      (option == "--timing" ? timing : outside) = true;
    }
    else if (option == "-o" && valued)
    {
      output = argv[++a];
    }
    else if (option == "--sign" && valued)
    {
      sign = argv[++a];
    }
    else if (option == "--value" && valued)
    {
      value = ParseNumber("--value", argv[++a]);
    }
    else
    {
      const bool known = option == "-o" || option == "--sign" || option == "--value";
      return Usage((option + (known ? " needs a value" : ": unknown option")).c_str());
    }
  }
  if (output.empty())
  {
    return Usage("clip needs -o OUT.vtu");
  }
  vtkNew<vtkClipByMeshDistance> filter;
  filter->SetSignMode(EnumWord("--sign", sign, vtkdf::enums::LinearFactorSign));
  filter->SetSurfaceData(ReadMeshOrExit(argv[2]));
  filter->SetInputData(0, ReadDataSetOrExit(argv[3]));
  filter->SetValue(value);
  filter->SetInsideOut(!outside);
  filter->Update();
  vtkUnstructuredGrid* result = filter->GetOutput();
  if (filter->GetErrorCode())
  {
    std::fprintf(stderr, "vtkdf: no output was computed\n");
    return 1;
  }
  std::printf("vtkdf: clip cells=%lld points=%lld\n",
    static_cast<long long>(result->GetNumberOfCells()),
    static_cast<long long>(result->GetNumberOfPoints()));
  if (timing)
  {
    std::printf("vtkdf: clip time_s=%.6f stages=%s peak_memory_mb=%.1f\n",
      filter->GetLastTime(),
      filter->GetLastStageTimes(),
      filter->GetLastPeakMemory());
  }
  return WriteDataSet(result, output);
}

} // namespace vtkdf::cli
