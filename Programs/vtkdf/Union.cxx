#include "Subcommands.h"

#include "Files.h"
#include "Options.h"
#include "QueryOptions.h"
#include "SlicePictures.h"
#include "vtkUnionClosestPoint.h"

#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkXMLPolyDataWriter.h"

#include <chrono>
#include <cstdio>

namespace vtkdf::cli
{

/// vtkdf union POLYTOPES -o OUT.vtp [--query X Y Z | --queries POINTS]
///   [--piece-array NAME] [--convex-hulls] [--timing]
int Union(int argc, char* argv[])
{
  std::string queriesPath;
  double query[3] = { 0, 0, 0 };
  QueryOptions where;
  for (int a = 3; a < argc; ++a)
  {
    const std::string option = argv[a];
    if (where.Parse(argc, argv, a))
    {
      continue;
    }
    if (option == "--query" && a + 3 < argc)
    {
      for (int c = 0; c < 3; ++c)
      {
        query[c] = ParseNumber("--query", argv[++a]);
      }
      continue;
    }
    if (option == "--queries" && a + 1 < argc)
    {
      queriesPath = argv[++a];
      continue;
    }
    return Usage(QueryOptions::Refuse(option).c_str());
  }
  if (where.Output.empty())
  {
    return Usage("union needs -o OUT.vtp");
  }
  vtkNew<vtkUnionClosestPoint> filter;
  filter->SetInputData(0, ReadPolytopesOrExit(argv[2]));
  if (!queriesPath.empty())
  {
    filter->SetQueryData(ReadMeshOrExit(queriesPath));
  }
  filter->SetQueryPoint(query);
  where.Apply(filter.Get());
  const auto start = std::chrono::steady_clock::now();
  filter->Update();
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  vtkPolyData* result = filter->GetOutput();
  if (filter->GetErrorCode() || result->GetNumberOfPoints() == 0)
  {
    std::fprintf(stderr, "vtkdf: no output was computed\n");
    return 1;
  }
  if (where.Timing)
  {
    std::printf("vtkdf: union pieces=%d queries=%lld backend=%s renderer=\"%s\" time_s=%.6f "
                "faces_visited=%lld\n",
      filter->GetLastPieceCount(),
      static_cast<long long>(result->GetNumberOfPoints() / 2),
      filter->GetLastBackend() == vtkUnionClosestPoint::BACKEND_GPU ? "gpu" : "cpu",
      filter->GetLastRenderer(),
      seconds,
      static_cast<long long>(filter->GetLastFacesVisited()));
  }
  return WriteXML<vtkXMLPolyDataWriter>(result, where.Output) ? 0 : 1;
}

} // namespace vtkdf::cli
