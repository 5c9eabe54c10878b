// Unit test of the VTK-free core: procedural meshes, every culling mode, the CPU scan
// against an exact brute-force reference on every sample; the per-sample query route
// against the brute force and against the scan. And the sites' boxes' rounding to float
// (Common/FloatBounds.h) against std::nextafter, the scan's branch-free Max and Min
// (Common/MinMax.h) against std::max and std::min.
#include "Common/FloatBounds.h"
#include "Common/MinMax.h"
#include "CoreTest.h"
#include "ExactDistance.h"
#include "LinearFactor/LinearFactorField.h"
#include "LinearFactor/LinearFactorScan.h"
#include "LinearFactor/MeshSites.h"
#include "LinearFactor/NearestTriangleQueries.h"
#include "LinearFactor/SliceDomain.h"
#include "ThreadFor.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <thread>
#include <vector>

using namespace vtkdf;
using namespace vtkdf::coretest;

namespace
{

double BruteForce(const MeshInput& m, const double x[3])
{
  double best = HUGE_VAL, c[3];
  const double* P = m.Points.data();
  auto consider = [&]()
  {
    best = std::min(best,
      std::sqrt((c[0] - x[0]) * (c[0] - x[0]) + (c[1] - x[1]) * (c[1] - x[1]) +
        (c[2] - x[2]) * (c[2] - x[2])));
  };
  for (size_t t = 0; t < m.Triangles.size(); t += 3)
  {
    reference::ClosestOnTriangle(
      x, P + 3 * m.Triangles[t], P + 3 * m.Triangles[t + 1], P + 3 * m.Triangles[t + 2], c);
    consider();
  }
  for (size_t s = 0; s < m.Segments.size(); s += 2)
  {
    reference::ClosestOnSegment(x, P + 3 * m.Segments[s], P + 3 * m.Segments[s + 1], c);
    consider();
  }
  for (int64_t v : m.Vertices)
  {
    std::copy(P + 3 * v, P + 3 * v + 3, c);
    consider();
  }
  return best;
}

/// Calls visit(x, at) for every sample of the request's extent: its position and its
/// index in the extent's arrays (x fastest).
template<typename Visit>
void ForEachSample(const LinearFactorRequest& request, const Visit& visit)
{
  const IndexBox& e = request.Extent;
  int64_t at = 0;
  for (int k = e.Lo[2]; k <= e.Hi[2]; ++k)
  {
    for (int j = e.Lo[1]; j <= e.Hi[1]; ++j)
    {
      for (int i = e.Lo[0]; i <= e.Hi[0]; ++i, ++at)
      {
        const double x[3] = { request.Grid.Coordinate(0, i),
          request.Grid.Coordinate(1, j),
          request.Grid.Coordinate(2, k) };
        visit(x, at);
      }
    }
  }
}

/// The field of `mesh` by the family's entry point (as the filter calls it) against the
/// brute force, every culling mode; and the parallel build of its sites against the
/// serial one.
/// Three uneven slabs along each axis (a distributed run's pieces) equal the whole grid
/// bit for bit: distances, closest cells and closest points, ties included (each sample's
/// key does not depend on where its site's run of samples begins).
void CheckPieces(const std::string& name, const MeshInput& mesh, const LinearFactorRequest& whole)
{
  struct Field
  {
    std::vector<float> Distance, Point;
    std::vector<int64_t> Cell;
  };
  auto compute = [&](const IndexBox& extent, Field& f)
  {
    LinearFactorRequest request = whole;
    request.Extent = extent;
    const size_t n = static_cast<size_t>(extent.Count());
    f.Distance.assign(n, 0), f.Point.assign(3 * n, 0), f.Cell.assign(n, 0);
    LinearFactorArrays arrays;
    arrays.Distance = f.Distance.data();
    arrays.ClosestPoint = f.Point.data();
    arrays.ClosestCellId = f.Cell.data();
    Execution execution;
    execution.For = ThreadFor;
    LinearFactorReport report;
    std::string error;
    return ComputeLinearFactorField(mesh, request, nullptr, arrays, execution, report, error);
  };
  Field all;
  const IndexBox& e = whole.Grid.Whole;
  Check(compute(e, all), "%s: the whole grid", name.c_str());
  int64_t differing = 0;
  for (int a = 0; a < 3; ++a)
  {
    const int cuts[4] = { e.Lo[a], e.Lo[a] + e.Size(a) / 5, e.Lo[a] + e.Size(a) / 2, e.Hi[a] };
    for (int s = 0; s < 3; ++s)
    {
      IndexBox slab = e;
      slab.Lo[a] = cuts[s], slab.Hi[a] = cuts[s + 1];
      Field part;
      Check(compute(slab, part), "%s: a slab", name.c_str());
      int64_t v = 0;
      for (int k = slab.Lo[2]; k <= slab.Hi[2]; ++k)
      {
        for (int j = slab.Lo[1]; j <= slab.Hi[1]; ++j)
        {
          for (int i = slab.Lo[0]; i <= slab.Hi[0]; ++i, ++v)
          {
            const int64_t w = (i - e.Lo[0]) +
              int64_t(e.Size(0)) * ((j - e.Lo[1]) + int64_t(e.Size(1)) * (k - e.Lo[2]));
            differing += std::memcmp(&part.Distance[v], &all.Distance[w], 4) != 0 ||
              part.Cell[v] != all.Cell[w] ||
              std::memcmp(&part.Point[3 * v], &all.Point[3 * w], 12) != 0;
          }
        }
      }
    }
  }
  Check(differing == 0,
    "%s: %lld samples of the slabs differ from the whole grid",
    name.c_str(),
    (long long)differing);
}

void RunCase(const std::string& name, const MeshInput& input, int resolution)
{
  MeshInput mesh = input;
  Check(UsedPointBounds(mesh, mesh.Bounds), "%s: no point used", name.c_str());
  for (DomainShape culling : { DomainShape::Auto, DomainShape::NonManifold, DomainShape::Manifold })
  {
    LinearFactorRequest request;
    request.Grid = SampleGrid::FromBounds(mesh.Bounds.data(), resolution, 0.25);
    request.Extent = request.Grid.Whole;
    request.Domains = culling;
    const double h = request.Grid.MinSpacing();
    std::vector<float> distance(request.Extent.Count());
    LinearFactorArrays arrays;
    arrays.Distance = distance.data();
    Execution execution;
    execution.For = ThreadFor;
    LinearFactorReport report;
    std::string error;
    Check(ComputeLinearFactorField(mesh, request, nullptr, arrays, execution, report, error),
      "%s: %s",
      name.c_str(),
      error.c_str());

    // The parallel build writes the same sites and planes.
    MeshSites sites, parallel;
    Check(sites.Build(mesh, culling, 1e-5 * h, error), "%s: build %s", name.c_str(), error.c_str());
    Check(parallel.Build(mesh, culling, 1e-5 * h, error, ThreadFor),
      "%s: build %s",
      name.c_str(),
      error.c_str());
    // Every site and its planes alike, field by field (a Site has padding).
    bool same = parallel.Count() == sites.Count();
    for (int64_t s = 0; same && s < sites.Count(); ++s)
    {
      Site x, y;
      sites.Describe(s, x);
      parallel.Describe(s, y);
      HalfSpace px[MaxDomainPlanes], py[MaxDomainPlanes];
      const int n = sites.Planes(s, x, px, MaxDomainPlanes);
      same = x.Type == y.Type && x.Required == y.Required && x.PlaneCount == y.PlaneCount &&
        x.CellId == y.CellId && std::memcmp(x.Anchor, y.Anchor, sizeof(x.Anchor)) == 0 &&
        std::memcmp(x.Axis, y.Axis, sizeof(x.Axis)) == 0 &&
        std::memcmp(x.Normal, y.Normal, sizeof(x.Normal)) == 0 &&
        std::memcmp(x.BoundsMin, y.BoundsMin, sizeof(x.BoundsMin)) == 0 &&
        std::memcmp(x.BoundsMax, y.BoundsMax, sizeof(x.BoundsMax)) == 0 &&
        parallel.Planes(s, y, py, MaxDomainPlanes) == n &&
        std::memcmp(px, py, n * sizeof(HalfSpace)) == 0;
    }
    Check(same, "%s: the parallel build differs from the serial one", name.c_str());

    double worst = 0;
    int64_t worstAt = -1;
    const IndexBox& e = request.Extent;
    ForEachSample(request,
      [&](const double* x, int64_t at)
      {
        const double err = std::fabs(distance[at] - BruteForce(mesh, x));
        if (!(err <= worst))
        {
          worst = err;
          worstAt = at;
        }
      });
    const char* mode = culling == DomainShape::Auto ? "auto"
      : culling == DomainShape::NonManifold         ? "nonmanifold"
                                                    : "manifold";
    std::printf("%-14s %-12s max|err| = %.3g h  culling factor %.2f  (sites %zu, pyramids %lld, "
                "unbounded vertices %lld)\n",
      name.c_str(),
      mode,
      worst / h,
      double(report.Evaluations) / double(e.Count()),
      static_cast<size_t>(sites.Count()),
      (long long)sites.Statistics.PyramidVertices,
      (long long)sites.Statistics.UnboundedVertices);
    Check(worst <= 1e-3 * h,
      "%s %s: error %g h at sample %lld",
      name.c_str(),
      mode,
      worst / h,
      (long long)worstAt);
    CheckPieces(name + " " + mode, mesh, request);
  }
}

MeshInput Sphere(int rings, int segments, double jitter, unsigned seed)
{
  MeshInput m;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-jitter, jitter);
  m.Points = { 0, 0, 1 };
  for (int r = 1; r < rings; ++r)
  {
    const double th = M_PI * r / rings;
    for (int s = 0; s < segments; ++s)
    {
      const double ph = 2 * M_PI * s / segments;
      const double rad = 1 + u(rng);
      m.Points.insert(m.Points.end(),
        { rad * std::sin(th) * std::cos(ph),
          rad * std::sin(th) * std::sin(ph),
          rad * std::cos(th) });
    }
  }
  m.Points.insert(m.Points.end(), { 0, 0, -1 });
  const int64_t south = static_cast<int64_t>(m.Points.size() / 3 - 1);
  auto id = [&](int r, int s) { return int64_t(1 + (r - 1) * segments + (s % segments)); };
  auto tri = [&](int64_t a, int64_t b, int64_t c)
  {
    m.Triangles.insert(m.Triangles.end(), { a, b, c });
    m.TriangleCells.push_back(static_cast<int64_t>(m.TriangleCells.size()));
  };
  for (int s = 0; s < segments; ++s)
  {
    tri(0, id(1, s), id(1, s + 1));
    for (int r = 1; r + 1 < rings; ++r)
    {
      tri(id(r, s), id(r + 1, s), id(r + 1, s + 1));
      tri(id(r, s), id(r + 1, s + 1), id(r, s + 1));
    }
    tri(south, id(rings - 1, s + 1), id(rings - 1, s));
  }
  return m;
}

