// The exact closest point on the boundary of a union of convex polytopes
// (Filters/Core/Union/UnionClosestPoint.h), VTK-free:
// - touching pieces: two unit cubes side by side (from (0.9, 0.5, 0.5): 0.5, not
//   0.1), a block of 27 touching cubes, O exactly on a shared face, nested pieces, a
//   piece holding O alone, O outside;
// - random unions (seeded) of rotated boxes and octahedra, and of 5 to 70 hulls of 8 to
//   40 faces, around and away from O, O
//   inside and outside, against a brute force: inside, the exit distance along 20000
//   rays from O (each ray's intervals through the pieces merged), the best refined by a
//   local search over directions; outside, the nearest point of every piece's faces: the
//   exact answer never above the reference and within 1e-4 of it (what the local
//   search reaches at creases, where the exit distance has a kink; the pieces are ~1); the closest
//   point at the answer's distance, on the boundary (probes around it in and out of the union), and
//   the ray through it leaving (or entering) the union there;
// - ConvexPiece::Build refuses an open, a non-manifold, a flat and a non-convex piece.
#include "CoreTest.h"
#include "RaySpans.h"
#include "Union/ConvexHull.h"
#include "Union/UnionClosestPoint.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

using namespace vtkdf;
using namespace vtkdf::coretest;

namespace
{

/// A box: centre, half sizes, rotated by the unit quaternion q.
ConvexPiece Box(const double c[3], const double half[3], const double q[4] = nullptr)
{
  std::vector<double> points;
  for (int k = 0; k < 8; ++k)
  {
    double p[3] = {
      (k & 1 ? 1 : -1) * half[0], (k & 2 ? 1 : -1) * half[1], (k & 4 ? 1 : -1) * half[2]
    };
    if (q)
    {
      // p' = q p q*.
      const double w = q[0], x = q[1], y = q[2], z = q[3];
      const double r[3][3] = {
        { 1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y) },
        { 2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x) },
        { 2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y) }
      };
      const double o[3] = { p[0], p[1], p[2] };
      for (int a = 0; a < 3; ++a)
      {
        p[a] = r[a][0] * o[0] + r[a][1] * o[1] + r[a][2] * o[2];
      }
    }
    for (int a = 0; a < 3; ++a)
    {
      points.push_back(c[a] + p[a]);
    }
  }
  const std::vector<std::vector<int64_t>> faces = {
    { 0, 2, 3, 1 }, { 4, 5, 7, 6 }, { 0, 1, 5, 4 }, { 2, 6, 7, 3 }, { 0, 4, 6, 2 }, { 1, 3, 7, 5 }
  };
  ConvexPiece piece;
  std::string error;
  Check(piece.Build(points, faces, 1e-9, error), "%s", std::string("a box: " + error).c_str());
  return piece;
}

ConvexPiece Octahedron(const double c[3], double r)
{
  std::vector<double> points = { c[0] + r,
    c[1],
    c[2],
    c[0] - r,
    c[1],
    c[2],
    c[0],
    c[1] + r,
    c[2],
    c[0],
    c[1] - r,
    c[2],
    c[0],
    c[1],
    c[2] + r,
    c[0],
    c[1],
    c[2] - r };
  const std::vector<std::vector<int64_t>> faces = { { 0, 2, 4 },
    { 2, 1, 4 },
    { 1, 3, 4 },
    { 3, 0, 4 },
    { 2, 0, 5 },
    { 1, 2, 5 },
    { 3, 1, 5 },
    { 0, 3, 5 } };
  ConvexPiece piece;
  std::string error;
  Check(
    piece.Build(points, faces, 1e-9, error), "%s", std::string("an octahedron: " + error).c_str());
  return piece;
}

