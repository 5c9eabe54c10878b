#include "Polygons/PolygonTriangulation.h"

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>

namespace vtkdf
{

namespace
{
using Vector = std::array<double, 3>;

Vector Cross(const Vector& a, const Vector& b)
{
  return { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
}

double Dot(const Vector& a, const Vector& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

double Norm(const Vector& a)
{
  return std::sqrt(Dot(a, a));
}

/// Twice the signed area of the plane triangle abc (positive: counter-clockwise).
double Orient(const double* a, const double* b, const double* c)
{
  return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

double Distance(const double* a, const double* b)
{
  return std::hypot(b[0] - a[0], b[1] - a[1]);
}

/// Below this fraction of the polygon's size, lengths and distances are taken as zero: a
/// corner this close to a line through its neighbours is flat, a corner this close to an
/// ear blocks it. Far above double rounding, far below any feature a field resolves.
constexpr double RelativeZero = 1e-10;
} // namespace

bool PolygonTriangulation::Triangulate(const double* xyz, int64_t count)
{
  this->Result.clear();
  this->Why.clear();
  if (!this->Project(xyz, count) || !this->FindCrossing(count) || !this->ClipEars(count))
  {
    this->Result.clear();
    return false;
  }
  return true;
}

bool PolygonTriangulation::Project(const double* xyz, int64_t count)
{
  Vector lo{ HUGE_VAL, HUGE_VAL, HUGE_VAL }, hi{ -HUGE_VAL, -HUGE_VAL, -HUGE_VAL }, mean{};
  double magnitude = 0;
  for (int64_t i = 0; i < count; ++i)
  {
    for (int a = 0; a < 3; ++a)
    {
      const double x = xyz[3 * i + a];
      lo[a] = std::min(lo[a], x);
      hi[a] = std::max(hi[a], x);
      mean[a] += x;
      magnitude = std::max(magnitude, std::fabs(x));
    }
  }
  for (int a = 0; a < 3; ++a)
  {
    mean[a] /= static_cast<double>(count);
  }
  this->Size = Norm({ hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2] });
  this->Noise = 64 * DBL_EPSILON * (magnitude + this->Size);
  auto corner = [&](int64_t i) -> Vector
  {
    const double* p = xyz + 3 * (i % count);
    return { p[0] - mean[0], p[1] - mean[1], p[2] - mean[2] };
  };

  // Newell's normal: the polygon's area vector. A polygon with (almost) no area has none:
  // then the plane through its corners' widest spread, where a figure eight shows its
  // crossing and a polygon on one line has only flat corners.
  Vector normal{};
  for (int64_t i = 0; i < count; ++i)
  {
    const Vector c = Cross(corner(i), corner(i + 1));
    for (int a = 0; a < 3; ++a)
    {
      normal[a] += c[a];
    }
  }
  if (Norm(normal) <= RelativeZero * RelativeZero * this->Size * this->Size)
  {
    Vector along{}, across{};
    for (int64_t i = 0; i < count; ++i)
    {
      const Vector d = corner(i);
      if (Dot(d, d) > Dot(along, along))
      {
        along = d;
      }
    }
    for (int64_t i = 0; i < count; ++i)
    {
      const Vector c = Cross(along, corner(i));
      if (Dot(c, c) > Dot(across, across))
      {
        across = c;
      }
    }
    normal = across;
    if (Norm(normal) == 0)
    {
      // On one line (or one point): any plane through it.
      const int axis =
        std::fabs(along[0]) <= std::fabs(along[1]) && std::fabs(along[0]) <= std::fabs(along[2])
        ? 0
        : (std::fabs(along[1]) <= std::fabs(along[2]) ? 1 : 2);
      Vector unit{};
      unit[axis] = 1;
      normal = Cross(along, unit);
      if (Norm(normal) == 0)
      {
        normal = { 0, 0, 1 };
      }
    }
  }
  const double length = Norm(normal);
  for (double& v : normal)
  {
    v /= length;
  }

  // A basis (u, v) of the plane with u x v = normal: the polygon turns counter-clockwise
  // in it (its area vector points along the normal).
  Vector u{};
  for (int64_t i = 0; i < count; ++i)
  {
    const Vector d = corner(i);
    const double off = Dot(d, normal);
    const Vector inPlane{ d[0] - off * normal[0], d[1] - off * normal[1], d[2] - off * normal[2] };
    if (Dot(inPlane, inPlane) > Dot(u, u))
    {
      u = inPlane;
    }
  }
  if (Norm(u) == 0)
  {
    u = Cross(normal, std::fabs(normal[0]) < 0.9 ? Vector{ 1, 0, 0 } : Vector{ 0, 1, 0 });
  }
  const double uLength = Norm(u);
  for (double& x : u)
  {
    x /= uLength;
  }
  const Vector v = Cross(normal, u);

  this->Plane.resize(2 * count);
  double farthest = 0;
  for (int64_t i = 0; i < count; ++i)
  {
    const Vector d = corner(i);
    this->Plane[2 * i] = Dot(d, u);
    this->Plane[2 * i + 1] = Dot(d, v);
    farthest = std::max(farthest, std::fabs(Dot(d, normal)));
  }
  this->Flatness = this->Size > 0 ? farthest / this->Size : 0;
  return true;
}

bool PolygonTriangulation::FindCrossing(int64_t count)
{
  if (count < 4)
  {
    return true;
  }
  const double* p = this->Plane.data();
  const double zero = RelativeZero * this->Size + this->Noise;
  auto lowX = [&](int64_t e) { return std::min(p[2 * e], p[2 * ((e + 1) % count)]); };
  this->Edges.resize(count);
  for (int64_t e = 0; e < count; ++e)
  {
    this->Edges[e] = e;
  }
  std::sort(this->Edges.begin(),
    this->Edges.end(),
    [&](int64_t a, int64_t b) { return lowX(a) != lowX(b) ? lowX(a) < lowX(b) : a < b; });

  // Two edges cross when each one's ends lie strictly on both sides of the other's line
  // (beyond `zero`): touching, overlapping and near-duplicate corners are left to the ear
  // clipping, which follows them or finds no ear.
  auto strictlySplits = [&](const double* a, const double* b, const double* c, const double* d)
  {
    const double margin = zero * Distance(a, b);
    const double oc = Orient(a, b, c), od = Orient(a, b, d);
    return (oc > margin && od < -margin) || (oc < -margin && od > margin);
  };
  for (size_t i = 0; i < this->Edges.size(); ++i)
  {
    const int64_t e = this->Edges[i];
    const double* a = p + 2 * e;
    const double* b = p + 2 * ((e + 1) % count);
    const double highX = std::max(a[0], b[0]);
    const double lowY = std::min(a[1], b[1]), highY = std::max(a[1], b[1]);
    for (size_t j = i + 1; j < this->Edges.size() && lowX(this->Edges[j]) <= highX; ++j)
    {
      const int64_t f = this->Edges[j];
      if (f == (e + 1) % count || e == (f + 1) % count)
      {
        continue; // neighbours share a corner
      }
      const double* c = p + 2 * f;
      const double* d = p + 2 * ((f + 1) % count);
      if (std::max(c[1], d[1]) < lowY || std::min(c[1], d[1]) > highY)
      {
        continue;
      }
      if (strictlySplits(a, b, c, d) && strictlySplits(c, d, a, b))
      {
        this->Why = "its edges from corner " + std::to_string(std::min(e, f)) +
          " and from corner " + std::to_string(std::max(e, f)) + " cross in its best-fit plane";
        return false;
      }
    }
  }
  return true;
}

bool PolygonTriangulation::ClipEars(int64_t count)
{
  const double* p = this->Plane.data();
  const double zero = RelativeZero * this->Size + this->Noise;
  this->Next.resize(count);
  this->Previous.resize(count);
  this->Convex.resize(count);
  for (int64_t i = 0; i < count; ++i)
  {
    this->Next[i] = (i + 1) % count;
    this->Previous[i] = (i + count - 1) % count;
  }
  // 1: turns the polygon's way; 0: flat (a zero-area ear); -1: turns against it.
  auto turn = [&](int64_t c) -> int
  {
    const double* a = p + 2 * this->Previous[c];
    const double* b = p + 2 * c;
    const double* d = p + 2 * this->Next[c];
    const double ab = Distance(a, b), bd = Distance(b, d);
    const double flat = RelativeZero * ab * bd + this->Noise * (ab + bd);
    const double o = Orient(a, b, d);
    return o > flat ? 1 : (o < -flat ? -1 : 0);
  };
  for (int64_t i = 0; i < count; ++i)
  {
    this->Convex[i] = turn(i) > 0;
  }
  // A convex corner's triangle is an ear when no other corner that does not turn the
  // polygon's way lies in it or on its border (in a simple polygon, a corner inside an
  // ear implies such a one). Corners at the triangle's own corners (duplicate points, a
  // polygon touching itself there) do not block it.
  auto isEar = [&](int64_t c)
  {
    const double* a = p + 2 * this->Previous[c];
    const double* b = p + 2 * c;
    const double* d = p + 2 * this->Next[c];
    const double mab = zero * Distance(a, b), mbd = zero * Distance(b, d),
                 mda = zero * Distance(d, a);
    for (int64_t w = this->Next[this->Next[c]]; w != this->Previous[c]; w = this->Next[w])
    {
      if (this->Convex[w])
      {
        continue;
      }
      const double* x = p + 2 * w;
      if (Distance(x, a) <= zero || Distance(x, b) <= zero || Distance(x, d) <= zero)
      {
        continue;
      }
      if (Orient(a, b, x) >= -mab && Orient(b, d, x) >= -mbd && Orient(d, a, x) >= -mda)
      {
        return false;
      }
    }
    return true;
  };

  this->Result.reserve(3 * (count - 2));
  int64_t remaining = count, cursor = 1 % count, misses = 0;
  while (remaining > 3)
  {
    const int shape = turn(cursor);
    if (shape == 0 || (shape > 0 && isEar(cursor)))
    {
      const int64_t before = this->Previous[cursor], after = this->Next[cursor];
      this->Result.insert(this->Result.end(), { before, cursor, after });
      this->Next[before] = after;
      this->Previous[after] = before;
      --remaining;
      this->Convex[before] = turn(before) > 0;
      this->Convex[after] = turn(after) > 0;
      cursor = after;
      misses = 0;
    }
    else if (++misses > remaining)
    {
      this->Why = "it touches or overlaps itself in its best-fit plane so that no "
                  "triangulation follows its edges";
      return false;
    }
    else
    {
      cursor = this->Next[cursor];
    }
  }
  if (turn(cursor) < 0)
  {
    // The last triangle turns against the polygon: its edges wind back over themselves.
    this->Why = "it winds back over itself in its best-fit plane (its area is not "
                "bounded by its edges once)";
    return false;
  }
  this->Result.insert(this->Result.end(), { this->Previous[cursor], cursor, this->Next[cursor] });
  return true;
}

} // namespace vtkdf
