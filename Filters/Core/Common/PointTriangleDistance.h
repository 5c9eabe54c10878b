// PointTriangleDistance: the exact squared distance from a point to a segment and to a
// triangle, in double precision. The voxelizer's boundary rule (Voxels/), the segmented
// field's polygonizer (Segment/) and the proximity searches (Proximity/) use it;
// Shaders/TriangleDistance.glsl repeats it operation for operation for their GPU passes,
// so the file is compiled without fused multiply-adds.
#ifndef vtkdf_PointTriangleDistance_h
#define vtkdf_PointTriangleDistance_h

#include <algorithm>

namespace vtkdf
{

/// Where on a triangle abc (or segment ab) the closest point lies: a corner, an edge's
/// interior or the face's interior.
enum TriangleFeature : int
{
  AtCornerA = 0,
  AtCornerB = 1,
  AtCornerC = 2,
  OnEdgeAB = 3,
  OnEdgeBC = 4,
  OnEdgeCA = 5,
  InFace = 6
};

/// Squared distance from p to segment ab (a point when a = b); the closest point goes to
/// `closest` and where it lies (AtCornerA, AtCornerB or OnEdgeAB) to `feature` when given.
inline double SquaredDistanceToSegment(const double p[3],
  const double a[3],
  const double b[3],
  double* closest = nullptr,
  int* feature = nullptr)
{
  double ab[3], ap[3];
  double length2 = 0, along = 0;
  for (int k = 0; k < 3; ++k)
  {
    ab[k] = b[k] - a[k];
    ap[k] = p[k] - a[k];
    length2 += ab[k] * ab[k];
    along += ap[k] * ab[k];
  }
  const double t = length2 > 0 ? std::min(1.0, std::max(0.0, along / length2)) : 0.0;
  if (feature)
  {
    *feature = t <= 0 ? AtCornerA : (t >= 1 ? AtCornerB : OnEdgeAB);
  }
  double d2 = 0;
  for (int k = 0; k < 3; ++k)
  {
    const double e = a[k] + t * ab[k] - p[k];
    d2 += e * e;
    if (closest)
    {
      closest[k] = a[k] + t * ab[k];
    }
  }
  return d2;
}

/// Squared distance from p to the three edges of triangle abc (its distance when the
/// triangle is degenerate: a segment or a point), the first nearest edge's closest point
/// and feature as SquaredDistanceToTriangle gives them.
inline double SquaredDistanceToTriangleEdges(const double p[3],
  const double a[3],
  const double b[3],
  const double c[3],
  double* closest = nullptr,
  int* feature = nullptr)
{
  double onEdge[3][3];
  int at[3];
  const double d2[3] = { SquaredDistanceToSegment(p, a, b, onEdge[0], &at[0]),
    SquaredDistanceToSegment(p, b, c, onEdge[1], &at[1]),
    SquaredDistanceToSegment(p, c, a, onEdge[2], &at[2]) };
  const int e = d2[0] <= d2[1] ? (d2[0] <= d2[2] ? 0 : 2) : (d2[1] <= d2[2] ? 1 : 2);
  if (closest)
  {
    std::copy(onEdge[e], onEdge[e] + 3, closest);
  }
  if (feature)
  {
    // Edge e runs from corner e to corner e + 1.
    *feature = at[e] == OnEdgeAB ? OnEdgeAB + e : (e + (at[e] == AtCornerB)) % 3;
  }
  return d2[e];
}

/// Squared distance from p to triangle abc (Ericson, Real-Time Collision Detection,
/// 5.1.5); a degenerate triangle (collinear corners, repeated points) counts as the
/// segments it is made of. The closest point goes to `closest` and where it lies
/// (TriangleFeature) to `feature` when given.
inline double SquaredDistanceToTriangle(const double p[3],
  const double a[3],
  const double b[3],
  const double c[3],
  double* closest = nullptr,
  int* feature = nullptr)
{
  double ab[3], ac[3], ap[3], bp[3], cp[3];
  for (int k = 0; k < 3; ++k)
  {
    ab[k] = b[k] - a[k];
    ac[k] = c[k] - a[k];
    ap[k] = p[k] - a[k];
    bp[k] = p[k] - b[k];
    cp[k] = p[k] - c[k];
  }
  auto dot = [](const double* u, const double* v)
  { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; };
  double v = 0, w = 0;
  int where = InFace;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  const double vc = d1 * d4 - d3 * d2, vb = d5 * d2 - d1 * d6, va = d3 * d6 - d5 * d4;
  if (d1 <= 0 && d2 <= 0)
  {
    v = 0, w = 0, where = AtCornerA;
  }
  else if (d3 >= 0 && d4 <= d3)
  {
    v = 1, w = 0, where = AtCornerB;
  }
  else if (vc <= 0 && d1 >= 0 && d3 <= 0)
  {
    v = d1 / (d1 - d3), w = 0, where = OnEdgeAB;
  }
  else if (d6 >= 0 && d5 <= d6)
  {
    v = 0, w = 1, where = AtCornerC;
  }
  else if (vb <= 0 && d2 >= 0 && d6 <= 0)
  {
    v = 0, w = d2 / (d2 - d6), where = OnEdgeCA;
  }
  else if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
  {
    w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    v = 1 - w, where = OnEdgeBC;
  }
  else
  {
    // Only a proper triangle gets here with va + vb + vc = |ab x ac|^2 > 0; a degenerate
    // one (a segment or a point) is the union of its edges.
    const double area2 = va + vb + vc;
    if (!(area2 > 0))
    {
      return SquaredDistanceToTriangleEdges(p, a, b, c, closest, feature);
    }
    const double denominator = 1 / area2;
    v = vb * denominator, w = vc * denominator;
  }
  if (feature)
  {
    *feature = where;
  }
  double d2sum = 0;
  for (int k = 0; k < 3; ++k)
  {
    const double e = a[k] + v * ab[k] + w * ac[k] - p[k];
    d2sum += e * e;
    if (closest)
    {
      closest[k] = a[k] + v * ab[k] + w * ac[k];
    }
  }
  return d2sum;
}

} // namespace vtkdf

#endif
