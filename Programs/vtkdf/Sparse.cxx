#include "Subcommands.h"

#include "Files.h"
#include "Options.h"
#include "vtkDistanceFieldEnums.h"
#include "vtkSparseDistanceField.h"

#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkNew.h"
#include "vtkPartitionedDataSet.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkXMLImageDataWriter.h"
#include "vtkXMLPartitionedDataSetWriter.h"
#ifdef DF_HAVE_OPENVDB
#include "vtkOpenVDBLevelSetWriter.h"
#endif

#include <chrono>
#include <cstdio>

namespace vtkdf::cli
{

namespace
{
/// The band as an OpenVDB level set; false, with a message, when it cannot be written.
bool WriteLevelSet(vtkSparseDistanceField* filter, const std::string& path, bool timing)
{
#ifdef DF_HAVE_OPENVDB
  vtkNew<vtkOpenVDBLevelSetWriter> writer;
  writer->SetInputConnection(filter->GetOutputPort(0));
  writer->SetSidesConnection(filter->GetOutputPort(1));
  writer->SetFileName(path.c_str());
  const auto start = std::chrono::steady_clock::now();
  writer->Write();
  if (writer->GetErrorCode() != 0)
  {
    std::fprintf(stderr, "vtkdf: cannot write %s\n", path.c_str());
    return false;
  }
  if (timing)
  {
    std::printf("vtkdf: vdb active_voxels=%lld leaf_nodes=%lld write_s=%.6f\n",
      static_cast<long long>(writer->GetLastActiveVoxels()),
      static_cast<long long>(writer->GetLastLeafNodes()),
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  return true;
#else
  (void)filter;
  (void)timing;
  std::fprintf(stderr,
    "vtkdf: cannot write %s: this build has no OpenVDB (DF_USE_OPENVDB; Debian: "
    "libopenvdb-dev)\n",
    path.c_str());
  return false;
#endif
}
} // namespace

int LinfacSparse(vtkPolyData* mesh, CommonOptions& common, const SparseOptions& options)
{
  vtkNew<vtkSparseDistanceField> filter;
  filter->SetInputData(mesh);
  Configure(filter, common);
  filter->SetBandWidth(options.BandWidth);
  filter->SetBrickSize(options.BrickSize);
  filter->SetDomainShape(options.DomainShape);
  filter->SetSignMode(options.SignMode);
  filter->SetComputeClosestCellId(options.Arrays.find("cellid") != std::string::npos);
  filter->SetComputeClosestFeature(options.Arrays.find("feature") != std::string::npos);
  filter->SetComputeClosestPoint(options.Arrays.find("point") != std::string::npos);
  filter->Update();
  if (filter->GetErrorCode() || filter->GetLastPieces() == 0)
  {
    std::fprintf(stderr, "vtkdf: no output was computed\n");
    return 1;
  }
  if (common.Timing)
  {
    int whole[6];
    filter->GetOutputInformation(0)->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
    std::printf(
      "vtkdf: linfac dims=%dx%dx%d backend=%s time_s=%.6f band=%g band_samples=%lld "
      "pieces=%lld candidate_bricks=%lld winding_bricks_decided=%lld piece_memory_mb=%.1f "
      "stages=%s "
      "peak_memory_mb=%.1f\n",
      whole[1] - whole[0] + 1,
      whole[3] - whole[2] + 1,
      whole[5] - whole[4] + 1,
      filter->GetLastBackend(),
      filter->GetLastTime(),
      options.BandWidth,
      static_cast<long long>(filter->GetLastBandSamples()),
      static_cast<long long>(filter->GetLastPieces()),
      static_cast<long long>(filter->GetLastCandidateBricks()),
      static_cast<long long>(filter->GetLastWindingBricksDecided()),
      filter->GetLastPieceMemory(),
      filter->GetLastStageTimes(),
      filter->GetLastPeakMemory());
  }
  // The level set first: where it cannot be written (an anisotropic grid), nothing is.
  const bool levelSetOnly = EndsWith(common.Output, ".vdb");
  const std::string levelSet = levelSetOnly ? common.Output : options.Vdb;
  if (!levelSet.empty() && !WriteLevelSet(filter, levelSet, common.Timing))
  {
    return 1;
  }
  if (!levelSetOnly &&
    !WriteXML<vtkXMLPartitionedDataSetWriter>(filter->GetOutputDataObject(0), common.Output))
  {
    return 1;
  }
  if (!options.Sides.empty() &&
    !WriteXML<vtkXMLImageDataWriter>(filter->GetOutputDataObject(1), options.Sides))
  {
    return 1;
  }
  return 0;
}

} // namespace vtkdf::cli
