// ProcessMemory: the process's resident memory, the measure behind every "peak memory"
// the module reports (vtkdf --timing's peak_memory_mb, a filter's GetLastPeakMemory()).
//
// A run's peak is the most resident memory the process held during the run, less what
// it held when the run began: what the run's own allocations (and the pages they
// touched) cost at their worst. On Linux the kernel's high-water mark (VmHWM) gives the
// exact peak whenever the run raised it; when an earlier peak of the process was higher
// (a second run in the same process), the samples taken at the run's stage ends bound it
// from below. Elsewhere nothing is measured (-1).
#ifndef vtkdf_ProcessMemory_h
#define vtkdf_ProcessMemory_h

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>

namespace vtkdf
{
/// Resident bytes now (`peak` false) or at the process's high-water mark (`peak` true),
/// or -1 where the system does not say.
inline int64_t ResidentBytes(bool peak)
{
#ifdef __linux__
  std::FILE* status = std::fopen("/proc/self/status", "r");
  if (!status)
  {
    return -1;
  }
  const char* key = peak ? "VmHWM:" : "VmRSS:";
  char line[256];
  long long kib = -1;
  while (std::fgets(line, sizeof(line), status))
  {
    if (std::strncmp(line, key, std::strlen(key)) == 0)
    {
      std::sscanf(line + std::strlen(key), "%lld", &kib);
      break;
    }
  }
  std::fclose(status);
  return kib < 0 ? -1 : int64_t(kib) * 1024;
#else
  (void)peak;
  return -1;
#endif
}

/// The peak of one run (see above): Start() when it begins, Sample() at each stage's
/// end, Peak() when it is over.
class RunMemory
{
public:
  void Start()
  {
    this->Begin = ResidentBytes(false);
    this->BeginPeak = ResidentBytes(true);
    this->Sampled = this->Begin;
  }
  void Sample() { this->Sampled = std::max(this->Sampled, ResidentBytes(false)); }
  /// Bytes above the run's start at its peak; -1 when unknown.
  int64_t Peak() const
  {
    if (this->Begin < 0)
    {
      return -1;
    }
    const int64_t peak = ResidentBytes(true);
    const int64_t top =
      peak > this->BeginPeak ? peak : std::max(this->Sampled, ResidentBytes(false));
    return std::max<int64_t>(0, top - this->Begin);
  }

private:
  int64_t Begin = -1, BeginPeak = -1, Sampled = -1;
};
} // namespace vtkdf

#endif
