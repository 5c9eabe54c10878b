// SegmentFieldGPU: the side label of every sample (SegmentRegions' first pass) on the
// GPU, where the unsigned field lies (ComputeLinearFactorFieldOnGPU: every sample's
// nearest site, distance and closest point). A compute shader (Shaders/SideLabel.comp.glsl,
// SideLabel's arithmetic in double) labels every sample; only the distances, closest
// points and labels come back; the merge of the labels into regions runs on the CPU (SegmentRegions
// with SegmentInput::Labels), as it costs little next to the field.
#ifndef vtkdf_SegmentFieldGPU_h
#define vtkdf_SegmentFieldGPU_h

#include "GL/HeadlessGL.h"
#include "LinearFactor/LinearFactorField.h"
#include "Segment/SurfacePatches.h"

#include <cstdint>
#include <string>
#include <vector>

namespace vtkdf
{

/// The side label of every sample of `field` (ComputeLinearFactorFieldOnGPU, unsigned, in
/// world units: the CPU backend's floats; `patches` in the grid's local frame), computed
/// where the field lies from the closest points taken to the local frame as the CPU's
/// regions take them; `siteTriangle` gives per site its triangle in `patches` (-1: none)
/// and its type. Fills, per sample (x fastest), `distance` (unsigned, world units),
/// `closest` (xyz, world) and `label` (2 patch + side, -1 when the sample has none).
/// False and `error` when the GPU cannot.
bool SideLabelsOnGPUField(HeadlessGL& context,
  const GPUField& field,
  const SurfacePatches& patches,
  const std::vector<int32_t>& siteTriangle,
  float* distance,
  float* closest,
  int32_t* label,
  std::string& error);

} // namespace vtkdf

#endif
