// WindingSigns: inside or outside (|w| > 1/2, WindingNumber.h) at every sample of a grid,
// without evaluating w at every sample where a bound proves the answer for a block.
//
// w is harmonic off the surface. For a block of samples with centre c and half-diagonal
// r, every sample y of it has |w(y) - w(c)| <= r G, G = WindingNumber::GradientBound(c, r)
// (a bound of |grad w| over the block's ball, from the triangles' areas and distances).
// So when ||w(c)| - 1/2| exceeds the evaluation's error bound plus r G, the whole block
// takes c's answer; otherwise it splits in eight, down to single samples, which
// WindingNumber::Inside decides (exactly where the approximation cannot). The answer is
// the same as deciding every sample alone; only the work differs. Blocks start at 8^3
// samples; the ones within a few samples of the surface end as single samples.
#ifndef vtkdf_WindingSigns_h
#define vtkdf_WindingSigns_h

#include "Parallel.h"
#include "SampleGrid.h"
#include "WindingNumber.h"

#include <cstdint>

namespace vtkdf
{

struct WindingSignStatistics
{
  int64_t BlockSamples = 0; // samples decided by a block of more than one sample
  int64_t Evaluated = 0;    // samples decided alone
  int64_t Exact = 0;        // of those, decided by the exact sum
};

/// Writes inside[v] (1 or 0) for every sample v of `extent` on `grid` (x fastest, from
/// extent.Lo). With `value`, also w at every sample (every sample is then evaluated
/// alone). With `blocks` off, every sample is decided alone (the reference).
WindingSignStatistics WindingSigns(const WindingNumber& winding,
  const SampleGrid& grid,
  const IndexBox& extent,
  uint8_t* inside,
  float* value,
  bool blocks,
  const ParallelFor& parallelFor);

} // namespace vtkdf

#endif
