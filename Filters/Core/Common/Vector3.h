// Vector3: dot and cross products and equality of 3-vectors held as plain double[3], for
// the cores that work on raw coordinate arrays.
#ifndef vtkdf_Vector3_h
#define vtkdf_Vector3_h

#include <algorithm>
#include <cmath>

namespace vtkdf
{

inline double Dot(const double* u, const double* v)
{
  return u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
}

/// w = u x v (w must not alias u or v).
inline void Cross(const double* u, const double* v, double* w)
{
  w[0] = u[1] * v[2] - u[2] * v[1];
  w[1] = u[2] * v[0] - u[0] * v[2];
  w[2] = u[0] * v[1] - u[1] * v[0];
}

/// Whether u and v are the same point (coordinate by coordinate; -0 equals 0).
inline bool SamePoint(const double* u, const double* v)
{
  return u[0] == v[0] && u[1] == v[1] && u[2] == v[2];
}

/// Whether triangle abc, of distinct corners, is a proper face: twice its area above
/// `degenerate` times its longest side (the test of the sites and of the query tree).
/// Its normal, not normalized, into n and its length into area2. The longest side is
/// the square root of the largest squared side: the same double as the largest of the
/// roots, since a correctly rounded square root is monotonic.
inline bool ProperFace(const double* a,
  const double* b,
  const double* c,
  double degenerate,
  double n[3],
  double& area2)
{
  double e1[3], e2[3], e3[3];
  for (int k = 0; k < 3; ++k)
  {
    e1[k] = b[k] - a[k], e2[k] = c[k] - a[k], e3[k] = c[k] - b[k];
  }
  Cross(e1, e2, n);
  area2 = std::sqrt(Dot(n, n));
  const double longest = std::sqrt(std::max(Dot(e1, e1), std::max(Dot(e2, e2), Dot(e3, e3))));
  return area2 > degenerate * longest;
}

} // namespace vtkdf

#endif
