// SegmentBlend: the blend of two segmented distance fields whose regions mean the same
// (Yamazaki et al., SMI 2003, section 5.2: metamorphosis by interpolating the fields), without VTK
// types.
//
// At a sample where both fields give the same region, the distances are blended; where
// they give regions a (first) and b (second), the sample lies between the a|b interface's
// place in the first field and its place in the second, and is blended as a signed
// distance across that interface, negative on a's side: s = (1 - t)(-e_a) + t e_b, the
// sample going to a where s < 0, else to b. So every interface moves linearly from its
// position in the first field (t = 0) to its position in the second (t = 1): for
// concentric spheres of radii R0 and R1 the interface is the sphere of radius
// (1 - t) R0 + t R1. At t = 0 and t = 1 the result is the first or the second field
// exactly.
//
// e_a is the sample's distance to the a|b interface in the first field. Where that
// interface is the sample's nearest surface, it is the sample's distance d. Where
// another surface is nearer (inside a moving chamber, next to its walls), d would make s
// vanish all along those walls and put a spurious interface there; the distance to the
// interface is then taken from the nearest voxel of region b in the first field (an
// exact Euclidean distance transform of that region), less half a voxel diagonal:
//   e_a = max(d, g_b - (sqrt(3) / 2) h),
// which is d wherever region b lies just across the nearest surface (g_b <= d + that
// diagonal). Likewise e_b in the second field with region a. The blended distance is
// min(|s|, (1 - t) d_a + t d_b): the moving interface's distance, or the other surfaces'
// where they are nearer.
//
// Beyond an open surface's boundary its two regions meet without a sheet (a seam). Where
// a sample's two regions meet that way in either field (a voxel of the other region lies
// nearer than the nearest surface, g_b < d: inside the sample's empty ball), the region
// still follows the sign of s, so seams move too, but the distance is (1 - t) d_a + t d_b:
// with |s|, which vanishes between the two seams, the blend of a disk into a bowl of the
// same rim grew a sheet beyond the rim.
#ifndef vtkdf_SegmentBlend_h
#define vtkdf_SegmentBlend_h

#include "Common/Parallel.h"

#include <cstdint>

namespace vtkdf
{

struct SegmentedSamples
{
  const float* Distance = nullptr; // unsigned
  const int32_t* Region = nullptr;
};

/// The grid both fields share: samples per axis and spacing.
struct BlendGrid
{
  int Dims[3] = { 0, 0, 0 };
  double Spacing[3] = { 1, 1, 1 };
};

/// A box of the grid's samples (inclusive index ranges, from 0): a piece of the grid.
struct BlendBox
{
  int Lo[3] = { 0, 0, 0 };
  int Hi[3] = { -1, -1, -1 };

  int Size(int a) const { return Hi[a] - Lo[a] + 1; }
  int64_t Count() const { return int64_t(Size(0)) * Size(1) * Size(2); }
  static BlendBox Whole(const BlendGrid& grid)
  {
    BlendBox box;
    for (int a = 0; a < 3; ++a)
    {
      box.Hi[a] = grid.Dims[a] - 1;
    }
    return box;
  }
};

/// Blends the samples of `first` and `second` at `t` (0 gives `first`, 1 `second`) into
/// `distance` and `region`, and the blended field's SegmentedDistance, min(d, delta) +
/// offset r (the fields' shared delta and region offset), into `segmented`, over `box`
/// of `grid` (the whole grid, or a distributed run's piece): `first` and `second` hold
/// the samples of `box` (x fastest), `firstRegions` and `secondRegions` the whole grid's
/// regions of each field (a sample's distance to a region may be decided by any voxel).
/// A piece's values are the whole grid's there, bit for bit. Progress by the regions'
/// distance transforms; false when `execution` aborts (the arrays are then incomplete).
bool BlendSegmentedFields(const SegmentedSamples& first,
  const SegmentedSamples& second,
  const int32_t* firstRegions,
  const int32_t* secondRegions,
  const BlendBox& box,
  double t,
  const BlendGrid& grid,
  double delta,
  double offset,
  float* distance,
  int32_t* region,
  float* segmented,
  const Execution& execution);

/// The exact Euclidean distance from every sample of `box` to the nearest sample of the
/// grid whose region is `which` (infinity when there is none), into `out` (the box's
/// samples, x fastest), from the whole grid's `regions`: Felzenszwalb and Huttenlocher's
/// separable transform on squared distances. Its first pass runs over the whole grid,
/// the other two over the box's lines, each line whole: a box's values are the whole
/// grid's there, bit for bit.
void RegionDistance(const int32_t* regions,
  int32_t which,
  const BlendGrid& grid,
  const BlendBox& box,
  float* out,
  const ParallelFor& parallelFor = ParallelFor());

} // namespace vtkdf

#endif