/// DomainSpans against brute force: on random convex domains (random, axis-parallel and
/// nearly axis-parallel planes), the samples that the slice boxes and row spans visit
/// are those that satisfy every plane. Samples within 1e-9 of a plane may go either way.
void CheckDomainSpans()
{
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  int cases = 0, visited = 0, wrong = 0;
  for (int trial = 0; trial < 400; ++trial)
  {
    const int count = 1 + trial % 12 + (trial % 50 == 0 ? 40 : 0);
    const double centre[3] = { 10 + 4 * u(rng), 10 + 4 * u(rng), 10 + 4 * u(rng) };
    IndexPlane planes[MaxDomainPlanes];
    for (int p = 0; p < count; ++p)
    {
      double n[3] = { u(rng), u(rng), u(rng) };
      if (trial % 5 == 1)
      {
        n[p % 3] = 0; // parallel to an axis
      }
      if (trial % 5 == 2)
      {
        n[p % 3] = 1e-12 * u(rng); // nearly parallel
      }
      const double offset = 0.5 + 6 * std::fabs(u(rng)); // the centre stays inside
      planes[p] = {
        n[0], n[1], n[2], offset - (n[0] * centre[0] + n[1] * centre[1] + n[2] * centre[2])
      };
    }
    const double x0 = 2, x1 = 18, y0 = 3, y1 = 17;
    DomainSpans domain;
    domain.Setup(planes, count, count > 40 ? 3 : count, x0, x1, y0, y1);
    ++cases;
    for (int k = 0; k <= 20; ++k)
    {
      std::vector<char> seen(21 * 21, 0);
      double box[4];
      if (domain.SliceBox(k, box))
      {
        domain.BeginSlice(k);
        for (int j = std::max(3, int(std::ceil(box[2])));
             j <= std::min(17, int(std::floor(box[3])));
             ++j)
        {
          double xl, xr;
          if (domain.RowSpan(j, xl, xr))
          {
            for (int i = std::max(2, int(std::ceil(xl))); i <= std::min(18, int(std::floor(xr)));
                 ++i)
            {
              seen[j * 21 + i] = 1;
              ++visited;
            }
          }
        }
      }
      for (int j = 3; j <= 17; ++j)
      {
        for (int i = 2; i <= 18; ++i)
        {
          double margin = HUGE_VAL;
          for (int p = 0; p < count; ++p)
          {
            const IndexPlane& h = planes[p];
            const double scale = std::max(std::fabs(h.A), std::max(std::fabs(h.B), std::fabs(h.C)));
            margin = std::min(margin, (h.A * i + h.B * j + h.C * k + h.D) / scale);
          }
          // With 40 planes the optional ones may be dropped: then only a superset holds.
          const bool mustSee = margin > 1e-9;
          const bool mustNotSee = margin < -1e-9 && count <= 40;
          wrong += (mustSee && !seen[j * 21 + i]) || (mustNotSee && seen[j * 21 + i]);
        }
      }
    }
  }
  Check(wrong == 0,
    "%s",
    std::string("DomainSpans visits exactly the samples inside the planes (" +
      std::to_string(wrong) + " wrong of " + std::to_string(visited) + " visited, " +
      std::to_string(cases) + " domains)")
      .c_str());
  Check(visited > 10000, "DomainSpans test domains hold samples");
}
} // namespace

