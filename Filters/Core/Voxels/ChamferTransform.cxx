#include "Voxels/ChamferTransform.h"

#include "Voxels/ChamferPasses.h"

#include <algorithm>
#include <cstdlib>

namespace vtkdf
{
namespace chamfer
{
#ifdef VTKDF_HAVE_AVX2_CLONES
bool HaveAVX2()
{
  static const bool has =
    __builtin_cpu_supports("avx2") && std::getenv("VTKDF_DISABLE_AVX2") == nullptr;
  return has;
}
#endif
} // namespace chamfer

ChamferResult ChamferPropagate(const BitVolume& zero,
  ChamferMetric metric,
  int maximumLayers,
  int32_t unreached,
  const BitVolume* inside,
  int32_t* distance,
  const ParallelFor& parallelFor,
  const ProgressCallback& progress)
{
  // The sweeps pass over the whole array a fixed number of times, the wavefront over the
  // lanes it reaches once a layer: the separable Manhattan transform is the faster from
  // the first layer on, the chessboard sweeps beyond about WavefrontLayers layers
  // (measured on the bunny's boundary: the wavefront as fast at 16 layers at 512^3, at 24
  // at 256^3). Same bits either way, the layers beyond a limit unreached.
  constexpr int WavefrontLayers = 24;
  if (metric == ChamferMetric::Manhattan || maximumLayers <= 0 || maximumLayers > WavefrontLayers)
  {
    const int64_t zeroSet = zero.Count();
    // No path is as long as Far: the limit stops below it.
    const int32_t limit =
      maximumLayers > 0 ? std::min(maximumLayers, chamfer::Far - 1) : chamfer::Far - 1;
    if (zeroSet > 0)
    {
      return chamfer::SweepOutput(
        zero, metric, inside, limit, unreached, distance, parallelFor, progress, zeroSet);
    }
  }
  // An empty zero set, or a few chessboard layers: the wavefront.
  return chamfer::PropagateWavefront(
    zero, metric, maximumLayers, unreached, inside, distance, parallelFor, progress);
}

} // namespace vtkdf
