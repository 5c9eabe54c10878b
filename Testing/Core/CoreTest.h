// CoreTest: what the tests of the VTK-free cores share: a failure counter, a check that
// prints what failed (printf-style), and the verdict that is the test's exit status.
#ifndef vtkdf_CoreTest_h
#define vtkdf_CoreTest_h

#include <cstdarg>
#include <cstdio>

namespace vtkdf::coretest
{
inline int Failures = 0;

/// Counts a failure when `ok` is false and prints "FAIL: " and the message (the first 30
/// failures; the count covers all).
#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
inline void
Check(bool ok, const char* format, ...)
{
  if (ok || ++Failures > 30)
  {
    return;
  }
  std::va_list arguments;
  va_start(arguments, format);
  std::printf("FAIL: ");
  std::vprintf(format, arguments);
  std::printf("\n");
  va_end(arguments);
}

/// Prints the number of failures; 0 when there was none, else 1.
inline int Verdict()
{
  std::printf("%d failures\n", Failures);
  return Failures ? 1 : 0;
}
} // namespace vtkdf::coretest

#endif