/// The per-sample query route: exact against the brute force; the same signs, cells and
/// features as the site scan but where the two routes' closest points are both nearest
/// within the scan's accuracy (a tie: two features at the same distance, or the scan's
/// domains widened by 1e-4 h); slabs equal to the whole grid bit for bit. With a cap
/// (MaximumDistance = 1.5 h) too: beyond it the cap, no cell, and the scan's sides.
void RunQueryCase(const std::string& name, const MeshInput& input, int resolution, bool closed)
{
  MeshInput mesh = input;
  Check(UsedPointBounds(mesh, mesh.Bounds), "%s: no point used", name.c_str());
  LinearFactorRequest request;
  request.Grid = SampleGrid::FromBounds(mesh.Bounds.data(), resolution, 0.25);
  request.Extent = request.Grid.Whole;
  request.Sign = SignMode::PseudoNormal;
  const double h = request.Grid.MinSpacing();
  const size_t n = static_cast<size_t>(request.Extent.Count());
  struct Field
  {
    std::vector<float> Distance, Point;
    std::vector<int64_t> Cell;
    std::vector<uint8_t> Feature;
    LinearFactorReport Report;
  };
  auto compute = [&](FieldRoute route, double cap, Field& f)
  {
    f.Distance.assign(n, 0), f.Point.assign(3 * n, 0), f.Cell.assign(n, 0), f.Feature.assign(n, 0);
    LinearFactorArrays arrays;
    arrays.Distance = f.Distance.data();
    arrays.ClosestPoint = f.Point.data();
    arrays.ClosestCellId = f.Cell.data();
    arrays.ClosestFeature = f.Feature.data();
    Execution execution;
    execution.For = ThreadFor;
    std::string error;
    LinearFactorRequest r = request;
    r.Route = route;
    r.MaximumDistance = cap;
    Check(ComputeLinearFactorField(mesh, r, nullptr, arrays, execution, f.Report, error),
      "%s: %s",
      name.c_str(),
      error.c_str());
  };
  for (const double cap : { 0.0, 1.5 * h })
  {
    const std::string label = name + (cap > 0 ? " banded" : "");
    Field scan, queries;
    compute(FieldRoute::SiteScan, cap, scan);
    compute(FieldRoute::SampleQueries, cap, queries);
    Check(scan.Report.Route == FieldRoute::SiteScan &&
        queries.Report.Route == FieldRoute::SampleQueries,
      "%s: the routes asked for ran",
      label.c_str());
    double worst = 0;
    int64_t ties = 0, wrong = 0, signs = 0, band = 0;
    ForEachSample(request,
      [&](const double* x, int64_t at)
      {
        const double exact = BruteForce(mesh, x);
        const bool beyond = cap > 0 && exact > cap;
        worst =
          std::max(worst, std::fabs(std::fabs(queries.Distance[at]) - (beyond ? cap : exact)));
        signs += closed && exact > 1e-3 * h &&
          std::signbit(scan.Distance[at]) != std::signbit(queries.Distance[at]);
        if (cap > 0 && std::fabs(exact - cap) > 1e-6 * h)
        {
          // Clear of the cap: no cell beyond it, one within it, as the scan has them.
          band += beyond != (queries.Cell[at] < 0) || (scan.Cell[at] < 0) != (queries.Cell[at] < 0);
        }
        if (scan.Cell[at] < 0 || queries.Cell[at] < 0 ||
          (scan.Cell[at] == queries.Cell[at] && scan.Feature[at] == queries.Feature[at] &&
            std::signbit(scan.Distance[at]) == std::signbit(queries.Distance[at])))
        {
          return;
        }
        // Both closest points nearest within the scan's accuracy (and float rounding).
        auto reach = [&](const std::vector<float>& p)
        {
          double d2 = 0;
          for (int a = 0; a < 3; ++a)
          {
            d2 += (p[3 * at + a] - x[a]) * (p[3 * at + a] - x[a]);
          }
          return std::fabs(std::sqrt(d2) - exact);
        };
        const bool tie = reach(scan.Point) <= 2e-4 * h && reach(queries.Point) <= 2e-4 * h;
        ties += tie;
        wrong += !tie;
      });
    std::printf("%-21s queries      max|err| = %.3g h  %.1f evaluations a sample, %lld samples "
                "name another feature at a tie\n",
      label.c_str(),
      worst / h,
      double(queries.Report.Evaluations) / double(n),
      (long long)ties);
    Check(worst <= 1e-6 * h, "%s: the queries' error is %g h", label.c_str(), worst / h);
    Check(wrong == 0,
      "%s: %lld samples name another cell or feature than the scan's, away from ties",
      label.c_str(),
      (long long)wrong);
    Check(signs == 0,
      "%s: %lld samples of a closed mesh off the surface change sign between the routes",
      label.c_str(),
      (long long)signs);
    Check(band == 0,
      "%s: %lld samples clear of the cap on the wrong side of it",
      label.c_str(),
      (long long)band);
  }
  LinearFactorRequest pieces = request;
  pieces.Route = FieldRoute::SampleQueries;
  CheckPieces(name + " queries", mesh, pieces);
}

