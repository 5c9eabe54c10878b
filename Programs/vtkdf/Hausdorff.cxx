#include "Subcommands.h"

#include "Files.h"
#include "Options.h"
#include "vtkMeshHausdorffDistance.h"

#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkXMLPolyDataWriter.h"

#include <cstdio>
#include <string>

namespace vtkdf::cli
{

/// vtkdf hausdorff A B -o A_OUT.vtp [--output-b B_OUT.vtp] [--relative-error E] [--timing]
int Hausdorff(int argc, char* argv[])
{
  if (argc < 4)
  {
    return Usage("hausdorff needs two meshes");
  }
  std::string outputA, outputB;
  double relativeError = 1e-6;
  bool timing = false;
  for (int a = 4; a < argc; ++a)
  {
    const std::string option = argv[a];
    const bool valued = a + 1 < argc;
    if (option == "--timing")
    {
      timing = true;
    }
    else if (option == "-o" && valued)
    {
      outputA = argv[++a];
    }
    else if (option == "--output-b" && valued)
    {
      outputB = argv[++a];
    }
    else if (option == "--relative-error" && valued)
    {
      relativeError = ParseNumber("--relative-error", argv[++a]);
    }
    else
    {
      const bool known = option == "-o" || option == "--output-b" || option == "--relative-error";
      return Usage((option + (known ? " needs a value" : ": unknown option")).c_str());
    }
  }
  if (outputA.empty() || !EndsWith(outputA, ".vtp") ||
    (!outputB.empty() && !EndsWith(outputB, ".vtp")))
  {
    return Usage("hausdorff needs -o A_OUT.vtp (and --output-b, if given, a .vtp)");
  }
  vtkNew<vtkMeshHausdorffDistance> filter;
  filter->SetInputData(ReadMeshOrExit(argv[2]));
  filter->SetMeshBData(ReadMeshOrExit(argv[3]));
  filter->SetRelativeError(relativeError);
  filter->Update();
  vtkFieldData* fd = filter->GetOutput(0)->GetFieldData();
  vtkDataArray* oneSided = fd->GetArray("OneSidedHausdorffBounds");
  vtkDataArray* points = fd->GetArray("HausdorffPoints");
  if (filter->GetErrorCode() || !oneSided || !points)
  {
    std::fprintf(stderr, "vtkdf: no output was computed\n");
    return 1;
  }
  const double* bounds = filter->GetHausdorffBounds();
  double from[3], to[3];
  points->GetTuple(0, from);
  points->GetTuple(1, to);
  std::printf("vtkdf: hausdorff distance=%.17g lower=%.17g upper=%.17g "
              "a_to_b=%.17g a_to_b_lower=%.17g a_to_b_upper=%.17g "
              "b_to_a=%.17g b_to_a_lower=%.17g b_to_a_upper=%.17g "
              "on=%s point=%.17g,%.17g,%.17g closest=%.17g,%.17g,%.17g\n",
    filter->GetHausdorffDistance(),
    bounds[0],
    bounds[1],
    filter->GetDistanceAToB(),
    oneSided->GetComponent(0, 0),
    oneSided->GetComponent(0, 1),
    filter->GetDistanceBToA(),
    oneSided->GetComponent(1, 0),
    oneSided->GetComponent(1, 1),
    fd->GetArray("HausdorffSource")->GetTuple1(0) == 0 ? "A" : "B",
    from[0],
    from[1],
    from[2],
    to[0],
    to[1],
    to[2]);
  if (timing)
  {
    std::printf("vtkdf: hausdorff time_s=%.6f stages=%s pieces=%lld rounds=%lld "
                "evaluations=%lld peak_memory_mb=%.1f\n",
      filter->GetLastTime(),
      filter->GetLastStageTimes(),
      static_cast<long long>(filter->GetLastPieces()),
      static_cast<long long>(filter->GetLastRounds()),
      static_cast<long long>(filter->GetLastEvaluations()),
      filter->GetLastPeakMemory());
  }
  if (!WriteXML<vtkXMLPolyDataWriter>(filter->GetOutput(0), outputA))
  {
    return 1;
  }
  if (!outputB.empty() && !WriteXML<vtkXMLPolyDataWriter>(filter->GetOutput(1), outputB))
  {
    return 1;
  }
  return 0;
}

} // namespace vtkdf::cli
