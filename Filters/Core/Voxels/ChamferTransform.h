// ChamferTransform: the wavefront chamfer distance transform of Martinek et al. (VMV 2011) §5 on
// voxel lanes. Layer 0 is the zero set; layer n+1 holds the voxels that are not in any earlier
// layer (the accumulation grid A) and have a neighbour in layer n:
//   Manhattan:     n(w(x,y)) | w(x+-1,y) | w(x,y+-1)
//   Chessboard18:  n(w(x,y)) | n'(w(x+-1,y)) | n'(w(x,y+-1)) | w(x+-1,y+-1)
//   Chessboard26:  n(w(x,y)) | n'(w) of all 8 neighbouring lanes
// with n(w) = (w << 1) | (w >> 1) across words and n'(w) = n(w) | w. A whole lane is
// one word operation per 64 voxels. In each row (the lanes of one y), only the lanes
// within one lane of the last layer's lanes in rows y - 1, y, y + 1 are visited, in one
// flat loop over their words that the compiler vectorizes.
#ifndef vtkdf_ChamferTransform_h
#define vtkdf_ChamferTransform_h

#include "Common/Parallel.h"
#include "Voxels/BitVolume.h"

#include <cstdint>

namespace vtkdf
{

enum class ChamferMetric
{
  Manhattan,    // 6 face neighbours at distance 1
  Chessboard18, // the paper's "chessboard": face and edge neighbours at 1
  Chessboard26  // all 26 neighbours at 1 (L-infinity)
};

struct ChamferResult
{
  int Layers = 0;      // the largest layer index written
  int64_t Reached = 0; // voxels with a layer index (the zero set included)
  int64_t ZeroSet = 0; // voxels of layer 0
  bool Aborted = false;
};

/// Writes into `distance` (nx * ny * nz, x fastest) the layer index of every voxel
/// reached, and `unreached` elsewhere, negated at the voxels of `inside` (optional).
/// `maximumLayers` > 0 stops after that layer. `progress` (optional) is called with the
/// fraction done; when it aborts, `distance` is incomplete.
///
/// A chessboard field of at most 24 layers (or an empty zero set) is found a layer at a
/// time, the layers not written into `distance` as they are found: each new voxel's
/// layer index is OR-ed bit by bit into bit-plane lane grids (one word operation per 64
/// voxels and plane), and the planes are turned into the int32 array once at the end, in
/// 64 x 64 tiles, so that every output row is written once and in order. Otherwise the
/// layer indices come from sweeps over the array, the same bits (the layers beyond a
/// limit unreached): the separable L1 transform for Manhattan, three sweeps (z and x per
/// row of lanes, then y forward and back) for the chessboards.
ChamferResult ChamferPropagate(const BitVolume& zero,
  ChamferMetric metric,
  int maximumLayers,
  int32_t unreached,
  const BitVolume* inside,
  int32_t* distance,
  const ParallelFor& parallelFor,
  const ProgressCallback& progress);

} // namespace vtkdf

#endif
