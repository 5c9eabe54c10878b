// Exact double-precision point-to-primitive distances: the brute-force reference of
// the tests (independent of the sites/domains code under test).
#ifndef vtkdf_ExactDistance_h
#define vtkdf_ExactDistance_h

#include <algorithm>
#include <cmath>

namespace vtkdf
{
namespace reference
{

inline void ClosestOnSegment(const double p[3], const double a[3], const double b[3], double c[3])
{
  double ab[3], ap[3], l2 = 0, t = 0;
  for (int k = 0; k < 3; ++k)
  {
    ab[k] = b[k] - a[k];
    ap[k] = p[k] - a[k];
    l2 += ab[k] * ab[k];
    t += ap[k] * ab[k];
  }
  t = l2 > 0 ? std::min(1.0, std::max(0.0, t / l2)) : 0.0;
  for (int k = 0; k < 3; ++k)
  {
    c[k] = a[k] + t * ab[k];
  }
}

/// Closest point of triangle abc to p (Ericson, Real-Time Collision Detection, 5.1.5).
inline void ClosestOnTriangle(const double p[3],
  const double a[3],
  const double b[3],
  const double c[3],
  double out[3])
{
  auto dot = [](const double* u, const double* v)
  { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; };
  double ab[3], ac[3], ap[3], bp[3], cp[3];
  for (int k = 0; k < 3; ++k)
  {
    ab[k] = b[k] - a[k];
    ac[k] = c[k] - a[k];
    ap[k] = p[k] - a[k];
    bp[k] = p[k] - b[k];
    cp[k] = p[k] - c[k];
  }
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  auto set = [&](const double* q) { std::copy(q, q + 3, out); };
  auto lerp = [&](const double* u, const double* w, double t)
  {
    for (int k = 0; k < 3; ++k)
    {
      out[k] = u[k] + t * (w[k] - u[k]);
    }
  };
  if (d1 <= 0 && d2 <= 0)
  {
    return set(a);
  }
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3)
  {
    return set(b);
  }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0)
  {
    return lerp(a, b, d1 / (d1 - d3));
  }
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6)
  {
    return set(c);
  }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0)
  {
    return lerp(a, c, d2 / (d2 - d6));
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
  {
    return lerp(b, c, (d4 - d3) / ((d4 - d3) + (d5 - d6)));
  }
  const double denom = va + vb + vc;
  if (!(std::fabs(denom) > 0))
  {
    // Degenerate triangle: closest of its three edges.
    double best = HUGE_VAL, q[3];
    const double* v[3] = { a, b, c };
    for (int e = 0; e < 3; ++e)
    {
      ClosestOnSegment(p, v[e], v[(e + 1) % 3], q);
      const double d = (q[0] - p[0]) * (q[0] - p[0]) + (q[1] - p[1]) * (q[1] - p[1]) +
        (q[2] - p[2]) * (q[2] - p[2]);
      if (d < best)
      {
        best = d;
        set(q);
      }
    }
    return;
  }
  const double v = vb / denom, w = vc / denom;
  for (int k = 0; k < 3; ++k)
  {
    out[k] = a[k] + ab[k] * v + ac[k] * w;
  }
}

} // namespace reference
} // namespace vtkdf

#endif
