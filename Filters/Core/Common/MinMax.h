// MinMax: std::max and std::min of doubles, without branches. GCC compiles some uses of
// std::max(a, b) (a < b ? b : a) as a compare and a branch, which costs a misprediction
// wherever the data decides; SSE2's maxsd and minsd select the same operand in every
// case, NaN and signed zeros included: maxsd(x, y) is x > y ? x : y, so
// std::max(a, b) == maxsd(b, a), and std::min(a, b) (b < a ? b : a) == minsd(b, a).
#ifndef vtkdf_MinMax_h
#define vtkdf_MinMax_h

#include <algorithm>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace vtkdf
{

/// std::max(a, b), the same result in every case.
inline double Max(double a, double b)
{
#if defined(__SSE2__)
  return _mm_cvtsd_f64(_mm_max_sd(_mm_set_sd(b), _mm_set_sd(a)));
#else
  return std::max(a, b);
#endif
}

/// std::min(a, b), the same result in every case.
inline double Min(double a, double b)
{
#if defined(__SSE2__)
  return _mm_cvtsd_f64(_mm_min_sd(_mm_set_sd(b), _mm_set_sd(a)));
#else
  return std::min(a, b);
#endif
}

} // namespace vtkdf

#endif
