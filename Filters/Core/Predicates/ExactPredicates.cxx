#include "Predicates/ExactPredicates.h"

#include <boost/multiprecision/cpp_int.hpp>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>

namespace vtkdf
{
namespace
{
using Integer = boost::multiprecision::cpp_int;

// The unit roundoff of doubles, 2^-53.
constexpr double Epsilon = 0x1p-53;

// Differences within this range have products of two and three of them far from
// underflow and overflow, where the first-stage error bounds hold.
bool InFilterRange(double difference)
{
  const double magnitude = std::abs(difference);
  return difference == 0 || (magnitude > 1e-90 && magnitude < 1e90);
}

// `count` doubles as integers scaled by a common power of two (2 to the least exponent
// of their nonzero ones' 53-bit integer significands): exact.
template<int N>
void ToScaledIntegers(const double (&values)[N], Integer (&integers)[N])
{
  int64_t significand[N];
  int exponent[N];
  int least = INT_MAX;
  for (int k = 0; k < N; ++k)
  {
    int e = 0;
    const double fraction = std::frexp(values[k], &e); // values[k] = fraction 2^e
    significand[k] = static_cast<int64_t>(std::ldexp(fraction, 53));
    exponent[k] = e - 53;
    if (significand[k] != 0)
    {
      least = std::min(least, exponent[k]);
    }
  }
  for (int k = 0; k < N; ++k)
  {
    integers[k] = significand[k];
    if (significand[k] != 0)
    {
      integers[k] <<= static_cast<unsigned>(exponent[k] - least);
    }
  }
}

int Sign(const Integer& x)
{
  return x.sign();
}

int ExactOrient3D(const double a[3], const double b[3], const double c[3], const double d[3])
{
  const double values[12] = {
    a[0], a[1], a[2], b[0], b[1], b[2], c[0], c[1], c[2], d[0], d[1], d[2]
  };
  Integer x[12];
  ToScaledIntegers(values, x);
  const Integer ux = x[3] - x[0], uy = x[4] - x[1], uz = x[5] - x[2];
  const Integer vx = x[6] - x[0], vy = x[7] - x[1], vz = x[8] - x[2];
  const Integer wx = x[9] - x[0], wy = x[10] - x[1], wz = x[11] - x[2];
  const Integer det =
    wx * (uy * vz - uz * vy) + wy * (uz * vx - ux * vz) + wz * (ux * vy - uy * vx);
  return Sign(det);
}

int ExactOrient2D(const double a[3], const double b[3], const double c[3], int i, int j)
{
  const double values[6] = { a[i], a[j], b[i], b[j], c[i], c[j] };
  Integer x[6];
  ToScaledIntegers(values, x);
  const Integer det = (x[2] - x[0]) * (x[5] - x[1]) - (x[3] - x[1]) * (x[4] - x[0]);
  return Sign(det);
}
} // namespace

int Orient3D(const double a[3], const double b[3], const double c[3], const double d[3])
{
  const double ux = b[0] - a[0], uy = b[1] - a[1], uz = b[2] - a[2];
  const double vx = c[0] - a[0], vy = c[1] - a[1], vz = c[2] - a[2];
  const double wx = d[0] - a[0], wy = d[1] - a[1], wz = d[2] - a[2];
  const double nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
  const double det = wx * nx + wy * ny + wz * nz;
  const double permanent = std::abs(wx) * (std::abs(uy * vz) + std::abs(uz * vy)) +
    std::abs(wy) * (std::abs(uz * vx) + std::abs(ux * vz)) +
    std::abs(wz) * (std::abs(ux * vy) + std::abs(uy * vx));
  // Shewchuk's bound for this expression is (7 + 56 eps) eps times the permanent.
  const double bound = 8 * Epsilon * permanent;
  const bool inRange = InFilterRange(ux) && InFilterRange(uy) && InFilterRange(uz) &&
    InFilterRange(vx) && InFilterRange(vy) && InFilterRange(vz) && InFilterRange(wx) &&
    InFilterRange(wy) && InFilterRange(wz);
  if (inRange && std::abs(det) > bound)
  {
    return det > 0 ? 1 : -1;
  }
  return ExactOrient3D(a, b, c, d);
}

int Orient2D(const double a[3], const double b[3], const double c[3], int i, int j)
{
  const double ux = b[i] - a[i], uy = b[j] - a[j];
  const double vx = c[i] - a[i], vy = c[j] - a[j];
  const double left = ux * vy, right = uy * vx;
  const double det = left - right;
  // Shewchuk's bound for this expression is (3 + 16 eps) eps (|left| + |right|).
  const double bound = 4 * Epsilon * (std::abs(left) + std::abs(right));
  const bool inRange =
    InFilterRange(ux) && InFilterRange(uy) && InFilterRange(vx) && InFilterRange(vy);
  if (inRange && std::abs(det) > bound)
  {
    return det > 0 ? 1 : -1;
  }
  return ExactOrient2D(a, b, c, i, j);
}

bool Collinear(const double a[3], const double b[3], const double c[3])
{
  // (b - a) x (c - a) is zero exactly when its three components, the orientations of
  // the projections onto the coordinate planes, are.
  return Orient2D(a, b, c, 0, 1) == 0 && Orient2D(a, b, c, 1, 2) == 0 &&
    Orient2D(a, b, c, 2, 0) == 0;
}
} // namespace vtkdf
