// MedialAxis: the theta-simplified medial axis of a distance field (paper 000 §6.3, the
// separation-angle criterion of Foskey, Lin and Manocha's theta-SMA), without VTK types.
//
// For two 6-adjacent voxels x and y with closest boundary points c(x) and c(y), the
// angle between c(x) - m and c(y) - m (m the midpoint of x and y) estimates the
// separation angle of the medial surface crossing xy. When it reaches theta, the one of
// x and y with the larger |distance| (ties: the lower index) is medial, which keeps the
// axis one voxel thin. Pairs closer to the surface than one spacing are skipped: two
// voxels side by side at depth r over a flat surface see their closest points (one
// spacing h apart) at 2 atan(h / 2r), 53 degrees at r = h, so below that depth the
// angle says nothing. The depth does not depend on theta, so that a larger theta always
// keeps a subset. Each voxel decides only for itself, from its
// 6 pairs, so the pass is parallel and its result independent of the order.
#ifndef vtkdf_MedialAxis_h
#define vtkdf_MedialAxis_h

#include "Parallel.h"
#include "SampleGrid.h"

#include <cmath>
#include <cstdint>

namespace vtkdf
{

enum class MedialRegion
{
  Inside,  // only voxels with a negative distance
  Outside, // only voxels with a positive distance
  Both
};

struct MedialInput
{
  SampleGrid Grid;                     // Grid.Whole: the voxels (x fastest)
  const float* Distance = nullptr;     // one per voxel
  const float* ClosestPoint = nullptr; // three per voxel
  double SeparationAngle = 90;         // degrees, in (0, 180)
  MedialRegion Region = MedialRegion::Inside;
};

/// The depth, in spacings, a pair needs (see above).
constexpr double MedialMinimumDepth = 2.0;

/// The cosine of the pair (i, j)'s separation angle, or 2 when it has none (a closest
/// point at the midpoint, or not a number). Double precision; the GPU pass
/// (Shaders/MedialAxis.comp.glsl) computes it the same way.
inline double PairCosine(const double m[3], const float* ci, const float* cj)
{
  double u[3], v[3];
  for (int a = 0; a < 3; ++a)
  {
    u[a] = double(ci[a]) - m[a];
    v[a] = double(cj[a]) - m[a];
  }
  const double uu = u[0] * u[0] + u[1] * u[1] + u[2] * u[2];
  const double vv = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
  const double uv = u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
  const double norms = std::sqrt(uu * vv);
  if (!(norms > 0))
  {
    return 2;
  }
  return uv / norms;
}

/// Writes, per voxel, 1 or 0 in `medial`, and in `cosine` the smallest pair cosine that
/// made it medial (2 where it is not). Returns the number of medial voxels.
int64_t MedialAxisCPU(const MedialInput& input,
  uint8_t* medial,
  double* cosine,
  const ParallelFor& parallelFor);

} // namespace vtkdf

#endif
