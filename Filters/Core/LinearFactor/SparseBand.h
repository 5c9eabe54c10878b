// SparseBand: the exact field of the linear factorization in a narrow band around the
// mesh, stored only in the bricks of the grid that the band touches.
//
// The grid is cut into bricks of BrickSize samples along each axis; neighbouring bricks
// share their boundary samples (a brick's samples run from b * BrickSize to (b + 1) *
// BrickSize), so that a contour of the pieces has no cracks. The sites are built once
// for the whole grid, as for the dense field (LocalSites.h); every site is binned into
// the bricks where its band region (its box widened by the band's half-width, in whole
// samples: RangeCulling::Region) lies, and each brick then runs the dense field's own
// culling, scan and Finalize over its samples with those sites alone. A sample's nearest
// site depends neither on the extent that holds it nor on sites that cannot win there,
// so every brick holds the dense field's bits (the dense field with MaximumDistance the
// band's half-width, on the site scan). A brick whose samples are all beyond the band
// is dropped.
//
// Sides beyond the band, pseudonormal sign: within a brick they are flooded from its band
// samples as the dense field floods them over the whole grid; the bricks without band
// samples get one side each, flooded over the grid of bricks from the faces they share
// with their neighbours. Where the band's sides agree (a closed mesh), that is the dense
// field's side at every sample; where they do not (an open mesh under the pseudonormal
// sign), a far sample takes the side of a band sample of its own brick, the dense field
// that of the first band sample its breadth-first flood reaches. Winding-number sign:
// every sample's side is the dense field's (Winding/BrickWindingSigns.h); a brick beyond
// the band whose samples differ is kept, its samples all beyond the band.
//
// A distributed run splits the bricks among the processes (SparseBandRequest::Pieces);
// the sides and the pieces' numbers are then summed over them, so that every process
// holds the whole grid of sides.
#ifndef vtkdf_SparseBand_h
#define vtkdf_SparseBand_h

#include "Common/BlockArena.h"
#include "Common/BrickGrid.h"
#include "Common/MeshInput.h"
#include "Common/Parallel.h"
#include "Common/SampleGrid.h"
#include "LinearFactor/LinearFactorField.h"

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace vtkdf
{

/// An array of a brick: a block of BlockArena.h, which ReleaseBlock releases (a VTK array
/// can adopt it with ReleaseBlock as its free function).
template<typename T>
using BrickArray = BlockArray<T>;

struct SparseBandRequest
{
  SampleGrid Grid; // world coordinates; the whole grid
  /// The band's half-width in world units (> 0): samples farther from the mesh hold
  /// +-BandWidth, as the dense field's MaximumDistance.
  double BandWidth = 0;
  int BrickSize = 32; // samples per brick along each axis (the pieces have one more)
  DomainShape Domains = DomainShape::Auto;
  SignMode Sign = SignMode::Unsigned;
  bool ClosestCellId = false;
  bool ClosestPoint = false;
  /// Refuses a run whose bricks (the arrays asked for, on every brick the band may
  /// touch) would need more bytes than this; 0: no limit.
  double MemoryLimit = 0;
  /// A distributed run: this process computes its share of the bricks (Piece of Pieces:
  /// every Pieces-th brick the band may touch, and of those beyond it), and
  /// SumOverPieces, which every process calls alike, adds an array over all of them
  /// (unused with one piece). The sides and the pieces' numbers are the whole grid's on
  /// every process.
  int Piece = 0;
  int Pieces = 1;
  std::function<void(std::vector<int8_t>&)> SumOverPieces;
};

/// A brick that holds band samples: its samples (global indices, x fastest) and arrays.
struct SparseBrick
{
  std::array<int, 3> Index{ { 0, 0, 0 } }; // in the grid of bricks
  IndexBox Extent;
  int64_t BandSamples = 0;
  BrickArray<float> Distance;
  /// Always there: 0 vertex, 1 edge, 2 face, 255 beyond the band.
  BrickArray<uint8_t> ClosestFeature;
  BrickArray<int64_t> ClosestCellId; // when asked for; -1 beyond the band
  BrickArray<float> ClosestPoint;    // when asked for (3 per sample); NaN beyond the band
};

struct SparseBandField
{
  int BrickSize = 0;
  std::array<int, 3> BrickCounts{ { 0, 0, 0 } }; // the grid of bricks, x fastest
  /// The bricks that hold band samples (or, with the winding sign, samples of both
  /// sides), in the order of their index (x fastest): this process's share of them.
  std::vector<SparseBrick> Bricks;
  /// Per brick of the grid: the side of its samples beyond the band (-1 inside, 1
  /// outside, 0 unknown: an unsigned field, or no band anywhere, or a piece), and the
  /// number of its piece among all processes' pieces in the order of their index (-1:
  /// none; one process: its entry of Bricks).
  std::vector<int8_t> Sides;
  std::vector<int32_t> BrickOf;
  int64_t BandSamples = 0;     // counted once per brick that holds them (this process's)
  int64_t CandidateBricks = 0; // bricks that some site's band region reached
  /// The winding sign: bricks beyond the band whose sides no single test proved, decided
  /// sample by sample (BrickWindingSigns.h).
  int64_t WindingBricksDecided = 0;
  int64_t Evaluations = 0;
  bool Aborted = false;
  bool NoUsableCell = false;
  /// The bytes the bricks' arrays hold.
  int64_t Bytes() const;
};

/// The sparse band of `mesh` (world coordinates, Bounds filled; taken by value: moved into
/// the grid's local frame in place). Stages: sites, bricks (the binning), scan (the
/// bricks' culling, scan and Finalize), sides. Progress from 0 to 1. False and `error`
/// on invalid input or when the bricks would exceed MemoryLimit.
bool ComputeSparseBand(MeshInput mesh,
  const SparseBandRequest& request,
  const Execution& execution,
  SparseBandField& field,
  std::string& error);

} // namespace vtkdf

#endif
