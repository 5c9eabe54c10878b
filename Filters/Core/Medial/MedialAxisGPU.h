// MedialAxisGPU: the medial axis pass as a compute shader (Shaders/MedialAxis.comp.glsl),
// the same double-precision arithmetic as MedialAxisCPU, so the same voxels.
#ifndef vtkdf_MedialAxisGPU_h
#define vtkdf_MedialAxisGPU_h

#include "GL/HeadlessGL.h"
#include "LinearFactor/LinearFactorScan.h"
#include "Medial/MedialAxis.h"

#include <string>

namespace vtkdf
{

/// As MedialAxisCPU; false and `error` when the GPU cannot run it.
bool MedialAxisGPU(HeadlessGL& context,
  const MedialInput& input,
  uint8_t* medial,
  double* cosine,
  int64_t& count,
  std::string& error);

/// The field of a mesh and its medial axis, all on the GPU: the scan keeps the nearest
/// sites there, a GPU finalize turns them into the signed field with closest points
/// (FinalizeGPU), and the medial pass reads that field where it is. Only the distances
/// (for Radius) and the cosines come back. `parameters` gives the angle and region (its
/// Distance and ClosestPoint pointers are not used).
bool MedialAxisFromSitesGPU(HeadlessGL& context,
  const MeshSites& sites,
  const RangeCulling& culling,
  const FieldRequest& request,
  const MedialInput& parameters,
  float* distance,
  uint8_t* medial,
  double* cosine,
  int64_t& count,
  ScanStatistics& stats,
  std::string& error);

} // namespace vtkdf

#endif
