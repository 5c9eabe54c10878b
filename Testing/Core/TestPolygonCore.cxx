// PolygonTriangulation against the polygon itself: on concave, star-shaped, comb-like,
// collinear and near-duplicate polygons in tilted planes at several scales, the
// triangles keep the polygon's orientation, their areas add up to the polygon's, and a
// lattice of points in the plane is covered by a triangle exactly where it lies inside
// the polygon (even-odd rule, away from its edges). Convex polygons become the fan around
// corner 0. Polygons whose edges cross are refused.
#include "Polygons/PolygonTriangulation.h"

#include "CoreTest.h"

#include <array>
#include <chrono>
#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace
{
using vtkdf::coretest::Check;
using Point2 = std::array<double, 2>;

/// A plane in space: corner (x, y) of a 2D polygon goes to origin + x u + y v (+ lift n).
struct Placement
{
  std::array<double, 3> Origin, U, V, N;
  double Scale;

  static Placement Random(std::mt19937_64& random, double scale, double offset)
  {
    std::normal_distribution<double> gauss;
    std::array<double, 3> a{ gauss(random), gauss(random), gauss(random) };
    std::array<double, 3> b{ gauss(random), gauss(random), gauss(random) };
    auto normalize = [](std::array<double, 3>& x)
    {
      const double l = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
      for (double& c : x)
      {
        c /= l;
      }
    };
    normalize(a);
    const double along = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    for (int k = 0; k < 3; ++k)
    {
      b[k] -= along * a[k];
    }
    normalize(b);
    const std::array<double, 3> n{
      a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]
    };
    return {
      { offset * gauss(random), offset * gauss(random), offset * gauss(random) }, a, b, n, scale
    };
  }

  std::vector<double> Place(const std::vector<Point2>& polygon,
    const std::vector<double>& lift = {}) const
  {
    std::vector<double> xyz;
    for (size_t i = 0; i < polygon.size(); ++i)
    {
      const double h = lift.empty() ? 0 : lift[i];
      for (int k = 0; k < 3; ++k)
      {
        xyz.push_back(this->Origin[k] +
          this->Scale * (polygon[i][0] * this->U[k] + polygon[i][1] * this->V[k] + h * this->N[k]));
      }
    }
    return xyz;
  }
};

