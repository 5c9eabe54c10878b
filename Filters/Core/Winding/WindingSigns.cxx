#include "Winding/WindingSigns.h"

#include "Winding/WindingCrossings.h"
#include "Winding/WindingSignsGPU.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <numeric>

namespace vtkdf
{

namespace
{
constexpr int TopBlock = 8;
// Covers the rounding of the first-order prediction (its terms are at most a few units).
constexpr double RoundingSlack = 1e-12;
constexpr double SkipFactor = 2;

struct Decider
{
  const WindingNumber& Winding;
  const SampleGrid& Grid;
  const IndexBox& Extent;
  uint8_t* Inside;
  float* Value;
  const float* Distance;
  double DistanceScale;
  int64_t Stride[3];
  WindingSignStatistics Stats;

  int64_t Index(int i, int j, int k) const
  {
    return (i - Extent.Lo[0]) * Stride[0] + (j - Extent.Lo[1]) * Stride[1] +
      (k - Extent.Lo[2]) * Stride[2];
  }

  void Single(int i, int j, int k)
  {
    const double q[3] = { Grid.Coordinate(0, i), Grid.Coordinate(1, j), Grid.Coordinate(2, k) };
    double w = 0;
    bool exact = false;
    const int64_t at = this->Index(i, j, k);
    // Without values, Inside refines only as far as the sign needs.
    this->Inside[at] = this->Winding.Inside(q, this->Value ? &w : nullptr, &exact) ? 1 : 0;
    if (this->Value)
    {
      this->Value[at] = static_cast<float>(w);
    }
    ++this->Stats.Evaluated;
    this->Stats.Exact += exact;
  }

  /// The samples [lo, hi] (inclusive, within the extent).
  void Block(const int lo[3], const int hi[3])
  {
    const int64_t count = int64_t(hi[0] - lo[0] + 1) * (hi[1] - lo[1] + 1) * (hi[2] - lo[2] + 1);
    if (count == 1)
    {
      this->Single(lo[0], lo[1], lo[2]);
      return;
    }
    double c[3], radius2 = 0;
    for (int a = 0; a < 3; ++a)
    {
      c[a] = 0.5 * (this->Grid.Coordinate(a, lo[a]) + this->Grid.Coordinate(a, hi[a]));
      const double half = 0.5 * (hi[a] - lo[a]) * this->Grid.Spacing[a];
      radius2 += half * half;
    }
    const double radius = std::sqrt(radius2);
    if (this->Distance && this->NearSurface(lo, hi, radius))
    {
      this->Split(lo, hi);
      return;
    }
    // First order about the centre: every sample y has w(y) within Bound +
    // |y - c| GradientBound + |y - c|^2 H / 2 of w(c) + grad w(c) . (y - c).
    const double hessian = this->Winding.HessianBound(c, radius);
    if (hessian < HUGE_VAL)
    {
      const WindingGradient w = this->Winding.EvaluateWithGradient(c);
      bool decided = true;
      for (int k = lo[2]; k <= hi[2] && decided; ++k)
      {
        for (int j = lo[1]; j <= hi[1] && decided; ++j)
        {
          for (int i = lo[0]; i <= hi[0] && decided; ++i)
          {
            const double y[3] = { this->Grid.Coordinate(0, i) - c[0],
              this->Grid.Coordinate(1, j) - c[1],
              this->Grid.Coordinate(2, k) - c[2] };
            const double r2 = y[0] * y[0] + y[1] * y[1] + y[2] * y[2];
            const double predicted =
              w.Value + w.Gradient[0] * y[0] + w.Gradient[1] * y[1] + w.Gradient[2] * y[2];
            const double uncertainty =
              w.Bound + std::sqrt(r2) * w.GradientBound + 0.5 * r2 * hessian + RoundingSlack;
            const bool in = std::fabs(predicted) > 0.5;
            decided = std::fabs(std::fabs(predicted) - 0.5) > uncertainty;
            this->Inside[this->Index(i, j, k)] = in ? 1 : 0;
          }
        }
      }
      if (decided)
      {
        this->Stats.BlockSamples += count;
        return;
      }
    }
    this->Split(lo, hi);
  }

  /// Whether the surface comes so near the block (a sample of it closer than
  /// SkipFactor x its radius) that the Hessian bound cannot decide it: then the block splits
  /// without trying. This choice affects the work only, never a sign.
  bool NearSurface(const int lo[3], const int hi[3], double radius) const
  {
    const float limit = static_cast<float>(SkipFactor * radius / this->DistanceScale);
    for (int k = lo[2]; k <= hi[2]; ++k)
    {
      for (int j = lo[1]; j <= hi[1]; ++j)
      {
        const float* row = this->Distance + this->Index(lo[0], j, k);
        for (int i = 0; i <= hi[0] - lo[0]; ++i)
        {
          if (std::fabs(row[i]) < limit)
          {
            return true;
          }
        }
      }
    }
    return false;
  }

