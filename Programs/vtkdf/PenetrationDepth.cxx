#include "Subcommands.h"

#include "Files.h"
#include "Options.h"
#include "QueryOptions.h"
#include "SlicePictures.h"
#include "vtkPenetrationDepth.h"

#include "vtkNew.h"
#include "vtkXMLPolyDataWriter.h"

#include <chrono>
#include <cstdio>

namespace vtkdf::cli
{

/// vtkdf pd P Q -o OUT.vtp [--piece-array NAME] [--convex-hulls] [--timing]
int PenetrationDepth(int argc, char* argv[])
{
  if (argc < 4)
  {
    return Usage("pd needs two solids, P and Q");
  }
  QueryOptions where;
  for (int a = 4; a < argc; ++a)
  {
    const std::string option = argv[a];
    if (!where.Parse(argc, argv, a))
    {
      return Usage(QueryOptions::Refuse(option).c_str());
    }
  }
  if (where.Output.empty())
  {
    return Usage("pd needs -o OUT.vtp");
  }
  vtkNew<vtkPenetrationDepth> filter;
  filter->SetSolidPData(ReadPolytopesOrExit(argv[2]));
  filter->SetSolidQData(ReadPolytopesOrExit(argv[3]));
  where.Apply(filter.Get());
  const auto start = std::chrono::steady_clock::now();
  filter->Update();
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (filter->GetErrorCode() || filter->GetOutput()->GetNumberOfPoints() == 0)
  {
    std::fprintf(stderr, "vtkdf: no output was computed\n");
    return 1;
  }
  const double* n = filter->GetLastDirection();
  std::printf("vtkdf: pd intersecting=%d penetration_depth=%.17g separation_distance=%.17g "
              "direction=%.9f,%.9f,%.9f\n",
    filter->GetLastIntersecting() ? 1 : 0,
    filter->GetLastPenetrationDepth(),
    filter->GetLastSeparationDistance(),
    n[0],
    n[1],
    n[2]);
  if (where.Timing)
  {
    std::printf("vtkdf: pd pairs=%lld pairs_kept=%lld backend=%s renderer=\"%s\" time_s=%.6f "
                "faces_visited=%lld\n",
      static_cast<long long>(filter->GetLastPairsTotal()),
      static_cast<long long>(filter->GetLastPairsKept()),
      filter->GetLastBackend() == vtkPenetrationDepth::BACKEND_GPU ? "gpu" : "cpu",
      filter->GetLastRenderer(),
      seconds,
      static_cast<long long>(filter->GetLastFacesVisited()));
  }
  return WriteXML<vtkXMLPolyDataWriter>(filter->GetOutput(), where.Output) ? 0 : 1;
}

} // namespace vtkdf::cli
