// ExactSum: the exact sum of non-negative doubles in a fixed-point accumulator that spans
// the whole range of doubles, so that a sum does not depend on the order of its terms or
// on how they were split: the same bits on any number of threads or processes.
#ifndef vtkdf_ExactSum_h
#define vtkdf_ExactSum_h

#include <cmath>
#include <cstdint>

namespace vtkdf
{

class ExactSum
{
public:
  /// 32-bit digits from 2^-1074 (the smallest subnormal) past 2^1024.
  static constexpr int Digits = 68;

  /// Adds x (finite, >= 0; others are not counted).
  void Add(double x)
  {
    if (!(x > 0) || !std::isfinite(x))
    {
      return;
    }
    int exponent = 0;
    const double fraction = std::frexp(x, &exponent); // x = fraction * 2^exponent
    uint64_t mantissa = static_cast<uint64_t>(std::ldexp(fraction, 53));
    int bit = exponent - 53 + 1074; // the mantissa's lowest bit, counted from 2^-1074
    if (bit < 0)
    {
      // A subnormal: its low bits are zeros.
      mantissa >>= -bit;
      bit = 0;
    }
    const unsigned __int128 shifted = static_cast<unsigned __int128>(mantissa) << (bit % 32);
    const int digit = bit / 32;
    this->Digit[digit] += static_cast<int64_t>(shifted & 0xffffffffu);
    this->Digit[digit + 1] += static_cast<int64_t>((shifted >> 32) & 0xffffffffu);
    this->Digit[digit + 2] += static_cast<int64_t>(shifted >> 64);
    // Each digit holds 2^31 additions of less than 2^32 before it could overflow.
    if (++this->Pending == (int64_t(1) << 30))
    {
      this->Normalize();
    }
  }

  /// Carries every digit's excess into the next: the representation of the sum is then
  /// unique, each digit below 2^32 (the last holds what is left).
  void Normalize()
  {
    for (int d = 0; d + 1 < Digits; ++d)
    {
      this->Digit[d + 1] += this->Digit[d] >> 32;
      this->Digit[d] &= 0xffffffff;
    }
    this->Pending = 0;
  }

  /// The sum as a double: a function of the exact sum alone (within a few units in the
  /// last place of it).
  double Value() const
  {
    ExactSum normal = *this;
    normal.Normalize();
    double value = 0;
    for (int d = Digits - 1; d >= 0; --d)
    {
      value += std::ldexp(static_cast<double>(normal.Digit[d]), 32 * d - 1074);
    }
    return value;
  }

  /// The digits (to add up across processes: digit by digit, then Normalize).
  int64_t Digit[Digits] = {};

private:
  int64_t Pending = 0;
};

} // namespace vtkdf

#endif
