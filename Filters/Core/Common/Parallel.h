// The few execution hooks the VTK-free cores need from their host: a parallel loop
// (vtkSMPTools in the module, std::thread in stand-alone programs) and progress.
#ifndef vtkdf_Parallel_h
#define vtkdf_Parallel_h

#include <cstdint>
#include <functional>

namespace vtkdf
{
/// Calls body(begin, end) on disjoint sub-ranges of [0, n) covering it, possibly in parallel.
using ParallelFor =
  std::function<void(int64_t n, int64_t grain, const std::function<void(int64_t, int64_t)>& body)>;

/// Receives the fraction done; returns false to abort.
using ProgressCallback = std::function<bool(double)>;
} // namespace vtkdf

#endif
