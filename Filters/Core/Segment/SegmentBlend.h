// SegmentBlend: the blend of two segmented distance fields whose regions mean the same
// (paper 004, section 5.2: metamorphosis by interpolating the fields), without VTK types.
//
// At a sample where both fields give the same region, the distances are blended; where
// they give regions a and b, the two distances are blended as a signed distance across
// that pair, negative on a's side: s = (1 - t)(-d_a) + t d_b, and the sample goes to a
// (distance -s) where s < 0, else to b (distance s). So every interface moves linearly
// from its position in the first field (t = 0) to its position in the second (t = 1);
// for concentric spheres of radii R0 and R1 the interface is the sphere of radius
// (1 - t) R0 + t R1. At t = 0 and t = 1 the result is the first or the second field
// exactly.
#ifndef vtkdf_SegmentBlend_h
#define vtkdf_SegmentBlend_h

#include "Parallel.h"

#include <cstdint>

namespace vtkdf
{

struct SegmentedSamples
{
  const float* Distance = nullptr; // unsigned
  const int32_t* Region = nullptr;
};

/// Blends `count` samples of `first` and `second` at `t` (0 gives `first`, 1 `second`)
/// into `distance` and `region`.
void BlendSegmented(const SegmentedSamples& first,
  const SegmentedSamples& second,
  double t,
  int64_t count,
  float* distance,
  int32_t* region,
  const ParallelFor& parallelFor = ParallelFor());

} // namespace vtkdf

#endif
