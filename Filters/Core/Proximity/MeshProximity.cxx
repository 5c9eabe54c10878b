#include "Proximity/MeshProximity.h"

#include "Common/PointTriangleDistance.h"
#include "Common/TriangleBoxTree.h"
#include "Proximity/ProximitySearch.h"
#include "Segment/TriangleCrossings.h"
#include "Winding/WindingNumber.h"

#include <algorithm>
#include <cmath>
#include <queue>
#include <vector>

namespace vtkdf
{
namespace
{
/// Squared distance between the closed segments p0p1 and q0q1, with closest points:
/// the distance's minimum over both parameters, each clamped to [0, 1] (Ericson,
/// Real-Time Collision Detection, 5.1.9). Parallel segments take s = 0 first; the
/// corner-to-triangle distances cover what that choice may miss.
double SquaredSegmentDistance(const double* p0,
  const double* p1,
  const double* q0,
  const double* q1,
  double* onP,
  double* onQ)
{
  double d1[3], d2[3], r[3];
  for (int k = 0; k < 3; ++k)
  {
    d1[k] = p1[k] - p0[k];
    d2[k] = q1[k] - q0[k];
    r[k] = p0[k] - q0[k];
  }
  auto dot = [](const double* u, const double* v)
  { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; };
  auto clamp = [](double x) { return std::min(1.0, std::max(0.0, x)); };
  const double a = dot(d1, d1), e = dot(d2, d2), f = dot(d2, r);
  double s = 0, t = 0;
  if (a > 0 && e > 0)
  {
    const double b = dot(d1, d2), c = dot(d1, r);
    const double denominator = a * e - b * b;
    s = denominator > 0 ? clamp((b * f - c * e) / denominator) : 0;
    t = (b * s + f) / e;
    if (t < 0)
    {
      t = 0;
      s = clamp(-c / a);
    }
    else if (t > 1)
    {
      t = 1;
      s = clamp((b - c) / a);
    }
  }
  else if (a > 0)
  {
    s = clamp(-dot(d1, r) / a);
  }
  else if (e > 0)
  {
    t = clamp(f / e);
  }
  double d2sum = 0;
  for (int k = 0; k < 3; ++k)
  {
    onP[k] = p0[k] + s * d1[k];
    onQ[k] = q0[k] + t * d2[k];
    d2sum += (onP[k] - onQ[k]) * (onP[k] - onQ[k]);
  }
  return d2sum;
}

double Distance2(const double* a, const double* b)
{
  return (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
    (a[2] - b[2]) * (a[2] - b[2]);
}

/// Whether a vertex of `inner` lies inside `outer` by the winding number of outer's
/// triangles.
bool AnyVertexInside(const TriangleModel& inner, const MeshInput& outer)
{
  WindingNumber winding;
  winding.Build(outer.Points, outer.Triangles);
  std::vector<bool> tested(inner.Points.size(), false);
  for (const TriangleCorners& triangle : inner.Triangles)
  {
    for (const size_t id : triangle)
    {
      if (!tested[id])
      {
        tested[id] = true;
        if (winding.Inside(inner.Points[id].data()))
        {
          return true;
        }
      }
    }
  }
  return false;
}

} // namespace

std::vector<std::array<double, 3>> FaceSamples(const double p[9], double step)
{
  double longest = 0;
  for (int e = 0; e < 3; ++e)
  {
    longest = std::max(longest, std::sqrt(Distance2(p + 3 * e, p + 3 * ((e + 1) % 3))));
  }
  const double divisions = std::ceil(longest / step);
  const int64_t n = divisions >= 1 ? static_cast<int64_t>(divisions) : 1;
  std::vector<std::array<double, 3>> samples;
  samples.reserve(static_cast<size_t>((n + 1) * (n + 2) / 2));
  for (int64_t i = 0; i <= n; ++i)
  {
    for (int64_t j = 0; i + j <= n; ++j)
    {
      const double u = double(i) / n, v = double(j) / n;
      samples.push_back({ { p[0] + u * (p[3] - p[0]) + v * (p[6] - p[0]),
        p[1] + u * (p[4] - p[1]) + v * (p[7] - p[1]),
        p[2] + u * (p[5] - p[2]) + v * (p[8] - p[2]) } });
    }
  }
  return samples;
}

bool ComputePenetration(const MeshInput& a,
  const MeshInput& b,
  double step,
  PenetrationResult& result,
  std::string& error)
{
  result = PenetrationResult();
  if (!(step > 0) || !std::isfinite(step))
  {
    error =
      "the step of the face samples must be positive and finite; it is " + std::to_string(step);
    return false;
  }
  TriangleModel modelA, modelB;
  if (!modelA.Load(a, "A", error) || !modelB.Load(b, "B", error))
  {
    return false;
  }
  const TriangleBoxTree treeB(modelB.Points, modelB.Triangles);
  WindingNumber winding;
  winding.Build(b.Points, b.Triangles);
  auto sample = [&](const double x[3])
  {
    ++result.Samples;
    if (!winding.Inside(x))
    {
      return;
    }
    ++result.SamplesInside;
    double closest[3];
    int64_t triangle = -1;
    const double depth = std::sqrt(NearestTriangle(modelB, treeB, x, closest, triangle));
    if (depth > result.Depth || result.TriangleB < 0)
    {
      result.Depth = depth;
      std::copy(x, x + 3, result.Deepest.begin());
      std::copy(closest, closest + 3, result.ClosestOnB.begin());
      result.TriangleB = triangle;
    }
  };
  // The lattices hold the corners: every vertex is a sample.
  for (size_t t = 0; t < modelA.Triangles.size(); ++t)
  {
    double p[9];
    modelA.Corners(t, p);
    for (const auto& x : FaceSamples(p, step))
    {
      sample(x.data());
    }
  }
  return true;
}

double SquaredTriangleDistance(const double p[9], const double q[9], double onP[3], double onQ[3])
{
  double best = HUGE_VAL, x[3], y[3];
  auto keep = [&](double d2, const double* u, const double* v)
  {
    if (d2 < best)
    {
      best = d2;
      std::copy(u, u + 3, onP);
      std::copy(v, v + 3, onQ);
    }
  };
  for (int c = 0; c < 3; ++c)
  {
    keep(SquaredDistanceToTriangle(p + 3 * c, q, q + 3, q + 6, y), p + 3 * c, y);
    keep(SquaredDistanceToTriangle(q + 3 * c, p, p + 3, p + 6, x), x, q + 3 * c);
  }
  for (int e = 0; e < 3; ++e)
  {
    const double* p0 = p + 3 * e;
    const double* p1 = p + 3 * ((e + 1) % 3);
    for (int f = 0; f < 3; ++f)
    {
      const double d2 = SquaredSegmentDistance(p0, p1, q + 3 * f, q + 3 * ((f + 1) % 3), x, y);
      keep(d2, x, y);
    }
  }
  return best;
}

bool ComputeMeshProximity(const MeshInput& a,
  const MeshInput& b,
  const ProximityOptions& options,
  ProximityResult& result,
  std::string& error)
{
  result = ProximityResult();
  TriangleModel modelA, modelB;
  if (!modelA.Load(a, "A", error) || !modelB.Load(b, "B", error))
  {
    return false;
  }
  const TriangleBoxTree treeA(modelA.Points, modelA.Triangles);
  const TriangleBoxTree treeB(modelB.Points, modelB.Triangles);

  treeA.ForEachOverlappingPair(treeB,
    [&](size_t s, size_t t)
    {
      Point3 p[3], q[3];
      modelA.Corners(s, p);
      modelB.Corners(t, q);
      ++result.ContactTests;
      if (ClosedTrianglesIntersect(p, q))
      {
        result.ContactA = static_cast<int64_t>(s);
        result.ContactB = static_cast<int64_t>(t);
        return false;
      }
      return true;
    });
  if (result.ContactA >= 0)
  {
    result.Colliding = true;
    result.Separation = 0;
    return true;
  }
  if (options.Containment)
  {
    result.AInsideB = AnyVertexInside(modelA, b);
    result.BInsideA = AnyVertexInside(modelB, a);
    if (result.AInsideB || result.BInsideA)
    {
      result.Colliding = true;
      result.Separation = 0;
      return true;
    }
  }
  if (options.Separation)
  {
    // A bound below the true separation finds nothing: the search runs again unbounded.
    const double bound = options.UpperBound * options.UpperBound;
    if (!(bound < HUGE_VAL) || !NearestPair(modelA, treeA, modelB, treeB, bound, result))
    {
      NearestPair(modelA, treeA, modelB, treeB, HUGE_VAL, result);
    }
  }
  return true;
}
} // namespace vtkdf
