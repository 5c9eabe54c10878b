// BrickWindingSigns: the winding number's sign (WindingSigns.h: inside where |w| > 1/2)
// at the samples of chosen bricks of a grid (BrickGrid.h), and one side for each brick
// that a single test proves the same throughout, without a pass over the whole grid: the
// sign of the sparse band (LinearFactor/SparseBand.h).
//
// The routes are WindingSigns': a closed chain's crossings along the x lines, an open
// mesh closed by cones (w = N - w_C), else the hierarchy's blocks; each sample gets the
// side that deciding it alone gives. The chain's triangles (the mesh's, and the cones')
// are binned by columns of bricks (the bricks that share a range of lines), so that a
// brick's crossings visit only the triangles whose footprint may reach its lines: a
// crossing left of the brick still counts for its samples, so the counts are the whole
// chain's.
//
// A brick whose box meets no triangle's box of the chain has the same N at all its
// samples (the count of a closed chain changes only across it), read once per column
// from the crossings of the column's first line. For a closed chain that decides the
// brick; for a chain closed by cones, a bound of w_C over the brick's ball must prove
// the side of N - w_C; for the blocks' route, a bound of w (WindingBoxSide). A brick the
// test cannot prove is decided sample by sample (Decide).
#ifndef vtkdf_BrickWindingSigns_h
#define vtkdf_BrickWindingSigns_h

#include "Common/BrickGrid.h"
#include "Common/LargeVector.h"
#include "Common/Parallel.h"
#include "Common/SampleGrid.h"
#include "Winding/WindingCrossings.h"
#include "Winding/WindingNumber.h"
#include "Winding/WindingSigns.h"

#include <array>
#include <cstdint>
#include <mutex>
#include <vector>

namespace vtkdf
{

class BrickWindingSigns
{
public:
  enum class Route
  {
    Crossings, // a closed chain
    Cones,     // an open mesh closed by cones
    Blocks     // neither: the hierarchy's blocks
  };

  /// The route and what it needs for the triangles (3 ids each into xyz `points`, which
  /// must outlive this object) on `grid`'s bricks. Each brick's test is made here.
  void Prepare(const LargeVector<double>& points,
    const LargeVector<int64_t>& triangles,
    const SampleGrid& grid,
    const BrickGrid& bricks,
    const ParallelFor& parallelFor);

  Route GetRoute() const { return this->Chosen; }

  /// The side of every sample of brick `id` when Prepare's test proved one: 1 inside, 0
  /// outside; -1 when it did not (then Decide).
  int ProvenSide(int64_t id) const { return this->Proven[static_cast<size_t>(id)]; }

  /// inside[v] (1 or 0) at every sample of `box` (x fastest), a box within one brick;
  /// `distance` (optional: the box's distances to the mesh, or lower bounds, times
  /// `distanceScale` in the grid's units) lets the blocks skip near the surface. Serial
  /// (the bricks run in parallel); the same sides as WindingSigns over any extent.
  WindingSignStatistics Decide(const IndexBox& box,
    uint8_t* inside,
    const float* distance = nullptr,
    double distanceScale = 1) const;

private:
  /// The chain's triangles whose footprint may reach some line of column (j, k), as 3
  /// point ids each: those with a corner at x <= `right`.
  LargeVector<int64_t> ColumnTriangles(int64_t column, double right) const;
  void BinColumns(const ParallelFor& parallelFor);
  void ProveBricks(const ParallelFor& parallelFor);
  const WindingNumber& MeshHierarchy() const;

  Route Chosen = Route::Blocks;
  SampleGrid Grid;
  BrickGrid Bricks;
  const LargeVector<double>* MeshPoints = nullptr;
  const LargeVector<int64_t>* MeshTriangles = nullptr;
  ConeClosure Closure; // Cones: the mesh's corners and the cones
  WindingNumber Cones; // Cones: w_C
  // The crossings' chain: the mesh's (Crossings) or the closure's (Cones).
  const LargeVector<double>* ChainPoints = nullptr;
  const LargeVector<int64_t>* ChainTriangles = nullptr;
  // Per column (j + Counts[1] * k) of bricks, the chain's triangles: ColumnStart[c] ..
  // ColumnStart[c + 1] in ColumnMembers.
  std::vector<int64_t> ColumnStart;
  std::vector<int64_t> ColumnMembers;
  std::vector<int8_t> Proven; // per brick
  // The mesh's hierarchy: built by Prepare except on the crossings' route, where only
  // samples on the surface need it (then built once, on the first).
  mutable WindingNumber Surface;
  mutable std::once_flag SurfaceBuilt;
};

} // namespace vtkdf

#endif
