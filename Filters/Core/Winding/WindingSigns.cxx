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
// Covers the rounding of the first-order prediction too (its terms are at most a few
// units).
constexpr double RoundingSlack = WindingNumber::RoundingSlack;
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
  // An open mesh closed by cones (WindingCrossings.h): Winding is then the cones', w at a
  // sample is Offset (the closed chain's crossings' count) minus theirs, and a sample
  // that this does not decide (or whose count is CountUnknown) goes to Surface, the
  // mesh's own hierarchy.
  const int8_t* Offset = nullptr;
  const WindingNumber* Surface = nullptr;

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
    if (this->Offset)
    {
      if (this->Offset[at] != CountUnknown)
      {
        const WindingValue cone = this->Winding.Evaluate(q);
        const double value = this->Offset[at] - cone.Value;
        if (std::fabs(std::fabs(value) - 0.5) > cone.Bound + RoundingSlack)
        {
          this->Inside[at] = std::fabs(value) > 0.5 ? 1 : 0;
          ++this->Stats.LineSamples;
          return;
        }
      }
      this->Inside[at] = this->Surface->Inside(q, nullptr, &exact) ? 1 : 0;
      ++this->Stats.Evaluated;
      this->Stats.Exact += exact;
      return;
    }
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
            const int64_t at = this->Index(i, j, k);
            const double first =
              w.Value + w.Gradient[0] * y[0] + w.Gradient[1] * y[1] + w.Gradient[2] * y[2];
            const double predicted = this->Offset ? this->Offset[at] - first : first;
            const double uncertainty =
              w.Bound + std::sqrt(r2) * w.GradientBound + 0.5 * r2 * hessian + RoundingSlack;
            const bool in = std::fabs(predicted) > 0.5;
            decided = std::fabs(std::fabs(predicted) - 0.5) > uncertainty &&
              !(this->Offset && this->Offset[at] == CountUnknown);
            this->Inside[at] = in ? 1 : 0;
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

WindingSignStatistics DecideWindingBlocks(const WindingNumber& winding,
  const SampleGrid& grid,
  const IndexBox& extent,
  uint8_t* inside,
  const WindingSignOptions& options,
  const ParallelFor& parallelFor,
  const int8_t* offsets,
  const WindingNumber* surface)
{
  const int n[3] = { extent.Size(0), extent.Size(1), extent.Size(2) };
  const int64_t stride[3] = { 1, n[0], int64_t(n[0]) * n[1] };
  // With values wanted, or no blocks, every sample alone.
  const int size = options.Value || !options.Blocks ? 1 : TopBlock;
  const int b[3] = { (n[0] + size - 1) / size, (n[1] + size - 1) / size, (n[2] + size - 1) / size };
  std::atomic<int64_t> blockSamples{ 0 }, lineSamples{ 0 }, evaluated{ 0 }, exact{ 0 };
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
        {},
        offsets,
        surface };
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
      lineSamples += decider.Stats.LineSamples;
      evaluated += decider.Stats.Evaluated;
      exact += decider.Stats.Exact;
    });
  WindingSignStatistics stats;
  stats.BlockSamples = blockSamples.load();
  stats.LineSamples = lineSamples.load();
  stats.Evaluated = evaluated.load();
  stats.Exact = exact.load();
  return stats;
}

int WindingBoxSide(const WindingNumber& winding,
  const SampleGrid& grid,
  const IndexBox& box,
  const int* offset)
{
  double c[3], radius2 = 0;
  for (int a = 0; a < 3; ++a)
  {
    c[a] = 0.5 * (grid.Coordinate(a, box.Lo[a]) + grid.Coordinate(a, box.Hi[a]));
    const double half = 0.5 * (box.Hi[a] - box.Lo[a]) * std::fabs(grid.Spacing[a]);
    radius2 += half * half;
  }
  const double radius = std::sqrt(radius2);
  const double hessian = winding.HessianBound(c, radius);
  if (!(hessian < HUGE_VAL))
  {
    return -1;
  }
  // Decider::Block's bound, for every y of the ball: |grad w(c) . (y - c)| <= |grad| r.
  const WindingGradient w = winding.EvaluateWithGradient(c);
  const double gradient = std::sqrt(
    w.Gradient[0] * w.Gradient[0] + w.Gradient[1] * w.Gradient[1] + w.Gradient[2] * w.Gradient[2]);
  const double spread =
    w.Bound + radius * (gradient + w.GradientBound) + 0.5 * radius2 * hessian + RoundingSlack;
  const double value = offset ? *offset - w.Value : w.Value;
  if (value - spread > 0.5 || value + spread < -0.5)
  {
    return 1;
  }
  if (value - spread > -0.5 && value + spread < 0.5)
  {
    return 0;
  }
  return -1;
}

