// SliceDomain: a site's domain (an intersection of half-spaces) cut by the slice k and
// clipped to a rectangle of sample indices: the convex polygon that is scan-converted.
// Shaders/LinearFactorDomain.glsl performs the same clipping on the GPU.
#ifndef vtkdf_SliceDomain_h
#define vtkdf_SliceDomain_h

#include <cmath>

namespace vtkdf
{

/// A*i + B*j + C*k + D >= 0, in sample-index coordinates.
struct IndexPlane
{
  double A, B, C, D;
};

struct SlicePolygon
{
  static constexpr int MaxPlanes = 60;
  static constexpr int MaxVertices = 4 + MaxPlanes;
  int Count = 0;
  double X[MaxVertices];
  double Y[MaxVertices];
};

/// Clips the rectangle [x0,x1]x[y0,y1] by the planes restricted to slice k
/// (Sutherland-Hodgman). Returns false when nothing is left.
inline bool ClipSlice(const IndexPlane* planes,
  int count,
  double k,
  double x0,
  double x1,
  double y0,
  double y1,
  SlicePolygon& poly)
{
  double bx[SlicePolygon::MaxVertices], by[SlicePolygon::MaxVertices];
  double* inX = poly.X;
  double* inY = poly.Y;
  double* outX = bx;
  double* outY = by;
  int n = 4;
  inX[0] = x0, inY[0] = y0;
  inX[1] = x1, inY[1] = y0;
  inX[2] = x1, inY[2] = y1;
  inX[3] = x0, inY[3] = y1;
  double f[SlicePolygon::MaxVertices];
  for (int p = 0; p < count && n > 0; ++p)
  {
    const double a = planes[p].A, b = planes[p].B, c = planes[p].C * k + planes[p].D;
    // Each corner's side once; a plane that keeps every corner changes nothing.
    bool all = true, none = true;
    for (int v = 0; v < n; ++v)
    {
      f[v] = a * inX[v] + b * inY[v] + c;
      all = all && f[v] >= 0;
      none = none && !(f[v] >= 0);
    }
    if (all)
    {
      continue;
    }
    if (none)
    {
      n = 0;
      break;
    }
    int m = 0;
    for (int v = 0; v < n; ++v)
    {
      const int w = (v + 1 == n) ? 0 : v + 1;
      const double fv = f[v], fw = f[w];
      if (fv >= 0)
      {
        outX[m] = inX[v], outY[m] = inY[v], ++m;
      }
      if ((fv >= 0) != (fw >= 0))
      {
        const double t = fv / (fv - fw);
        outX[m] = inX[v] + t * (inX[w] - inX[v]);
        outY[m] = inY[v] + t * (inY[w] - inY[v]);
        ++m;
      }
    }
    n = m;
    double* tx = inX;
    double* ty = inY;
    inX = outX, inY = outY;
    outX = tx, outY = ty;
  }
  if (inX != poly.X)
  {
    for (int v = 0; v < n; ++v)
    {
      poly.X[v] = inX[v], poly.Y[v] = inY[v];
    }
  }
  poly.Count = n;
  return n > 0;
}

/// The x-range of the convex polygon on the row y (false when the row misses it).
inline bool RowSpan(const SlicePolygon& poly, double y, double& xl, double& xr)
{
  xl = HUGE_VAL;
  xr = -HUGE_VAL;
  for (int v = 0; v < poly.Count; ++v)
  {
    const int w = (v + 1 == poly.Count) ? 0 : v + 1;
    const double yv = poly.Y[v], yw = poly.Y[w];
    if ((yv <= y && y <= yw) || (yw <= y && y <= yv))
    {
      double x;
      if (yv == yw)
      {
        xl = std::fmin(xl, std::fmin(poly.X[v], poly.X[w]));
        xr = std::fmax(xr, std::fmax(poly.X[v], poly.X[w]));
        continue;
      }
      x = poly.X[v] + (y - yv) / (yw - yv) * (poly.X[w] - poly.X[v]);
      xl = std::fmin(xl, x);
      xr = std::fmax(xr, x);
    }
  }
  return xl <= xr;
}

} // namespace vtkdf

#endif
