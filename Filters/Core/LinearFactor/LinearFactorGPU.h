// LinearFactorGPU: the scan pass of LinearFactorField on the GPU. Domain polygons are
// built by a geometry shader, many slices per draw (layered rendering into texture
// arrays); the depth test keeps the nearest site; the field is read back once per batch.
#ifndef vtkdf_LinearFactorGPU_h
#define vtkdf_LinearFactorGPU_h

#include "GL/HeadlessGL.h"
#include "LinearFactor/LinearFactorScan.h"

#include <string>

namespace vtkdf
{

/// Fills `nearest` like ScanSitesCPU; false (and `error`) when the GPU cannot run it.
/// With `residentIds` (a GL buffer of one int per sample of the extent), the nearest
/// site ids stay on the GPU, in that buffer, and `nearest` is not touched.
/// With a progress callback, the scan's first batch holds 1/MinimumBatches of the
/// slices and later ones what the measured rate scans in BatchSeconds (at most twice the
/// last); `progress` is
/// called after each batch, once the GPU has finished it.
constexpr int MinimumBatches = 16;
constexpr double BatchSeconds = 0.25;

bool ScanSitesGPU(HeadlessGL& gl,
  const MeshSites& sites,
  const RangeCulling& culling,
  const LocalFieldRequest& request,
  NearestSiteBuffer& nearest,
  const ProgressCallback& progress,
  ScanStatistics& stats,
  std::string& error,
  unsigned residentIds = 0);

/// Finalize on the GPU, from resident ids: the (signed) distance and closest point of
/// every sample into GL buffers of 1 and 3 floats per sample, with the same double
/// arithmetic as Finalize. No narrow band (MaximumDistance) here.
bool FinalizeGPU(HeadlessGL& gl,
  const MeshSites& sites,
  const LocalFieldRequest& request,
  unsigned residentIds,
  bool signedField,
  unsigned distanceBuffer,
  unsigned closestBuffer,
  std::string& error);

} // namespace vtkdf

#endif
