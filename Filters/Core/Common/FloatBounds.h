// FloatBounds: a double rounded to the float on either side of it, for boxes stored in
// float that must still hold what they bound.
#ifndef vtkdf_FloatBounds_h
#define vtkdf_FloatBounds_h

#include <cstdint>
#include <cstring>

namespace vtkdf
{

// By the bits and without branches: the scan rounds a box for every site, millions of
// them, and whether a rounding went up or down is a coin toss the CPU cannot predict
// (branches there cost the bunny's scan at 128 samples 4 %).

/// The bits of the float one step from the float with bits `bits` (not NaN, not already
/// the end it moves to), towards minus infinity or, with `up`, plus infinity, as
/// std::nextafter gives it. Zero of either sign steps to the smallest subnormal.
inline uint32_t NextFloatBits(uint32_t bits, bool up)
{
  const uint32_t sign = 0x80000000u;
  // Zero takes the sign of the direction: the step from it then moves away from zero.
  const uint32_t isZero = static_cast<uint32_t>((bits & ~sign) == 0);
  bits = (bits & ~(isZero * sign)) | (isZero * (up ? 0u : sign));
  // Away from zero is one more in the bits' magnitude, towards zero one less.
  const uint32_t negative = bits >> 31;
  return up ? bits + 1 - 2 * negative : bits - 1 + 2 * negative;
}

/// f if keep, else the float with bits `other`, by a mask.
inline float SelectFloat(bool keep, float f, uint32_t other)
{
  uint32_t bits;
  std::memcpy(&bits, &f, sizeof(bits));
  const uint32_t mask = 0u - static_cast<uint32_t>(keep);
  bits = (bits & mask) | (other & ~mask);
  std::memcpy(&f, &bits, sizeof(f));
  return f;
}

/// The largest float <= x.
inline float FloatBelow(double x)
{
  const float f = static_cast<float>(x);
  uint32_t bits;
  std::memcpy(&bits, &f, sizeof(bits));
  return SelectFloat(!(f > x), f, NextFloatBits(bits, false));
}

/// The smallest float >= x.
inline float FloatAbove(double x)
{
  const float f = static_cast<float>(x);
  uint32_t bits;
  std::memcpy(&bits, &f, sizeof(bits));
  return SelectFloat(!(f < x), f, NextFloatBits(bits, true));
}

} // namespace vtkdf

#endif
