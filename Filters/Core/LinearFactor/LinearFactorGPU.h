// LinearFactorGPU: the scan pass of LinearFactorField on the GPU, in compute shaders. The
// CPU walks the sites' domains as its own scan does and hands the GPU the rows of
// samples each site is offered to; the GPU evaluates them with the CPU's arithmetic and
// keeps, per sample, the least (squared distance, site) pair: the CPU's nearest sites.
#ifndef vtkdf_LinearFactorGPU_h
#define vtkdf_LinearFactorGPU_h

#include "GL/HeadlessGL.h"
#include "LinearFactor/LinearFactorScan.h"

#include <string>

namespace vtkdf
{

/// Fills `nearest` like ScanSitesCPU, with its bits: the CPU walks the sites' domains
/// (CollectScanRows) and the GPU evaluates the rows. False (and `error`) when the GPU
/// cannot run it. With `residentIds` (a GL buffer of one int per sample of the extent),
/// the nearest site ids (-1 for none) stay on the GPU, in that buffer, and `nearest` is
/// not touched. `progress` is called after each batch of sites, once the GPU has
/// evaluated it.
bool ScanSitesGPU(HeadlessGL& gl,
  const MeshSites& sites,
  const RangeCulling& culling,
  const LocalFieldRequest& request,
  NearestSiteBuffer& nearest,
  const ParallelFor& parallelFor,
  const ProgressCallback& progress,
  ScanStatistics& stats,
  std::string& error,
  unsigned residentIds = 0);

/// Finalize on the GPU, from resident ids: the (signed) distance and closest point of
/// every sample, in world units (`frame` takes the local frame's there), into GL buffers
/// of 1 and 3 floats per sample, with the same double arithmetic as Finalize: the same
/// floats. No narrow band (MaximumDistance) here.
bool FinalizeGPU(HeadlessGL& gl,
  const MeshSites& sites,
  const LocalFieldRequest& request,
  const GridFrame& frame,
  unsigned residentIds,
  bool signedField,
  unsigned distanceBuffer,
  unsigned closestBuffer,
  std::string& error);

} // namespace vtkdf

#endif
