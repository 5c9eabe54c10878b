#include "Segment/TriangleCrossings.h"

#include "Predicates/ExactPredicates.h"

#include <algorithm>

namespace vtkdf
{
namespace
{
// Whether a and b have opposite strict signs.
bool Opposite(int a, int b)
{
  return a * b < 0;
}

// The coordinate axes (i, j) of a projection that keeps the triangle t from collapsing:
// one whose normal component, the orientation of t's projection, is nonzero. Every
// figure in t's plane is projected one to one there.
void ProjectionAxes(const Point3 t[3], int& i, int& j)
{
  for (const int k : { 2, 1, 0 })
  {
    i = (k + 1) % 3;
    j = (k + 2) % 3;
    if (Orient2D(t[0].data(), t[1].data(), t[2].data(), i, j) != 0)
    {
      return;
    }
  }
}

// In the projection (i, j): whether x lies in the closed triangle t.
bool InTriangle2D(const Point3& x, const Point3 t[3], int i, int j)
{
  const int s0 = Orient2D(t[0].data(), t[1].data(), x.data(), i, j);
  const int s1 = Orient2D(t[1].data(), t[2].data(), x.data(), i, j);
  const int s2 = Orient2D(t[2].data(), t[0].data(), x.data(), i, j);
  return !(Opposite(s0, s1) || Opposite(s1, s2) || Opposite(s2, s0));
}

// In the projection (i, j), for x collinear with a and b: whether x lies between them.
bool Between2D(const Point3& a, const Point3& b, const Point3& x, int i, int j)
{
  return std::min(a[i], b[i]) <= x[i] && x[i] <= std::max(a[i], b[i]) &&
    std::min(a[j], b[j]) <= x[j] && x[j] <= std::max(a[j], b[j]);
}

// In the projection (i, j): whether the closed segments ab and cd meet.
bool SegmentsMeet2D(const Point3& a,
  const Point3& b,
  const Point3& c,
  const Point3& d,
  int i,
  int j)
{
  const int s1 = Orient2D(a.data(), b.data(), c.data(), i, j);
  const int s2 = Orient2D(a.data(), b.data(), d.data(), i, j);
  const int s3 = Orient2D(c.data(), d.data(), a.data(), i, j);
  const int s4 = Orient2D(c.data(), d.data(), b.data(), i, j);
  if (Opposite(s1, s2) && Opposite(s3, s4))
  {
    return true;
  }
  return (s1 == 0 && Between2D(a, b, c, i, j)) || (s2 == 0 && Between2D(a, b, d, i, j)) ||
    (s3 == 0 && Between2D(c, d, a, i, j)) || (s4 == 0 && Between2D(c, d, b, i, j));
}

// Whether coplanar triangles p and q meet: a corner of one inside the other, or two
// edges that meet.
bool CoplanarTrianglesMeet(const Point3 p[3], const Point3 q[3])
{
  int i = 0, j = 1;
  ProjectionAxes(q, i, j);
  for (int k = 0; k < 3; ++k)
  {
    if (InTriangle2D(p[k], q, i, j) || InTriangle2D(q[k], p, i, j))
    {
      return true;
    }
  }
  for (int e = 0; e < 3; ++e)
  {
    for (int f = 0; f < 3; ++f)
    {
      if (SegmentsMeet2D(p[e], p[(e + 1) % 3], q[f], q[(f + 1) % 3], i, j))
      {
        return true;
      }
    }
  }
  return false;
}

// Whether the segment ab meets triangle t, given the sides sa, sb of a and b with respect
// to t's plane (Orient3D), for triangles that are not coplanar. Off the plane, the line
// ab crosses it at one point, inside the closed triangle when the line passes all three
// edges on one side (the orientations of ab with each edge do not have opposite signs).
// A segment lying in t's plane needs no test of its own: where it meets t, either one
// of its ends does, found by the triangle's other edges through that end, which leave
// the plane, or one of t's edges meets the segment's triangle, found from t's side.
bool SegmentMeetsTriangle(const Point3& a, const Point3& b, int sa, int sb, const Point3 t[3])
{
  if (sa == sb)
  {
    return false; // both strictly on one side, or both in the plane
  }
  const int e0 = Orient3D(a.data(), b.data(), t[0].data(), t[1].data());
  const int e1 = Orient3D(a.data(), b.data(), t[1].data(), t[2].data());
  const int e2 = Orient3D(a.data(), b.data(), t[2].data(), t[0].data());
  return !(Opposite(e0, e1) || Opposite(e1, e2) || Opposite(e2, e0));
}

} // namespace

bool TrianglesIntersect(const Point3 p[3], const Point3 q[3])
{
  // The sides of p's corners with respect to q's plane: all strictly on one side, no
  // point in common; all on it, a question in that plane.
  int sp[3], sq[3];
  for (int k = 0; k < 3; ++k)
  {
    sp[k] = Orient3D(q[0].data(), q[1].data(), q[2].data(), p[k].data());
  }
  if ((sp[0] > 0 && sp[1] > 0 && sp[2] > 0) || (sp[0] < 0 && sp[1] < 0 && sp[2] < 0))
  {
    return false;
  }
  if (sp[0] == 0 && sp[1] == 0 && sp[2] == 0)
  {
    return CoplanarTrianglesMeet(p, q);
  }
  for (int k = 0; k < 3; ++k)
  {
    sq[k] = Orient3D(p[0].data(), p[1].data(), p[2].data(), q[k].data());
  }
  if ((sq[0] > 0 && sq[1] > 0 && sq[2] > 0) || (sq[0] < 0 && sq[1] < 0 && sq[2] < 0))
  {
    return false;
  }
  // Not coplanar: the triangles' common part is a segment of the planes' common line
  // whose ends lie on edges, so they meet exactly when an edge of one meets the other.
  for (int e = 0; e < 3; ++e)
  {
    const int f = (e + 1) % 3;
    if (SegmentMeetsTriangle(p[e], p[f], sp[e], sp[f], q) ||
      SegmentMeetsTriangle(q[e], q[f], sq[e], sq[f], p))
    {
      return true;
    }
  }
  return false;
}

bool SegmentIntersectsTriangle(const Point3& a, const Point3& b, const Point3 t[3])
{
  const int sa = Orient3D(t[0].data(), t[1].data(), t[2].data(), a.data());
  const int sb = Orient3D(t[0].data(), t[1].data(), t[2].data(), b.data());
  if (sa != 0 || sb != 0)
  {
    return SegmentMeetsTriangle(a, b, sa, sb, t);
  }
  // In t's plane: an end inside t, or the segment across one of t's edges.
  int i = 0, j = 1;
  ProjectionAxes(t, i, j);
  if (InTriangle2D(a, t, i, j) || InTriangle2D(b, t, i, j))
  {
    return true;
  }
  for (int e = 0; e < 3; ++e)
  {
    if (SegmentsMeet2D(a, b, t[e], t[(e + 1) % 3], i, j))
    {
      return true;
    }
  }
  return false;
}

bool SegmentsIntersect(const Point3& a, const Point3& b, const Point3& c, const Point3& d)
{
  if (Orient3D(a.data(), b.data(), c.data(), d.data()) != 0)
  {
    return false;
  }
  // Coplanar: a projection that keeps the plane one to one (from three corners that are
  // not collinear) or, when all four lie on one line, keeps the line one to one (the
  // axis along which the four spread most, and any other).
  const Point3* triples[4][3] = { { &a, &b, &c }, { &a, &b, &d }, { &c, &d, &a }, { &c, &d, &b } };
  for (const auto& triple : triples)
  {
    if (!Collinear(triple[0]->data(), triple[1]->data(), triple[2]->data()))
    {
      const Point3 t[3] = { *triple[0], *triple[1], *triple[2] };
      int i = 0, j = 1;
      ProjectionAxes(t, i, j);
      return SegmentsMeet2D(a, b, c, d, i, j);
    }
  }
  int axis = 0;
  double widest = -1;
  for (int k = 0; k < 3; ++k)
  {
    const double low = std::min(std::min(a[k], b[k]), std::min(c[k], d[k]));
    const double high = std::max(std::max(a[k], b[k]), std::max(c[k], d[k]));
    if (high - low > widest)
    {
      widest = high - low;
      axis = k;
    }
  }
  return SegmentsMeet2D(a, b, c, d, axis, (axis + 1) % 3);
}

bool ClosedTrianglesIntersect(const Point3 p[3], const Point3 q[3])
{
  const bool flatP = Collinear(p[0].data(), p[1].data(), p[2].data());
  const bool flatQ = Collinear(q[0].data(), q[1].data(), q[2].data());
  if (!flatP && !flatQ)
  {
    return TrianglesIntersect(p, q);
  }
  // A triangle with collinear corners is the union of its edges.
  for (int e = 0; e < 3; ++e)
  {
    const Point3& a = p[e];
    const Point3& b = p[(e + 1) % 3];
    if (!flatP)
    {
      if (SegmentIntersectsTriangle(q[e], q[(e + 1) % 3], p))
      {
        return true;
      }
      continue;
    }
    if (!flatQ)
    {
      if (SegmentIntersectsTriangle(a, b, q))
      {
        return true;
      }
      continue;
    }
    for (int f = 0; f < 3; ++f)
    {
      if (SegmentsIntersect(a, b, q[f], q[(f + 1) % 3]))
      {
        return true;
      }
    }
  }
  return false;
}

void ForEachOverlappingPair(const std::vector<Point3>& points,
  const std::vector<TriangleCorners>& triangles,
  const std::function<void(size_t, size_t)>& report)
{
  TriangleBoxTree(points, triangles).ForEachOverlappingPair(report);
}
} // namespace vtkdf
