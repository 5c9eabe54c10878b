// ChamferPasses: the passes of ChamferPropagate, each in its own source: the wavefront
// (one pass per layer on bit lanes, ChamferWavefront.cxx) and the sweeps over the output
// (the separable Manhattan transform and the chessboard sweeps, ChamferSweeps.cxx). The
// driver (ChamferTransform.cxx) chooses between them. Private to the voxels family.
#ifndef vtkdf_ChamferPasses_h
#define vtkdf_ChamferPasses_h

#include "Voxels/ChamferTransform.h"

#include <cstdint>

namespace vtkdf
{
namespace chamfer
{
// The row loops are compiled twice on x86-64: for the generic target (SSE2, two
// words per operation) and for AVX2 (four), chosen once at run time (the environment
// variable VTKDF_DISABLE_AVX2 forces the generic one, which is how its test runs on a
// machine with AVX2). Each loop body is an always-inlined function, so both versions
// come from the same source.
#if defined(__GNUC__) && defined(__x86_64__)
#define VTKDF_HAVE_AVX2_CLONES 1
#define VTKDF_INLINE inline __attribute__((always_inline))
bool HaveAVX2();
#else
#define VTKDF_INLINE inline
#endif

constexpr int32_t Far = int32_t(1) << 29; // beyond any distance on a grid of int extents

/// The wavefront: one pass over the lanes each layer reaches, up to `maximumLayers`
/// (every layer when <= 0).
ChamferResult PropagateWavefront(const BitVolume& zero,
  ChamferMetric metric,
  int maximumLayers,
  int32_t unreached,
  const BitVolume* inside,
  int32_t* distance,
  const ParallelFor& parallelFor,
  const ProgressCallback& progress);

/// The sweeps: a fixed number of passes over the output for a non-empty zero set of
/// `zeroSet` voxels, the layers beyond `limit` (< Far) unreached.
ChamferResult SweepOutput(const BitVolume& zero,
  ChamferMetric metric,
  const BitVolume* inside,
  int32_t limit,
  int32_t unreached,
  int32_t* distance,
  const ParallelFor& parallelFor,
  const ProgressCallback& progress,
  int64_t zeroSet);
} // namespace chamfer
} // namespace vtkdf

#endif
