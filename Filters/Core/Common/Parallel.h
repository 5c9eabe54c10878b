// The few execution hooks the VTK-free cores need from their host: a parallel loop
// (vtkSMPTools in the module, std::thread in stand-alone programs), progress with abort,
// and the time each stage took (and the run's peak memory).
#ifndef vtkdf_Parallel_h
#define vtkdf_Parallel_h

#include "Common/ProcessMemory.h"

#include <chrono>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace vtkdf
{
/// Calls body(begin, end) on disjoint sub-ranges of [0, n) covering it, possibly in parallel.
using ParallelFor =
  std::function<void(int64_t n, int64_t grain, const std::function<void(int64_t, int64_t)>& body)>;

/// A ParallelFor that runs the whole range at once on the calling thread: for work items
/// small enough that their callers run many of them in parallel.
inline void SerialFor(int64_t n, int64_t, const std::function<void(int64_t, int64_t)>& body)
{
  if (n > 0)
  {
    body(0, n);
  }
}

/// Receives the fraction done; returns false to abort.
using ProgressCallback = std::function<bool(double)>;

/// Seconds per stage of a run, in the order the stages ended: each stage runs from the
/// end of the previous one (or the timer's start) to its End().
class StageTimer
{
public:
  StageTimer()
  {
    this->Start = this->Last = Now();
    this->Memory.Start();
  }
  void End(const char* name)
  {
    const double now = Now();
    this->Stages.emplace_back(name, now - this->Last);
    this->Last = now;
    this->Memory.Sample();
  }
  /// Seconds since the timer started.
  double Elapsed() const { return Now() - this->Start; }
  /// The run's peak memory above its start, in bytes (ProcessMemory.h); -1: unknown.
  int64_t PeakMemory() const { return this->Memory.Peak(); }
  const std::vector<std::pair<std::string, double>>& Times() const { return this->Stages; }

private:
  static double Now()
  {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
  }
  double Start, Last;
  std::vector<std::pair<std::string, double>> Stages;
  RunMemory Memory;
};

/// How a core's entry point runs: its loops, its progress (and abort), its stage times.
/// Every member may be left empty.
struct Execution
{
  ParallelFor For;
  ProgressCallback Progress;
  StageTimer* Stages = nullptr;

  /// Tells the fraction done; false when the host asks to abort.
  bool Report(double fraction) const { return !this->Progress || this->Progress(fraction); }
  void EndStage(const char* name) const
  {
    if (this->Stages)
    {
      this->Stages->End(name);
    }
  }
  /// The same hooks with progress mapped onto [from, to] of this run's.
  Execution Part(double from, double to) const
  {
    Execution part = *this;
    if (this->Progress)
    {
      const ProgressCallback whole = this->Progress;
      part.Progress = [whole, from, to](double f) { return whole(from + (to - from) * f); };
    }
    return part;
  }
};
} // namespace vtkdf

#endif
