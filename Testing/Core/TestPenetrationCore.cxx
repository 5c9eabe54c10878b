// The penetration depth of unions of convex pieces (Filters/Core/Union/PenetrationDepth.h),
// VTK-free, against references that do not use the Minkowski sums' hulls:
// - random convex pairs (hulls of random points, seeded), overlapping and apart: the depth
//   equals the separating-axis brute force (the minimum over the face normals of both and
//   the cross products of their edges of the support function of P - Q) and the
//   separation distance the brute force over features (corners against triangles, edges
//   against edges), within 1e-9 of the pieces' size; Q translated by the answer touches P
//   (the separating-axis depth of the moved pair is 0);
// - two interlocked tori made of 12 convex pieces each, intersecting: the global depth is
//   never below the largest per-pair depth, Q translated by it touches P without any pair
//   overlapping, 99.9 % of it still overlaps, and no direction of 4000 leaves the union
//   of the sums sooner (each ray's intervals by the separating axes of each pair);
// - the pairs skipped by the box bound change nothing (the same answer with every pair);
// - a distributed run's split: the sums built in 2, 3 and 7 shares, each packed, the
//   packs read back in order, give Compute's answer bit for bit; a failed share and
//   truncated packs are refused;
// - with the argument gpu, all of it with the union query on the GPU, certified, the
//   pairs' and the tori's answers the CPU's bit for bit (and the tori's image-only depth
//   never below the exact one).
#include "CoreTest.h"
#include "GLCoreTest.h"
#include "RaySpans.h"
#include "Union/ConvexHull.h"
#include "Union/PenetrationDepth.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

using namespace vtkdf;
using namespace vtkdf::coretest;