namespace
{

/// An open mesh's signs (options as CrossingsApply allows): its closure by cones
/// (WindingCrossings.h), the closed chain's crossings counted along the lines, then
/// WindingSigns' blocks on w = N - w_C; false (nothing written) where it cannot be closed.
bool OpenSigns(const WindingNumber& surface,
  const SampleGrid& grid,
  const IndexBox& extent,
  uint8_t* inside,
  const WindingSignOptions& options,
  const ParallelFor& parallelFor,
  WindingSignStatistics& stats)
{
  ConeClosure closure;
  if (!CloseWithCones(surface.TriangleCorners(), closure))
  {
    return false;
  }
  std::vector<int8_t> counts(static_cast<size_t>(extent.Count()));
  CrossingCounts(closure.Points, closure.Triangles, grid, extent, counts.data(), parallelFor);
  WindingNumber cones;
  cones.Build(closure.Points, closure.Cone);
  WindingSignOptions blocks = options;
  blocks.Distance = nullptr; // the mesh's own distance says nothing of the cones' w
  stats =
    DecideWindingBlocks(cones, grid, extent, inside, blocks, parallelFor, counts.data(), &surface);
  return true;
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
    const LargeVector<double>& corners = winding.TriangleCorners();
    LargeVector<int64_t> ids(corners.size() / 3);
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
    // An open mesh: closed by cones, w = N - w_C.
    WindingSignStatistics stats;
    if (OpenSigns(winding, grid, extent, inside, options, parallelFor, stats))
    {
      return stats;
    }
  }
  return DecideWindingBlocks(winding, grid, extent, inside, options, parallelFor, nullptr, nullptr);
}

namespace
{
/// The power of two that brings the points and the grid's corners near 1 (0 where their
/// largest coordinate lies within 2^+-100 already).
int ScaleExponent(const LargeVector<double>& points, const SampleGrid& grid)
{
  double largest = 0;
  for (const double x : points)
  {
    largest = std::fmax(largest, std::fabs(x));
  }
  for (int a = 0; a < 3; ++a)
  {
    largest = std::fmax(largest, std::fabs(grid.Origin[a]));
    largest = std::fmax(largest, std::fabs(grid.Coordinate(a, grid.Whole.Hi[a])));
  }
  int exponent = 0;
  std::frexp(largest, &exponent);
  return largest > 0 && std::isfinite(largest) && std::abs(exponent) > 100 ? exponent : 0;
}
} // namespace

bool ComputeWindingSigns(const LargeVector<double>& points,
  const LargeVector<int64_t>& triangles,
  const SampleGrid& grid,
  const IndexBox& extent,
  uint8_t* inside,
  const WindingSignOptions& options,
  HeadlessGL* gl,
  const ParallelFor& parallelFor,
  WindingSignStatistics& stats,
  std::string& error)
{
  // The hierarchy's sums (w's terms, their bounds) under- and overflow near the least and
  // the largest doubles: there the points and the grid are scaled by a power of two, which
  // is exact (short of subnormal coordinates) and keeps every sign and value.
  if (const int exponent = ScaleExponent(points, grid))
  {
    LargeVector<double> scaledPoints(points);
    for (double& x : scaledPoints)
    {
      x = std::ldexp(x, -exponent);
    }
    SampleGrid scaledGrid = grid;
    WindingSignOptions scaledOptions = options;
    for (int a = 0; a < 3; ++a)
    {
      scaledGrid.Origin[a] = std::ldexp(grid.Origin[a], -exponent);
      scaledGrid.Spacing[a] = std::ldexp(grid.Spacing[a], -exponent);
    }
    scaledOptions.DistanceScale = std::ldexp(options.DistanceScale, -exponent);
    return ComputeWindingSigns(scaledPoints,
      triangles,
      scaledGrid,
      extent,
      inside,
      scaledOptions,
      gl,
      parallelFor,
      stats,
      error);
  }
  // On the CPU, a closed mesh: the crossings along the lines, the hierarchy built only
  // for samples on the surface; an open one closed by cones.
  WindingNumber winding;
  const bool crossings = (!gl || options.CrossingsOnCPU) && CrossingsApply(options, grid);
  if (crossings && IsClosedChain(points, triangles))
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
  if (crossings && OpenSigns(winding, grid, extent, inside, options, parallelFor, stats))
  {
    return true;
  }
  if (gl)
  {
    const bool ok =
      WindingSignsGPU(*gl, winding, grid, extent, inside, options, parallelFor, stats, error);
    stats.GPU = true;
    return ok;
  }
  // The routes above could not take it (values, or a boundary used twice over).
  stats =
    DecideWindingBlocks(winding, grid, extent, inside, options, parallelFor, nullptr, nullptr);
  return true;
}

} // namespace vtkdf
