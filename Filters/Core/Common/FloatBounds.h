// FloatBounds: a double rounded to the float on either side of it, for boxes stored in
// float that must still hold what they bound.
#ifndef vtkdf_FloatBounds_h
#define vtkdf_FloatBounds_h

#include <cstdint>
#include <cstring>

namespace vtkdf
{

/// The float next to f towards minus infinity (towards plus infinity with `up`), as
/// std::nextafter gives it, for f not NaN and not already the end it moves to. By the
/// bits, without the library call: the scan's sites round their boxes millions of times.
inline float NextFloat(float f, bool up)
{
  if (f == 0)
  {
    return up ? 1e-45f : -1e-45f; // the smallest subnormal, either side of zero
  }
  uint32_t bits;
  std::memcpy(&bits, &f, sizeof(bits));
  // Away from zero is one more in the bits' magnitude, towards zero one less.
  bits = ((f > 0) == up) ? bits + 1 : bits - 1;
  std::memcpy(&f, &bits, sizeof(f));
  return f;
}

/// The largest float <= x.
inline float FloatBelow(double x)
{
  const float f = static_cast<float>(x);
  return f > x ? NextFloat(f, false) : f;
}

/// The smallest float >= x.
inline float FloatAbove(double x)
{
  const float f = static_cast<float>(x);
  return f < x ? NextFloat(f, true) : f;
}

} // namespace vtkdf

#endif