  /// Eight halves (or fewer along axes of one sample).
  void Split(const int lo[3], const int hi[3])
  {
    int mid[3];
    for (int a = 0; a < 3; ++a)
    {
      mid[a] = lo[a] + (hi[a] - lo[a]) / 2; // the first half ends at mid
    }
    for (int o = 0; o < 8; ++o)
    {
      int clo[3], chi[3];
      bool empty = false;
      for (int a = 0; a < 3; ++a)
      {
        const bool upper = (o >> a) & 1;
        clo[a] = upper ? mid[a] + 1 : lo[a];
        chi[a] = upper ? hi[a] : mid[a];
        empty = empty || clo[a] > chi[a];
      }
      if (!empty)
      {
        this->Block(clo, chi);
      }
    }
  }
};
} // namespace

namespace
{
/// Whether the crossings' route may decide: signs only, by the default route, on a grid
/// whose coordinates grow with the indices.
bool CrossingsApply(const WindingSignOptions& options, const SampleGrid& grid)
{
  return !options.Value && options.Blocks && grid.Spacing[0] > 0 && grid.Spacing[1] > 0 &&
    grid.Spacing[2] > 0;
}
} // namespace

WindingSignStatistics WindingSigns(const WindingNumber& winding,
  const SampleGrid& grid,
  const IndexBox& extent,
  uint8_t* inside,
  const WindingSignOptions& options,
  const ParallelFor& parallelFor)
{
  // A closed mesh: w is the count of crossings along each line (WindingCrossings.h).
  if (CrossingsApply(options, grid))
  {
    const std::vector<double>& corners = winding.TriangleCorners();
    std::vector<int64_t> ids(corners.size() / 3);
    std::iota(ids.begin(), ids.end(), int64_t(0));
    if (IsClosedChain(corners, ids))
    {
      return CrossingSigns(corners,
        ids,
        grid,
        extent,
        inside,
        parallelFor,
        [&]() -> const WindingNumber& { return winding; });
    }
  }
  const int n[3] = { extent.Size(0), extent.Size(1), extent.Size(2) };
  const int64_t stride[3] = { 1, n[0], int64_t(n[0]) * n[1] };
  // With values wanted, or no blocks, every sample alone.
  const int size = options.Value || !options.Blocks ? 1 : TopBlock;
  const int b[3] = { (n[0] + size - 1) / size, (n[1] + size - 1) / size, (n[2] + size - 1) / size };
  std::atomic<int64_t> blockSamples{ 0 }, evaluated{ 0 }, exact{ 0 };
  parallelFor(int64_t(b[0]) * b[1] * b[2],
    size == 1 ? 256 : 1,
    [&](int64_t begin, int64_t end)
    {
      Decider decider{ winding,
        grid,
        extent,
        inside,
        options.Value,
        options.Distance,
        options.DistanceScale,
        { stride[0], stride[1], stride[2] },
        {} };
      for (int64_t t = begin; t < end; ++t)
      {
        const int bi[3] = { static_cast<int>(t % b[0]),
          static_cast<int>((t / b[0]) % b[1]),
          static_cast<int>(t / (int64_t(b[0]) * b[1])) };
        int lo[3], hi[3];
        for (int a = 0; a < 3; ++a)
        {
          lo[a] = extent.Lo[a] + bi[a] * size;
          hi[a] = std::min(extent.Hi[a], lo[a] + size - 1);
        }
        decider.Block(lo, hi);
      }
      blockSamples += decider.Stats.BlockSamples;
      evaluated += decider.Stats.Evaluated;
      exact += decider.Stats.Exact;
    });
  WindingSignStatistics stats;
  stats.BlockSamples = blockSamples.load();
  stats.Evaluated = evaluated.load();
  stats.Exact = exact.load();
  return stats;
}

bool ComputeWindingSigns(const std::vector<double>& points,
  const std::vector<int64_t>& triangles,
  const SampleGrid& grid,
  const IndexBox& extent,
  uint8_t* inside,
  const WindingSignOptions& options,
  HeadlessGL* gl,
  const ParallelFor& parallelFor,
  WindingSignStatistics& stats,
  std::string& error)
{
  // A closed mesh on the CPU: the crossings along the lines, the hierarchy built only for
  // samples on the surface.
  WindingNumber winding;
  if ((!gl || options.ClosedOnCPU) && CrossingsApply(options, grid) &&
    IsClosedChain(points, triangles))
  {
    bool built = false;
    stats = CrossingSigns(points,
      triangles,
      grid,
      extent,
      inside,
      parallelFor,
      [&]() -> const WindingNumber&
      {
        if (!built)
        {
          winding.Build(points, triangles);
          built = true;
        }
        return winding;
      });
    return true;
  }
  winding.Build(points, triangles);
  if (gl)
  {
    const bool ok = WindingSignsGPU(*gl, winding, grid, extent, inside, options, stats, error);
    stats.GPU = true;
    return ok;
  }
  stats = WindingSigns(winding, grid, extent, inside, options, parallelFor);
  return true;
}

} // namespace vtkdf