/// FloatBelow and FloatAbove (the float on either side of a double, by the bits) give
/// what the rounding and std::nextafter give: at zero, subnormals, the float range's
/// ends, infinities, and random doubles of every exponent and sign.
void CheckFloatBounds()
{
  std::vector<double> values = { 0.0,
    -0.0,
    1e-320,
    -1e-320,
    1e-46,
    -1e-46,
    1e-45,
    -1e-45,
    1.17e-38,
    -1.17e-38,
    3.4028234663852886e38,
    -3.4028234663852886e38,
    3.5e38,
    -3.5e38,
    1e300,
    -1e300,
    HUGE_VAL,
    -HUGE_VAL,
    1.0,
    -1.0,
    0.1,
    -0.1 };
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> mantissa(-1, 1);
  std::uniform_int_distribution<int> exponent(-160, 140);
  for (int i = 0; i < 200000; ++i)
  {
    values.push_back(std::ldexp(mantissa(random), exponent(random)));
    uint64_t bits = random();
    double any;
    std::memcpy(&any, &bits, sizeof(any));
    if (!std::isnan(any))
    {
      values.push_back(any);
    }
  }
  int wrong = 0;
  for (const double x : values)
  {
    const float f = static_cast<float>(x);
    const float below = f > x ? std::nextafter(f, -HUGE_VALF) : f;
    const float above = f < x ? std::nextafter(f, HUGE_VALF) : f;
    const float gotBelow = FloatBelow(x), gotAbove = FloatAbove(x);
    wrong += std::memcmp(&gotBelow, &below, sizeof(float)) != 0;
    wrong += std::memcmp(&gotAbove, &above, sizeof(float)) != 0;
  }
  Check(wrong == 0, "FloatBelow or FloatAbove differ from std::nextafter %d times", wrong);
}