/// Where the ray o + t d (t >= 0) first leaves the union (o inside) or enters it (o
/// outside): each piece's interval by its planes, the intervals merged.
double RayEvent(const UnionClosestPoint& u,
  const double o[3],
  const double d[3],
  bool inside,
  double slack = 0)
{
  std::vector<std::pair<double, double>> spans;
  for (const ConvexPiece& piece : u.Pieces)
  {
    RaySpan span;
    for (size_t f = 0; f < piece.Faces.size(); ++f)
    {
      const double* p = &piece.Planes[4 * f];
      span.Constrain(p[0] * d[0] + p[1] * d[1] + p[2] * d[2],
        p[3] + slack - (p[0] * o[0] + p[1] * o[1] + p[2] * o[2]));
    }
    span.AddTo(spans);
  }
  return inside ? FirstExit(spans) : FirstEntry(spans);
}

/// The distance from x to triangle (a, b, c), by projection or the edges.
double TriangleDistance(const double* x, const double* a, const double* b, const double* c)
{
  auto sub = [](const double* p, const double* q, double* r)
  { r[0] = p[0] - q[0], r[1] = p[1] - q[1], r[2] = p[2] - q[2]; };
  auto dot = [](const double* p, const double* q)
  { return p[0] * q[0] + p[1] * q[1] + p[2] * q[2]; };
  auto segment = [&](const double* p, const double* q)
  {
    double e[3], f[3];
    sub(q, p, e);
    sub(x, p, f);
    const double t = std::min(1.0, std::max(0.0, dot(e, f) / dot(e, e)));
    const double g[3] = { f[0] - t * e[0], f[1] - t * e[1], f[2] - t * e[2] };
    return std::sqrt(dot(g, g));
  };
  double e[3], f[3], g[3], n[3];
  sub(b, a, e);
  sub(c, a, f);
  sub(x, a, g);
  n[0] = e[1] * f[2] - e[2] * f[1], n[1] = e[2] * f[0] - e[0] * f[2],
  n[2] = e[0] * f[1] - e[1] * f[0];
  const double nn = dot(n, n), h = dot(g, n) / nn;
  const double y[3] = { g[0] - h * n[0], g[1] - h * n[1], g[2] - h * n[2] };
  // Barycentric test of the projection.
  double c0[3], c1[3];
  const double* corners[3] = { a, b, c };
  bool inside = true;
  for (int k = 0; k < 3; ++k)
  {
    double ek[3], yk[3];
    sub(corners[(k + 1) % 3], corners[k], ek);
    const double py[3] = {
      a[0] + y[0] - corners[k][0], a[1] + y[1] - corners[k][1], a[2] + y[2] - corners[k][2]
    };
    std::copy(py, py + 3, yk);
    c0[0] = ek[1] * yk[2] - ek[2] * yk[1], c0[1] = ek[2] * yk[0] - ek[0] * yk[2],
    c0[2] = ek[0] * yk[1] - ek[1] * yk[0];
    inside = inside && dot(c0, n) >= 0;
  }
  (void)c1;
  if (inside)
  {
    return std::fabs(h) * std::sqrt(nn);
  }
  return std::min({ segment(a, b), segment(b, c), segment(c, a) });
}