double Orient(const Point2& a, const Point2& b, const Point2& c)
{
  return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

double SignedArea(const std::vector<Point2>& polygon)
{
  double twice = 0;
  for (size_t i = 0; i < polygon.size(); ++i)
  {
    const Point2& p = polygon[i];
    const Point2& q = polygon[(i + 1) % polygon.size()];
    twice += p[0] * q[1] - p[1] * q[0];
  }
  return twice / 2;
}

bool InsideEvenOdd(const std::vector<Point2>& polygon, const Point2& x)
{
  bool inside = false;
  for (size_t i = 0; i < polygon.size(); ++i)
  {
    const Point2& p = polygon[i];
    const Point2& q = polygon[(i + 1) % polygon.size()];
    if ((p[1] > x[1]) != (q[1] > x[1]) &&
      x[0] < p[0] + (x[1] - p[1]) * (q[0] - p[0]) / (q[1] - p[1]))
    {
      inside = !inside;
    }
  }
  return inside;
}

double DistanceToEdges(const std::vector<Point2>& polygon, const Point2& x)
{
  double best = HUGE_VAL;
  for (size_t i = 0; i < polygon.size(); ++i)
  {
    const Point2& p = polygon[i];
    const Point2& q = polygon[(i + 1) % polygon.size()];
    const double dx = q[0] - p[0], dy = q[1] - p[1], l2 = dx * dx + dy * dy;
    const double t =
      l2 > 0 ? std::fmin(1, std::fmax(0, ((x[0] - p[0]) * dx + (x[1] - p[1]) * dy) / l2)) : 0;
    best = std::fmin(best, std::hypot(x[0] - p[0] - t * dx, x[1] - p[1] - t * dy));
  }
  return best;
}

/// Triangulates `polygon` (2D, counter-clockwise or not) placed by `placement` and checks
/// the triangles against it (see the file's comment).
void CheckTiling(const std::string& name,
  const std::vector<Point2>& polygon,
  const Placement& placement,
  bool convex = false)
{
  vtkdf::PolygonTriangulation cut;
  const std::vector<double> xyz = placement.Place(polygon);
  const int64_t n = static_cast<int64_t>(polygon.size());
  if (!cut.Triangulate(xyz.data(), n))
  {
    Check(false, "%s: refused (%s)", name.c_str(), cut.Problem().c_str());
    return;
  }
  const std::vector<int64_t>& t = cut.Triangles();
  Check(static_cast<int64_t>(t.size()) == 3 * (n - 2),
    "%s: %zu triangle corners for %lld corners",
    name.c_str(),
    t.size(),
    static_cast<long long>(n));
  const double area = SignedArea(polygon);
  double size = 0;
  for (const Point2& p : polygon)
  {
    size = std::fmax(size, std::hypot(p[0] - polygon[0][0], p[1] - polygon[0][1]));
  }
  double sum = 0;
  for (size_t k = 0; k + 2 < t.size(); k += 3)
  {
    const double a = Orient(polygon[t[k]], polygon[t[k + 1]], polygon[t[k + 2]]) / 2;
    // Same orientation as the polygon (zero-area ears allowed).
    Check(a * area >= -1e-9 * size * size,
      "%s: triangle %zu turns against the polygon (%g)",
      name.c_str(),
      k / 3,
      a);
    sum += std::fabs(a);
    if (convex)
    {
      Check(t[k] == 0 && t[k + 1] == static_cast<int64_t>(k / 3 + 1) &&
          t[k + 2] == static_cast<int64_t>(k / 3 + 2),
        "%s: a convex polygon is not the fan around corner 0",
        name.c_str());
    }
  }
  Check(std::fabs(sum - std::fabs(area)) <= 1e-9 * size * size,
    "%s: triangles cover %.17g, the polygon %.17g",
    name.c_str(),
    sum,
    std::fabs(area));
  Check(cut.Planarity() <= 1e-12,
    "%s: planarity %g of a planar polygon",
    name.c_str(),
    cut.Planarity());

  // Coverage on a lattice over the polygon's box, away from its edges.
  double lo[2] = { HUGE_VAL, HUGE_VAL }, hi[2] = { -HUGE_VAL, -HUGE_VAL };
  for (const Point2& p : polygon)
  {
    for (int a = 0; a < 2; ++a)
    {
      lo[a] = std::fmin(lo[a], p[a]);
      hi[a] = std::fmax(hi[a], p[a]);
    }
  }
  int wrong = 0;
  const int steps = 60;
  for (int i = 0; i <= steps; ++i)
  {
    for (int j = 0; j <= steps; ++j)
    {
      const Point2 x{ lo[0] + (hi[0] - lo[0]) * (i + 0.37) / steps,
        lo[1] + (hi[1] - lo[1]) * (j + 0.61) / steps };
      if (DistanceToEdges(polygon, x) < 1e-6 * size)
      {
        continue;
      }
      bool covered = false;
      for (size_t k = 0; k + 2 < t.size() && !covered; k += 3)
      {
        const Point2 &a = polygon[t[k]], &b = polygon[t[k + 1]], &c = polygon[t[k + 2]];
        const double s = Orient(a, b, c) >= 0 ? 1 : -1;
        covered = s * Orient(a, b, x) >= 0 && s * Orient(b, c, x) >= 0 && s * Orient(c, a, x) >= 0;
      }
      wrong += covered != InsideEvenOdd(polygon, x);
    }
  }
  Check(
    wrong == 0, "%s: %d lattice points covered otherwise than the polygon", name.c_str(), wrong);
}

void CheckRefused(const std::string& name,
  const std::vector<Point2>& polygon,
  const Placement& placement,
  const std::string& problem)
{
  vtkdf::PolygonTriangulation cut;
  const std::vector<double> xyz = placement.Place(polygon);
  const bool done = cut.Triangulate(xyz.data(), static_cast<int64_t>(polygon.size()));
  Check(!done, "%s: triangulated, should be refused", name.c_str());
  Check(done || cut.Problem().find(problem) != std::string::npos,
    "%s: problem \"%s\", not \"%s\"",
    name.c_str(),
    cut.Problem().c_str(),
    problem.c_str());
}

/// A random simple polygon: star-shaped around the origin, `count` corners at increasing
/// angles and random radii.
std::vector<Point2> RandomStar(std::mt19937_64& random, int count)
{
  std::uniform_real_distribution<double> radius(0.2, 1.0), jitter(0.1, 0.9);
  std::vector<Point2> polygon;
  for (int i = 0; i < count; ++i)
  {
    const double angle = 2 * M_PI * (i + jitter(random)) / count;
    const double r = radius(random);
    polygon.push_back({ r * std::cos(angle), r * std::sin(angle) });
  }
  return polygon;
}
} // namespace