/// Max and Min select what std::max and std::min select, bit for bit: NaNs of either
/// sign, signed zeros, infinities, subnormals, ordinary values.
void CheckMinMax()
{
  const double values[] = { 0.0,
    -0.0,
    1.0,
    -1.0,
    2.5,
    NAN,
    -NAN,
    HUGE_VAL,
    -HUGE_VAL,
    1e-310,
    -1e-310,
    std::numeric_limits<double>::max() };
  int wrong = 0;
  for (const double a : values)
  {
    for (const double b : values)
    {
      const double max = Max(a, b), min = Min(a, b);
      const double stdMax = std::max(a, b), stdMin = std::min(a, b);
      wrong += std::memcmp(&max, &stdMax, sizeof(double)) != 0;
      wrong += std::memcmp(&min, &stdMin, sizeof(double)) != 0;
    }
  }
  Check(wrong == 0, "Max or Min differ from std::max or std::min %d times", wrong);
}

/// Auto takes the queries where the mesh has 2.5 times more cells than the grid has
/// samples (with a cap, samples within the band), the scan elsewhere.
void CheckRouteChoice()
{
  MeshInput mesh = Sphere(30, 40, 0.1, 5);
  const int64_t cells = static_cast<int64_t>(mesh.Triangles.size() / 3);
  Check(UsedPointBounds(mesh, mesh.Bounds), "sphere: no point used");
  Execution execution;
  execution.For = ThreadFor;
  // (resolution, cap in spacings): queries, scan, queries for the band alone.
  const std::pair<int, double> cases[] = { { 8, 0.0 }, { 16, 0.0 }, { 16, 0.5 } };
  const bool expected[] = { true, false, true };
  for (int c = 0; c < 3; ++c)
  {
    const int resolution = cases[c].first;
    LinearFactorRequest request;
    request.Grid = SampleGrid::FromBounds(mesh.Bounds.data(), resolution, 0.1);
    request.Extent = request.Grid.Whole;
    request.MaximumDistance = cases[c].second * request.Grid.MinSpacing();
    std::vector<float> distance(request.Extent.Count());
    LinearFactorArrays arrays;
    arrays.Distance = distance.data();
    LinearFactorReport report;
    std::string error;
    Check(ComputeLinearFactorField(mesh, request, nullptr, arrays, execution, report, error),
      "route choice: %s",
      error.c_str());
    const bool queries = cells >=
      SampleQueriesCellsPerSample * QueriedSamples(mesh, request.Grid, request.MaximumDistance);
    Check(queries == expected[c], "route choice case %d: the counts changed", c);
    Check((report.Route == FieldRoute::SampleQueries) == queries,
      "route choice at %d samples, cap %g h: Auto took the %s",
      int(request.Extent.Count()),
      cases[c].second,
      queries ? "scan" : "queries");
  }
}

