#include "Segment/SegmentBlend.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <set>
#include <vector>

namespace vtkdf
{
namespace
{
void Run(const ParallelFor& parallelFor,
  int64_t n,
  int64_t grain,
  const std::function<void(int64_t, int64_t)>& body)
{
  if (parallelFor)
  {
    parallelFor(n, grain, body);
  }
  else
  {
    body(0, n);
  }
}

/// The 1D squared-distance transform of f (n samples, `step` apart) into d: the lower
/// envelope of the parabolas (x - q)^2 step^2 + f(q). v and z are scratch (n and n + 1).
void Transform1D(const double* f, int n, double step, double* d, int* v, double* z)
{
  const double inf = std::numeric_limits<double>::infinity();
  int k = -1;
  for (int q = 0; q < n; ++q)
  {
    if (f[q] == inf)
    {
      continue;
    }
    double s = -inf;
    while (k >= 0)
    {
      const int p = v[k];
      s = ((f[q] + q * q * step * step) - (f[p] + p * p * step * step)) /
        (2.0 * step * step * (q - p));
      if (s > z[k])
      {
        break;
      }
      --k;
    }
    ++k;
    v[k] = q;
    z[k] = k == 0 ? -inf : s;
    z[k + 1] = inf;
  }
  if (k < 0)
  {
    std::fill(d, d + n, inf);
    return;
  }
  int j = 0;
  for (int q = 0; q < n; ++q)
  {
    while (z[j + 1] < q)
    {
      ++j;
    }
    const double dq = (q - v[j]) * step;
    d[q] = dq * dq + f[v[j]];
  }
}
} // namespace

void RegionDistance(const int32_t* regions,
  int32_t which,
  const BlendGrid& grid,
  const BlendBox& box,
  float* out,
  const ParallelFor& parallelFor)
{
  const int nx = grid.Dims[0], ny = grid.Dims[1], nz = grid.Dims[2];
  const double inf = std::numeric_limits<double>::infinity();
  // The transform along x, then y, then z, each on whole lines: along x every row of the
  // grid, kept where x lies in the box; along y the lines through the box's x range,
  // kept where y lies in it; along z the lines through the box's (x, y). A line's values
  // are those of the whole grid's transform, so the box's are too, bit for bit.
  const int bx = box.Size(0), by = box.Size(1);
  // Line `line` of `count` along `axis` reads `n` values from `in` and writes the kept
  // ones to `keep`.
  auto pass = [&](int n,
                int64_t count,
                double step,
                bool transform,
                const std::function<double(int64_t, int)>& in,
                const std::function<void(int64_t, int, double)>& keep)
  {
    Run(parallelFor,
      count,
      64,
      [&](int64_t begin, int64_t end)
      {
        std::vector<double> f(n), d(n), z(n + 1);
        std::vector<int> v(n);
        for (int64_t line = begin; line < end; ++line)
        {
          for (int q = 0; q < n; ++q)
          {
            f[q] = in(line, q);
          }
          if (transform)
          {
            Transform1D(f.data(), n, step, d.data(), v.data(), z.data());
          }
          else
          {
            d = f;
          }
          for (int q = 0; q < n; ++q)
          {
            keep(line, q, d[q]);
          }
        }
      });
  };
  // Along x: rows (y, z) of the whole grid; kept: x in the box.
  std::vector<double> alongX(static_cast<size_t>(bx) * ny * nz);
  pass(
    nx,
    int64_t(ny) * nz,
    grid.Spacing[0],
    nx > 1,
    [&](int64_t row, int x) { return regions[row * nx + x] == which ? 0.0 : inf; },
    [&](int64_t row, int x, double value)
    {
      if (x >= box.Lo[0] && x <= box.Hi[0])
      {
        alongX[row * bx + (x - box.Lo[0])] = value;
      }
    });
  // Along y: lines (x in the box, z); kept: y in the box.
  std::vector<double> alongY(static_cast<size_t>(bx) * by * nz);
  pass(
    ny,
    int64_t(bx) * nz,
    grid.Spacing[1],
    ny > 1,
    [&](int64_t line, int y)
    {
      const int64_t x = line % bx, zz = line / bx;
      return alongX[(zz * ny + y) * bx + x];
    },
    [&](int64_t line, int y, double value)
    {
      if (y >= box.Lo[1] && y <= box.Hi[1])
      {
        const int64_t x = line % bx, zz = line / bx;
        alongY[(zz * by + (y - box.Lo[1])) * bx + x] = value;
      }
    });
  alongX = std::vector<double>();
  // Along z: lines (x, y) of the box; kept: z in the box, as distances.
  pass(
    nz,
    int64_t(bx) * by,
    grid.Spacing[2],
    nz > 1,
    [&](int64_t line, int zz) { return alongY[zz * int64_t(bx) * by + line]; },
    [&](int64_t line, int zz, double value)
    {
      if (zz >= box.Lo[2] && zz <= box.Hi[2])
      {
        out[(zz - box.Lo[2]) * int64_t(bx) * by + line] = static_cast<float>(std::sqrt(value));
      }
    });
}

namespace
{
/// BlendSegmentedFields without the segmented values.
bool BlendPiece(const SegmentedSamples& first,
  const SegmentedSamples& second,
  const int32_t* firstRegions,
  const int32_t* secondRegions,
  const BlendBox& box,
  double t,
  const BlendGrid& grid,
  float* distance,
  int32_t* region,
  const Execution& execution)
{
  const ParallelFor& parallelFor = execution.For;
  const int64_t count = box.Count();
  // The ends exactly (the formulas below round at t = 0 and 1 otherwise).
  if (t == 0 || t == 1)
  {
    const SegmentedSamples& end = t == 0 ? first : second;
    std::copy(end.Distance, end.Distance + count, distance);
    std::copy(end.Region, end.Region + count, region);
    return true;
  }
  // The regions whose distance transforms the differing samples need: in the first
  // field the second's region there, and the other way round.
  std::set<int32_t> inFirst, inSecond;
  for (int64_t v = 0; v < count; ++v)
  {
    if (first.Region[v] != second.Region[v])
    {
      inFirst.insert(second.Region[v]);
      inSecond.insert(first.Region[v]);
    }
  }
  // e_a and e_b of every differing sample (see the header), region by region.
  const double halfDiagonal = 0.5 *
    std::sqrt(grid.Spacing[0] * grid.Spacing[0] + grid.Spacing[1] * grid.Spacing[1] +
      grid.Spacing[2] * grid.Spacing[2]);
  std::vector<float> toInterfaceFirst(static_cast<size_t>(count), 0.0f);
  std::vector<float> toInterfaceSecond(static_cast<size_t>(count), 0.0f);
  std::vector<float> scratch(static_cast<size_t>(count));
  // Whether, in either field, the sample's region meets the other one across a seam:
  // a voxel of the other region nearer than the nearest surface lies in the sample's
  // empty ball, so the two regions touch there without a sheet between them.
  std::vector<uint8_t> seam(static_cast<size_t>(count), 0);
  // Progress and abort by the regions' distance transforms, the bulk of the work.
  const double transforms = double(inFirst.size() + inSecond.size()) + 1;
  double done = 0;
  for (const int32_t r : inFirst)
  {
    if (!execution.Report(done++ / transforms))
    {
      return false;
    }
    RegionDistance(firstRegions, r, grid, box, scratch.data(), parallelFor);
    for (int64_t v = 0; v < count; ++v)
    {
      if (first.Region[v] != second.Region[v] && second.Region[v] == r)
      {
        toInterfaceFirst[v] =
          static_cast<float>(std::max<double>(first.Distance[v], scratch[v] - halfDiagonal));
        seam[v] |= scratch[v] < first.Distance[v] ? 1 : 0;
      }
    }
  }
  for (const int32_t r : inSecond)
  {
    if (!execution.Report(done++ / transforms))
    {
      return false;
    }
    RegionDistance(secondRegions, r, grid, box, scratch.data(), parallelFor);
    for (int64_t v = 0; v < count; ++v)
    {
      if (first.Region[v] != second.Region[v] && first.Region[v] == r)
      {
        toInterfaceSecond[v] =
          static_cast<float>(std::max<double>(second.Distance[v], scratch[v] - halfDiagonal));
        seam[v] |= scratch[v] < second.Distance[v] ? 1 : 0;
      }
    }
  }
  Run(parallelFor,
    count,
    4096,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t v = begin; v < end; ++v)
      {
        const double a = first.Distance[v], b = second.Distance[v];
        const int32_t ra = first.Region[v], rb = second.Region[v];
        if (ra == rb)
        {
          distance[v] = static_cast<float>((1 - t) * a + t * b);
          region[v] = ra;
        }
        else
        {
          const double s = (1 - t) * -toInterfaceFirst[v] + t * toInterfaceSecond[v];
          // Across a seam the region still changes where s does, but no sheet moves
          // there: the distance is the surfaces', which eq. 7 keeps from making one.
          const double blended = (1 - t) * a + t * b;
          distance[v] = static_cast<float>(seam[v] ? blended : std::min(std::fabs(s), blended));
          region[v] = s < 0 ? ra : rb;
        }
      }
    });
  return execution.Report(done / transforms);
}

} // namespace

bool BlendSegmentedFields(const SegmentedSamples& first,
  const SegmentedSamples& second,
  const int32_t* firstRegions,
  const int32_t* secondRegions,
  const BlendBox& box,
  double t,
  const BlendGrid& grid,
  double delta,
  double offset,
  float* distance,
  int32_t* region,
  float* segmented,
  const Execution& execution)
{
  if (!BlendPiece(
        first, second, firstRegions, secondRegions, box, t, grid, distance, region, execution))
  {
    return false;
  }
  const int64_t count = box.Count();
  Run(execution.For,
    count,
    4096,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t v = begin; v < end; ++v)
      {
        segmented[v] =
          static_cast<float>(std::min(double(distance[v]), delta) + offset * region[v]);
      }
    });
  return execution.Report(1.0);
}

} // namespace vtkdf
