#ifndef vtkdf_ArcTangent_h
#define vtkdf_ArcTangent_h

#include <cmath>

namespace vtkdf
{

/// The constants of ArcTangent2, computed once. A shader that gives ArcTangent2's bits
/// (Shaders/ArcTangent2.glsl) takes them as uniforms, so that both read the same doubles.
struct ArcTangentTable
{
  static constexpr int Points = 9; // atan(k / 8), k = 0..8
  static constexpr int Terms = 8;  // the odd Taylor terms z, z^3, ..., z^15
  double AtPoint[Points];
  double Coefficient[Terms]; // (-1)^n / (2n + 1)
  double Pi, HalfPi;
};

inline const ArcTangentTable& ArcTangentConstants()
{
  static const ArcTangentTable table = []
  {
    ArcTangentTable t;
    for (int k = 0; k < ArcTangentTable::Points; ++k)
    {
      t.AtPoint[k] = std::atan(k / 8.0);
    }
    for (int n = 0; n < ArcTangentTable::Terms; ++n)
    {
      t.Coefficient[n] = (n % 2 ? -1.0 : 1.0) / (2 * n + 1);
    }
    t.Pi = M_PI;
    t.HalfPi = M_PI / 2;
    return t;
  }();
  return table;
}

/// atan2(y, x) in [-pi, pi] (y = 0 of either sign gives 0 for x >= 0, else pi; -pi only
/// as the rounding of an angle just above it, as std::atan2 gives it) within a few ulps, from +, -,
/// * and / alone, so that a GL's double arithmetic, which has no atan, gives the same bits. The
/// ratio t of the smaller to the larger |y|, |x| lies within 1/16 of a point c = k/8, and atan t =
/// atan c + atan z, z = (t - c) / (1 + t c), |z| <= 1/16: eight terms of atan's Taylor series leave
/// an error below 2^-64 |z|.
inline double ArcTangent2(double y, double x)
{
  const ArcTangentTable& table = ArcTangentConstants();
  if (y == 0)
  {
    return x >= 0 ? 0.0 : table.Pi;
  }
  if (x == 0)
  {
    return y > 0 ? table.HalfPi : -table.HalfPi;
  }
  const double ax = std::fabs(x), ay = std::fabs(y);
  const bool steep = ay > ax;
  const double t = steep ? ax / ay : ay / ax; // in (0, 1]
  if (!(t <= 1))
  {
    return t; // a NaN operand (or two infinities)
  }
  const int k = static_cast<int>(t * 8 + 0.5);
  const double c = k * 0.125;
  const double z = (t - c) / (1 + t * c); // t - c is exact (Sterbenz)
  const double z2 = z * z;
  double series = table.Coefficient[ArcTangentTable::Terms - 1];
  for (int n = ArcTangentTable::Terms - 2; n >= 0; --n)
  {
    series = series * z2 + table.Coefficient[n];
  }
  double angle = table.AtPoint[k] + z * series;
  if (steep)
  {
    angle = table.HalfPi - angle;
  }
  if (x < 0)
  {
    angle = table.Pi - angle;
  }
  return y < 0 ? -angle : angle;
}

} // namespace vtkdf

#endif
