// FloatBounds: a double rounded to the float on either side of it, for boxes stored in
// float that must still hold what they bound.
#ifndef vtkdf_FloatBounds_h
#define vtkdf_FloatBounds_h

#include <cmath>

namespace vtkdf
{

/// The largest float <= x.
inline float FloatBelow(double x)
{
  const float f = static_cast<float>(x);
  return f > x ? std::nextafter(f, -HUGE_VALF) : f;
}

/// The smallest float >= x.
inline float FloatAbove(double x)
{
  const float f = static_cast<float>(x);
  return f < x ? std::nextafter(f, HUGE_VALF) : f;
}

} // namespace vtkdf

#endif
