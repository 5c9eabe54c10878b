// WindingSigns: inside or outside (|w| > 1/2, WindingNumber.h) at every sample of a grid,
// without evaluating w at every sample where a bound proves the answer for a block.
//
// w is harmonic off the surface. For a block of samples with centre c and half-diagonal
// r, w at c, its gradient (each within its error bound) and H, a bound of the norm of
// w's Hessian over the block's ball (WindingNumber::HessianBound, from the triangles'
// areas and distances), give every sample y of the block w(y) within
//   Bound + |y - c| GradientBound + |y - c|^2 H / 2
// of w(c) + grad w(c) . (y - c). Where that decides every sample of the block, the
// block is done; otherwise it splits in eight, down to single samples, which
// WindingNumber::Inside decides (exactly where the approximation cannot). The answer is
// the same as deciding every sample alone; only the work differs. Blocks start at 8^3
// samples; the first-order test decides blocks down to about three spacings from the
// surface (H grows as 1/g^4 near it), where the blocks end as single samples.
//
// A closed mesh (every edge used as often in each direction) takes another route with
// the same answer: w is then the signed count of the surface's crossings along each grid
// line (WindingCrossings.h), and only the samples on the surface are decided alone. An
// open mesh is closed by cones over its boundary: w = N - w_cones, whose blocks decide
// up to the mesh itself.
#ifndef vtkdf_WindingSigns_h
#define vtkdf_WindingSigns_h

#include "Common/LargeVector.h"
#include "Common/Parallel.h"
#include "Common/SampleGrid.h"
#include "Winding/WindingNumber.h"

#include <cstdint>
#include <string>
#include <vector>

namespace vtkdf
{
class HeadlessGL;

struct WindingSignStatistics
{
  int64_t BlockSamples = 0; // samples decided by a block of more than one sample
  int64_t LineSamples = 0;  // samples of a closed mesh decided by crossings along lines
  int64_t Evaluated = 0;    // samples decided alone
  int64_t Exact = 0;        // of those, decided by the exact sum
  bool GPU = false;         // decided on the GPU (WindingSignsGPU)
  // Of those, the samples a software renderer could not finish within its loop limit
  // (HeadlessGL::InvocationLoopBudget), decided on the CPU by the same function.
  int64_t CPUSamples = 0;
};

/// What WindingSigns writes besides the signs, and what it may use.
struct WindingSignOptions
{
  /// When set, w at every sample (every sample is then evaluated alone).
  float* Value = nullptr;
  /// Optional, the layout of the signs: each sample's distance to the surface (or a lower
  /// bound of it) times DistanceScale, in the grid's units. Blocks that it shows near
  /// the surface split without trying: less work, the same answer.
  const float* Distance = nullptr;
  double DistanceScale = 1;
  /// Off: every sample decided alone (the reference for the blocks and the crossings).
  bool Blocks = true;
  /// ComputeWindingSigns with a GPU context: the signs on the CPU all the same where the
  /// crossings decide them (CrossingsDecide: closed, or closed by cones), in less time
  /// than any winding pass (Backend Auto's choice).
  bool CrossingsOnCPU = false;
  /// WindingSignsGPU: the loop iterations a sample may run on the GPU (0: as the context
  /// allows, HeadlessGL::InvocationLoopBudget); the rest go to the CPU. For tests.
  int IterationBudget = 0;
};

/// Writes inside[v] (1 or 0) for every sample v of `extent` on `grid` (x fastest, from
/// extent.Lo).
WindingSignStatistics WindingSigns(const WindingNumber& winding,
  const SampleGrid& grid,
  const IndexBox& extent,
  uint8_t* inside,
  const WindingSignOptions& options,
  const ParallelFor& parallelFor);

/// WindingSigns' blocks alone, without the crossings' routes: w from `winding`, or, with
/// `offsets` (N at every sample of `extent`, WindingCrossings.h's CrossingCounts) and
/// `surface`, w = N - w_C for an open mesh closed by cones C (`winding` the cones'), the
/// samples that this does not decide decided by `surface`.
WindingSignStatistics DecideWindingBlocks(const WindingNumber& winding,
  const SampleGrid& grid,
  const IndexBox& extent,
  uint8_t* inside,
  const WindingSignOptions& options,
  const ParallelFor& parallelFor,
  const int8_t* offsets = nullptr,
  const WindingNumber* surface = nullptr);

/// The side that one first-order bound about the centre of `box` proves for all its
/// samples (WindingSigns' test of a block, over the box's ball): 1 inside, 0 outside, -1
/// none. Of w, or with `offset` of offset - w (a chain closed by cones whose count N is
/// `offset` throughout the box).
int WindingBoxSide(const WindingNumber& winding,
  const SampleGrid& grid,
  const IndexBox& box,
  const int* offset = nullptr);

/// The family's entry point: on the CPU, WindingSigns (a closed mesh's crossings with the
/// hierarchy of `triangles`, 3 ids each into xyz `points`, built only for samples on the
/// surface); on the GPU when `gl` is given (but where the crossings decide, with
/// options.CrossingsOnCPU), WindingSignsGPU (which honours options.Value only). False
/// and `error` when the GPU cannot run it.
bool ComputeWindingSigns(const LargeVector<double>& points,
  const LargeVector<int64_t>& triangles,
  const SampleGrid& grid,
  const IndexBox& extent,
  uint8_t* inside,
  const WindingSignOptions& options,
  HeadlessGL* gl,
  const ParallelFor& parallelFor,
  WindingSignStatistics& stats,
  std::string& error);

} // namespace vtkdf

#endif