namespace
{
/// With the argument gpu: the union query with the GPU's bound.
HeadlessGL* GPU = nullptr;
UnionGPUSettings Settings()
{
  return UnionGPUSettings();
}

/// On the GPU: the certified answer equals the CPU's bit for bit.
void CheckSameAsCPU(const std::string& name,
  const PenetrationDepth& depth,
  const std::vector<ConvexPiece>& p,
  const std::vector<ConvexPiece>& q,
  const double origin[3],
  const PenetrationAnswer& answer)
{
  if (!GPU)
  {
    return;
  }
  PenetrationAnswer cpu;
  std::string error;
  Check(depth.Compute(p, q, origin, cpu, error, nullptr, Settings()),
    "%s",
    std::string(name + ", on the CPU: " + error).c_str());
  Check(answer.Distance == cpu.Distance && answer.Intersecting == cpu.Intersecting &&
      std::equal(answer.Translation, answer.Translation + 3, cpu.Translation) &&
      answer.PieceP == cpu.PieceP && answer.PieceQ == cpu.PieceQ,
    "%s (%.17g, the CPU's %.17g)",
    std::string(name + ": the GPU's certified answer is the CPU's bit for bit").c_str(),
    answer.Distance,
    cpu.Distance);
}

double Dot(const double* a, const double* b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

ConvexPiece HullPiece(const std::vector<double>& points)
{
  std::vector<std::vector<int64_t>> faces;
  int64_t corners = 0;
  std::string error;
  ConvexPiece piece;
  const bool ok =
    ConvexHull(points, faces, corners, error) && piece.Build(points, faces, 1e-9, error);
  Check(ok, "%s", std::string("a test piece: " + error).c_str());
  return piece;
}

ConvexPiece Moved(const ConvexPiece& piece, const double t[3])
{
  std::vector<double> points = piece.Corners();
  for (size_t k = 0; k < points.size(); ++k)
  {
    points[k] += t[k % 3];
  }
  return HullPiece(points);
}

/// The separating-axis candidates of a pair: face normals of both, edge cross products.
std::vector<std::array<double, 3>> Axes(const ConvexPiece& p, const ConvexPiece& q)
{
  std::vector<std::array<double, 3>> axes, edges[2];
  const ConvexPiece* pieces[2] = { &p, &q };
  for (int s = 0; s < 2; ++s)
  {
    for (size_t f = 0; f < pieces[s]->Faces.size(); ++f)
    {
      const double* n = &pieces[s]->Planes[4 * f];
      axes.push_back({ n[0], n[1], n[2] });
      const std::vector<double>& c = pieces[s]->Faces[f];
      for (size_t k = 0; k < c.size(); k += 3)
      {
        const size_t next = (k + 3) % c.size();
        edges[s].push_back({ c[next] - c[k], c[next + 1] - c[k + 1], c[next + 2] - c[k + 2] });
      }
    }
  }
  for (const auto& a : edges[0])
  {
    for (const auto& b : edges[1])
    {
      const double n[3] = {
        a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]
      };
      const double length = std::sqrt(Dot(n, n));
      if (length > 1e-12 * std::sqrt(Dot(a.data(), a.data()) * Dot(b.data(), b.data())))
      {
        axes.push_back({ n[0] / length, n[1] / length, n[2] / length });
      }
    }
  }
  const size_t count = axes.size();
  for (size_t k = 0; k < count; ++k)
  {
    axes.push_back({ -axes[k][0], -axes[k][1], -axes[k][2] });
  }
  return axes;
}

/// h_{P-Q}(n) = max n.p - min n.q.
double Support(const std::vector<double>& p, const std::vector<double>& q, const double* n)
{
  double hi = -HUGE_VAL, lo = HUGE_VAL;
  for (size_t k = 0; k < p.size(); k += 3)
  {
    hi = std::max(hi, Dot(n, &p[k]));
  }
  for (size_t k = 0; k < q.size(); k += 3)
  {
    lo = std::min(lo, Dot(n, &q[k]));
  }
  return hi - lo;
}

/// The separating-axis depth: the distance from the origin to the boundary of P - Q
/// when positive (overlap), negative when some axis separates them.
double AxisDepth(const ConvexPiece& p, const ConvexPiece& q)
{
  const std::vector<double> a = p.Corners(), b = q.Corners();
  double depth = HUGE_VAL;
  for (const auto& n : Axes(p, q))
  {
    depth = std::min(depth, Support(a, b, n.data()));
  }
  return depth;
}

double PointSegment(const double* x, const double* a, const double* b)
{
  const double e[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
  const double ax[3] = { x[0] - a[0], x[1] - a[1], x[2] - a[2] };
  const double t = std::min(1.0, std::max(0.0, Dot(ax, e) / Dot(e, e)));
  const double d[3] = { ax[0] - t * e[0], ax[1] - t * e[1], ax[2] - t * e[2] };
  return std::sqrt(Dot(d, d));
}

double PointTriangle(const double* x, const double* a, const double* b, const double* c)
{
  const double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
  const double v[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
  const double w[3] = { x[0] - a[0], x[1] - a[1], x[2] - a[2] };
  const double uu = Dot(u, u), uv = Dot(u, v), vv = Dot(v, v), wu = Dot(w, u), wv = Dot(w, v);
  const double det = uu * vv - uv * uv;
  const double s = (vv * wu - uv * wv) / det, t = (uu * wv - uv * wu) / det;
  if (s >= 0 && t >= 0 && s + t <= 1)
  {
    const double d[3] = {
      w[0] - s * u[0] - t * v[0], w[1] - s * u[1] - t * v[1], w[2] - s * u[2] - t * v[2]
    };
    return std::sqrt(Dot(d, d));
  }
  return std::min({ PointSegment(x, a, b), PointSegment(x, b, c), PointSegment(x, c, a) });
}

double SegmentSegment(const double* a, const double* b, const double* c, const double* d)
{
  double best = std::min(
    { PointSegment(a, c, d), PointSegment(b, c, d), PointSegment(c, a, b), PointSegment(d, a, b) });
  const double e[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
  const double f[3] = { d[0] - c[0], d[1] - c[1], d[2] - c[2] };
  const double r[3] = { a[0] - c[0], a[1] - c[1], a[2] - c[2] };
  const double ee = Dot(e, e), ff = Dot(f, f), ef = Dot(e, f), er = Dot(e, r), fr = Dot(f, r);
  const double det = ee * ff - ef * ef;
  if (det > 1e-14 * ee * ff)
  {
    const double s = (ef * fr - ff * er) / det, t = (ee * fr - ef * er) / det;
    if (s >= 0 && s <= 1 && t >= 0 && t <= 1)
    {
      const double g[3] = {
        r[0] + s * e[0] - t * f[0], r[1] + s * e[1] - t * f[1], r[2] + s * e[2] - t * f[2]
      };
      best = std::min(best, std::sqrt(Dot(g, g)));
    }
  }
  return best;
}

/// The distance between two disjoint convex pieces by their features.
double FeatureDistance(const ConvexPiece& p, const ConvexPiece& q)
{
  double best = HUGE_VAL;
  const ConvexPiece* pieces[2] = { &p, &q };
  for (int s = 0; s < 2; ++s)
  {
    const std::vector<double> corners = pieces[s]->Corners();
    for (const auto& face : pieces[1 - s]->Faces)
    {
      for (size_t k = 3; k + 3 < face.size(); k += 3)
      {
        for (size_t c = 0; c < corners.size(); c += 3)
        {
          best = std::min(best, PointTriangle(&corners[c], &face[0], &face[k], &face[k + 3]));
        }
      }
    }
  }
  for (const auto& f : p.Faces)
  {
    for (const auto& g : q.Faces)
    {
      for (size_t a = 0; a < f.size(); a += 3)
      {
        for (size_t b = 0; b < g.size(); b += 3)
        {
          best = std::min(
            best, SegmentSegment(&f[a], &f[(a + 3) % f.size()], &g[b], &g[(b + 3) % g.size()]));
        }
      }
    }
  }
  return best;
}

/// One segment of a torus: the hull of the cross sections (k-gons of radius r) at angles
/// a0 and a1 around the axis `axis` (2: z, 1: y), centred at c, ring radius R.
ConvexPiece
TorusSegment(const double c[3], int axis, double R, double r, double a0, double a1, int k)
{
  std::vector<double> points;
  for (const double a : { a0, a1 })
  {
    for (int s = 0; s < k; ++s)
    {
      const double phi = 2 * M_PI * (s + 0.5) / k;
      const double radial = R + r * std::cos(phi), height = r * std::sin(phi);
      const double x = radial * std::cos(a), y = radial * std::sin(a);
      if (axis == 2)
      {
        points.insert(points.end(), { c[0] + x, c[1] + y, c[2] + height });
      }
      else
      {
        points.insert(points.end(), { c[0] + x, c[1] + height, c[2] + y });
      }
    }
  }
  return HullPiece(points);
}

void ConvexPairs()
{
  std::mt19937 random(20261124);
  std::uniform_real_distribution<double> unit(-1, 1);
  int overlapping = 0, apart = 0;
  for (int trial = 0; trial < 60; ++trial)
  {
    std::vector<double> a, b;
    const double shift[3] = { 1.2 * unit(random), 1.2 * unit(random), 1.2 * unit(random) };
    for (int k = 0; k < 40; ++k)
    {
      a.insert(a.end(), { 0.8 * unit(random), 0.5 * unit(random), 0.6 * unit(random) });
    }
    for (int k = 0; k < 25; ++k)
    {
      b.insert(b.end(),
        { shift[0] + 0.4 * unit(random),
          shift[1] + 0.7 * unit(random),
          shift[2] + 0.5 * unit(random) });
    }
    const std::vector<ConvexPiece> p = { HullPiece(a) }, q = { HullPiece(b) };
    PenetrationDepth depth;
    const double origin[3] = { 0, 0, 0 };
    PenetrationAnswer answer;
    std::string error;
    Check(depth.Compute(p, q, origin, answer, error, GPU, Settings()),
      "%s (%.17g)",
      std::string("a convex pair: " + error).c_str(),
      static_cast<double>(trial));
    Check(!GPU || answer.Estimate >= answer.Distance - 1e-12,
      "a convex pair: the GPU's bound above the answer (%.17g)",
      static_cast<double>(trial));
    const double reference = AxisDepth(p[0], q[0]);
    const std::string name = "pair " + std::to_string(trial);
    CheckSameAsCPU(name, depth, p, q, origin, answer);
    if (std::fabs(reference) < 1e-6)
    {
      continue; // touching: either flag is right
    }
    Check(answer.Intersecting == (reference > 0),
      "%s (%.17g)",
      std::string(name + ": intersecting flag").c_str(),
      static_cast<double>(reference));
    if (reference > 0)
    {
      ++overlapping;
      Check(std::fabs(answer.Distance - reference) <= 1e-9,
        "%s (%.17g)",
        std::string(name + ": depth = SAT").c_str(),
        static_cast<double>(answer.Distance - reference));
    }
    else
    {
      ++apart;
      const double distance = FeatureDistance(p[0], q[0]);
      Check(std::fabs(answer.Distance - distance) <= 1e-9,
        "%s (%.17g)",
        std::string(name + ": separation = features").c_str(),
        static_cast<double>(answer.Distance - distance));
    }
    // Moved by the answer, the pair touches.
    const double moved = AxisDepth(p[0], Moved(q[0], answer.Translation));
    Check(std::fabs(moved) <= 1e-9,
      "%s (%.17g)",
      std::string(name + ": Q moved by the translation touches P").c_str(),
      static_cast<double>(moved));
  }
  std::printf("convex pairs: %d overlapping, %d apart\n", overlapping, apart);
  Check(overlapping >= 15 && apart >= 15,
    "both kinds of pairs tested (%.17g)",
    static_cast<double>(overlapping));
}

/// The tori's sums built in `shares` blocks, packed, gathered and read back: the same
/// answer as one Compute, bit for bit.
void Shares(const std::vector<ConvexPiece>& p,
  const std::vector<ConvexPiece>& q,
  const PenetrationAnswer& whole)
{
  const double origin[3] = { 0, 0, 0 };
  std::string error;
  for (int shares : { 2, 3, 7 })
  {
    std::vector<double> gathered;
    int64_t total = 0;
    for (int share = 0; share < shares; ++share)
    {
      PenetrationDepth depth;
      depth.Share = share;
      depth.Shares = shares;
      UnionClosestPoint sums;
      std::vector<std::pair<int64_t, int64_t>> pairs;
      Check(depth.BuildSums(p, q, origin, sums, pairs, total, error), "%s", error.c_str());
      const std::vector<double> pack = PackSums(true, sums.Pieces, pairs);
      gathered.insert(gathered.end(), pack.begin(), pack.end());
    }
    PenetrationDepth depth;
    UnionClosestPoint sums;
    std::vector<std::pair<int64_t, int64_t>> pairs;
    PenetrationAnswer answer;
    Check(UnpackSums(gathered.data(), gathered.size(), shares, sums.Pieces, pairs, error) &&
        depth.Query(sums, pairs, total, origin, answer, error, GPU, Settings()),
      "%d shares: %s",
      shares,
      error.c_str());
    const bool same = answer.Distance == whole.Distance &&
      answer.Intersecting == whole.Intersecting && answer.PieceP == whole.PieceP &&
      answer.PieceQ == whole.PieceQ && answer.PairsKept == whole.PairsKept &&
      answer.PairsTotal == whole.PairsTotal &&
      std::equal(answer.Translation, answer.Translation + 3, whole.Translation);
    Check(same,
      "tori in %d shares: the answer of one process (%.17g vs %.17g)",
      shares,
      answer.Distance,
      whole.Distance);
    // Cut short anywhere, or a failed share among them: refused, never a partial union.
    for (size_t cut : { gathered.size() - 1, gathered.size() / 2, size_t(5) })
    {
      UnionClosestPoint partial;
      pairs.clear();
      Check(!UnpackSums(gathered.data(), cut, shares, partial.Pieces, pairs, error),
        "%d shares cut at %zu values: refused",
        shares,
        cut);
    }
    std::vector<double> failed = PackSums(true, {}, {});
    const std::vector<double> bad = PackSums(false, {}, { { 3, 4 } });
    failed.insert(failed.end(), bad.begin(), bad.end());
    sums.Pieces.clear();
    pairs.clear();
    Check(!UnpackSums(failed.data(), failed.size(), 2, sums.Pieces, pairs, error) &&
        error.find("piece 3 of P and piece 4 of Q") != std::string::npos &&
        error.find("share 1") != std::string::npos,
      "a failed share is reported by its pair and share (%s)",
      error.c_str());
  }
  std::printf("tori in 2, 3 and 7 shares: the answer of one process\n");
}

void Tori()
{
  // Torus P in the xy plane around the origin; Q in the xz plane around (1, 0, 0), its
  // ring through P's tube: linked, and intersecting everywhere along Q.
  const int n = 12, k = 6;
  const double r = 0.3;
  std::vector<ConvexPiece> p, q;
  const double cp[3] = { 0, 0, 0 }, cq[3] = { 1, 0, 0 };
  for (int s = 0; s < n; ++s)
  {
    const double a0 = 2 * M_PI * s / n, a1 = 2 * M_PI * (s + 1) / n;
    p.push_back(TorusSegment(cp, 2, 1.0, r, a0, a1, k));
    q.push_back(TorusSegment(cq, 1, 0.5, r, a0, a1, k));
  }
  PenetrationDepth depth;
  const double origin[3] = { 0, 0, 0 };
  PenetrationAnswer answer;
  std::string error;
  Check(depth.Compute(p, q, origin, answer, error, GPU, Settings()),
    "%s",
    std::string("tori: " + error).c_str());
  CheckSameAsCPU("tori", depth, p, q, origin, answer);
  if (GPU)
  {
    std::printf(
      "tori on the GPU: depth %.9f, the GPU's bound %.9f\n", answer.Distance, answer.Estimate);
    Check(answer.Estimate >= answer.Distance - 1e-9,
      "tori: the GPU's bound is never below the depth (%.17g)",
      static_cast<double>(answer.Estimate));
  }
  Check(answer.Intersecting, "tori intersect (%.17g)", static_cast<double>(answer.Distance));
  double pairMax = 0;
  std::vector<std::vector<std::array<double, 3>>> axes;
  std::vector<std::vector<double>> supports;
  for (size_t i = 0; i < p.size(); ++i)
  {
    for (size_t j = 0; j < q.size(); ++j)
    {
      pairMax = std::max(pairMax, AxisDepth(p[i], q[j]));
      axes.push_back(Axes(p[i], q[j]));
      supports.emplace_back();
      const std::vector<double> a = p[i].Corners(), b = q[j].Corners();
      for (const auto& axis : axes.back())
      {
        supports.back().push_back(Support(a, b, axis.data()));
      }
    }
  }
  std::printf("tori: global depth %.9f (pairs kept %lld of %lld), largest per-pair depth %.9f\n",
    answer.Distance,
    static_cast<long long>(answer.PairsKept),
    static_cast<long long>(answer.PairsTotal),
    pairMax);
  Check(answer.Distance >= pairMax - 1e-9,
    "tori: global depth >= every pair's depth (%.17g)",
    static_cast<double>(pairMax));
  Check(answer.Distance > 1.5 * pairMax,
    "tori: the union matters (global depth well above the pairs') (%.17g)",
    static_cast<double>(answer.Distance / pairMax));
  // Q moved by the translation: no pair overlaps, one touches; at 99.9 % one overlaps.
  auto deepest = [&](double scale)
  {
    double worst = -HUGE_VAL;
    for (size_t s = 0; s < axes.size(); ++s)
    {
      double d = HUGE_VAL;
      for (size_t c = 0; c < axes[s].size(); ++c)
      {
        d = std::min(d, supports[s][c] - scale * Dot(axes[s][c].data(), answer.Translation));
      }
      worst = std::max(worst, d);
    }
    return worst;
  };
  Check(std::fabs(deepest(1.0)) <= 1e-9,
    "tori: moved by the translation, they touch (%.17g)",
    static_cast<double>(deepest(1.0)));
  Check(deepest(0.999) > 0,
    "tori: moved by 99.9 %% of it, they still overlap (%.17g)",
    static_cast<double>(deepest(0.999)));
  // No direction leaves the union of the sums sooner.
  std::mt19937 random(7);
  std::normal_distribution<double> gauss;
  double soonest = HUGE_VAL;
  for (int ray = 0; ray < 4000; ++ray)
  {
    double u[3] = { gauss(random), gauss(random), gauss(random) };
    const double length = std::sqrt(Dot(u, u));
    for (double& c : u)
    {
      c /= length;
    }
    std::vector<std::pair<double, double>> spans;
    for (size_t s = 0; s < axes.size(); ++s)
    {
      RaySpan span;
      for (size_t c = 0; c < axes[s].size() && !span.Empty(); ++c)
      {
        span.Constrain(Dot(axes[s][c].data(), u), supports[s][c]);
      }
      span.AddTo(spans);
    }
    const double reach = FirstExit(spans);
    soonest = std::min(soonest, reach);
  }
  std::printf("tori: the soonest exit of 4000 rays %.9f\n", soonest);
  Check(soonest >= answer.Distance - 1e-9,
    "tori: no ray leaves sooner than the depth (%.17g)",
    static_cast<double>(soonest));
  Check(soonest <= answer.Distance * 1.05,
    "tori: the rays find the depth (within 5 %%) (%.17g)",
    static_cast<double>(soonest));

  // The box bound skipped pairs without changing the answer: compare with no skipping
  // (the query from a far origin keeps every pair, then a shift brings it back).
  UnionClosestPoint all;
  all.Tolerance = 1e-9;
  for (size_t i = 0; i < p.size(); ++i)
  {
    for (size_t j = 0; j < q.size(); ++j)
    {
      std::vector<double> a = p[i].Corners(), b = q[j].Corners(), differences;
      for (size_t x = 0; x < a.size(); x += 3)
      {
        for (size_t y = 0; y < b.size(); y += 3)
        {
          differences.insert(
            differences.end(), { a[x] - b[y], a[x + 1] - b[y + 1], a[x + 2] - b[y + 2] });
        }
      }
      all.Pieces.push_back(HullPiece(differences));
    }
  }
  const UnionAnswer every = all.Query(origin);
  Check(std::fabs(std::fabs(every.Distance) - answer.Distance) <= 1e-12,
    "tori: the same depth with every pair (%.17g)",
    static_cast<double>(every.Distance));
  Shares(p, q, answer);
}
} // namespace

int main(int argc, char* argv[])
{
  if (argc > 1 && std::string(argv[1]) == "gpu")
  {
    GPU = vtkdf::coretest::GLContext();
    if (!GPU)
    {
      return 1;
    }
  }
  ConvexPairs();
  Tori();
  if (Failures == 0)
  {
    std::printf("all penetration-depth checks passed\n");
  }
  return Verdict();
}
