#include "LinearFactor/RangeCulling.h"

#include <algorithm>
#include <cmath>
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

} // namespace

void RangeCulling::Build(const MeshSites& sites,
  const SampleGrid& grid,
  const IndexBox& extent,
  double maximumDistance,
  const ParallelFor& parallelFor)
{
  const int64_t numSites = static_cast<int64_t>(sites.Sites.size());
  this->Regions.assign(numSites, IndexBox());
  this->Order.resize(numSites);
  if (numSites == 0 || extent.Empty())
  {
    for (int64_t s = 0; s < numSites; ++s)
    {
      this->Order[s] = s;
    }
    return;
  }
  const int b = BlockSize;
  std::array<int, 3> nb;
  for (int a = 0; a < 3; ++a)
  {
    nb[a] = (extent.Size(a) - 1) / b + 1; // no overflow for an extent of 2^31 - 1
  }
  const int64_t numBlocks = int64_t(nb[0]) * nb[1] * nb[2];
  auto blockBox = [&](int bi, int bj, int bk, int span)
  {
    const int ids[3] = { bi, bj, bk };
    Box box;
    for (int a = 0; a < 3; ++a)
    {
      // In 64 bits: the last block of a 2^31 - 1 extent ends past INT_MAX.
      const int64_t lo = extent.Lo[a] + int64_t(ids[a]) * b;
      const int64_t hi =
        std::min<int64_t>(extent.Lo[a] + int64_t(ids[a] + span) * b - 1, extent.Hi[a]);
      box.Lo[a] = grid.Coordinate(a, static_cast<int>(lo));
      box.Hi[a] = grid.Coordinate(a, static_cast<int>(hi));
    }
    return box;
  };

  // Upper bound of the field over each block: the distance from the farthest point of
  // its cell to a mesh point p. Each block starts with the nearest of the points
  // that fall in it (points outside the extent count for the nearest block), then two
  // sweeps pass every block's point on to its 26 neighbours when it is nearer to their
  // centres (a vector distance transform). The point found is not always the nearest
  // one, but the bound only has to hold, and it does for any mesh point.
  // The bound holds over the block's cell: its samples' box widened by half a spacing,
  // so that cells tile space (the CPU scan tests continuous slices against them).
  for (int a = 0; a < 3; ++a)
  {
    this->CellOrigin[a] = grid.Coordinate(a, extent.Lo[a]) - 0.5 * grid.Spacing[a];
    this->CellSize[a] = b * grid.Spacing[a];
  }
  std::vector<std::array<double, 3>> centres(numBlocks);
  for (int64_t id = 0; id < numBlocks; ++id)
  {
    const int ids[3] = { static_cast<int>(id % nb[0]),
      static_cast<int>((id / nb[0]) % nb[1]),
      static_cast<int>(id / (int64_t(nb[0]) * nb[1])) };
    const Box box = blockBox(ids[0], ids[1], ids[2], 1);
    for (int a = 0; a < 3; ++a)
    {
      centres[id][a] = 0.5 * (box.Lo[a] + box.Hi[a]);
    }
  }
  const std::vector<double>& points = sites.SitePoints;
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
  for (int64_t p = 0; p < numPoints; ++p)
  {
    int64_t id = 0, stride = 1;
    for (int a = 0; a < 3; ++a)
    {
      const double x = (points[3 * p + a] - grid.Origin[a]) / grid.Spacing[a] - extent.Lo[a];
      const int blk = static_cast<int>(std::min<double>(std::max<double>(x / b, 0.0), nb[a] - 1));
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
  auto sweep = [&](int direction)
  {
    const int64_t first = direction > 0 ? 0 : numBlocks - 1;
    for (int64_t n = 0, id = first; n < numBlocks; ++n, id += direction)
    {
      const int ids[3] = { static_cast<int>(id % nb[0]),
        static_cast<int>((id / nb[0]) % nb[1]),
        static_cast<int>(id / (int64_t(nb[0]) * nb[1])) };
      for (int dk = -1; dk <= 1; ++dk)
      {
        for (int dj = -1; dj <= 1; ++dj)
        {
          for (int di = -1; di <= 1; ++di)
          {
            const int o[3] = { ids[0] + di, ids[1] + dj, ids[2] + dk };
            if (o[0] < 0 || o[1] < 0 || o[2] < 0 || o[0] >= nb[0] || o[1] >= nb[1] || o[2] >= nb[2])
            {
              continue;
            }
            const int64_t other = o[0] + int64_t(nb[0]) * (o[1] + int64_t(nb[1]) * o[2]);
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
          }
        }
      }
    }
  };
  sweep(+1);
  sweep(-1);
  BoundPyramid pyramid;
  pyramid.Dims.push_back(nb);
  pyramid.Max.emplace_back(numBlocks);
  std::vector<float>& level0 = pyramid.Max.back();
  for (int64_t id = 0; id < numBlocks; ++id)
  {
    // The farthest point of the block's cell from its mesh point p (never above
    // |centre - p| + the half diagonal, and often well below).
    double bound = HUGE_VAL;
    if (nearestPoint[id] >= 0)
    {
      const int ids[3] = { static_cast<int>(id % nb[0]),
        static_cast<int>((id / nb[0]) % nb[1]),
        static_cast<int>(id / (int64_t(nb[0]) * nb[1])) };
      const double* p = &points[3 * nearestPoint[id]];
      double far2 = 0;
      for (int a = 0; a < 3; ++a)
      {
        const double cellLo = this->CellOrigin[a] + ids[a] * this->CellSize[a];
        const double cellHi = cellLo + this->CellSize[a];
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
  this->BlockBound = level0;
  // Each block's mesh point, for MayWin's bisector test (NaN: none, the bound alone).
  this->BlockPoint.assign(3 * numBlocks, std::numeric_limits<double>::quiet_NaN());
  for (int64_t id = 0; id < numBlocks; ++id)
  {
    if (nearestPoint[id] >= 0)
    {
      std::copy(&points[3 * nearestPoint[id]],
        &points[3 * nearestPoint[id]] + 3,
        &this->BlockPoint[3 * id]);
    }
  }
  this->BlockCounts = nb;
  this->BlockExtent = extent;
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
  const int top = static_cast<int>(pyramid.Dims.size()) - 1;

  // Group sites by the block of their anchor.
  std::vector<int64_t> siteBlock(numSites);
  std::vector<int64_t> offsets(numBlocks + 1, 0);
  for (int64_t s = 0; s < numSites; ++s)
  {
    int64_t id = 0, stride = 1;
    for (int a = 0; a < 3; ++a)
    {
      // Clamped before the conversion: an anchor far outside an explicit grid is
      // beyond int's range in blocks.
      const double x = (sites.Sites[s].Anchor[a] - grid.Origin[a]) / grid.Spacing[a];
      const double at = std::floor((x - extent.Lo[a]) / b);
      const int blk = static_cast<int>(std::min(std::max(at, 0.0), double(nb[a] - 1)));
      id += blk * stride;
      stride *= nb[a];
    }
    siteBlock[s] = id;
    ++offsets[id + 1];
  }
  for (int64_t c = 0; c < numBlocks; ++c)
  {
    offsets[c + 1] += offsets[c];
  }
  {
    std::vector<int64_t> fill(offsets.begin(), offsets.end() - 1);
    for (int64_t s = 0; s < numSites; ++s)
    {
      this->Order[fill[siteBlock[s]]++] = s;
    }
  }

  // Reach of each group, then each site's region; the descent stops at ReachLevel.
  parallelFor(numBlocks,
    16,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t cluster = begin; cluster < end; ++cluster)
      {
        if (offsets[cluster] == offsets[cluster + 1])
        {
          continue;
        }
        Box group{ { HUGE_VAL, HUGE_VAL, HUGE_VAL }, { -HUGE_VAL, -HUGE_VAL, -HUGE_VAL } };
        for (int64_t o = offsets[cluster]; o < offsets[cluster + 1]; ++o)
        {
          const Site& s = sites.Sites[this->Order[o]];
          for (int a = 0; a < 3; ++a)
          {
            group.Lo[a] = std::min<double>(group.Lo[a], s.BoundsMin[a]);
            group.Hi[a] = std::max<double>(group.Hi[a], s.BoundsMax[a]);
          }
        }
        int reachLo[3] = { INT32_MAX, INT32_MAX, INT32_MAX };
        int reachHi[3] = { -1, -1, -1 };
        // Depth-first descent; a node already inside the reach adds nothing.
        struct Node
        {
          int Level, I, J, K;
        };
        std::vector<Node> stack{ { top, 0, 0, 0 } };
        while (!stack.empty())
        {
          const Node node = stack.back();
          stack.pop_back();
          const int span = 1 << node.Level;
          const int lo[3] = { node.I * span, node.J * span, node.K * span };
          int hi[3];
          bool inside = true;
          for (int a = 0; a < 3; ++a)
          {
            hi[a] = std::min(lo[a] + span, nb[a]) - 1;
            inside = inside && lo[a] >= reachLo[a] && hi[a] <= reachHi[a];
          }
          if (inside)
          {
            continue;
          }
          const auto& d = pyramid.Dims[node.Level];
          const int64_t at = node.I + int64_t(d[0]) * (node.J + int64_t(d[1]) * node.K);
          const Box box = blockBox(lo[0], lo[1], lo[2], span);
          if (BoxDistance(box, group) > pyramid.Max[node.Level][at])
          {
            continue;
          }
          if (node.Level <= this->ReachLevel ||
            FarthestDistance(box, group) <= pyramid.Min[node.Level][at])
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
                const Node child{
                  node.Level - 1, 2 * node.I + di, 2 * node.J + dj, 2 * node.K + dk
                };
                if (child.I < cd[0] && child.J < cd[1] && child.K < cd[2])
                {
                  stack.push_back(child);
                }
              }
            }
          }
        }
        if (reachHi[0] < 0)
        {
          continue; // no block can have these sites as closest (MaximumDistance band)
        }
        IndexBox reach;
        for (int a = 0; a < 3; ++a)
        {
          reach.Lo[a] = extent.Lo[a] + reachLo[a] * b;
          reach.Hi[a] = static_cast<int>(
            std::min<int64_t>(extent.Lo[a] + int64_t(reachHi[a] + 1) * b - 1, extent.Hi[a]));
        }
        for (int64_t o = offsets[cluster]; o < offsets[cluster + 1]; ++o)
        {
          const int64_t id = this->Order[o];
          const Site& s = sites.Sites[id];
          IndexBox region = reach;
          if (std::isfinite(maximumDistance))
          {
            IndexBox band;
            for (int a = 0; a < 3; ++a)
            {
              const double lo =
                (s.BoundsMin[a] - maximumDistance - grid.Origin[a]) / grid.Spacing[a];
              const double hi =
                (s.BoundsMax[a] + maximumDistance - grid.Origin[a]) / grid.Spacing[a];
              // Clamped both ways: a site far off the grid puts either end past int.
              band.Lo[a] = static_cast<int>(std::min(std::max(std::ceil(lo), -2e9), 2e9));
              band.Hi[a] = static_cast<int>(std::min(std::max(std::floor(hi), -2e9), 2e9));
            }
            region = region.Intersect(band);
          }
          this->Regions[id] = region;
        }
      }
    });
}

} // namespace vtkdf
