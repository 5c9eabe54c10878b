// The proximity of two triangle meshes (Filters/Core/Proximity/MeshProximity.h), VTK-free,
// against brute force over every pair of triangles:
// - the exact contact tests of triangles whose corners are collinear or repeated (slivers
//   and points, Segment/TriangleCrossings.h) on cases whose answer is known;
// - Colliding equal to the brute force's "some pair of triangles intersects, or a vertex
//   of one model is inside the other", on spheres, boxes and random soups at many poses:
//   apart, near-touching (gaps of 1e-3 to 2^-40), touching face to face and edge to edge
//   (grazing: exact coordinates), intersecting, one inside the other;
// - the separation of models that do not collide within 1e-6 relative plus 1e-12 of the
//   scene's diagonal of the brute force's, whose edge-to-edge distances come from a
//   golden-section search written here (not the core's closed form); the closest points
//   on their triangles and as far apart as the separation;
// - an upper bound below the true separation still gives it; a bound above it, the same;
// - the penetration (the deepest of A's face samples inside B, at its exact distance to
//   B) within 1e-3 of the step of a brute force over the same lattice, written here, and
//   the direction to B's closest point within 1 degree where the deepest sample is
//   unique; the number of samples inside equal.
#include "CoreTest.h"
#include "ExactDistance.h"
#include "Proximity/MeshProximity.h"
#include "Proximity/ProximityQuery.h"
#include "Segment/TriangleCrossings.h"
#include "Winding/WindingNumber.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <string>
#include <utility>
#include <vector>

using namespace vtkdf;
using namespace vtkdf::coretest;

