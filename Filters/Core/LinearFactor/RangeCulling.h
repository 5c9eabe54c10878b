// RangeCulling: clips every site's domain to the region where the site can still be the
// closest one (the "range culling" of DiFi, made exact).
//
// The grid is cut into blocks of BlockSize^3 samples. For each block B, U(B) bounds the
// distance field from above over B (distance from its centre to the nearest mesh point,
// plus the block's half diagonal). A site s can be the closest one somewhere in B only
// if dist(B, s) <= U(B). Sites are grouped by the block that holds their anchor; the
// reach of a group is the bounding box of the blocks (or pairs of blocks, ReachLevel)
// that pass this test for its bounding box, found by descending a min/max pyramid of U.
// The CPU scan then tests single blocks with MayWin.
#ifndef vtkdf_RangeCulling_h
#define vtkdf_RangeCulling_h

#include "Common/MinMax.h"
#include "Common/Parallel.h"
#include "Common/SampleGrid.h"
#include "LinearFactor/MeshSites.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace vtkdf
{

class RangeCulling
{
public:
  static constexpr int BlockSize = 4;

  /// The pyramid level where the search for a group's reach stops: pairs of blocks (the
  /// scan tests single blocks anyway and gains more from a cheaper search than it loses
  /// to a block-wider reach).
  static constexpr int ReachLevel = 1;

  /// Computes Order (site indices grouped by the block of their anchor, for memory
  /// locality), GroupStart and every group's Reach (in sample indices, within `extent`).
  /// `subset` (optional, ascending): the only sites to consider, as for a piece of a
  /// narrow band, which holds every site within the band of its samples; the blocks'
  /// bounds then come from their anchors (any mesh point bounds the field from above).
  void Build(const MeshSites& sites,
    const SampleGrid& grid,
    const IndexBox& extent,
    double maximumDistance,
    const ParallelFor& parallelFor,
    const std::vector<uint32_t>* subset = nullptr);

  /// Sites grouped by block: group g holds Order[GroupStart[g] .. GroupStart[g + 1]).
  std::vector<uint32_t> Order;
  std::vector<int64_t> GroupStart;
  /// The samples where a group's sites may be the nearest (empty: nowhere).
  std::vector<IndexBox> Reach;

  /// Calls visit(site, reach of its group) for the sites at Order[begin .. end).
  template<typename Visit>
  void ForEachSite(int64_t begin, int64_t end, const Visit& visit) const
  {
    if (begin >= end)
    {
      return;
    }
    size_t group = static_cast<size_t>(
      std::upper_bound(this->GroupStart.begin(), this->GroupStart.end(), begin) -
      this->GroupStart.begin() - 1);
    for (int64_t o = begin; o < end; ++o)
    {
      while (o >= this->GroupStart[group + 1])
      {
        ++group;
      }
      visit(static_cast<int64_t>(this->Order[o]), this->Reach[group]);
    }
  }

  /// The samples of a site's region: its group's reach, within MaximumDistance of the
  /// site's box when the field has a cap.
  IndexBox Region(const IndexBox& reach, const Site& site) const
  {
    if (!std::isfinite(this->MaximumDistance) || reach.Empty())
    {
      return reach;
    }
    IndexBox band;
    for (int a = 0; a < 3; ++a)
    {
      const double lo =
        (site.BoundsMin[a] - this->MaximumDistance - this->Origin[a]) / this->Spacing[a];
      const double hi =
        (site.BoundsMax[a] + this->MaximumDistance - this->Origin[a]) / this->Spacing[a];
      // Clamped both ways: a site far off the grid puts either end past int.
      band.Lo[a] = static_cast<int>(std::min(std::max(std::ceil(lo), -2e9), 2e9));
      band.Hi[a] = static_cast<int>(std::min(std::max(std::floor(hi), -2e9), 2e9));
    }
    return reach.Intersect(band);
  }

  /// Whether a site within the world box [lo, hi] may be the nearest one somewhere in
  /// the cell of block `block` (block indices within the extent; the cell is the
  /// block's samples widened by half a spacing, so cells tile space).
  ///
  /// Two necessary conditions. The site is within the field's upper bound of the block:
  /// dist(cell, box) <= BlockBound. And, with p the block's mesh point, some x of the
  /// cell is at least as close to the box as to p (else p beats every point of the
  /// site there): min over x of dist(x, box)^2 - |x - p|^2 <= 0. For a fixed point of
  /// the box that difference is affine in x, so its minimum is at a corner of the cell,
  /// and the minimum over the corners splits into one choice per axis.
  bool MayWin(const int block[3], const float lo[3], const float hi[3]) const
  {
    const int64_t id = block[0] +
      int64_t(this->BlockCounts[0]) * (block[1] + int64_t(this->BlockCounts[1]) * block[2]);
    const double bound = this->BlockBound[id];
    // The distance condition first: about half the tests fail it (the dragon's and the
    // armadillo's sites at 128 samples), and then the bisector's terms are not needed.
    double cellLo[3], cellHi[3], d2 = 0;
    for (int a = 0; a < 3; ++a)
    {
      cellLo[a] = this->CellOrigin[a] + block[a] * this->CellSize[a];
      cellHi[a] = cellLo[a] + this->CellSize[a];
      const double gap = Max(Max(lo[a] - cellHi[a], cellLo[a] - hi[a]), 0.0);
      d2 += gap * gap;
    }
    if (!(d2 <= bound * bound))
    {
      return false;
    }
    const double* p = &this->BlockPoint[3 * id];
    double bisector = 0, scale = 0;
    for (int a = 0; a < 3; ++a)
    {
      // Distances along the axis from the box [lo, hi] to the cell's corner coordinates
      // cellLo and cellHi (lo <= hi, so at most one difference is positive).
      const double boxLo = lo[a], boxHi = hi[a];
      const double gLo = Max(Max(boxLo - cellLo[a], cellLo[a] - boxHi), 0.0);
      const double gHi = Max(Max(boxLo - cellHi[a], cellHi[a] - boxHi), 0.0);
      const double pLo = cellLo[a] - p[a], pHi = cellHi[a] - p[a];
      bisector += Min(gLo * gLo - pLo * pLo, gHi * gHi - pHi * pHi);
      scale += Max(pLo * pLo, pHi * pHi) + this->CellSize[a] * this->CellSize[a];
    }
    // The relative margin covers rounding (a site through p itself ties at 0).
    return !(bisector > 1e-9 * scale);
  }

  /// The block of the cell holding the continuous sample-index coordinate `index`
  /// along axis `a`.
  int BlockOf(int a, double index) const
  {
    // floor without a library call: the argument may be negative.
    // Clamped first, so that an index far outside the extent converts to int safely.
    const double x = Min(Max((index - this->BlockExtent.Lo[a] + 0.5) * (1.0 / BlockSize), -1.0),
      double(this->BlockCounts[a]));
    int blk = static_cast<int>(x);
    blk -= blk > x;
    return blk < 0 ? 0 : (blk >= this->BlockCounts[a] ? this->BlockCounts[a] - 1 : blk);
  }

  /// The block of sample `index` (within the extent) along axis `a`.
  int BlockOfSample(int a, int index) const
  {
    return std::min((index - this->BlockExtent.Lo[a]) / BlockSize, this->BlockCounts[a] - 1);
  }

  /// Upper bounds of the field per block (x fastest), BlockCounts blocks over BlockExtent.
  std::vector<float> BlockBound;
  /// The mesh point that gave each block its bound (xyz per block).
  std::vector<double> BlockPoint;
  std::array<int, 3> BlockCounts{ { 0, 0, 0 } };
  IndexBox BlockExtent;
  /// World coordinate where the cells of block 0 start, and a cell's width, per axis.
  double CellOrigin[3] = { 0, 0, 0 };
  double CellSize[3] = { 0, 0, 0 };
  /// The field's cap and the grid's origin and spacing, for Region.
  double MaximumDistance = HUGE_VAL;
  double Origin[3] = { 0, 0, 0 };
  double Spacing[3] = { 1, 1, 1 };
};

} // namespace vtkdf

#endif
