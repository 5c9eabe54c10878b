#include "Subcommands.h"

#include "Files.h"
#include "Options.h"
#include "SlicePictures.h"
#include "vtkSegmentedDistanceField.h"

#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkSegmentedDistanceContour.h"
#include "vtkXMLPolyDataWriter.h"

#include <chrono>
#include <cstdio>
#include <string>

namespace vtkdf::cli
{

int Segment(int argc, char* argv[])
{
  CommonOptions common;
  std::string png, surface;
  double delta = 0, offset = 0, featureAngle = 30;
  bool paperVertices = false, uncut = false;
  ParseOptions(argc,
    argv,
    common,
    { Number("--delta", delta),
      Number("--region-offset", offset),
      Flag("--uncut", uncut),
      Text("--png", png),
      Text("--surface", surface),
      Number("--feature-angle", featureAngle),
      Flag("--paper-vertices", paperVertices) });
  vtkNew<vtkSegmentedDistanceField> filter;
  filter->SetInputData(ReadMeshOrExit(argv[2]));
  Configure(filter, common);
  filter->SetDelta(delta);
  filter->SetRegionOffset(offset);
  filter->SetCutSelfIntersections(!uncut);
  // The surface, before any file is written: its errors (a FeatureAngle out of range)
  // leave no output behind.
  auto polygonize = [&]()
  {
    if (surface.empty())
    {
      return true;
    }
    vtkNew<vtkSegmentedDistanceContour> contour;
    contour->SetInputData(filter->GetOutput());
    contour->SetFeatureAngle(featureAngle);
    contour->SetUseClosestPoints(!paperVertices);
    const auto start = std::chrono::steady_clock::now();
    contour->Update();
    const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (contour->GetErrorCode() || !WriteXML<vtkXMLPolyDataWriter>(contour->GetOutput(), surface))
    {
      return false;
    }
    if (common.Timing)
    {
      std::printf("vtkdf: surface time_s=%g triangles=%lld marching_cells=%lld "
                  "feature_cells=%lld other_cells=%lld\n",
        seconds,
        static_cast<long long>(contour->GetOutput()->GetNumberOfCells()),
        static_cast<long long>(contour->GetLastMarchingCells()),
        static_cast<long long>(contour->GetLastFeatureCells()),
        static_cast<long long>(contour->GetLastOtherCells()));
    }
    return true;
  };
  int code = Finish(
    "segment",
    filter,
    common,
    [&]()
    {
      return " regions=" + std::to_string(filter->GetLastRegionCount()) +
        " patches=" + std::to_string(filter->GetLastPatchCount()) +
        " crossed_triangles=" + std::to_string(filter->GetLastCrossedTriangles()) +
        " refused_merges=" + std::to_string(filter->GetLastRefusedMerges());
    },
    polygonize);
  vtkDataArray* usedDelta = filter->GetOutput()->GetFieldData()->GetArray("Delta");
  if (code == 0 && !png.empty() &&
    !(usedDelta && WriteRegionPNG(filter->GetOutput(), usedDelta->GetTuple1(0), png)))
  {
    std::fprintf(stderr, "vtkdf: cannot write %s\n", png.c_str());
    code = 1;
  }
  return code;
}

} // namespace vtkdf::cli
