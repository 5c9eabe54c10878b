// The crossing search of the self-intersection cut against exact references:
// - Orient3D / Orient2D on nearly and exactly degenerate points (integer lattices scaled by
//   powers of two, so that a 128-bit integer determinant is the reference), at scales
//   from 2^-600 to 2^500, where rounding alone gets the sign wrong;
// - TrianglesIntersect on hand-made cases (crossing, apart, touching at a corner, an
//   edge or a point of an edge, coplanar overlapping, nested, a hexagram or apart, one
//   ulp off a plane) and, in builds with CGAL, against CGAL::do_intersect on random triangles of a
//   small lattice (full of coplanar and touching pairs);
// - ForEachOverlappingPair against every pair of boxes;
// - CutSelfIntersections on two squares crossing without a shared edge: cut (with CGAL),
//   or one group left uncut with a message naming DF_USE_CGAL (without).
#include "Predicates/ExactPredicates.h"
#include "Segment/SelfIntersections.h"
#include "Segment/TriangleCrossings.h"

#include "CoreTest.h"

#ifdef DF_HAVE_CGAL
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#endif

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <set>
#include <utility>
#include <vector>

namespace
{
using vtkdf::Point3;
using vtkdf::coretest::Check;
using Int3 = std::array<int64_t, 3>;

int Sign(__int128 x)
{
  return x > 0 ? 1 : (x < 0 ? -1 : 0);
}

__int128 Det3(const Int3& a, const Int3& b, const Int3& c, const Int3& d)
{
  const __int128 ux = b[0] - a[0], uy = b[1] - a[1], uz = b[2] - a[2];
  const __int128 vx = c[0] - a[0], vy = c[1] - a[1], vz = c[2] - a[2];
  const __int128 wx = d[0] - a[0], wy = d[1] - a[1], wz = d[2] - a[2];
  return wx * (uy * vz - uz * vy) + wy * (uz * vx - ux * vz) + wz * (ux * vy - uy * vx);
}

Point3 Scaled(const Int3& p, int exponent)
{
  return { std::ldexp(static_cast<double>(p[0]), exponent),
    std::ldexp(static_cast<double>(p[1]), exponent),
    std::ldexp(static_cast<double>(p[2]), exponent) };
}

/// Lattice points up to 2^40 (determinants up to 2^123, within 128 bits), each fourth
/// point on the plane of the first three or one unit off it: the floating-point
/// determinant cancels to nothing, and the sign is that of the integer one.
void TestOrientations()
{
  std::mt19937_64 random(7);
  std::uniform_int_distribution<int64_t> big(-(int64_t(1) << 40), int64_t(1) << 40);
  std::uniform_int_distribution<int64_t> small(-3, 3);
  std::uniform_int_distribution<int> unit(-1, 1);
  int wrongNaively = 0, cases = 0;
  for (const int exponent : { 0, -20, -600, 500 })
  {
    for (int trial = 0; trial < 4000; ++trial)
    {
      const Int3 a{ big(random), big(random), big(random) };
      // b, c near a so that differences stay within 2^41.
      Int3 b, c, d;
      const int64_t s = small(random), t = small(random);
      for (int k = 0; k < 3; ++k)
      {
        b[k] = a[k] + big(random) / 2;
        c[k] = a[k] + big(random) / 2;
      }
      for (int k = 0; k < 3; ++k)
      {
        // d = a + s (b - a) + t (c - a), kept within range, plus a unit offset.
        d[k] = a[k] + (s * (b[k] - a[k])) / 4 + (t * (c[k] - a[k])) / 4;
      }
      if (trial % 3 == 0)
      {
        // exactly on the plane: d = a + (b - a) + (c - a) - ... with integer steps
        for (int k = 0; k < 3; ++k)
        {
          d[k] = b[k] + c[k] - a[k];
        }
      }
      d[trial % 3] += unit(random);
      const int expected = Sign(Det3(a, b, c, d));
      const Point3 pa = Scaled(a, exponent), pb = Scaled(b, exponent), pc = Scaled(c, exponent),
                   pd = Scaled(d, exponent);
      const int got = vtkdf::Orient3D(pa.data(), pb.data(), pc.data(), pd.data());
      Check(got == expected,
        "Orient3D at 2^%d, trial %d: %d, expected %d",
        exponent,
        trial,
        got,
        expected);
      // The naive determinant, for the record: the filter has to matter here.
      const double ux = pb[0] - pa[0], uy = pb[1] - pa[1], uz = pb[2] - pa[2];
      const double vx = pc[0] - pa[0], vy = pc[1] - pa[1], vz = pc[2] - pa[2];
      const double wx = pd[0] - pa[0], wy = pd[1] - pa[1], wz = pd[2] - pa[2];
      const double naive =
        wx * (uy * vz - uz * vy) + wy * (uz * vx - ux * vz) + wz * (ux * vy - uy * vx);
      wrongNaively += (naive > 0) - (naive < 0) != expected;
      ++cases;
      // The 2D orientation of the projections, against the same integers.
      for (int i = 0; i < 3; ++i)
      {
        const int j = (i + 1) % 3;
        const __int128 det2 =
          __int128(b[i] - a[i]) * (c[j] - a[j]) - __int128(b[j] - a[j]) * (c[i] - a[i]);
        Int3 e = c;
        e[i] = a[i] + (b[i] - a[i]) * (trial % 2);
        e[j] = a[j] + (b[j] - a[j]) * (trial % 2) + unit(random);
        const __int128 det2e =
          __int128(b[i] - a[i]) * (e[j] - a[j]) - __int128(b[j] - a[j]) * (e[i] - a[i]);
        const Point3 pe = Scaled(e, exponent);
        Check(vtkdf::Orient2D(pa.data(), pb.data(), pc.data(), i, j) == Sign(det2),
          "Orient2D at 2^%d, trial %d",
          exponent,
          trial);
        Check(vtkdf::Orient2D(pa.data(), pb.data(), pe.data(), i, j) == Sign(det2e),
          "Orient2D near a line at 2^%d, trial %d",
          exponent,
          trial);
      }
    }
  }
  std::printf(
    "orientations: %d cases, the naive determinant's sign wrong in %d\n", cases, wrongNaively);
  Check(wrongNaively > 0, "the cases never defeat the naive determinant: they test nothing");
}

bool Meet(const std::array<Point3, 3>& p, const std::array<Point3, 3>& q)
{
  const bool pq = vtkdf::TrianglesIntersect(p.data(), q.data());
  const bool qp = vtkdf::TrianglesIntersect(q.data(), p.data());
  Check(pq == qp, "TrianglesIntersect is not symmetric");
  return pq;
}

void TestTriangleCases()
{
  const std::array<Point3, 3> flat{ { { 0, 0, 0 }, { 4, 0, 0 }, { 0, 4, 0 } } };
  auto standing = [](double x, double y, double z0, double z1) {
    return std::array<Point3, 3>{ { { x - 1, y, z0 }, { x + 1, y, z0 }, { x, y, z1 } } };
  };
  Check(Meet(flat, standing(1, 1, -1, 1)), "a triangle through the other's interior");
  Check(!Meet(flat, standing(1, 1, 0.5, 1)), "a triangle above the other");
  Check(!Meet(flat, standing(5, 5, -1, 1)), "a triangle beside the other");
  Check(Meet(flat, standing(1, 1, 0, 1)), "an edge lying on the other's interior");
  // A corner touching the interior from above, and one ulp above it.
  const std::array<Point3, 3> tip{ { { 1, 1, 0 }, { 1, 2, 3 }, { 2, 1, 3 } } };
  Check(Meet(flat, tip), "a corner on the other's interior");
  std::array<Point3, 3> lifted = tip;
  lifted[0][2] = std::nextafter(0.0, 1.0);
  Check(!Meet(flat, lifted), "a corner one ulp above the other");
  // A corner touching the middle of the hypotenuse (x + y = 4), and just beyond.
  const std::array<Point3, 3> onEdge{ { { 2, 2, 0 }, { 3, 3, 1 }, { 3, 3, -1 } } };
  Check(Meet(flat, onEdge), "a corner on the other's edge");
  std::array<Point3, 3> beyond = onEdge;
  beyond[0][0] = std::nextafter(2.0, 3.0);
  Check(!Meet(flat, beyond), "a corner one ulp beyond the other's edge");
  // Edge against edge, skew: the x axis edge of `flat` and a segment crossing it.
  const std::array<Point3, 3> skew{ { { 2, 0, -1 }, { 2, 0, 1 }, { 2, -3, 0 } } };
  Check(Meet(flat, skew), "an edge crossing the other's edge");
  // Coplanar: overlapping, nested, touching at a point of an edge, apart.
  const std::array<Point3, 3> overlap{ { { 1, 1, 0 }, { 5, 1, 0 }, { 1, -3, 0 } } };
  Check(Meet(flat, overlap), "coplanar triangles overlapping");
  const std::array<Point3, 3> nested{ { { 0.5, 0.5, 0 }, { 1, 0.5, 0 }, { 0.5, 1, 0 } } };
  Check(Meet(flat, nested), "a coplanar triangle inside the other");
  const std::array<Point3, 3> touching{ { { 2, 2, 0 }, { 5, 5, 0 }, { 2, 5, 0 } } };
  Check(Meet(flat, touching), "coplanar triangles touching at a point of an edge");
  // A corner on the line of the other's edge, beyond its end.
  const std::array<Point3, 3> inLine{ { { 6, -2, 0 }, { 8, -1, 0 }, { 8, -3, 0 } } };
  Check(!Meet(flat, inLine), "coplanar: a corner on the line of the other's edge, beyond it");
  // A hexagram: no corner of either inside the other, only edges crossing.
  const std::array<Point3, 3> up{ { { 0, 0, 1 }, { 6, 0, 1 }, { 3, 6, 1 } } };
  const std::array<Point3, 3> down{ { { 0, 4, 1 }, { 6, 4, 1 }, { 3, -2, 1 } } };
  Check(Meet(up, down), "coplanar triangles of a hexagram");
  const std::array<Point3, 3> apart{ { { 2.5, 2.5, 0 }, { 5, 5, 0 }, { 2.5, 5, 0 } } };
  Check(!Meet(flat, apart), "coplanar triangles apart");
  // The same in a tilted plane whose points are not exact in binary: decided by the
  // predicates on the given coordinates, whatever they are; symmetric at least, and the
  // triangle against itself shifted far away apart.
  const std::array<Point3, 3> tilted{ { { 0.1, 0.2, 0.3 }, { 1.7, 0.4, 0.9 }, { 0.3, 1.9, 1.3 } } };
  std::array<Point3, 3> far = tilted;
  for (Point3& p : far)
  {
    p[0] += 10;
  }
  Check(Meet(tilted, tilted), "a triangle meets itself");
  Check(!Meet(tilted, far), "a triangle and a copy far away");
}

#ifdef DF_HAVE_CGAL
/// Random triangles with corners on a 4 x 4 x 4 lattice: many coplanar, touching and
/// edge-sharing pairs. Each answer against CGAL's exact do_intersect.
void TestAgainstCGAL()
{
  using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
  std::mt19937_64 random(11);
  std::uniform_int_distribution<int> lattice(0, 3);
  auto triangle = [&]()
  {
    std::array<Point3, 3> t;
    do
    {
      for (Point3& p : t)
      {
        // A lattice in an oblique frame whose coordinates are not exact in binary.
        const double i = lattice(random), j = lattice(random), k = lattice(random);
        p = { 0.1 * i + 0.3 * j, 0.7 * j - 0.2 * k, 0.3 * i + 0.5 * k };
      }
    } while (vtkdf::Collinear(t[0].data(), t[1].data(), t[2].data()));
    return t;
  };
  auto cgal = [](const std::array<Point3, 3>& t)
  {
    return Kernel::Triangle_3(Kernel::Point_3(t[0][0], t[0][1], t[0][2]),
      Kernel::Point_3(t[1][0], t[1][1], t[1][2]),
      Kernel::Point_3(t[2][0], t[2][1], t[2][2]));
  };
  int meeting = 0;
  const int trials = 200000;
  for (int trial = 0; trial < trials; ++trial)
  {
    const std::array<Point3, 3> p = triangle(), q = triangle();
    const bool expected = CGAL::do_intersect(cgal(p), cgal(q));
    meeting += expected;
    Check(Meet(p, q) == expected,
      "trial %d: TrianglesIntersect says %d, CGAL %d",
      trial,
      !expected,
      expected);
  }
  std::printf("against CGAL: %d pairs, %d meeting\n", trials, meeting);
}
#endif

void TestOverlappingPairs()
{
  std::mt19937_64 random(3);
  std::uniform_real_distribution<double> where(0, 10), size(0, 1.5);
  std::vector<Point3> points;
  std::vector<vtkdf::TriangleCorners> triangles;
  for (size_t t = 0; t < 3000; ++t)
  {
    const Point3 base{ where(random), where(random), std::round(where(random)) };
    for (int c = 0; c < 3; ++c)
    {
      // Some triangles flat in z = integer: boxes that touch exactly.
      points.push_back({ base[0] + size(random),
        base[1] + size(random),
        t % 2 ? base[2] : base[2] + size(random) });
    }
    triangles.push_back({ 3 * t, 3 * t + 1, 3 * t + 2 });
  }
  std::set<std::pair<size_t, size_t>> found;
  size_t reports = 0;
  vtkdf::ForEachOverlappingPair(points,
    triangles,
    [&](size_t a, size_t b)
    {
      ++reports;
      found.emplace(a, b);
      Check(a < b, "a pair reported as (%zu, %zu)", a, b);
    });
  std::set<std::pair<size_t, size_t>> expected;
  for (size_t a = 0; a < triangles.size(); ++a)
  {
    for (size_t b = a + 1; b < triangles.size(); ++b)
    {
      bool meets = true;
      for (int k = 0; k < 3; ++k)
      {
        double minA = 1e300, maxA = -1e300, minB = 1e300, maxB = -1e300;
        for (int c = 0; c < 3; ++c)
        {
          minA = std::min(minA, points[triangles[a][c]][k]);
          maxA = std::max(maxA, points[triangles[a][c]][k]);
          minB = std::min(minB, points[triangles[b][c]][k]);
          maxB = std::max(maxB, points[triangles[b][c]][k]);
        }
        meets = meets && maxA >= minB && maxB >= minA;
      }
      if (meets)
      {
        expected.emplace(a, b);
      }
    }
  }
  std::printf("overlapping boxes: %zu pairs\n", expected.size());
  Check(found == expected && reports == expected.size(),
    "the hierarchy reports %zu pairs (%zu distinct), every pair's test %zu",
    reports,
    found.size(),
    expected.size());
}

/// Two squares crossing along the z axis without a shared edge.
void TestCut()
{
  vtkdf::LargeVector<double> points;
  vtkdf::LargeVector<int64_t> triangles;
  auto square = [&](double ux, double uy)
  {
    const int64_t base = static_cast<int64_t>(points.size() / 3);
    for (const double s : { -1.0, 1.0 })
    {
      for (const double z : { -1.0, 1.0 })
      {
        points.insert(points.end(), { s * ux, s * uy, z });
      }
    }
    triangles.insert(triangles.end(), { base, base + 2, base + 3, base, base + 3, base + 1 });
  };
  square(1, 0);
  square(0, 1);
  vtkdf::SelfIntersectionCut cut;
  vtkdf::CutSelfIntersections(points, triangles, cut);
  Check(cut.CrossingGroups == 1, "crossing squares: %lld groups", (long long)cut.CrossingGroups);
#ifdef DF_HAVE_CGAL
  Check(cut.Cut() && cut.FailedGroups == 0,
    "crossing squares not cut (%lld failed: %s)",
    (long long)cut.FailedGroups,
    cut.FailedMessage.c_str());
#else
  Check(!cut.Cut() && cut.FailedGroups == 1 && cut.FailedTriangles == 4 &&
      cut.FailedMessage.find("DF_USE_CGAL=OFF") != std::string::npos,
    "without CGAL: %lld groups left uncut (%lld triangles), message '%s'",
    (long long)cut.FailedGroups,
    (long long)cut.FailedTriangles,
    cut.FailedMessage.c_str());
#endif
}
} // namespace

int main()
{
  TestOrientations();
  TestTriangleCases();
#ifdef DF_HAVE_CGAL
  TestAgainstCGAL();
#endif
  TestOverlappingPairs();
  TestCut();
  return vtkdf::coretest::Verdict();
}
