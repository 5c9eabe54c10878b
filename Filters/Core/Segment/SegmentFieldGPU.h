// SegmentFieldGPU: the unsigned field of a mesh and the side label of every sample
// (SegmentRegions' first pass), on the GPU. The scan keeps each sample's nearest site
// there (ScanSitesGPU), FinalizeGPU turns the sites into distances and closest points,
// and a compute shader (Shaders/SideLabel.comp.glsl, SideLabel's arithmetic in double)
// labels every sample where the field lies. Only the distances, closest points and labels
// come back; the merge of the labels into regions runs on the CPU (SegmentRegions with
// SegmentInput::Labels), as it costs little next to the field.
#ifndef vtkdf_SegmentFieldGPU_h
#define vtkdf_SegmentFieldGPU_h

#include "GL/HeadlessGL.h"
#include "LinearFactor/LinearFactorScan.h"
#include "Segment/SurfacePatches.h"

#include <cstdint>
#include <string>
#include <vector>

namespace vtkdf
{

/// `sites` and `request` in the grid's local frame, as `patches`; `siteTriangle` gives
/// per site its triangle in `patches` (-1: none). Fills, per sample of request.Extent
/// (x fastest), `distance` (unsigned), `closest` (xyz, the local frame) and `label`
/// (2 patch + side, -1 when the sample has none). False and `error` when the GPU cannot.
/// `progress` (optional) is called as the scan's batches finish; when it returns false
/// the scan stops, stats.Aborted is set and nothing is filled.
bool SegmentFieldGPU(HeadlessGL& context,
  const MeshSites& sites,
  const RangeCulling& culling,
  const FieldRequest& request,
  const SurfacePatches& patches,
  const std::vector<int32_t>& siteTriangle,
  float* distance,
  float* closest,
  int32_t* label,
  ScanStatistics& stats,
  std::string& error,
  const ProgressCallback& progress = nullptr);

} // namespace vtkdf

#endif