namespace
{
MeshInput Sphere(const double centre[3], double radius, int subdivisions)
{
  const double t = (1 + std::sqrt(5.0)) / 2;
  std::vector<std::array<double, 3>> v = { { -1, t, 0 },
    { 1, t, 0 },
    { -1, -t, 0 },
    { 1, -t, 0 },
    { 0, -1, t },
    { 0, 1, t },
    { 0, -1, -t },
    { 0, 1, -t },
    { t, 0, -1 },
    { t, 0, 1 },
    { -t, 0, -1 },
    { -t, 0, 1 } };
  std::vector<std::array<int64_t, 3>> f = { { 0, 11, 5 },
    { 0, 5, 1 },
    { 0, 1, 7 },
    { 0, 7, 10 },
    { 0, 10, 11 },
    { 1, 5, 9 },
    { 5, 11, 4 },
    { 11, 10, 2 },
    { 10, 7, 6 },
    { 7, 1, 8 },
    { 3, 9, 4 },
    { 3, 4, 2 },
    { 3, 2, 6 },
    { 3, 6, 8 },
    { 3, 8, 9 },
    { 4, 9, 5 },
    { 2, 4, 11 },
    { 6, 2, 10 },
    { 8, 6, 7 },
    { 9, 8, 1 } };
  for (int s = 0; s < subdivisions; ++s)
  {
    std::map<std::pair<int64_t, int64_t>, int64_t> middles;
    auto middle = [&](int64_t a, int64_t b)
    {
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      auto found = middles.find(key);
      if (found != middles.end())
      {
        return found->second;
      }
      v.push_back({ (v[a][0] + v[b][0]) / 2, (v[a][1] + v[b][1]) / 2, (v[a][2] + v[b][2]) / 2 });
      return middles[key] = static_cast<int64_t>(v.size()) - 1;
    };
    std::vector<std::array<int64_t, 3>> finer;
    for (const auto& tri : f)
    {
      const int64_t ab = middle(tri[0], tri[1]), bc = middle(tri[1], tri[2]),
                    ca = middle(tri[2], tri[0]);
      finer.push_back({ tri[0], ab, ca });
      finer.push_back({ tri[1], bc, ab });
      finer.push_back({ tri[2], ca, bc });
      finer.push_back({ ab, bc, ca });
    }
    f = finer;
  }
  MeshInput mesh;
  for (const auto& p : v)
  {
    const double n = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    for (int k = 0; k < 3; ++k)
    {
      mesh.Points.push_back(centre[k] + radius * p[k] / n);
    }
  }
  for (const auto& tri : f)
  {
    mesh.Triangles.insert(mesh.Triangles.end(), tri.begin(), tri.end());
  }
  return mesh;
}

/// An axis-aligned box from lo to hi, 12 triangles facing out.
MeshInput Cube(const double lo[3], const double hi[3])
{
  MeshInput mesh;
  for (int c = 0; c < 8; ++c)
  {
    mesh.Points.push_back(c & 1 ? hi[0] : lo[0]);
    mesh.Points.push_back(c & 2 ? hi[1] : lo[1]);
    mesh.Points.push_back(c & 4 ? hi[2] : lo[2]);
  }
  mesh.Triangles = { 0,
    2,
    1,
    1,
    2,
    3,
    4,
    5,
    6,
    5,
    7,
    6,
    0,
    1,
    4,
    1,
    5,
    4,
    2,
    6,
    3,
    3,
    6,
    7,
    0,
    4,
    2,
    2,
    4,
    6,
    1,
    3,
    5,
    3,
    7,
    5 };
  return mesh;
}

/// Random triangles in the box [lo, lo + size]^3, some of them slivers and points.
MeshInput Soup(std::mt19937& random, int count, double lo, double size)
{
  std::uniform_real_distribution<double> u(lo, lo + size);
  MeshInput mesh;
  for (int t = 0; t < count; ++t)
  {
    double c[3][3];
    for (auto& p : c)
    {
      for (double& x : p)
      {
        x = u(random);
      }
    }
    if (t % 17 == 5)
    {
      for (int k = 0; k < 3; ++k)
      {
        c[2][k] = c[0][k] + 0.5 * (c[1][k] - c[0][k]); // a sliver (near collinear)
      }
    }
    if (t % 29 == 7)
    {
      for (int k = 0; k < 3; ++k)
      {
        c[1][k] = c[2][k] = c[0][k]; // a point
      }
    }
    for (const auto& p : c)
    {
      mesh.Points.insert(mesh.Points.end(), p, p + 3);
      mesh.Triangles.push_back(static_cast<int64_t>(mesh.Triangles.size()));
    }
  }
  return mesh;
}

MeshInput Moved(MeshInput mesh, double dx, double dy, double dz)
{
  for (size_t i = 0; i < mesh.Points.size(); i += 3)
  {
    mesh.Points[i] += dx;
    mesh.Points[i + 1] += dy;
    mesh.Points[i + 2] += dz;
  }
  return mesh;
}

void Corners(const MeshInput& mesh, size_t t, Point3 out[3])
{
  for (int c = 0; c < 3; ++c)
  {
    const double* x = &mesh.Points[3 * mesh.Triangles[3 * t + c]];
    out[c] = { { x[0], x[1], x[2] } };
  }
}

double Distance2(const double* a, const double* b)
{
  return (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
    (a[2] - b[2]) * (a[2] - b[2]);
}

/// The squared distance between segments ab and cd: the distance from a point of ab to
/// cd is convex along ab, minimized by a golden-section search.
double SegmentDistance2(const double* a, const double* b, const double* c, const double* d)
{
  auto at = [&](double s)
  {
    double p[3], q[3];
    for (int k = 0; k < 3; ++k)
    {
      p[k] = a[k] + s * (b[k] - a[k]);
    }
    reference::ClosestOnSegment(p, c, d, q);
    return Distance2(p, q);
  };
  const double ratio = (std::sqrt(5.0) - 1) / 2;
  double lo = 0, hi = 1;
  double x1 = hi - ratio * (hi - lo), x2 = lo + ratio * (hi - lo);
  double f1 = at(x1), f2 = at(x2);
  for (int i = 0; i < 200 && hi - lo > 1e-17; ++i)
  {
    if (f1 <= f2)
    {
      hi = x2, x2 = x1, f2 = f1;
      x1 = hi - ratio * (hi - lo), f1 = at(x1);
    }
    else
    {
      lo = x1, x1 = x2, f1 = f2;
      x2 = lo + ratio * (hi - lo), f2 = at(x2);
    }
  }
  return std::min({ f1, f2, at(0), at(1) });
}

/// The brute force's squared distance of two triangles that do not intersect.
double TriangleDistance2(const Point3 p[3], const Point3 q[3])
{
  double best = HUGE_VAL, c[3];
  for (int k = 0; k < 3; ++k)
  {
    reference::ClosestOnTriangle(p[k].data(), q[0].data(), q[1].data(), q[2].data(), c);
    best = std::min(best, Distance2(p[k].data(), c));
    reference::ClosestOnTriangle(q[k].data(), p[0].data(), p[1].data(), p[2].data(), c);
    best = std::min(best, Distance2(q[k].data(), c));
    for (int e = 0; e < 3; ++e)
    {
      best = std::min(best,
        SegmentDistance2(p[k].data(), p[(k + 1) % 3].data(), q[e].data(), q[(e + 1) % 3].data()));
    }
  }
  return best;
}

struct Truth
{
  bool Colliding = false;
  double Separation = HUGE_VAL;
};

double BoxGap2(const Point3 p[3], const Point3 q[3])
{
  double d2 = 0;
  for (int k = 0; k < 3; ++k)
  {
    const double pl = std::min({ p[0][k], p[1][k], p[2][k] });
    const double ph = std::max({ p[0][k], p[1][k], p[2][k] });
    const double ql = std::min({ q[0][k], q[1][k], q[2][k] });
    const double qh = std::max({ q[0][k], q[1][k], q[2][k] });
    const double gap = std::max(0.0, std::max(ql - ph, pl - qh));
    d2 += gap * gap;
  }
  return d2;
}

bool AnyVertexInside(const MeshInput& inner, const MeshInput& outer)
{
  WindingNumber w;
  w.Build(outer.Points, outer.Triangles);
  for (const int64_t id : inner.Triangles)
  {
    if (std::fabs(w.Exact(&inner.Points[3 * id])) > 0.5)
    {
      return true;
    }
  }
  return false;
}

/// Every pair of triangles: contact, else containment, else the least distance.
Truth BruteForce(const MeshInput& a, const MeshInput& b)
{
  Truth truth;
  const size_t na = a.Triangles.size() / 3, nb = b.Triangles.size() / 3;
  for (size_t s = 0; s < na && !truth.Colliding; ++s)
  {
    Point3 p[3];
    Corners(a, s, p);
    for (size_t t = 0; t < nb; ++t)
    {
      Point3 q[3];
      Corners(b, t, q);
      if (ClosedTrianglesIntersect(p, q))
      {
        truth.Colliding = true;
        break;
      }
    }
  }
  if (truth.Colliding || AnyVertexInside(a, b) || AnyVertexInside(b, a))
  {
    truth.Colliding = true;
    return truth;
  }
  double best = HUGE_VAL;
  for (size_t s = 0; s < na; ++s)
  {
    Point3 p[3];
    Corners(a, s, p);
    for (size_t t = 0; t < nb; ++t)
    {
      Point3 q[3];
      Corners(b, t, q);
      if (BoxGap2(p, q) <= best)
      {
        best = std::min(best, TriangleDistance2(p, q));
      }
    }
  }
  truth.Separation = std::sqrt(best);
  return truth;
}

double Diagonal(const MeshInput& a, const MeshInput& b)
{
  double lo[3] = { HUGE_VAL, HUGE_VAL, HUGE_VAL }, hi[3] = { -HUGE_VAL, -HUGE_VAL, -HUGE_VAL };
  for (const MeshInput* m : { &a, &b })
  {
    for (size_t i = 0; i < m->Points.size(); ++i)
    {
      lo[i % 3] = std::min(lo[i % 3], m->Points[i]);
      hi[i % 3] = std::max(hi[i % 3], m->Points[i]);
    }
  }
  return std::sqrt(Distance2(lo, hi));
}

int cases = 0, collisions = 0;

std::string Named(const char* what, double value)
{
  char text[128];
  std::snprintf(text, sizeof(text), "%s %g", what, value);
  return text;
}

void Compare(const std::string& name, const MeshInput& a, const MeshInput& b)
{
  ++cases;
  const Truth truth = BruteForce(a, b);
  ProximityResult result;
  std::string error;
  Check(ComputeMeshProximity(a, b, ProximityOptions(), result, error),
    "%s: %s",
    name.c_str(),
    error.c_str());
  collisions += truth.Colliding;
  Check(result.Colliding == truth.Colliding,
    "%s: colliding %d, brute force %d",
    name.c_str(),
    result.Colliding,
    truth.Colliding);
  if (truth.Colliding || result.Colliding)
  {
    std::printf("%-40s colliding (%s), %lld contact tests\n",
      name.c_str(),
      result.ContactA >= 0 ? "surfaces" : "containment",
      static_cast<long long>(result.ContactTests));
    return;
  }
  const double diagonal = Diagonal(a, b);
  const double tolerance = 1e-6 * truth.Separation + 1e-12 * diagonal;
  std::printf("%-40s separation %.17g (brute force %.17g), %lld distance tests of %lld pairs\n",
    name.c_str(),
    result.Separation,
    truth.Separation,
    static_cast<long long>(result.DistanceTests),
    static_cast<long long>((a.Triangles.size() / 3) * (b.Triangles.size() / 3)));
  Check(std::fabs(result.Separation - truth.Separation) <= tolerance,
    "%s: separation %.17g, brute force %.17g",
    name.c_str(),
    result.Separation,
    truth.Separation);
  // The witnesses: as far apart as the separation, each on its triangle.
  const double apart = std::sqrt(Distance2(result.ClosestA.data(), result.ClosestB.data()));
  Check(std::fabs(apart - result.Separation) <= tolerance,
    "%s: the closest points are %.17g apart",
    name.c_str(),
    apart);
  Point3 p[3], q[3];
  Corners(a, static_cast<size_t>(result.ClosestTriangleA), p);
  Corners(b, static_cast<size_t>(result.ClosestTriangleB), q);
  double c[3];
  reference::ClosestOnTriangle(result.ClosestA.data(), p[0].data(), p[1].data(), p[2].data(), c);
  Check(std::sqrt(Distance2(c, result.ClosestA.data())) <= 1e-12 * diagonal,
    "%s: the closest point on A is off its triangle",
    name.c_str());
  reference::ClosestOnTriangle(result.ClosestB.data(), q[0].data(), q[1].data(), q[2].data(), c);
  Check(std::sqrt(Distance2(c, result.ClosestB.data())) <= 1e-12 * diagonal,
    "%s: the closest point on B is off its triangle",
    name.c_str());
  // A bound below the separation, and one above it, change nothing.
  for (const double factor : { 0.5, 1.5 })
  {
    ProximityOptions bounded;
    bounded.UpperBound = factor * truth.Separation;
    ProximityResult again;
    ComputeMeshProximity(a, b, bounded, again, error);
    Check(again.Separation == result.Separation,
      "%s: with the bound %g x the separation: %.17g",
      name.c_str(),
      factor,
      again.Separation);
  }
}

/// The brute force's penetration of a into b: the lattice of MeshProximity.h's definition,
/// each sample inside b by the exact winding number, at its distance to every triangle.
void ComparePenetration(const std::string& name,
  const MeshInput& a,
  const MeshInput& b,
  double step)
{
  WindingNumber w;
  w.Build(b.Points, b.Triangles);
  double depth = 0, second = 0, deepest[3] = { 0, 0, 0 }, onB[3] = { 0, 0, 0 };
  int64_t inside = 0, samples = 0;
  for (size_t s = 0; s < a.Triangles.size() / 3; ++s)
  {
    Point3 p[3];
    Corners(a, s, p);
    double longest = 0;
    for (int e = 0; e < 3; ++e)
    {
      longest = std::max(longest, std::sqrt(Distance2(p[e].data(), p[(e + 1) % 3].data())));
    }
    const int n = std::max(1, static_cast<int>(std::ceil(longest / step)));
    for (int i = 0; i <= n; ++i)
    {
      for (int j = 0; i + j <= n; ++j)
      {
        double x[3];
        for (int k = 0; k < 3; ++k)
        {
          x[k] =
            p[0][k] + double(i) / n * (p[1][k] - p[0][k]) + double(j) / n * (p[2][k] - p[0][k]);
        }
        ++samples;
        if (!(std::fabs(w.Exact(x)) > 0.5))
        {
          continue;
        }
        ++inside;
        double best = HUGE_VAL, closest[3], c[3];
        for (size_t t = 0; t < b.Triangles.size() / 3; ++t)
        {
          Point3 q[3];
          Corners(b, t, q);
          reference::ClosestOnTriangle(x, q[0].data(), q[1].data(), q[2].data(), c);
          if (Distance2(x, c) < best)
          {
            best = Distance2(x, c);
            std::copy(c, c + 3, closest);
          }
        }
        const double d = std::sqrt(best);
        if (d > depth)
        {
          second = depth;
          depth = d;
          std::copy(x, x + 3, deepest);
          std::copy(closest, closest + 3, onB);
        }
        else
        {
          second = std::max(second, d);
        }
      }
    }
  }
  PenetrationResult result;
  std::string error;
  Check(ComputePenetration(a, b, step, result, error), "%s: %s", name.c_str(), error.c_str());
  std::printf("%-40s penetration %.12g (brute force %.12g), %lld of %lld samples inside\n",
    name.c_str(),
    result.Depth,
    depth,
    static_cast<long long>(result.SamplesInside),
    static_cast<long long>(result.Samples));
  Check(std::fabs(result.Depth - depth) <= 1e-3 * step,
    "%s: penetration %.17g, brute force %.17g",
    name.c_str(),
    result.Depth,
    depth);
  Check(result.Samples == samples && result.SamplesInside == inside,
    "%s: %lld of %lld samples inside, brute force %lld of %lld",
    name.c_str(),
    static_cast<long long>(result.SamplesInside),
    static_cast<long long>(result.Samples),
    static_cast<long long>(inside),
    static_cast<long long>(samples));
  if (depth >= 0.01 * step && depth - second > 1e-3 * step)
  {
    double u[3], v[3], dot = 0;
    for (int k = 0; k < 3; ++k)
    {
      u[k] = (result.ClosestOnB[k] - result.Deepest[k]) / result.Depth;
      v[k] = (onB[k] - deepest[k]) / depth;
      dot += u[k] * v[k];
    }
    Check(dot >= std::cos(M_PI / 180),
      "%s: the contact normal is %g degrees off",
      name.c_str(),
      std::acos(std::min(1.0, dot)) * 180 / M_PI);
  }
}

void DegenerateContacts()
{
  const Point3 t[3] = { { { 0, 0, 0 } }, { { 1, 0, 0 } }, { { 0, 1, 0 } } };
  auto sliver = [](Point3 a, Point3 b)
  {
    return std::array<Point3, 3>{
      { a, b, { { (a[0] + b[0]) / 2, (a[1] + b[1]) / 2, (a[2] + b[2]) / 2 } } }
    };
  };
  struct Case
  {
    const char* Name;
    std::array<Point3, 3> Other;
    bool Meets;
  };
  const Case cases[] = {
    { "sliver through the interior", sliver({ { 0.2, 0.2, -1 } }, { { 0.2, 0.2, 1 } }), true },
    { "sliver above", sliver({ { 0.2, 0.2, 0.5 } }, { { 0.2, 0.2, 1 } }), false },
    { "sliver ending on the face", sliver({ { 0.2, 0.2, 0 } }, { { 0.2, 0.2, 1 } }), true },
    { "sliver in the plane, inside", sliver({ { 0.1, 0.1, 0 } }, { { 0.3, 0.2, 0 } }), true },
    { "sliver in the plane, outside", sliver({ { 1, 1, 0 } }, { { 2, 1, 0 } }), false },
    { "sliver in the plane, across", sliver({ { -1, 0.5, 0 } }, { { 2, 0.5, 0 } }), true },
    { "sliver along an edge, beyond", sliver({ { 1.5, 0, 0 } }, { { 2, 0, 0 } }), false },
    { "sliver touching a corner", sliver({ { 1, 0, 0 } }, { { 2, 0, 0 } }), true },
    { "point on the face",
      { { { { 0.25, 0.25, 0 } }, { { 0.25, 0.25, 0 } }, { { 0.25, 0.25, 0 } } } },
      true },
    { "point above the face",
      { { { { 0.25, 0.25, 1e-300 } }, { { 0.25, 0.25, 1e-300 } }, { { 0.25, 0.25, 1e-300 } } } },
      false },
  };
  for (const Case& c : cases)
  {
    Check(
      ClosedTrianglesIntersect(t, c.Other.data()) == c.Meets, "%s: expected %d", c.Name, c.Meets);
    Check(ClosedTrianglesIntersect(c.Other.data(), t) == c.Meets,
      "%s (swapped): expected %d",
      c.Name,
      c.Meets);
  }
  // Two degenerate triangles: segments and points.
  const Point3 o{ { 0, 0, 0 } }, x{ { 1, 0, 0 } }, y{ { 0, 1, 0 } }, xy{ { 1, 1, 0 } },
    z{ { 0.5, 0.5, 1 } }, far{ { 2, 0, 0 } }, third{ { 3, 0, 0 } }, half{ { 0.5, 0, 0 } };
  Check(SegmentsIntersect(o, xy, x, y), "diagonals of a square cross");
  Check(!SegmentsIntersect(o, x, y, xy), "opposite sides of a square do not meet");
  Check(!SegmentsIntersect(o, xy, x, z), "skew segments do not meet");
  Check(SegmentsIntersect(o, x, half, far), "collinear overlapping segments meet");
  Check(!SegmentsIntersect(o, x, far, third), "collinear disjoint segments do not meet");
  Check(SegmentsIntersect(o, x, x, far), "collinear segments sharing an end meet");
  Check(SegmentsIntersect(half, half, o, x), "a point on a segment meets it");
  Check(!SegmentsIntersect(z, z, o, x), "a point off a segment does not meet it");
  Check(SegmentIntersectsTriangle(z, half, t), "a segment to the edge meets the triangle");
}
} // namespace

int main()
{
  DegenerateContacts();

  const double origin[3] = { 0, 0, 0 };
  const MeshInput ball = Sphere(origin, 1, 2);
  const MeshInput small = Sphere(origin, 0.6, 2);
  for (const double gap : { 0.5, 1e-3, 1e-7 })
  {
    Compare(Named("spheres, centres 1.6 +", gap), ball, Moved(small, 1.6 + gap, 0.1, -0.05));
  }
  // A cube's face at the sphere's farthest vertex plus a gap: touching at gap 0.
  double xmax = -HUGE_VAL;
  for (size_t i = 0; i < ball.Points.size(); i += 3)
  {
    xmax = std::max(xmax, ball.Points[i]);
  }
  for (const double gap : { 0.0, 1e-9, 1e-4 })
  {
    const double near[3] = { xmax + gap, -1, -1 }, beyond[3] = { xmax + gap + 1, 1, 1 };
    Compare(Named("sphere and a cube's face, gap", gap), ball, Cube(near, beyond));
  }
  Compare("spheres, intersecting", ball, Moved(small, 1.2, 0.3, 0.2));
  Compare("small sphere inside", ball, Moved(small, 0.1, 0, 0));
  Compare("ball around a small sphere (swapped)", Moved(small, 0.1, 0, 0), ball);

  const double lo[3] = { 0, 0, 0 }, hi[3] = { 1, 1, 1 };
  const MeshInput cube = Cube(lo, hi);
  Compare("cubes face to face (touching)", cube, Moved(cube, 1, 0.25, 0.5));
  Compare("cubes edge to edge (touching)", cube, Moved(cube, 1, 1, 0.5));
  Compare("cubes corner to corner (touching)", cube, Moved(cube, 1, 1, 1));
  Compare(
    "cubes, parallel faces 2^-40 apart", cube, Moved(cube, 1 + std::ldexp(1.0, -40), 0.25, 0));
  Compare("cubes, edges 2^-40 apart", cube, Moved(cube, 1 + std::ldexp(1.0, -40), 1, 0.5));
  Compare("cubes, parallel faces 0.25 apart", cube, Moved(cube, 0, 0, 1.25));
  const double inLo[3] = { 0.25, 0.25, 0.25 }, inHi[3] = { 0.75, 0.75, 0.75 };
  Compare("cube inside a cube", cube, Cube(inLo, inHi));
  Compare("sphere and cube apart", Moved(small, -1, 0.5, 0.5), cube);

  ComparePenetration("penetration, spheres intersecting", Moved(small, 1.2, 0.3, 0.2), ball, 0.05);
  ComparePenetration("penetration, swapped", ball, Moved(small, 1.2, 0.3, 0.2), 0.05);
  ComparePenetration("penetration, small sphere inside", Moved(small, 0.1, 0, 0), ball, 0.1);
  ComparePenetration("penetration, cubes overlapping", cube, Moved(cube, 0.75, 0.1, 0.05), 0.1);
  ComparePenetration("penetration, cubes apart", cube, Moved(cube, 1.5, 0, 0), 0.1);

  std::mt19937 random(7);
  for (int trial = 0; trial < 12; ++trial)
  {
    const MeshInput a = Soup(random, 150, 0, 1);
    const double offset = 0.6 + 0.1 * trial;
    Compare(Named("soups, offset", offset), a, Soup(random, 150, offset, 1));
  }

  // A query split into shares (a distributed run), packed, unpacked and merged, equals
  // the query in one call bit for bit, whatever the number of shares.
  {
    const MeshInput a = Sphere(origin, 1, 3), b = Moved(Sphere(origin, 0.7, 3), 0.6, 0.2, 0.1);
    const MeshInput far = Moved(Sphere(origin, 0.7, 3), 2.5, 0.2, 0.1);
    for (const MeshInput* other : { &b, &far })
    {
      ProximityModel ma, mb;
      std::string error;
      Check(ma.Load(a, "A", InsideRule::WindingNumber, error) &&
          mb.Load(*other, "B", InsideRule::WindingNumber, error),
        "models: %s",
        error.c_str());
      ProximityRequest request;
      request.Resolution = 40;
      ProximityReport whole;
      Check(ComputeProximity(ma, mb, request, whole, Execution(), error), "%s", error.c_str());
      for (int shares : { 2, 3, 7 })
      {
        std::vector<double> packed;
        ProximityReport first;
        for (int share = 0; share < shares; ++share)
        {
          request.Share = share;
          request.Shares = shares;
          ProximityReport part;
          Check(ComputeProximity(ma, mb, request, part, Execution(), error), "%s", error.c_str());
          const std::vector<double> numbers = PackProximityShare(part);
          packed.insert(packed.end(), numbers.begin(), numbers.end());
          if (share == 0)
          {
            first = part;
          }
          // Only the first share tests for contact and searches the separation.
          Check(share == 0 || (part.Contact.ContactTests == 0 && part.Contact.DistanceTests == 0),
            "share %d of %d tested %lld pairs for contact and %lld for the separation",
            share,
            shares,
            static_cast<long long>(part.Contact.ContactTests),
            static_cast<long long>(part.Contact.DistanceTests));
        }
        std::vector<ProximityReport> parts;
        ProximityReport merged;
        Check(UnpackProximityShares(packed.data(), packed.size(), first, parts) &&
            parts.size() == static_cast<size_t>(shares),
          "%d shares unpacked",
          shares);
        MergeProximityShares(parts, merged);
        bool same = merged.Contact.Colliding == whole.Contact.Colliding &&
          merged.Contact.Separation == whole.Contact.Separation &&
          merged.Contact.ClosestA == whole.Contact.ClosestA &&
          merged.Contact.ContactA == whole.Contact.ContactA &&
          merged.Contact.ContactB == whole.Contact.ContactB &&
          merged.Contact.ContactTests == whole.Contact.ContactTests &&
          merged.Contact.DistanceTests == whole.Contact.DistanceTests &&
          merged.PointQueries == whole.PointQueries && merged.DistanceA == whole.DistanceA &&
          merged.DistanceB == whole.DistanceB;
        for (const auto& sides :
          { std::make_pair(&merged.AInB, &whole.AInB), std::make_pair(&merged.BInA, &whole.BInA) })
        {
          const PenetrationSide& x = *sides.first;
          const PenetrationSide& y = *sides.second;
          same = same && x.Depth == y.Depth && x.Deepest == y.Deepest && x.Normal == y.Normal &&
            x.Samples == y.Samples && x.SamplesInside == y.SamplesInside &&
            x.Contacts.size() == y.Contacts.size();
          for (size_t k = 0; same && k < x.Contacts.size(); ++k)
          {
            same = x.Contacts[k].Point == y.Contacts[k].Point &&
              x.Contacts[k].Depth == y.Contacts[k].Depth &&
              x.Contacts[k].Vertex == y.Contacts[k].Vertex;
          }
        }
        std::printf("%-40s colliding %d, %zu + %zu contacts: %s\n",
          Named(other == &b ? "shares, overlapping" : "shares, apart", shares).c_str(),
          whole.Contact.Colliding ? 1 : 0,
          whole.AInB.Contacts.size(),
          whole.BInA.Contacts.size(),
          same ? "equal" : "DIFFERENT");
        Check(same, "%d shares differ from one call", shares);
      }
      request.Share = 0;
      request.Shares = 1;
    }
  }

  // Invalid input: an error, not a result.
  ProximityResult result;
  std::string error;
  Check(!ComputeMeshProximity(MeshInput(), ball, ProximityOptions(), result, error) &&
      error.find("no triangle") != std::string::npos,
    "an empty model: %s",
    error.c_str());
  MeshInput bad = cube;
  bad.Points[4] = NAN;
  Check(!ComputeMeshProximity(ball, bad, ProximityOptions(), result, error) &&
      error.find("not finite") != std::string::npos,
    "a NaN coordinate: %s",
    error.c_str());

  std::printf("%d cases, %d colliding\n", cases, collisions);
  Check(collisions >= 8 && cases - collisions >= 10, "the cases cover both answers");
  return Verdict();
}
