#include "WindingSigns.h"

#include <algorithm>
#include <atomic>
#include <cmath>

namespace vtkdf
{

namespace
{
constexpr int TopBlock = 8;

struct Decider
{
  const WindingNumber& Winding;
  const SampleGrid& Grid;
  const IndexBox& Extent;
  uint8_t* Inside;
  float* Value;
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
    this->Inside[at] = this->Winding.Inside(q, &w, &exact) ? 1 : 0;
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
    const WindingValue w = this->Winding.Evaluate(c);
    const double margin = std::fabs(std::fabs(w.Value) - 0.5);
    if (margin > w.Bound)
    {
      const double gradient = this->Winding.GradientBound(c, radius);
      if (margin > w.Bound + radius * gradient)
      {
        const uint8_t answer = std::fabs(w.Value) > 0.5 ? 1 : 0;
        for (int k = lo[2]; k <= hi[2]; ++k)
        {
          for (int j = lo[1]; j <= hi[1]; ++j)
          {
            uint8_t* row = this->Inside + this->Index(lo[0], j, k);
            std::fill(row, row + (hi[0] - lo[0] + 1), answer);
          }
        }
        this->Stats.BlockSamples += count;
        return;
      }
    }
    // Eight halves (or fewer along axes of one sample).
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

WindingSignStatistics WindingSigns(const WindingNumber& winding,
  const SampleGrid& grid,
  const IndexBox& extent,
  uint8_t* inside,
  float* value,
  bool blocks,
  const ParallelFor& parallelFor)
{
  const int n[3] = { extent.Size(0), extent.Size(1), extent.Size(2) };
  const int64_t stride[3] = { 1, n[0], int64_t(n[0]) * n[1] };
  // With values wanted, or no blocks, every sample alone.
  const int size = value || !blocks ? 1 : TopBlock;
  const int b[3] = { (n[0] + size - 1) / size, (n[1] + size - 1) / size, (n[2] + size - 1) / size };
  std::atomic<int64_t> blockSamples{ 0 }, evaluated{ 0 }, exact{ 0 };
  parallelFor(int64_t(b[0]) * b[1] * b[2],
    size == 1 ? 256 : 1,
    [&](int64_t begin, int64_t end)
    {
      Decider decider{
        winding, grid, extent, inside, value, { stride[0], stride[1], stride[2] }, {}
      };
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

} // namespace vtkdf