/// The brute force against the exact answer at o: outside, the nearest point of any
/// piece (triangle fans); inside, the rays' exits refined by a local search.
void Compare(const UnionClosestPoint& u, const double o[3], const std::string& name)
{
  const UnionAnswer exact = u.Query(o);
  const double d = std::fabs(exact.Distance);
  double rays = HUGE_VAL;
  double bestDir[3] = { 0, 0, 1 };
  const int count = 20000;
  for (int k = 0; k < count; ++k)
  {
    // Fibonacci directions.
    const double z = 1 - (2 * k + 1.0) / count, r = std::sqrt(1 - z * z);
    const double phi = k * M_PI * (3 - std::sqrt(5.0));
    const double dir[3] = { r * std::cos(phi), r * std::sin(phi), z };
    const double event = RayEvent(u, o, dir, exact.Inside);
    if (event < rays)
    {
      rays = event;
      std::copy(dir, dir + 3, bestDir);
    }
  }
  if (exact.Inside)
  {
    // Local search from the best ray: random steps, halved after 60 failures in a row.
    std::mt19937 random(5);
    double step = 0.05;
    int failures = 0;
    for (int i = 0; i < 20000 && step > 1e-10; ++i)
    {
      double dir[3], n = 0;
      for (int a = 0; a < 3; ++a)
      {
        dir[a] = bestDir[a] + step * std::normal_distribution<double>()(random);
        n += dir[a] * dir[a];
      }
      for (double& x : dir)
      {
        x /= std::sqrt(n);
      }
      const double event = RayEvent(u, o, dir, true);
      if (event < rays)
      {
        rays = event;
        std::copy(dir, dir + 3, bestDir);
        failures = 0;
      }
      else if (++failures == 60)
      {
        step *= 0.5;
        failures = 0;
      }
    }
  }
  else
  {
    rays = HUGE_VAL;
    for (const ConvexPiece& piece : u.Pieces)
    {
      for (const auto& face : piece.Faces)
      {
        for (size_t k = 6; k < face.size(); k += 3)
        {
          rays = std::min(rays, TriangleDistance(o, &face[0], &face[k - 3], &face[k]));
        }
      }
    }
  }
  const double at = std::sqrt((exact.Closest[0] - o[0]) * (exact.Closest[0] - o[0]) +
    (exact.Closest[1] - o[1]) * (exact.Closest[1] - o[1]) +
    (exact.Closest[2] - o[2]) * (exact.Closest[2] - o[2]));
  // 1e-8: the touching tolerance (1e-9) of several pieces at a crease.
  Check(d <= rays + 1e-8,
    "%s (%.17g)",
    std::string(name + ": the exact answer exceeds the reference").c_str(),
    static_cast<double>(d - rays));
  Check(rays - d <= 1e-4,
    "%s (%.17g)",
    std::string(name + ": the reference finds no point this near").c_str(),
    static_cast<double>(rays - d));
  Check(std::fabs(at - d) <= 1e-9,
    "%s (%.17g)",
    std::string(name + ": the closest point is not at the distance").c_str(),
    static_cast<double>(at - d));
  Check(u.Contains(exact.Closest),
    "%s",
    std::string(name + ": the closest point is not in the union").c_str());
  // On the boundary: points around it both in and out of the union.
  int out = 0;
  std::mt19937 probe(3);
  for (int k = 0; k < 400; ++k)
  {
    double x[3];
    for (int a = 0; a < 3; ++a)
    {
      x[a] = exact.Closest[a] + 1e-6 * std::uniform_real_distribution<double>(-1, 1)(probe);
    }
    out += !u.Contains(x);
  }
  Check(out > 0 && out < 400,
    "%s (%.17g)",
    std::string(name + ": the closest point is not on the boundary").c_str(),
    static_cast<double>(out));
  if (d > 1e-9)
  {
    const double dir[3] = {
      (exact.Closest[0] - o[0]) / at, (exact.Closest[1] - o[1]) / at, (exact.Closest[2] - o[2]) / at
    };
    double event = RayEvent(u, o, dir, exact.Inside);
    if (!exact.Inside && event == HUGE_VAL)
    {
      // A ray to a corner or an edge grazes it and may miss by a rounding: the pieces
      // grown by 1e-9 must be entered there (within what growing moves a grazing entry).
      event = RayEvent(u, o, dir, false, 1e-9);
      event = std::fabs(event - d) <= 1e-6 ? d : event;
    }
    Check(exact.Inside ? event >= d - 1e-9 : std::fabs(event - d) <= 1e-9,
      "%s (%.17g)",
      std::string(name + ": the ray through the closest point does not leave or enter there")
        .c_str(),
      static_cast<double>(event - d));
  }
}
} // namespace