int main()
{
  CheckDomainSpans();
  CheckRouteChoice();
  CheckFloatBounds();
  CheckMinMax();
  RunQueryCase("bumpy sphere", Sphere(9, 12, 0.15, 7), 24, true);
  RunQueryCase("fine sphere", Sphere(30, 40, 0.1, 5), 20, true);
  {
    MeshInput m;
    m.Points = { 0, 0, 0, 1, 0.2, 0.1, 0.3, 0.9, -0.2 };
    m.Triangles = { 0, 1, 2 };
    m.TriangleCells = { 0 };
    RunCase("triangle", m, 24);
  }
  {
    MeshInput m;
    m.Points = { 0, 0, 0, 1, 0.7, 0.3 };
    m.Segments = { 0, 1 };
    m.SegmentCells = { 0 };
    RunCase("segment", m, 24);
  }
  {
    MeshInput m;
    m.Points = { 0.2, 0.3, 0.4 };
    m.Vertices = { 0 };
    m.VertexCells = { 0 };
    RunCase("point", m, 16);
  }
  {
    // Axis-aligned cube on grid-friendly coordinates: samples on domain boundaries.
    MeshInput m;
    m.Points = { 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1 };
    m.Triangles = { 0,
      2,
      1,
      0,
      3,
      2,
      4,
      5,
      6,
      4,
      6,
      7,
      0,
      1,
      5,
      0,
      5,
      4,
      1,
      2,
      6,
      1,
      6,
      5,
      2,
      3,
      7,
      2,
      7,
      6,
      3,
      0,
      4,
      3,
      4,
      7 };
    for (int t = 0; t < 12; ++t)
    {
      m.TriangleCells.push_back(t);
    }
    RunCase("cube", m, 21);
    RunQueryCase("cube", m, 21, true);
    // The same cube as a soup: every triangle with its own points.
    MeshInput soup;
    for (size_t t = 0; t < m.Triangles.size(); ++t)
    {
      const double* x = &m.Points[3 * m.Triangles[t]];
      soup.Points.insert(soup.Points.end(), x, x + 3);
      soup.Triangles.push_back(static_cast<int64_t>(t));
    }
    soup.TriangleCells = m.TriangleCells;
    RunQueryCase("cube soup", soup, 17, true);
  }
  RunCase("bumpy sphere", Sphere(9, 12, 0.15, 7), 24);
  {
    // Soup: random triangles (some degenerate), segments and points.
    MeshInput m;
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(0, 1);
    for (int t = 0; t < 30; ++t)
    {
      for (int k = 0; k < 3; ++k)
      {
        m.Points.insert(m.Points.end(), { u(rng), u(rng), u(rng) });
      }
      const int64_t b = 3 * t;
      if (t % 7 == 3)
      {
        // collinear (zero area)
        for (int a = 0; a < 3; ++a)
        {
          m.Points[3 * (b + 2) + a] = 0.5 * (m.Points[3 * b + a] + m.Points[3 * (b + 1) + a]);
        }
      }
      m.Triangles.insert(m.Triangles.end(), { b, b + 1, t % 11 == 5 ? b : b + 2 });
      m.TriangleCells.push_back(t);
    }
    m.Segments = { 0, 4, 7, 9 };
    m.SegmentCells = { 30, 31 };
    m.Vertices = { 10, 20 };
    m.VertexCells = { 32, 33 };
    RunCase("soup", m, 20);
    RunQueryCase("soup", m, 20, false);
  }
  return Verdict();
}
