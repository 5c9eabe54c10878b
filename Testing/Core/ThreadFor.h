// The parallel loop the core tests hand to the VTK-free cores (ParallelFor in
// Filters/Core/Parallel.h): two std::threads, each on half of the range.
#ifndef vtkdf_ThreadFor_h
#define vtkdf_ThreadFor_h

#include <cstdint>
#include <functional>
#include <thread>

inline void ThreadFor(int64_t n, int64_t, const std::function<void(int64_t, int64_t)>& body)
{
  const int64_t half = n / 2;
  std::thread other([&] { body(half, n); });
  if (half > 0)
  {
    body(0, half);
  }
  other.join();
}

#endif
