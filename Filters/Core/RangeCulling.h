// RangeCulling: clips every site's domain to the region where the site can still be the
// closest one (the "range culling" of DiFi, made exact).
//
// The grid is cut into blocks of BlockSize^3 samples. For each block B, U(B) bounds the
// distance field from above over B (distance from its centre to the nearest mesh point,
// plus the block's half diagonal). A site s can be the closest one somewhere in B only
// if dist(B, s) <= U(B). Sites are grouped by the block that holds their anchor; the
// reach of a group is the bounding box of the blocks that pass this test for its
// bounding box, found by descending a min/max pyramid of U.
#ifndef vtkdf_RangeCulling_h
#define vtkdf_RangeCulling_h

#include "MeshSites.h"
#include "Parallel.h"
#include "SampleGrid.h"

#include <vector>

namespace vtkdf
{

class RangeCulling
{
public:
  static constexpr int BlockSize = 4;

  /// Computes Regions (one per site, in sample indices, within `extent`) and Order
  /// (site indices grouped by anchor block, for memory locality).
  void Build(const MeshSites& sites,
    const SampleGrid& grid,
    const IndexBox& extent,
    double maximumDistance,
    const ParallelFor& parallelFor);

  std::vector<IndexBox> Regions;
  std::vector<int64_t> Order;
};

} // namespace vtkdf

#endif
