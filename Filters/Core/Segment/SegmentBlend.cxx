#include "Segment/SegmentBlend.h"

#include <algorithm>
#include <cmath>
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
  float* out,
  const ParallelFor& parallelFor)
{
  const int nx = grid.Dims[0], ny = grid.Dims[1], nz = grid.Dims[2];
  const int64_t count = static_cast<int64_t>(nx) * ny * nz;
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> squared(static_cast<size_t>(count));
  for (int64_t i = 0; i < count; ++i)
  {
    squared[i] = regions[i] == which ? 0.0 : inf;
  }
  // One axis at a time: the lines along it, in parallel.
  auto pass = [&](int axis)
  {
    const int n = grid.Dims[axis];
    const int64_t stride = axis == 0 ? 1 : axis == 1 ? nx : static_cast<int64_t>(nx) * ny;
    const int64_t lines = count / n;
    Run(parallelFor,
      lines,
      64,
      [&](int64_t begin, int64_t end)
      {
        std::vector<double> f(n), d(n), z(n + 1);
        std::vector<int> v(n);
        for (int64_t line = begin; line < end; ++line)
        {
          // The line's first sample: its index with the axis coordinate 0.
          int64_t first;
          if (axis == 0)
          {
            first = line * nx;
          }
          else if (axis == 1)
          {
            first = (line / nx) * nx * ny + line % nx;
          }
          else
          {
            first = line;
          }
          for (int q = 0; q < n; ++q)
          {
            f[q] = squared[first + q * stride];
          }
          Transform1D(f.data(), n, grid.Spacing[axis], d.data(), v.data(), z.data());
          for (int q = 0; q < n; ++q)
          {
            squared[first + q * stride] = d[q];
          }
        }
      });
  };
  for (int axis = 0; axis < 3; ++axis)
  {
    if (grid.Dims[axis] > 1)
    {
      pass(axis);
    }
  }
  for (int64_t i = 0; i < count; ++i)
  {
    out[i] = static_cast<float>(std::sqrt(squared[i]));
  }
}

void BlendSegmented(const SegmentedSamples& first,
  const SegmentedSamples& second,
  double t,
  const BlendGrid& grid,
  float* distance,
  int32_t* region,
  const ParallelFor& parallelFor)
{
  const int64_t count = static_cast<int64_t>(grid.Dims[0]) * grid.Dims[1] * grid.Dims[2];
  // The ends exactly (the formulas below round at t = 0 and 1 otherwise).
  if (t == 0 || t == 1)
  {
    const SegmentedSamples& end = t == 0 ? first : second;
    std::copy(end.Distance, end.Distance + count, distance);
    std::copy(end.Region, end.Region + count, region);
    return;
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
  for (const int32_t r : inFirst)
  {
    RegionDistance(first.Region, r, grid, scratch.data(), parallelFor);
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
    RegionDistance(second.Region, r, grid, scratch.data(), parallelFor);
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
}

void BlendSegmentedFields(const SegmentedSamples& first,
  const SegmentedSamples& second,
  double t,
  const BlendGrid& grid,
  double delta,
  double offset,
  float* distance,
  int32_t* region,
  float* segmented,
  const ParallelFor& parallelFor)
{
  BlendSegmented(first, second, t, grid, distance, region, parallelFor);
  const int64_t count = static_cast<int64_t>(grid.Dims[0]) * grid.Dims[1] * grid.Dims[2];
  parallelFor(count,
    4096,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t v = begin; v < end; ++v)
      {
        segmented[v] =
          static_cast<float>(std::min(double(distance[v]), delta) + offset * region[v]);
      }
    });
}

} // namespace vtkdf
