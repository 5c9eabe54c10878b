// Rounding: ceil, floor and round-half-away of a double to an integer by truncation.
// GCC expands std::ceil and std::floor on baseline x86-64 (no SSE4.1) into a sequence of
// compares and conversions; in the per-lane and per-row loops of the voxelizer and the
// scan that cost more than the conversion itself. The results equal the library's for
// arguments within the integer type's range.
#ifndef vtkdf_Rounding_h
#define vtkdf_Rounding_h

#include <cstdint>

namespace vtkdf
{

/// static_cast<int>(std::ceil(x)) for -2^31 < x < 2^31.
inline int CeilToInt(double x)
{
  const int whole = static_cast<int>(x); // truncates toward zero
  return whole + (whole < x);
}

/// static_cast<int>(std::floor(x)) for -2^31 < x < 2^31.
inline int FloorToInt(double x)
{
  const int whole = static_cast<int>(x);
  return whole - (whole > x);
}

/// std::llround(x) for |x| < 2^62: the fractional part x - trunc(x) is exact, so halfway
/// cases round away from zero as llround rounds them.
inline int64_t RoundHalfAway(double x)
{
  const int64_t whole = static_cast<int64_t>(x);
  const double fraction = x - static_cast<double>(whole);
  return whole + (fraction >= 0.5) - (fraction <= -0.5);
}

} // namespace vtkdf

#endif
