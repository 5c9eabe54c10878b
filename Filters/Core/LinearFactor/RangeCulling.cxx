#include "LinearFactor/RangeCulling.h"

#include "Common/FloatBounds.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace vtkdf
{
namespace
{

struct Box
{
  double Lo[3], Hi[3];
};

double BoxDistance(const Box& a, const Box& b)
{
  double d2 = 0;
  for (int k = 0; k < 3; ++k)
  {
    const double gap = std::max(0.0, std::max(a.Lo[k] - b.Hi[k], b.Lo[k] - a.Hi[k]));
    d2 += gap * gap;
  }
  return std::sqrt(d2);
}

/// Largest distance from a point of `a` to the box `b`.
double FarthestDistance(const Box& a, const Box& b)
{
  double d2 = 0;
  for (int k = 0; k < 3; ++k)
  {
    const double gap = std::max(0.0, std::max(b.Lo[k] - a.Lo[k], a.Hi[k] - b.Hi[k]));
    d2 += gap * gap;
  }
  return std::sqrt(d2);
}

/// Min/max pyramid of the block upper bounds, level 0 = blocks.
struct BoundPyramid
{
  std::vector<std::array<int, 3>> Dims;
  std::vector<std::vector<float>> Max, Min;
};

/// The blocks of an extent: their counts, their boxes and centres.
struct Blocks
{
  const SampleGrid& Grid;
  const IndexBox& Extent;
  std::array<int, 3> Counts;
  int64_t Total;

  Blocks(const SampleGrid& grid, const IndexBox& extent)
    : Grid(grid)
    , Extent(extent)
  {
    for (int a = 0; a < 3; ++a)
    {
      // No overflow for an extent of 2^31 - 1.
      this->Counts[a] = (extent.Size(a) - 1) / RangeCulling::BlockSize + 1;
    }
    this->Total = int64_t(this->Counts[0]) * this->Counts[1] * this->Counts[2];
  }

  std::array<int, 3> Indices(int64_t id) const
  {
    return { { static_cast<int>(id % this->Counts[0]),
      static_cast<int>((id / this->Counts[0]) % this->Counts[1]),
      static_cast<int>(id / (int64_t(this->Counts[0]) * this->Counts[1])) } };
  }

  /// The samples' box of `span` blocks along each axis from block (bi, bj, bk).
  Box BlockBox(int bi, int bj, int bk, int span) const
  {
    const int b = RangeCulling::BlockSize;
    const int ids[3] = { bi, bj, bk };
    Box box;
    for (int a = 0; a < 3; ++a)
    {
      // In 64 bits: the last block of a 2^31 - 1 extent ends past INT_MAX.
      const int64_t lo = this->Extent.Lo[a] + int64_t(ids[a]) * b;
      const int64_t hi =
        std::min<int64_t>(this->Extent.Lo[a] + int64_t(ids[a] + span) * b - 1, this->Extent.Hi[a]);
      box.Lo[a] = this->Grid.Coordinate(a, static_cast<int>(lo));
      box.Hi[a] = this->Grid.Coordinate(a, static_cast<int>(hi));
    }
    return box;
  }
};

/// A mesh point near every block: each block starts with the nearest of the points that
/// fall in it (points outside the extent count for the nearest block), then two sweeps
/// pass every block's point on to its 26 neighbours when it is nearer to their centres (a
/// vector distance transform). The point found is not always the nearest one, but the
/// bound only has to hold, and it does for any mesh point. -1: none.
std::vector<int64_t> NearBlockPoints(const Blocks& blocks, const std::vector<double>& points)
{
  const int64_t numBlocks = blocks.Total;
  const std::array<int, 3>& nb = blocks.Counts;
  std::vector<std::array<double, 3>> centres(numBlocks);
  for (int64_t id = 0; id < numBlocks; ++id)
  {
    const std::array<int, 3> ids = blocks.Indices(id);
    const Box box = blocks.BlockBox(ids[0], ids[1], ids[2], 1);
    for (int a = 0; a < 3; ++a)
    {
      centres[id][a] = 0.5 * (box.Lo[a] + box.Hi[a]);
    }
  }
  auto distance2 = [&](int64_t point, int64_t block)
  {
    double d2 = 0;
    for (int a = 0; a < 3; ++a)
    {
      const double e = points[3 * point + a] - centres[block][a];
      d2 += e * e;
    }
    return d2;
  };
  std::vector<int64_t> nearestPoint(numBlocks, -1);
  std::vector<double> nearest2(numBlocks, HUGE_VAL);
  const int64_t numPoints = static_cast<int64_t>(points.size() / 3);
  const SampleGrid& grid = blocks.Grid;
  for (int64_t p = 0; p < numPoints; ++p)
  {
    int64_t id = 0, stride = 1;
    for (int a = 0; a < 3; ++a)
    {
      const double x = (points[3 * p + a] - grid.Origin[a]) / grid.Spacing[a] - blocks.Extent.Lo[a];
      const int blk = static_cast<int>(
        std::min<double>(std::max<double>(x / RangeCulling::BlockSize, 0.0), nb[a] - 1));
      id += blk * stride;
      stride *= nb[a];
    }
    const double d2 = distance2(p, id);
    if (d2 < nearest2[id])
    {
      nearest2[id] = d2;
      nearestPoint[id] = p;
    }
  }
  // The neighbours' id offsets, in the order the sweeps visit them.
  int64_t offsets[27];
  for (int dk = -1, n = 0; dk <= 1; ++dk)
  {
    for (int dj = -1; dj <= 1; ++dj)
    {
      for (int di = -1; di <= 1; ++di, ++n)
      {
        offsets[n] = di + int64_t(nb[0]) * (dj + int64_t(nb[1]) * dk);
      }
    }
  }
  auto pass = [&](int64_t id, int64_t other)
  {
    const int64_t p = nearestPoint[other];
    if (p >= 0 && p != nearestPoint[id])
    {
      const double d2 = distance2(p, id);
      if (d2 < nearest2[id])
      {
        nearest2[id] = d2;
        nearestPoint[id] = p;
      }
    }
  };
  // Blocks in id order (x fastest), forwards or backwards; an interior block's
  // neighbours need no bounds test.
  auto sweep = [&](int direction)
  {
    for (int n2 = 0; n2 < nb[2]; ++n2)
    {
      const int k = direction > 0 ? n2 : nb[2] - 1 - n2;
      for (int n1 = 0; n1 < nb[1]; ++n1)
      {
        const int j = direction > 0 ? n1 : nb[1] - 1 - n1;
        for (int n0 = 0; n0 < nb[0]; ++n0)
        {
          const int i = direction > 0 ? n0 : nb[0] - 1 - n0;
          const int64_t id = i + int64_t(nb[0]) * (j + int64_t(nb[1]) * k);
          const bool interior =
            i > 0 && j > 0 && k > 0 && i < nb[0] - 1 && j < nb[1] - 1 && k < nb[2] - 1;
          for (int dk = -1, n = 0; dk <= 1; ++dk)
          {
            for (int dj = -1; dj <= 1; ++dj)
            {
              for (int di = -1; di <= 1; ++di, ++n)
              {
                if (interior ||
                  (i + di >= 0 && j + dj >= 0 && k + dk >= 0 && i + di < nb[0] && j + dj < nb[1] &&
                    k + dk < nb[2]))
                {
                  pass(id, id + offsets[n]);
                }
              }
            }
          }
        }
      }
    }
  };
  sweep(+1);
  sweep(-1);
  return nearestPoint;
}

/// Coarser levels until one block holds all: each node the max and min of its children.
void BuildPyramid(BoundPyramid& pyramid)
{
  while (pyramid.Dims.back()[0] > 1 || pyramid.Dims.back()[1] > 1 || pyramid.Dims.back()[2] > 1)
  {
    const auto d = pyramid.Dims.back();
    const std::array<int, 3> up = { (d[0] + 1) / 2, (d[1] + 1) / 2, (d[2] + 1) / 2 };
    std::vector<float> mx(int64_t(up[0]) * up[1] * up[2], -HUGE_VALF);
    std::vector<float> mn(mx.size(), HUGE_VALF);
    const auto& cmx = pyramid.Max.back();
    const auto& cmn = pyramid.Min.back();
    for (int k = 0; k < d[2]; ++k)
    {
      for (int j = 0; j < d[1]; ++j)
      {
        for (int i = 0; i < d[0]; ++i)
        {
          const int64_t c = i + int64_t(d[0]) * (j + int64_t(d[1]) * k);
          const int64_t p = i / 2 + int64_t(up[0]) * (j / 2 + int64_t(up[1]) * (k / 2));
          mx[p] = std::max(mx[p], cmx[c]);
          mn[p] = std::min(mn[p], cmn[c]);
        }
      }
    }
    pyramid.Dims.push_back(up);
    pyramid.Max.push_back(std::move(mx));
    pyramid.Min.push_back(std::move(mn));
  }
}

/// The blocks (inclusive ranges per axis) that sites within `group` may win in: the
/// depth-first descent of the pyramid, stopping at `reachLevel`; a node already inside
/// the reach adds nothing. False when no block can have them as closest.
bool GroupReach(const Blocks& blocks,
  const BoundPyramid& pyramid,
  const Box& group,
  int reachLevel,
  int reachLo[3],
  int reachHi[3])
{
  struct Node
  {
    int Level, I, J, K;
  };
  for (int a = 0; a < 3; ++a)
  {
    reachLo[a] = INT32_MAX;
    reachHi[a] = -1;
  }
  // Depth first: each step pops a node and pushes at most its 8 children, one level
  // down, so the stack holds at most 7 a level (the pyramid has at most 32) and the root.
  Node stack[7 * 32 + 1];
  int depth = 0;
  stack[depth++] = { static_cast<int>(pyramid.Dims.size()) - 1, 0, 0, 0 };
  while (depth > 0)
  {
    const Node node = stack[--depth];
    const int span = 1 << node.Level;
    const int lo[3] = { node.I * span, node.J * span, node.K * span };
    int hi[3];
    bool inside = true;
    for (int a = 0; a < 3; ++a)
    {
      hi[a] = std::min(lo[a] + span, blocks.Counts[a]) - 1;
      inside = inside && lo[a] >= reachLo[a] && hi[a] <= reachHi[a];
    }
    if (inside)
    {
      continue;
    }
    const auto& d = pyramid.Dims[node.Level];
    const int64_t at = node.I + int64_t(d[0]) * (node.J + int64_t(d[1]) * node.K);
    const Box box = blocks.BlockBox(lo[0], lo[1], lo[2], span);
    if (BoxDistance(box, group) > pyramid.Max[node.Level][at])
    {
      continue;
    }
    if (node.Level <= reachLevel || FarthestDistance(box, group) <= pyramid.Min[node.Level][at])
    {
      for (int a = 0; a < 3; ++a)
      {
        reachLo[a] = std::min(reachLo[a], lo[a]);
        reachHi[a] = std::max(reachHi[a], hi[a]);
      }
      continue;
    }
    const auto& cd = pyramid.Dims[node.Level - 1];
    for (int dk = 0; dk < 2; ++dk)
    {
      for (int dj = 0; dj < 2; ++dj)
      {
        for (int di = 0; di < 2; ++di)
        {
          const Node child{ node.Level - 1, 2 * node.I + di, 2 * node.J + dj, 2 * node.K + dk };
          if (child.I < cd[0] && child.J < cd[1] && child.K < cd[2])
          {
            stack[depth++] = child;
          }
        }
      }
    }
  }
  return reachHi[0] >= 0;
}

/// The upper bound of the field over every block (BlockBound, level 0 of the pyramid)
/// and the mesh point that gave it (BlockPoint).
void BoundBlocks(RangeCulling& culling,
  const Blocks& blocks,
  const std::vector<double>& points,
  double maximumDistance,
  BoundPyramid& pyramid)
{
  // Upper bound of the field over each block: the distance from the farthest point of
  // its cell to a mesh point p.
  const std::vector<int64_t> nearestPoint = NearBlockPoints(blocks, points);
  const int64_t numBlocks = blocks.Total;
  pyramid.Dims.push_back(blocks.Counts);
  pyramid.Max.emplace_back(numBlocks);
  std::vector<float>& level0 = pyramid.Max.back();
  for (int64_t id = 0; id < numBlocks; ++id)
  {
    // The farthest point of the block's cell from its mesh point p (never above
    // |centre - p| + the half diagonal, and often well below).
    double bound = HUGE_VAL;
    if (nearestPoint[id] >= 0)
    {
      const std::array<int, 3> ids = blocks.Indices(id);
      const double* p = &points[3 * nearestPoint[id]];
      double far2 = 0;
      for (int a = 0; a < 3; ++a)
      {
        const double cellLo = culling.CellOrigin[a] + ids[a] * culling.CellSize[a];
        const double cellHi = cellLo + culling.CellSize[a];
        const double reach = std::max(std::fabs(p[a] - cellLo), std::fabs(cellHi - p[a]));
        far2 += reach * reach;
      }
      bound = std::sqrt(far2);
    }
    bound = std::min(bound, maximumDistance);
    // Round up so that float storage never makes the bound smaller.
    level0[id] = std::nextafter(static_cast<float>(bound), HUGE_VALF);
  }
  pyramid.Min.push_back(level0);
  culling.BlockBound = level0;
  // Each block's mesh point, for MayWin's bisector test (NaN: none, the bound alone).
  culling.BlockPoint.assign(3 * numBlocks, std::numeric_limits<double>::quiet_NaN());
  for (int64_t id = 0; id < numBlocks; ++id)
  {
    if (nearestPoint[id] >= 0)
    {
      std::copy(&points[3 * nearestPoint[id]],
        &points[3 * nearestPoint[id]] + 3,
        &culling.BlockPoint[3 * id]);
    }
  }
  culling.BlockCounts = blocks.Counts;
  culling.BlockExtent = blocks.Extent;
}

/// Order: the sites grouped by the block of their anchor (GroupStart: where each block's
/// group starts, one more than the blocks). Counted, then placed: the blocks are found
/// twice rather than stored. Chunks of consecutive sites are counted and placed in
/// parallel, a block's sites chunk after chunk, so each group lists its sites in
/// ascending order, as one pass would. A chunk counts every block: chunks are at most
/// sites / blocks (the counts take at most 4 bytes a site), and one when blocks
/// outnumber sites.
void GroupSites(RangeCulling& culling,
  const MeshSites& sites,
  const Blocks& blocks,
  const std::vector<uint32_t>& subset,
  const ParallelFor& parallelFor)
{
  const bool all = subset.empty();
  const int64_t numSites = all ? sites.Count() : static_cast<int64_t>(subset.size());
  const SampleGrid& grid = blocks.Grid;
  auto blockOfPoint = [&](const double* anchor)
  {
    int64_t id = 0, stride = 1;
    for (int a = 0; a < 3; ++a)
    {
      // Clamped before the conversion: an anchor far outside an explicit grid is
      // beyond int's range in blocks.
      const double x = (anchor[a] - grid.Origin[a]) / grid.Spacing[a];
      const double at = std::floor((x - blocks.Extent.Lo[a]) / RangeCulling::BlockSize);
      const int blk = static_cast<int>(std::min(std::max(at, 0.0), double(blocks.Counts[a] - 1)));
      id += blk * stride;
      stride *= blocks.Counts[a];
    }
    return id;
  };
  const int64_t total = blocks.Total;
  // A site's block is its anchor's: with every site, each point's block is found once
  // (a point anchors about six sites, and each site is placed twice).
  std::vector<uint32_t> pointBlocks;
  const bool byPoint = all && total <= int64_t(UINT32_MAX);
  if (byPoint)
  {
    pointBlocks.resize(sites.SitePoints.size() / 3);
    parallelFor(static_cast<int64_t>(pointBlocks.size()),
      4096,
      [&](int64_t begin, int64_t end)
      {
        for (int64_t p = begin; p < end; ++p)
        {
          pointBlocks[p] = static_cast<uint32_t>(blockOfPoint(&sites.SitePoints[3 * p]));
        }
      });
  }
  auto blockOf = [&](int64_t s)
  {
    return byPoint ? int64_t(pointBlocks[sites.AnchorPointOf(s)]) : blockOfPoint(sites.AnchorOf(s));
  };
  const int64_t numChunks = std::max<int64_t>(1, std::min<int64_t>(8, numSites / total));
  // counts[c * total + b]: the sites of chunk c in block b, then where they go.
  std::vector<uint32_t> counts(static_cast<size_t>(numChunks * total), 0);
  auto forChunks = [&](const auto& visit)
  {
    parallelFor(numChunks,
      1,
      [&](int64_t begin, int64_t end)
      {
        for (int64_t c = begin; c < end; ++c)
        {
          uint32_t* chunkCounts = &counts[c * total];
          for (int64_t s = numSites * c / numChunks; s < numSites * (c + 1) / numChunks; ++s)
          {
            const int64_t site = all ? s : subset[s];
            visit(chunkCounts, site, blockOf(site));
          }
        }
      });
  };
  forChunks([](uint32_t* chunkCounts, int64_t, int64_t block) { ++chunkCounts[block]; });
  std::vector<int64_t>& offsets = culling.GroupStart;
  offsets.assign(total + 1, 0);
  uint32_t next = 0; // fewer than 2^32 - 1 sites (MeshSites checks): positions fit
  for (int64_t b = 0; b < total; ++b)
  {
    offsets[b] = next;
    for (int64_t c = 0; c < numChunks; ++c)
    {
      const uint32_t n = counts[c * total + b];
      counts[c * total + b] = next;
      next += n;
    }
  }
  offsets[total] = next;
  forChunks([&culling](uint32_t* chunkCounts, int64_t site, int64_t block)
    { culling.Order[chunkCounts[block]++] = static_cast<uint32_t>(site); });
}

} // namespace

void RangeCulling::Build(const MeshSites& sites,
  const SampleGrid& grid,
  const IndexBox& extent,
  double maximumDistance,
  const ParallelFor& parallelFor,
  const std::vector<uint32_t>* subset)
{
  static const std::vector<uint32_t> everySite;
  const std::vector<uint32_t>& only = subset ? *subset : everySite;
  const int64_t numSites = subset ? static_cast<int64_t>(subset->size()) : sites.Count();
  this->MaximumDistance = maximumDistance;
  for (int a = 0; a < 3; ++a)
  {
    this->Origin[a] = grid.Origin[a];
    this->Spacing[a] = grid.Spacing[a];
  }
  this->Order.resize(numSites);
  if (numSites == 0 || extent.Empty())
  {
    // One group that reaches nowhere.
    for (int64_t s = 0; s < numSites; ++s)
    {
      this->Order[s] = subset ? only[s] : static_cast<uint32_t>(s);
    }
    this->GroupStart = { 0, numSites };
    this->Reach.assign(1, IndexBox());
    return;
  }
  const Blocks blocks(grid, extent);
  // The bound holds over the block's cell: its samples' box widened by half a spacing,
  // so that cells tile space (the CPU scan tests continuous slices against them).
  for (int a = 0; a < 3; ++a)
  {
    this->CellOrigin[a] = grid.Coordinate(a, extent.Lo[a]) - 0.5 * grid.Spacing[a];
    this->CellSize[a] = BlockSize * grid.Spacing[a];
  }
  BoundPyramid pyramid;
  if (subset)
  {
    std::vector<double> anchors(3 * only.size());
    for (size_t s = 0; s < only.size(); ++s)
    {
      std::copy(sites.AnchorOf(only[s]), sites.AnchorOf(only[s]) + 3, &anchors[3 * s]);
    }
    BoundBlocks(*this, blocks, anchors, maximumDistance, pyramid);
  }
  else
  {
    BoundBlocks(*this, blocks, sites.SitePoints, maximumDistance, pyramid);
  }
  BuildPyramid(pyramid);
  GroupSites(*this, sites, blocks, only, parallelFor);

  // The reach of each group.
  this->Reach.assign(blocks.Total, IndexBox());
  parallelFor(blocks.Total,
    16,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t cluster = begin; cluster < end; ++cluster)
      {
        if (this->GroupStart[cluster] == this->GroupStart[cluster + 1])
        {
          continue;
        }
        // The union of the sites' boxes (BoxOf): their corners' bounds, rounded outward
        // to float once (the rounding is monotonic, so it commutes with min and max).
        Box group{ { HUGE_VAL, HUGE_VAL, HUGE_VAL }, { -HUGE_VAL, -HUGE_VAL, -HUGE_VAL } };
        for (int64_t o = this->GroupStart[cluster]; o < this->GroupStart[cluster + 1]; ++o)
        {
          double lo[3], hi[3];
          sites.CornerBounds(this->Order[o], lo, hi);
          for (int a = 0; a < 3; ++a)
          {
            group.Lo[a] = std::min(group.Lo[a], lo[a]);
            group.Hi[a] = std::max(group.Hi[a], hi[a]);
          }
        }
        for (int a = 0; a < 3; ++a)
        {
          group.Lo[a] = FloatBelow(group.Lo[a]);
          group.Hi[a] = FloatAbove(group.Hi[a]);
        }
        int reachLo[3], reachHi[3];
        if (!GroupReach(blocks, pyramid, group, this->ReachLevel, reachLo, reachHi))
        {
          continue; // no block can have these sites as closest (MaximumDistance band)
        }
        IndexBox& reach = this->Reach[cluster];
        for (int a = 0; a < 3; ++a)
        {
          reach.Lo[a] = extent.Lo[a] + reachLo[a] * BlockSize;
          reach.Hi[a] = static_cast<int>(std::min<int64_t>(
            extent.Lo[a] + int64_t(reachHi[a] + 1) * BlockSize - 1, extent.Hi[a]));
        }
      }
    });
}

} // namespace vtkdf