int main()
{
  std::mt19937_64 random(7);
  const std::vector<Point2> L{ { 0, 0 }, { 2, 0 }, { 2, 1 }, { 1, 1 }, { 1, 2 }, { 0, 2 } };
  const std::vector<Point2> U{
    { 0, 0 }, { 3, 0 }, { 3, 3 }, { 2, 3 }, { 2, 1 }, { 1, 1 }, { 1, 3 }, { 0, 3 }
  };
  const std::vector<Point2> comb{ { 0, 0 },
    { 1, 0 },
    { 2, 0 },
    { 3, 0 },
    { 4, 0 },
    { 4, 2 },
    { 3.5, 2 },
    { 3.5, 0.5 },
    { 3, 0.5 },
    { 3, 2 },
    { 2.5, 2 },
    { 2.5, 0.5 },
    { 2, 0.5 },
    { 2, 1.25 },
    { 2, 2 },
    { 1.5, 2 },
    { 1.5, 0.5 },
    { 1, 0.5 },
    { 1, 2 },
    { 0, 2 },
    { 0, 1 } };
  std::vector<Point2> star;
  for (int k = 0; k < 10; ++k)
  {
    const double r = k % 2 ? 0.6 : 1.5;
    star.push_back({ r * std::cos(M_PI * k / 5 + 0.3), r * std::sin(M_PI * k / 5 + 0.3) });
  }
  std::vector<Point2> hexagon;
  for (int k = 0; k < 6; ++k)
  {
    hexagon.push_back({ std::cos(M_PI * k / 3), std::sin(M_PI * k / 3) });
  }
  // A spiral corridor: deeply concave, every ear found late.
  std::vector<Point2> spiral;
  for (int k = 0; k <= 40; ++k)
  {
    const double a = 0.35 * k, r = 1 + 0.25 * a;
    spiral.push_back({ r * std::cos(a), r * std::sin(a) });
  }
  for (int k = 40; k >= 0; --k)
  {
    const double a = 0.35 * k, r = 1.6 + 0.25 * a;
    spiral.push_back({ r * std::cos(a), r * std::sin(a) });
  }

  // Every shape in both orientations, in random planes, from tiny to huge and far away.
  for (double scale : { std::ldexp(1.0, -40), 1e-3, 1.0, 37.0, std::ldexp(1.0, 40) })
  {
    for (double offset : { 0.0, 1e3 })
    {
      const Placement place = Placement::Random(random, scale, offset * scale);
      const std::string at =
        " at scale " + std::to_string(scale) + " offset " + std::to_string(offset);
      for (const auto& [name, shape] : std::vector<std::pair<std::string, std::vector<Point2>>>{
             { "L", L }, { "U", U }, { "comb", comb }, { "star", star }, { "spiral", spiral } })
      {
        CheckTiling(name + at, shape, place);
        CheckTiling(name + " reversed" + at, { shape.rbegin(), shape.rend() }, place);
      }
      CheckTiling("hexagon" + at, hexagon, place, true);
    }
  }

  // Near-duplicate corners (an exported mesh's unmerged points), 1e-18 to 1e-6 of the
  // polygon's size away, after a convex and after a reflex corner of the U.
  for (int exponent = 6; exponent <= 18; exponent += 2)
  {
    for (int at : { 2, 4 })
    {
      // Off the corner along the bisector of its edges, so that the polygon stays simple.
      std::vector<Point2> twin = U;
      const double d = 3 * std::pow(10.0, -exponent);
      const Point2 &c = U[at], &before = U[at - 1], &after = U[at + 1];
      const double lb = std::hypot(before[0] - c[0], before[1] - c[1]),
                   la = std::hypot(after[0] - c[0], after[1] - c[1]);
      twin.insert(twin.begin() + at + 1,
        { c[0] + d * ((before[0] - c[0]) / lb + (after[0] - c[0]) / la),
          c[1] + d * ((before[1] - c[1]) / lb + (after[1] - c[1]) / la) });
      const Placement place = Placement::Random(random, 1.0, 10.0);
      CheckTiling("U with a duplicate of corner " + std::to_string(at) + " 1e-" +
          std::to_string(exponent) + " away",
        twin,
        place);
    }
  }
  {
    std::vector<Point2> exact = comb;
    exact.insert(exact.begin() + 7, comb[6]);
    exact.insert(exact.begin() + 2, comb[1]);
    CheckTiling("comb with exact duplicates", exact, Placement::Random(random, 1.0, 0.0));
  }

  // Random star-shaped polygons, in both orientations.
  for (int trial = 0; trial < 200; ++trial)
  {
    const std::vector<Point2> polygon = RandomStar(random, 4 + trial % 60);
    const Placement place = Placement::Random(random, std::ldexp(1.0, trial % 21 - 10), 4.0);
    CheckTiling("random star " + std::to_string(trial), polygon, place);
    CheckTiling(
      "random star reversed " + std::to_string(trial), { polygon.rbegin(), polygon.rend() }, place);
  }

  // On one line: zero-area triangles, which cover the polygon's edges and nothing else.
  {
    const std::vector<Point2> line{ { 0, 0 }, { 1, 0 }, { 3, 0 }, { 2, 0 } };
    vtkdf::PolygonTriangulation cut;
    const std::vector<double> xyz = Placement::Random(random, 1.0, 1.0).Place(line);
    Check(cut.Triangulate(xyz.data(), 4) && cut.Triangles().size() == 6,
      "a polygon on one line: %s",
      cut.Problem().c_str());
  }

  // Not planar: the corners lifted +-0.05 of the U's size; still triangulated, its
  // planarity reported.
  {
    const Placement place = Placement::Random(random, 2.0, 1.0);
    std::vector<double> lift;
    for (size_t i = 0; i < U.size(); ++i)
    {
      lift.push_back(i % 2 ? 0.05 * 4.24 : -0.05 * 4.24);
    }
    const std::vector<double> xyz = place.Place(U, lift);
    vtkdf::PolygonTriangulation cut;
    Check(cut.Triangulate(xyz.data(), static_cast<int64_t>(U.size())),
      "a non-planar U is refused: %s",
      cut.Problem().c_str());
    Check(cut.Planarity() > 0.02 && cut.Planarity() <= 0.05,
      "a U lifted 0.05 of its size has "
      "planarity %g",
      cut.Planarity());
  }

  // No triangulation along the edges.
  const Placement place = Placement::Random(random, 3.0, 2.0);
  CheckRefused("bow tie",
    { { 0, 0 }, { 2, 2 }, { 2, 0 }, { 0, 2 } },
    place,
    "edges from corner 0 and from corner 2 cross");
  std::vector<Point2> pentagram;
  for (int k = 0; k < 5; ++k)
  {
    pentagram.push_back({ std::cos(4 * M_PI * k / 5), std::sin(4 * M_PI * k / 5) });
  }
  CheckRefused("pentagram", pentagram, place, "cross");
  CheckRefused(
    "figure eight (no area)", { { 0, 0 }, { 1, 1 }, { 1, 0 }, { 0, 1 } }, place, "cross");
  // A path there and back encloses no area: refused, or zero-area triangles (its edges).
  for (int trial = 0; trial < 20; ++trial)
  {
    const std::vector<Point2> path{ { 0, 0 }, { 1, 0 }, { 1, 1 }, { 1, 0 } };
    const std::vector<double> xyz = Placement::Random(random, 1.0, 1.0).Place(path);
    vtkdf::PolygonTriangulation cut;
    double area = 0;
    if (cut.Triangulate(xyz.data(), 4))
    {
      for (size_t k = 0; k < 6; k += 3)
      {
        const auto& t = cut.Triangles();
        area += std::fabs(Orient(path[t[k]], path[t[k + 1]], path[t[k + 2]]));
      }
    }
    Check(area == 0, "a path there and back covers area %g", area);
  }

  // A polygon of 4000 corners (a cap of a cut): quick enough to be a cell among many.
  {
    const std::vector<Point2> big = RandomStar(random, 4000);
    const std::vector<double> xyz = Placement::Random(random, 1.0, 1.0).Place(big);
    vtkdf::PolygonTriangulation cut;
    const auto start = std::chrono::steady_clock::now();
    const bool done = cut.Triangulate(xyz.data(), 4000);
    const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    Check(done, "4000 corners: %s", cut.Problem().c_str());
    std::printf("4000 random star corners: %.3f s\n", seconds);
  }
  return vtkdf::coretest::Verdict();
}