int main()
{
  {
    UnionClosestPoint u;
    const double half[3] = { 0.5, 0.5, 0.5 };
    const double c0[3] = { 0.5, 0.5, 0.5 }, c1[3] = { 1.5, 0.5, 0.5 };
    u.Pieces = { Box(c0, half), Box(c1, half) };
    const double o[3] = { 0.9, 0.5, 0.5 };
    const UnionAnswer a = u.Query(o);
    std::printf(
      "two cubes from (0.9, 0.5, 0.5): %.12f (%s)\n", a.Distance, a.Inside ? "inside" : "outside");
    Check(
      std::fabs(a.Distance + 0.5) < 1e-12, "two cubes (%.17g)", static_cast<double>(a.Distance));
    const double onFace[3] = { 1, 0.5, 0.3 };
    const UnionAnswer b = u.Query(onFace);
    Check(std::fabs(b.Distance + 0.3) < 1e-12,
      "O on the shared face (%.17g)",
      static_cast<double>(b.Distance));
    const double outside[3] = { 2.5, 0.5, 0.5 };
    Check(std::fabs(u.Query(outside).Distance - 0.5) < 1e-12,
      "O outside (%.17g)",
      static_cast<double>(u.Query(outside).Distance));
  }
  {
    // 27 touching unit cubes: from the centre, 1.5 to the block's faces.
    UnionClosestPoint u;
    const double half[3] = { 0.5, 0.5, 0.5 };
    for (int k = 0; k < 27; ++k)
    {
      const double c[3] = { 0.5 + k % 3, 0.5 + (k / 3) % 3, 0.5 + k / 9 };
      u.Pieces.push_back(Box(c, half));
    }
    const double o[3] = { 1.5, 1.5, 1.4 };
    const UnionAnswer a = u.Query(o);
    std::printf("27 cubes from the centre: %.12f, %lld faces visited of 162\n",
      a.Distance,
      static_cast<long long>(a.FacesVisited));
    Check(std::fabs(a.Distance + 1.4) < 1e-12, "27 cubes (%.17g)", static_cast<double>(a.Distance));
  }
  {
    // Nested: a small cube inside a big one; O in the small one.
    UnionClosestPoint u;
    const double big[3] = { 2, 2, 2 }, small[3] = { 0.3, 0.3, 0.3 }, c[3] = { 0, 0, 0 };
    const double s[3] = { 0.5, 0.2, 0.1 };
    u.Pieces = { Box(s, small), Box(c, big) };
    const double o[3] = { 0.6, 0.1, 0.0 };
    Check(std::fabs(u.Query(o).Distance + 1.4) < 1e-12,
      "nested (%.17g)",
      static_cast<double>(u.Query(o).Distance));
  }
  // Random unions.
  std::mt19937_64 random(13);
  auto uniform = [&](double lo, double hi)
  { return std::uniform_real_distribution<double>(lo, hi)(random); };
  int cases = 0;
  for (int trial = 0; trial < 24; ++trial)
  {
    UnionClosestPoint u;
    const int pieces = 5 + static_cast<int>(uniform(0, 20));
    for (int k = 0; k < pieces; ++k)
    {
      const double spread = trial % 2 ? 0.8 : 1.6;
      const double c[3] = {
        uniform(-spread, spread), uniform(-spread, spread), uniform(-spread, spread)
      };
      if (k % 3 == 2)
      {
        u.Pieces.push_back(Octahedron(c, uniform(0.4, 1.2)));
      }
      else
      {
        double q[4] = { uniform(-1, 1), uniform(-1, 1), uniform(-1, 1), uniform(-1, 1) };
        const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
        for (double& x : q)
        {
          x /= n;
        }
        const double half[3] = { uniform(0.2, 0.9), uniform(0.2, 0.9), uniform(0.2, 0.9) };
        u.Pieces.push_back(Box(c, half, q));
      }
    }
    for (int query = 0; query < 4; ++query)
    {
      const double o[3] = { uniform(-1, 1), uniform(-1, 1), uniform(-1, 1) };
      Compare(u, o, "random union " + std::to_string(trial) + " query " + std::to_string(query));
      ++cases;
    }
  }
  // Random unions of 5 to 70 hulls of random points on ellipsoids: 8 to 40 faces each.
  for (int trial = 0; trial < 8; ++trial)
  {
    UnionClosestPoint u;
    const int pieces = std::vector<int>{ 5, 20, 45, 70 }[trial % 4];
    const double spread = 0.35 * std::cbrt(double(pieces));
    for (int k = 0; k < pieces; ++k)
    {
      const int corners = 6 + static_cast<int>(uniform(0, 17)); // 2 corners - 4 triangles
      const double c[3] = {
        uniform(-spread, spread), uniform(-spread, spread), uniform(-spread, spread)
      };
      const double r[3] = { uniform(0.3, 0.9), uniform(0.3, 0.9), uniform(0.3, 0.9) };
      std::vector<double> points;
      for (int p = 0; p < corners; ++p)
      {
        double d[3] = { uniform(-1, 1), uniform(-1, 1), uniform(-1, 1) };
        const double length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) + 1e-12;
        for (int a = 0; a < 3; ++a)
        {
          points.push_back(c[a] + r[a] * d[a] / length);
        }
      }
      std::vector<std::vector<int64_t>> faces;
      int64_t onHull = 0;
      std::string error;
      ConvexPiece piece;
      Check(ConvexHull(points, faces, onHull, error) && piece.Build(points, faces, 1e-9, error) &&
          piece.Faces.size() >= 8 && piece.Faces.size() <= 40,
        "%s (%.17g)",
        std::string("a hull piece of 8 to 40 faces: " + error).c_str(),
        static_cast<double>(static_cast<double>(piece.Faces.size())));
      u.Pieces.push_back(piece);
    }
    for (int query = 0; query < 3; ++query)
    {
      const double reach = query == 2 ? 2 * spread + 1.5 : 0.8 * spread;
      const double o[3] = {
        uniform(-reach, reach), uniform(-reach, reach), uniform(-reach, reach)
      };
      Compare(u,
        o,
        "random hulls " + std::to_string(trial) + " (" + std::to_string(pieces) + ") query " +
          std::to_string(query));
      ++cases;
    }
  }
  std::printf("%d random queries compared with 20000 rays each\n", cases);
  {
    // Refusals.
    std::string error;
    ConvexPiece piece;
    const std::vector<double> points = { 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0.1, 0.1, 0.1 };
    Check(!piece.Build(points, { { 0, 1, 2 }, { 0, 1, 3 }, { 0, 2, 3 } }, 1e-9, error),
      "an open piece accepted");
    std::printf("open: %s\n", error.c_str());
    Check(!piece.Build(points,
            { { 0, 2, 1 },
              { 0, 1, 4 },
              { 1, 2, 4 },
              { 2, 0, 4 },
              { 1, 2, 3 },
              { 0, 3, 2 },
              { 0, 1, 3 } },
            1e-9,
            error),
      "a non-manifold piece accepted");
    // A tetrahedron whose four corners lie in one plane.
    const std::vector<double> flat = { 0, 0, 0, 1, 0, 0, 0, 1, 0, 0.3, 0.3, 0 };
    Check(!piece.Build(flat, { { 0, 2, 1 }, { 0, 1, 3 }, { 1, 2, 3 }, { 2, 0, 3 } }, 1e-9, error),
      "a flat piece accepted");
    std::printf("flat: %s\n", error.c_str());
    // A non-convex one: a bipyramid whose top apex is pushed below the base (a funnel).
    const std::vector<double> funnel = {
      1, 0, 0, -0.5, 0.87, 0, -0.5, -0.87, 0, 0, 0, -0.5, 0, 0, -1
    };
    Check(!piece.Build(funnel,
            { { 0, 1, 3 }, { 1, 2, 3 }, { 2, 0, 3 }, { 1, 0, 4 }, { 2, 1, 4 }, { 0, 2, 4 } },
            1e-9,
            error),
      "a non-convex piece accepted");
    std::printf("non-convex: %s\n", error.c_str());
  }
  return Verdict();
}
