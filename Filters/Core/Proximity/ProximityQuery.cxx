#include "Proximity/ProximityQuery.h"

#include "Common/Vector3.h"
#include "Proximity/ProximityGPU.h"
#include "Proximity/ProximitySearch.h"
#include "Segment/TriangleCrossings.h"
#include "Winding/WindingCrossings.h"
#include "Winding/WindingNumber.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <map>
#include <utility>

namespace vtkdf
{
struct ProximityModel::Data
{
  InsideRule Rule = InsideRule::WindingNumber;
  bool Loaded = false, Reused = false;
  uint64_t Topology = 0; // a new number for each new topology (the GPU's copy follows it)
  std::vector<int64_t> TriangleIds;
  TriangleModel Model;
  std::vector<bool> Used; // points that a triangle uses
  std::array<double, 6> Bounds{ { 0, -1, 0, -1, 0, -1 } };
  std::unique_ptr<TriangleBoxTree> Tree;
  WindingNumber Winding; // InsideRule::WindingNumber
  // InsideRule::PseudoNormal: each triangle's three sides' edge ids (side c from corner c
  // to corner c + 1), and the normals of the faces, vertices and edges.
  // Points at identical coordinates are one vertex (Canonical: the least such id), as
  // the linear factorization's sites merge them; Outward is -1 for a mesh whose signed
  // volume is negative (oriented inward), so that its pseudonormals point out.
  std::vector<std::array<int64_t, 3>> Sides;
  std::vector<size_t> Canonical;
  std::vector<Point3> FaceNormals, VertexNormals, EdgeNormals;
  double Outward = 1;
  // Whether the triangles, on the merged points, make a closed chain: every edge used as
  // often in one direction as in the other, and no triangle repeated with the same
  // orientation (the winding number counts those once). Then w is an integer off the
  // surface and constant on any ball that the surface does not meet.
  bool Closed = false;

  bool MergePoints();
  void BuildEdges();
  void ComputeNormals();
  bool Inside(const double x[3], const double closest[3], int64_t triangle, double d2) const;
};

namespace
{
/// The unit vector along v, or 0 for a zero vector.
Point3 Unit(const Point3& v)
{
  const double length = std::sqrt(Dot(v.data(), v.data()));
  return length > 0 ? Point3{ { v[0] / length, v[1] / length, v[2] / length } }
                    : Point3{ { 0, 0, 0 } };
}
} // namespace

/// Canonical ids for the points; true when they changed since the last call.
bool ProximityModel::Data::MergePoints()
{
  const auto& points = this->Model.Points;
  std::vector<size_t> order(points.size());
  for (size_t i = 0; i < order.size(); ++i)
  {
    order[i] = i;
  }
  std::sort(order.begin(),
    order.end(),
    [&](size_t a, size_t b) { return points[a] != points[b] ? points[a] < points[b] : a < b; });
  std::vector<size_t> canonical(points.size());
  for (size_t k = 0; k < order.size(); ++k)
  {
    canonical[order[k]] =
      k > 0 && points[order[k]] == points[order[k - 1]] ? canonical[order[k - 1]] : order[k];
  }
  const bool changed = canonical != this->Canonical;
  this->Canonical.swap(canonical);
  return changed;
}

void ProximityModel::Data::BuildEdges()
{
  std::map<std::pair<size_t, size_t>, int64_t> edges;
  this->Sides.resize(this->Model.Triangles.size());
  for (size_t t = 0; t < this->Model.Triangles.size(); ++t)
  {
    for (int c = 0; c < 3; ++c)
    {
      const size_t u = this->Canonical[this->Model.Triangles[t][c]];
      const size_t v = this->Canonical[this->Model.Triangles[t][(c + 1) % 3]];
      const auto key = std::make_pair(std::min(u, v), std::max(u, v));
      const auto found = edges.emplace(key, static_cast<int64_t>(edges.size())).first;
      this->Sides[t][c] = found->second;
    }
  }
  this->EdgeNormals.resize(edges.size());
}

// Bærentzen and Aanæs, "Signed distance computation using the angle weighted
// pseudonormal" (IEEE TVCG 11(3), 2005): a vertex's normal is the sum of its faces'
// normals weighted by their angles there, an edge's the sum of its faces' normals.
void ProximityModel::Data::ComputeNormals()
{
  const auto& points = this->Model.Points;
  this->FaceNormals.resize(this->Model.Triangles.size());
  this->VertexNormals.assign(points.size(), Point3{ { 0, 0, 0 } });
  std::fill(this->EdgeNormals.begin(), this->EdgeNormals.end(), Point3{ { 0, 0, 0 } });
  double volume = 0;
  for (size_t t = 0; t < this->Model.Triangles.size(); ++t)
  {
    const auto& corners = this->Model.Triangles[t];
    const double* p0 = points[corners[0]].data();
    const double* p1 = points[corners[1]].data();
    const double* p2 = points[corners[2]].data();
    double u[3], v[3];
    for (int k = 0; k < 3; ++k)
    {
      u[k] = p1[k] - p0[k];
      v[k] = p2[k] - p0[k];
    }
    const Point3 n =
      Unit({ { u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0] } });
    this->FaceNormals[t] = n;
    volume += p0[0] * (p1[1] * p2[2] - p1[2] * p2[1]) - p0[1] * (p1[0] * p2[2] - p1[2] * p2[0]) +
      p0[2] * (p1[0] * p2[1] - p1[1] * p2[0]);
    for (int c = 0; c < 3; ++c)
    {
      const double* here = points[corners[c]].data();
      const double* next = points[corners[(c + 1) % 3]].data();
      const double* previous = points[corners[(c + 2) % 3]].data();
      double e[3], f[3];
      for (int k = 0; k < 3; ++k)
      {
        e[k] = next[k] - here[k];
        f[k] = previous[k] - here[k];
      }
      const double le = std::sqrt(Dot(e, e)), lf = std::sqrt(Dot(f, f));
      const double angle =
        le > 0 && lf > 0 ? std::acos(std::max(-1.0, std::min(1.0, Dot(e, f) / (le * lf)))) : 0;
      Point3& vertex = this->VertexNormals[this->Canonical[corners[c]]];
      Point3& edge = this->EdgeNormals[this->Sides[t][c]];
      for (int k = 0; k < 3; ++k)
      {
        vertex[k] += angle * n[k];
        edge[k] += n[k];
      }
    }
  }
  this->Outward = volume < 0 ? -1 : 1;
}

bool ProximityModel::Data::Inside(const double x[3],
  const double closest[3],
  int64_t triangle,
  double d2) const
{
  if (this->Rule == InsideRule::WindingNumber)
  {
    return this->Winding.Inside(x);
  }
  if (!(d2 > 0))
  {
    return false; // on the surface
  }
  // The closest point's feature: a corner, a side, or the face, with a tolerance far
  // below any distance that matters (a point near a side may take the side's normal:
  // both give the same sign there).
  double p[9];
  this->Model.Corners(static_cast<size_t>(triangle), p);
  double longest = 0;
  for (int c = 0; c < 3; ++c)
  {
    const double* u = p + 3 * c;
    const double* v = p + 3 * ((c + 1) % 3);
    const double e[3] = { v[0] - u[0], v[1] - u[1], v[2] - u[2] };
    longest = std::max(longest, Dot(e, e));
  }
  const double tolerance = 1e-24 * longest;
  const auto& corners = this->Model.Triangles[static_cast<size_t>(triangle)];
  const double* normal = this->FaceNormals[static_cast<size_t>(triangle)].data();
  bool found = false;
  for (int c = 0; c < 3 && !found; ++c)
  {
    const double* q = p + 3 * c;
    const double gap = (closest[0] - q[0]) * (closest[0] - q[0]) +
      (closest[1] - q[1]) * (closest[1] - q[1]) + (closest[2] - q[2]) * (closest[2] - q[2]);
    if (gap <= tolerance)
    {
      normal = this->VertexNormals[this->Canonical[corners[c]]].data();
      found = true;
    }
  }
  for (int c = 0; c < 3 && !found; ++c)
  {
    if (SquaredDistanceToSegment(closest, p + 3 * c, p + 3 * ((c + 1) % 3)) <= tolerance)
    {
      normal = this->EdgeNormals[this->Sides[static_cast<size_t>(triangle)][c]].data();
      found = true;
    }
  }
  const double away[3] = { x[0] - closest[0], x[1] - closest[1], x[2] - closest[2] };
  return this->Outward * Dot(away, normal) < 0;
}

ProximityModel::ProximityModel()
  : D(new Data)
{
}

ProximityModel::~ProximityModel() = default;

bool ProximityModel::ReusedTopology() const
{
  return this->D->Reused;
}

int64_t ProximityModel::NumberOfPoints() const
{
  return static_cast<int64_t>(this->D->Model.Points.size());
}

int64_t ProximityModel::NumberOfTriangles() const
{
  return static_cast<int64_t>(this->D->Model.Triangles.size());
}

bool ProximityModel::Load(const MeshInput& mesh,
  const char* name,
  InsideRule rule,
  std::string& error)
{
  Data& d = *this->D;
  const bool same = d.Loaded && d.Rule == rule && d.TriangleIds == mesh.Triangles &&
    d.Model.Points.size() == mesh.Points.size() / 3;
  d.Loaded = false;
  if (!d.Model.Load(mesh, name, error))
  {
    return false;
  }
  d.Rule = rule;
  d.Reused = same;
  if (same)
  {
    d.Tree->Refit(d.Model.Points, d.Model.Triangles);
  }
  else
  {
    static std::atomic<uint64_t> topologies(0);
    d.Topology = ++topologies;
    d.TriangleIds = mesh.Triangles;
    d.Tree.reset(new TriangleBoxTree(d.Model.Points, d.Model.Triangles));
    d.Used.assign(d.Model.Points.size(), false);
    for (const auto& corners : d.Model.Triangles)
    {
      for (const size_t id : corners)
      {
        d.Used[id] = true;
      }
    }
  }
  // The edges and the chain follow the merged points, which the coordinates may change.
  if (d.MergePoints() || !same)
  {
    d.Closed = IsClosedChain(mesh.Points, mesh.Triangles);
    if (rule == InsideRule::PseudoNormal)
    {
      d.BuildEdges();
    }
  }
  d.Bounds = d.Tree->Nodes()[0].Bounds.Min[0] <= d.Tree->Nodes()[0].Bounds.Max[0]
    ? std::array<double, 6>{ { d.Tree->Nodes()[0].Bounds.Min[0],
        d.Tree->Nodes()[0].Bounds.Max[0],
        d.Tree->Nodes()[0].Bounds.Min[1],
        d.Tree->Nodes()[0].Bounds.Max[1],
        d.Tree->Nodes()[0].Bounds.Min[2],
        d.Tree->Nodes()[0].Bounds.Max[2] } }
    : std::array<double, 6>{ { 0, -1, 0, -1, 0, -1 } };
  if (rule == InsideRule::WindingNumber)
  {
    d.Winding.Build(mesh.Points, mesh.Triangles);
  }
  else
  {
    d.ComputeNormals();
  }
  d.Loaded = true;
  return true;
}

namespace
{
/// The squared distance from x to model m, its closest point and triangle, and whether x
/// is inside m.
struct PointQuery
{
  double D2 = HUGE_VAL;
  double Closest[3] = { 0, 0, 0 };
  int64_t Triangle = -1;
  bool Inside = false;

  PointQuery() = default;
  /// The nearest triangle, from `hint`'s distance when it is a triangle's index.
  PointQuery(const ProximityModel::Data& m, const double x[3], int64_t hint)
    : Triangle(hint)
  {
    this->D2 = NearestTriangle(m.Model, *m.Tree, x, this->Closest, this->Triangle);
  }
  /// The nearest triangle as the GPU found it (answers' point k).
  PointQuery(const NearestAnswers& answers, size_t k)
    : D2(answers.Values[4 * k + 3])
    , Triangle(answers.Triangles[k])
  {
    std::copy(&answers.Values[4 * k], &answers.Values[4 * k] + 3, this->Closest);
  }
  /// With whether x is inside m by m's rule.
  PointQuery(const ProximityModel::Data& m, const double x[3])
    : PointQuery(m, x, -1)
  {
    this->Inside = m.Inside(x, this->Closest, this->Triangle, this->D2);
  }
};

/// A point whose side of the other model is known, with its exact squared distance to it
/// (0 when not computed).
struct KnownPoint
{
  const double* X;
  double D2;
  bool Inside;
  int64_t Triangle;
};

/// The side of x from a known point y that a ball free of the surface joins to it: one
/// centred at y of radius d_y, or at x of radius d_x (`d2x`, 0 when not known), with a
/// margin far above the roundings of the squared distances.
const KnownPoint* SameSide(const std::vector<KnownPoint>& known, const double x[3], double d2x)
{
  const double shrink = 1 - 1e-9;
  for (auto it = known.rbegin(); it != known.rend(); ++it)
  {
    const double gap2 = (x[0] - it->X[0]) * (x[0] - it->X[0]) +
      (x[1] - it->X[1]) * (x[1] - it->X[1]) + (x[2] - it->X[2]) * (x[2] - it->X[2]);
    if (gap2 < shrink * std::max(it->D2, d2x))
    {
      return &*it;
    }
  }
  return nullptr;
}

bool InRegion(const std::array<double, 6>& region, const double x[3])
{
  for (int k = 0; k < 3; ++k)
  {
    if (x[k] < region[2 * k] || x[k] > region[2 * k + 1])
    {
      return false;
    }
  }
  return true;
}

bool BoxMeetsRegion(const Box& box, const std::array<double, 6>& region)
{
  for (int k = 0; k < 3; ++k)
  {
    if (box.Max[k] < region[2 * k] || box.Min[k] > region[2 * k + 1])
    {
      return false;
    }
  }
  return true;
}

/// Lattice divisions of a triangle for `step` (FaceSamples' n).
int64_t Divisions(const double p[9], double step)
{
  double longest = 0;
  for (int e = 0; e < 3; ++e)
  {
    const double* u = p + 3 * e;
    const double* v = p + 3 * ((e + 1) % 3);
    longest = std::max(longest,
      std::sqrt((u[0] - v[0]) * (u[0] - v[0]) + (u[1] - v[1]) * (u[1] - v[1]) +
        (u[2] - v[2]) * (u[2] - v[2])));
  }
  const double divisions = std::ceil(longest / step);
  return divisions >= 1 ? static_cast<int64_t>(divisions) : 1;
}

void RunFor(const Execution& execution,
  int64_t n,
  int64_t grain,
  const std::function<void(int64_t, int64_t)>& body)
{
  if (execution.For)
  {
    execution.For(n, grain, body);
  }
  else if (n > 0)
  {
    body(0, n);
  }
}

void Keep(PenetrationSide& side, const ContactSample& sample, const double closest[3], int64_t t)
{
  if (sample.Depth > side.Depth || side.TriangleOfOther < 0)
  {
    side.Depth = sample.Depth;
    side.Deepest = sample.Point;
    std::copy(closest, closest + 3, side.ClosestOnOther.begin());
    side.Normal = sample.Normal;
    side.TriangleOfOther = t;
  }
}

ContactSample MakeSample(const double x[3],
  const PointQuery& query,
  int64_t triangle,
  int64_t vertex)
{
  ContactSample sample;
  sample.Point = { { x[0], x[1], x[2] } };
  sample.Depth = std::sqrt(query.D2);
  const Point3 towards{
    { query.Closest[0] - x[0], query.Closest[1] - x[1], query.Closest[2] - x[2] }
  };
  sample.Normal = Unit(towards);
  sample.Triangle = triangle;
  sample.Vertex = vertex;
  return sample;
}

/// A query's device and the slots of its two models there (null: the CPU).
struct OnDevice
{
  ProximityDevice* Device;
  int Self, Other;
};

/// The signed distances of `self`'s points to `other` (NaN for the points no triangle
/// uses), with each point's query kept for the penetration. False with `error` when the
/// GPU fails.
bool PointDistances(const ProximityModel::Data& self,
  const ProximityModel::Data& other,
  const OnDevice& gpu,
  const Execution& execution,
  std::vector<double>& distances,
  std::vector<PointQuery>& queries,
  std::string& error)
{
  const int64_t n = static_cast<int64_t>(self.Model.Points.size());
  distances.assign(static_cast<size_t>(n), std::nan(""));
  queries.assign(static_cast<size_t>(n), PointQuery());
  NearestAnswers answers;
  if (gpu.Device && !DeviceNearestToPoints(*gpu.Device, gpu.Self, gpu.Other, answers, error))
  {
    return false;
  }
  RunFor(execution,
    n,
    256,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t i = begin; i < end; ++i)
      {
        if (!self.Used[static_cast<size_t>(i)])
        {
          continue;
        }
        const double* x = self.Model.Points[static_cast<size_t>(i)].data();
        PointQuery query;
        if (gpu.Device)
        {
          query = PointQuery(answers, static_cast<size_t>(i));
          query.Inside = other.Inside(x, query.Closest, query.Triangle, query.D2);
        }
        else
        {
          query = PointQuery(other, x);
        }
        queries[static_cast<size_t>(i)] = query;
        const double distance = std::sqrt(query.D2);
        distances[static_cast<size_t>(i)] = query.Inside ? -distance : distance;
      }
    });
  return true;
}

/// How many of the samples evaluated last in a triangle stay known points.
constexpr size_t RecentSamples = 4;

/// The vertices of `self` in `region` inside `other` (from their queries), into `side`.
void VertexPenetration(const ProximityModel::Data& self,
  const std::vector<PointQuery>& vertexQueries,
  const std::array<double, 6>& region,
  bool keepContacts,
  PenetrationSide& side)
{
  for (size_t i = 0; i < self.Model.Points.size(); ++i)
  {
    const double* x = self.Model.Points[i].data();
    if (!self.Used[i] || !InRegion(region, x))
    {
      continue;
    }
    ++side.Samples;
    const PointQuery& query = vertexQueries[i];
    if (query.Inside)
    {
      ++side.SamplesInside;
      const ContactSample sample = MakeSample(x, query, -1, static_cast<int64_t>(i));
      Keep(side, sample, query.Closest, query.Triangle);
      if (keepContacts)
      {
        side.Contacts.push_back(sample);
      }
    }
  }
}

/// A block's results, merged in order into the side (the report does not depend on the
/// threads).
struct BlockResult
{
  PenetrationSide Side;
  int64_t Queries = 0;  // exact nearest-triangle queries on the CPU
  int64_t Windings = 0; // winding-number evaluations
};

/// The face samples of `self`'s triangles (corners excluded) against `other`: which lie
/// inside, how deep, and the contacts. One instance per Penetrate; Triangle is called
/// from many threads, each with its own scratch.
struct FaceSampler
{
  const ProximityModel::Data& Self;
  const ProximityModel::Data& Other;
  const OnDevice& GPU;
  const NearestAnswers& Answers;           // the batch's nearest triangles (GPU)
  const std::vector<int64_t>& FirstSample; // each triangle's first answer in the batch
  const std::vector<PointQuery>& VertexQueries;
  const std::array<double, 6>& Region;
  double Step;
  bool KeepContacts;
  bool Chain; // the winding-number rule on a closed model: sides chained between samples

  /// The points whose side and distance are known: the corners, then the samples
  /// evaluated last (their coordinates in Recent).
  struct Scratch
  {
    std::vector<KnownPoint> Known;
    std::array<std::array<double, 3>, RecentSamples> Recent;
    size_t RecentNext = 0;
  };

  /// Triangle t's samples (batchTriangle: the batch's first triangle, for the answers).
  void Triangle(int64_t t, int64_t batchTriangle, BlockResult& result, Scratch& scratch) const
  {
    if (!BoxMeetsRegion(this->Self.Tree->Boxes()[static_cast<size_t>(t)], this->Region))
    {
      return;
    }
    double p[9];
    this->Self.Model.Corners(static_cast<size_t>(t), p);
    const int64_t n = Divisions(p, this->Step);
    // The corners are known points; the samples evaluated last join them.
    std::vector<KnownPoint>& known = scratch.Known;
    known.clear();
    for (const size_t id : this->Self.Model.Triangles[static_cast<size_t>(t)])
    {
      const PointQuery& corner = this->VertexQueries[id];
      known.push_back(
        { this->Self.Model.Points[id].data(), corner.D2, corner.Inside, corner.Triangle });
    }
    int64_t hint = known[0].Triangle;
    // The triangle's samples in the GPU's answers, in the lattice's order.
    size_t answer = this->GPU.Device
      ? static_cast<size_t>(this->FirstSample[static_cast<size_t>(t - batchTriangle)])
      : 0;
    for (int64_t i = 0; i <= n; ++i)
    {
      for (int64_t j = 0; i + j <= n; ++j)
      {
        if ((i == 0 && j == 0) || i == n || j == n)
        {
          continue; // a corner: a vertex, already counted
        }
        const size_t answerIndex = answer++;
        const double u = double(i) / n, v = double(j) / n;
        const double x[3] = { p[0] + u * (p[3] - p[0]) + v * (p[6] - p[0]),
          p[1] + u * (p[4] - p[1]) + v * (p[7] - p[1]),
          p[2] + u * (p[5] - p[2]) + v * (p[8] - p[2]) };
        if (!InRegion(this->Region, x))
        {
          continue;
        }
        ++result.Side.Samples;
        PointQuery query;
        const bool decided = this->Chain
          ? this->ChainedQuery(x, answerIndex, result, scratch, query)
          : this->FreshQuery(x, answerIndex, result, scratch, hint, query);
        if (decided || !query.Inside)
        {
          continue;
        }
        ++result.Side.SamplesInside;
        const ContactSample sample = MakeSample(x, query, t, -1);
        Keep(result.Side, sample, query.Closest, query.Triangle);
        if (this->KeepContacts)
        {
          result.Side.Contacts.push_back(sample);
        }
      }
    }
  }

  /// Without the contacts' list only the deepest matters: an inside sample whose distance
  /// cannot exceed the deepest so far (by the triangle inequality from a known point,
  /// d(x) <= d(y) + |x - y|) needs no exact distance.
  bool CannotDeepen(const double x[3], const PenetrationSide& part, const Scratch& scratch) const
  {
    if (this->KeepContacts || part.TriangleOfOther < 0)
    {
      return false;
    }
    double bound = HUGE_VAL;
    for (const KnownPoint& y : scratch.Known)
    {
      const double gap2 = (x[0] - y.X[0]) * (x[0] - y.X[0]) + (x[1] - y.X[1]) * (x[1] - y.X[1]) +
        (x[2] - y.X[2]) * (x[2] - y.X[2]);
      bound = std::min(bound, std::sqrt(y.D2) + std::sqrt(gap2));
    }
    return bound * (1 + 1e-12) <= part.Depth;
  }

  /// A closed chain: the side from a known point joined by a ball free of the surface,
  /// else the winding number; the distance only when needed. True when the sample is
  /// settled without a query (outside, or inside but no deeper); else `query` holds it.
  bool ChainedQuery(const double x[3],
    size_t answerIndex,
    BlockResult& result,
    Scratch& scratch,
    PointQuery& query) const
  {
    std::vector<KnownPoint>& known = scratch.Known;
    const KnownPoint* same = SameSide(known, x, 0);
    if (same && !same->Inside)
    {
      return true;
    }
    if (same && this->CannotDeepen(x, result.Side, scratch))
    {
      ++result.Side.SamplesInside;
      return true;
    }
    query = this->GPU.Device ? PointQuery(this->Answers, answerIndex)
                             : PointQuery(this->Other, x, known.back().Triangle);
    result.Queries += this->GPU.Device ? 0 : 1;
    same = same ? same : SameSide(known, x, query.D2);
    if (same)
    {
      query.Inside = same->Inside;
    }
    else
    {
      query.Inside = this->Other.Winding.Inside(x);
      ++result.Windings;
    }
    if (known.size() == 3 + RecentSamples)
    {
      known.erase(known.begin() + 3); // the corners stay
    }
    known.push_back({ nullptr, query.D2, query.Inside, query.Triangle });
    std::copy(x, x + 3, scratch.Recent[scratch.RecentNext].data());
    known.back().X = scratch.Recent[scratch.RecentNext].data();
    scratch.RecentNext = (scratch.RecentNext + 1) % scratch.Recent.size();
    return false;
  }

  /// Each sample alone: the winding number decides before the distance is needed; the
  /// pseudonormal rule after it. True when settled without a query, as ChainedQuery.
  bool FreshQuery(const double x[3],
    size_t answerIndex,
    BlockResult& result,
    const Scratch& scratch,
    int64_t& hint,
    PointQuery& query) const
  {
    const bool winding = this->Other.Rule == InsideRule::WindingNumber;
    if (winding)
    {
      ++result.Windings;
      if (!this->Other.Winding.Inside(x))
      {
        return true;
      }
      if (this->CannotDeepen(x, result.Side, scratch))
      {
        ++result.Side.SamplesInside;
        return true;
      }
    }
    query =
      this->GPU.Device ? PointQuery(this->Answers, answerIndex) : PointQuery(this->Other, x, hint);
    result.Queries += this->GPU.Device ? 0 : 1;
    hint = query.Triangle;
    query.Inside = winding || this->Other.Inside(x, query.Closest, query.Triangle, query.D2);
    return false;
  }
};
/// The GPU's batch from block batchBegin on: blocks (of blockSize triangles from block
/// firstBlock) up to `budget` samples and one block more, with each triangle's first
/// sample in `firstSample`. Returns the block after the batch.
int64_t DeviceBatch(const ProximityModel::Data& self,
  const std::array<double, 6>& region,
  double step,
  int64_t firstBlock,
  int64_t blockSize,
  int64_t batchBegin,
  int64_t blocks,
  int64_t budget,
  SampleBatch& batch,
  std::vector<int64_t>& firstSample)
{
  const int64_t triangles = static_cast<int64_t>(self.Model.Triangles.size());
  batch.Items.clear();
  batch.Samples = 0;
  firstSample.clear();
  int64_t batchEnd = batchBegin;
  for (; batchEnd < blocks && (batchEnd == batchBegin || batch.Samples < budget); ++batchEnd)
  {
    const int64_t end = std::min(triangles, (firstBlock + batchEnd + 1) * blockSize);
    for (int64_t t = (firstBlock + batchEnd) * blockSize; t < end; ++t)
    {
      firstSample.push_back(batch.Samples);
      if (!BoxMeetsRegion(self.Tree->Boxes()[static_cast<size_t>(t)], region))
      {
        continue;
      }
      double p[9];
      self.Model.Corners(static_cast<size_t>(t), p);
      const int64_t n = Divisions(p, step);
      const int64_t count = (n + 1) * (n + 2) / 2 - 3;
      if (count > 0)
      {
        batch.Items.insert(batch.Items.end(),
          { static_cast<int32_t>(t),
            static_cast<int32_t>(batch.Samples),
            static_cast<int32_t>(n),
            0 });
        batch.Samples += count;
      }
    }
  }
  return batchEnd;
}

/// The penetration of `self` into `other`: its vertices (from their queries) and face
/// samples in `region` inside `other`. False with `error` when the GPU fails.
bool Penetrate(const ProximityModel::Data& self,
  const ProximityModel::Data& other,
  const OnDevice& gpu,
  const std::vector<PointQuery>& vertexQueries,
  const std::array<double, 6>& region,
  double step,
  bool keepContacts,
  int share,
  int shares,
  const Execution& execution,
  PenetrationSide& side,
  int64_t& queries,
  int64_t& windings,
  std::string& error)
{
  side = PenetrationSide();
  // The vertices are the first share's; the blocks of triangles are split in order.
  if (share == 0)
  {
    VertexPenetration(self, vertexQueries, region, keepContacts, side);
  }
  // The face samples other than the corners, in blocks of triangles whose results are
  // merged in order: the report does not depend on the threads.
  const int64_t triangles = static_cast<int64_t>(self.Model.Triangles.size());
  const int64_t blockSize = 64;
  const int64_t allBlocks = (triangles + blockSize - 1) / blockSize;
  const int64_t firstBlock = allBlocks * share / shares;
  const int64_t blocks = allBlocks * (share + 1) / shares - firstBlock;
  std::vector<BlockResult> results(static_cast<size_t>(blocks));
  // On the CPU, every block at once, each sample's nearest triangle searched when it is
  // needed. On the GPU, batches of blocks: the nearest triangles of all the batch's
  // samples first (FirstSample: each triangle's first in the answers), then the blocks.
  SampleBatch batch;
  NearestAnswers answers;
  std::vector<int64_t> firstSample;
  const FaceSampler sampler{ self,
    other,
    gpu,
    answers,
    firstSample,
    vertexQueries,
    region,
    step,
    keepContacts,
    other.Rule == InsideRule::WindingNumber && other.Closed };
  // A batch holds blocks up to DeviceBatchSamples (and one block more).
  const int64_t batchBudget = gpu.Device ? DeviceBatchSamples(*gpu.Device) : 0;
  for (int64_t batchBegin = 0, batchEnd = 0; batchBegin < blocks; batchBegin = batchEnd)
  {
    batchEnd = blocks;
    const int64_t batchTriangle = (firstBlock + batchBegin) * blockSize;
    if (gpu.Device)
    {
      batchEnd = DeviceBatch(self,
        region,
        step,
        firstBlock,
        blockSize,
        batchBegin,
        blocks,
        batchBudget,
        batch,
        firstSample);
      if (batch.Samples > 0 &&
        !DeviceNearestToSamples(*gpu.Device, gpu.Self, gpu.Other, batch, answers, error))
      {
        return false;
      }
      queries += batch.Samples;
    }
    RunFor(execution,
      batchEnd - batchBegin,
      1,
      [&, batchBegin](int64_t first, int64_t last)
      {
        FaceSampler::Scratch scratch;
        scratch.Known.reserve(3 + RecentSamples);
        for (int64_t block = batchBegin + first; block < batchBegin + last; ++block)
        {
          const int64_t end = std::min(triangles, (firstBlock + block + 1) * blockSize);
          for (int64_t t = (firstBlock + block) * blockSize; t < end; ++t)
          {
            sampler.Triangle(t, batchTriangle, results[static_cast<size_t>(block)], scratch);
          }
        }
      });
  }
  for (const BlockResult& result : results)
  {
    const PenetrationSide& part = result.Side;
    side.Samples += part.Samples;
    side.SamplesInside += part.SamplesInside;
    queries += result.Queries;
    windings += result.Windings;
    if (part.TriangleOfOther >= 0 && (part.Depth > side.Depth || side.TriangleOfOther < 0))
    {
      side.Depth = part.Depth;
      side.Deepest = part.Deepest;
      side.ClosestOnOther = part.ClosestOnOther;
      side.Normal = part.Normal;
      side.TriangleOfOther = part.TriangleOfOther;
    }
    side.Contacts.insert(side.Contacts.end(), part.Contacts.begin(), part.Contacts.end());
  }
  return true;
}

/// Face samples (corners excluded) that `self`'s triangles meeting `region` would take.
double CountFaceSamples(const ProximityModel::Data& self,
  const std::array<double, 6>& region,
  double step)
{
  double count = 0;
  for (size_t t = 0; t < self.Model.Triangles.size(); ++t)
  {
    if (BoxMeetsRegion(self.Tree->Boxes()[t], region))
    {
      double p[9];
      self.Model.Corners(t, p);
      const double n = static_cast<double>(Divisions(p, step));
      count += (n + 1) * (n + 2) / 2 - 3;
    }
  }
  return count;
}
} // namespace

namespace
{
/// Whether the request can be answered for these models; false with `error`.
bool CheckRequest(const ProximityModel::Data& a,
  const ProximityModel::Data& b,
  const ProximityRequest& request,
  std::string& error)
{
  if (!a.Loaded || !b.Loaded)
  {
    error = "both models must be loaded before a query";
    return false;
  }
  if (a.Rule != request.Rule || b.Rule != request.Rule)
  {
    error = "the models were loaded for another inside rule than the request's";
    return false;
  }
  if (!(request.ContactMargin >= 0) || !std::isfinite(request.ContactMargin))
  {
    error = "the contact margin must be finite and at least 0; it is " +
      std::to_string(request.ContactMargin);
    return false;
  }
  if (!(request.Step >= 0) || !std::isfinite(request.Step))
  {
    error = "the step must be finite and at least 0 (0: from the resolution); it is " +
      std::to_string(request.Step);
    return false;
  }
  if (request.Shares < 1 || request.Share < 0 || request.Share >= request.Shares)
  {
    error = "share " + std::to_string(request.Share) + " of " + std::to_string(request.Shares) +
      " does not exist";
    return false;
  }
  if (request.Step == 0 && (request.Resolution < 1 || request.Resolution > 65536))
  {
    error = "the resolution must be 1 to 65536; it is " + std::to_string(request.Resolution);
    return false;
  }
  return true;
}

/// The interaction region (the boxes' overlap grown by the margin; empty: `empty`) and
/// the step from it, into the report; false with `error` when the face samples would
/// exceed the request's limit.
bool InteractionRegion(const ProximityModel::Data& a,
  const ProximityModel::Data& b,
  const ProximityRequest& request,
  ProximityReport& report,
  bool& empty,
  std::string& error)
{
  std::array<double, 6> hull;
  double longest = 0, regionLongest = 0;
  empty = false;
  for (int k = 0; k < 3; ++k)
  {
    const double m = request.ContactMargin;
    report.Region[2 * k] = std::max(a.Bounds[2 * k], b.Bounds[2 * k]) - m;
    report.Region[2 * k + 1] = std::min(a.Bounds[2 * k + 1], b.Bounds[2 * k + 1]) + m;
    hull[2 * k] = std::min(a.Bounds[2 * k], b.Bounds[2 * k]);
    hull[2 * k + 1] = std::max(a.Bounds[2 * k + 1], b.Bounds[2 * k + 1]);
    empty = empty || report.Region[2 * k] > report.Region[2 * k + 1];
    longest = std::max(longest, hull[2 * k + 1] - hull[2 * k]);
    regionLongest = std::max(regionLongest, report.Region[2 * k + 1] - report.Region[2 * k]);
  }
  if (empty)
  {
    report.Region = { { 0, -1, 0, -1, 0, -1 } };
  }
  report.Step = request.Step > 0
    ? request.Step
    : (empty || regionLongest <= 0 ? longest : regionLongest) / request.Resolution;
  if (!(report.Step > 0))
  {
    // Both models are one point: any positive step samples them.
    report.Step = 1;
  }
  if (!empty)
  {
    const double samples = CountFaceSamples(a, report.Region, report.Step) +
      CountFaceSamples(b, report.Region, report.Step);
    if (samples > static_cast<double>(request.MaximumSamples))
    {
      error = "the face samples at step " + std::to_string(report.Step) + " would number " +
        std::to_string(static_cast<long long>(samples)) + ", over the limit of " +
        std::to_string(request.MaximumSamples) + ": take a coarser step (a lower resolution)";
      return false;
    }
  }
  return true;
}

/// Contact: the first pair of triangles, one of each model, with a point in common.
void FindContactPair(const ProximityModel::Data& a,
  const ProximityModel::Data& b,
  ProximityResult& contact)
{
  a.Tree->ForEachOverlappingPair(*b.Tree,
    [&](size_t s, size_t t)
    {
      Point3 p[3], q[3];
      a.Model.Corners(s, p);
      b.Model.Corners(t, q);
      ++contact.ContactTests;
      if (ClosedTrianglesIntersect(p, q))
      {
        contact.ContactA = static_cast<int64_t>(s);
        contact.ContactB = static_cast<int64_t>(t);
        return false;
      }
      return true;
    });
}

/// Apart: the separation and its pair, from the least of the points' distances as the
/// bound (searched again without one should rounding leave the bound short).
void FindSeparation(const ProximityModel::Data& a,
  const ProximityModel::Data& b,
  ProximityReport& report)
{
  double bound = HUGE_VAL;
  for (const auto* distances : { &report.DistanceA, &report.DistanceB })
  {
    for (const double d : *distances)
    {
      bound = std::isnan(d) ? bound : std::min(bound, std::fabs(d));
    }
  }
  if (!NearestPair(a.Model, *a.Tree, b.Model, *b.Tree, bound * bound, report.Contact))
  {
    NearestPair(a.Model, *a.Tree, b.Model, *b.Tree, HUGE_VAL, report.Contact);
  }
}
} // namespace

bool ComputeProximity(const ProximityModel& modelA,
  const ProximityModel& modelB,
  const ProximityRequest& request,
  ProximityReport& report,
  const Execution& execution,
  std::string& error)
{
  report = ProximityReport();
  const ProximityModel::Data& a = modelA.Get();
  const ProximityModel::Data& b = modelB.Get();
  bool empty = false;
  if (!CheckRequest(a, b, request, error) ||
    !InteractionRegion(a, b, request, report, empty, error))
  {
    return false;
  }
  auto aborted = [&](double fraction)
  {
    if (execution.Report(fraction))
    {
      return false;
    }
    error = "aborted";
    return true;
  };

  // On the GPU: both models there (their coordinates; their topology when it is new).
  ProximityDevice* device = request.Device;
  if (device)
  {
    DeviceResetTraffic(*device);
    if (!DeviceLoadModel(*device, 0, a.Model, *a.Tree, a.Topology, error) ||
      !DeviceLoadModel(*device, 1, b.Model, *b.Tree, b.Topology, error))
    {
      return false;
    }
    execution.EndStage("upload");
  }
  const OnDevice gpuAB{ device, 0, 1 }, gpuBA{ device, 1, 0 };

  // The merged report takes the contact pair and the separation from the first share:
  // the others skip both.
  ProximityResult& contact = report.Contact;
  const bool first = request.Share == 0;
  if (first)
  {
    FindContactPair(a, b, contact);
  }
  if (aborted(0.1))
  {
    return false;
  }

  // Every point's distance to the other model: the fields where the points need them.
  std::vector<PointQuery> queriesA, queriesB;
  if (!PointDistances(a, b, gpuAB, execution, report.DistanceA, queriesA, error) ||
    !PointDistances(b, a, gpuBA, execution, report.DistanceB, queriesB, error))
  {
    return false;
  }
  if (request.Share == 0)
  {
    report.PointQueries += static_cast<int64_t>(std::count(a.Used.begin(), a.Used.end(), true) +
      std::count(b.Used.begin(), b.Used.end(), true));
  }
  execution.EndStage("point distances");
  if (aborted(0.3))
  {
    return false;
  }

  // Penetration, both ways, over the region's samples.
  auto penetrate = [&](const ProximityModel::Data& self,
                     const ProximityModel::Data& other,
                     const OnDevice& gpu,
                     const std::vector<PointQuery>& queries,
                     PenetrationSide& side)
  {
    return Penetrate(self,
      other,
      gpu,
      queries,
      report.Region,
      report.Step,
      request.Contacts,
      request.Share,
      request.Shares,
      execution,
      side,
      report.PointQueries,
      report.InsideEvaluations,
      error);
  };
  if (!empty &&
    (!penetrate(a, b, gpuAB, queriesA, report.AInB) || aborted(0.6) ||
      !penetrate(b, a, gpuBA, queriesB, report.BInA)))
  {
    return false;
  }
  execution.EndStage("penetration");
  if (device)
  {
    DeviceTraffic(*device, report.BytesToDevice, report.BytesFromDevice);
  }
  contact.AInsideB = report.AInB.SamplesInside > 0;
  contact.BInsideA = report.BInA.SamplesInside > 0;
  contact.Colliding = contact.ContactA >= 0 || contact.AInsideB || contact.BInsideA;
  if (contact.Colliding || !first)
  {
    contact.Separation = 0;
  }
  else
  {
    FindSeparation(a, b, report);
    execution.EndStage("separation");
  }
  return !aborted(1.0);
}

void MergeProximityShares(std::vector<ProximityReport>& shares, ProximityReport& merged)
{
  merged = std::move(shares[0]);
  for (size_t k = 1; k < shares.size(); ++k)
  {
    ProximityReport& share = shares[k];
    merged.PointQueries += share.PointQueries;
    merged.InsideEvaluations += share.InsideEvaluations;
    merged.Contact.ContactTests = std::max(merged.Contact.ContactTests, share.Contact.ContactTests);
    PenetrationSide* into[2] = { &merged.AInB, &merged.BInA };
    PenetrationSide* from[2] = { &share.AInB, &share.BInA };
    for (int m = 0; m < 2; ++m)
    {
      into[m]->Samples += from[m]->Samples;
      into[m]->SamplesInside += from[m]->SamplesInside;
      // The first deepest in the order of the samples: shares are in that order.
      if (from[m]->TriangleOfOther >= 0 &&
        (from[m]->Depth > into[m]->Depth || into[m]->TriangleOfOther < 0))
      {
        into[m]->Depth = from[m]->Depth;
        into[m]->Deepest = from[m]->Deepest;
        into[m]->ClosestOnOther = from[m]->ClosestOnOther;
        into[m]->Normal = from[m]->Normal;
        into[m]->TriangleOfOther = from[m]->TriangleOfOther;
      }
      into[m]->Contacts.insert(
        into[m]->Contacts.end(), from[m]->Contacts.begin(), from[m]->Contacts.end());
    }
  }
  ProximityResult& contact = merged.Contact;
  contact.AInsideB = merged.AInB.SamplesInside > 0;
  contact.BInsideA = merged.BInA.SamplesInside > 0;
  contact.Colliding = contact.ContactA >= 0 || contact.AInsideB || contact.BInsideA;
  if (contact.Colliding)
  {
    // The first share may have searched the separation before the others' samples
    // inside were known.
    contact.Separation = 0;
    contact.ClosestTriangleA = contact.ClosestTriangleB = -1;
    contact.DistanceTests = 0;
  }
}

namespace
{
constexpr int ContactDoubles = 9; // point, normal, depth, triangle, vertex

void PackSide(const PenetrationSide& side, std::vector<double>& out)
{
  const double head[] = { side.Depth,
    side.Deepest[0],
    side.Deepest[1],
    side.Deepest[2],
    side.ClosestOnOther[0],
    side.ClosestOnOther[1],
    side.ClosestOnOther[2],
    side.Normal[0],
    side.Normal[1],
    side.Normal[2],
    double(side.TriangleOfOther),
    double(side.Samples),
    double(side.SamplesInside),
    double(side.Contacts.size()) };
  out.insert(out.end(), std::begin(head), std::end(head));
  for (const ContactSample& c : side.Contacts)
  {
    const double values[ContactDoubles] = { c.Point[0],
      c.Point[1],
      c.Point[2],
      c.Normal[0],
      c.Normal[1],
      c.Normal[2],
      c.Depth,
      double(c.Triangle),
      double(c.Vertex) };
    out.insert(out.end(), std::begin(values), std::end(values));
  }
}

bool UnpackSide(const double*& at, const double* end, PenetrationSide& side)
{
  if (end - at < 14)
  {
    return false;
  }
  side.Depth = at[0];
  std::copy(at + 1, at + 4, side.Deepest.begin());
  std::copy(at + 4, at + 7, side.ClosestOnOther.begin());
  std::copy(at + 7, at + 10, side.Normal.begin());
  side.TriangleOfOther = static_cast<int64_t>(at[10]);
  side.Samples = static_cast<int64_t>(at[11]);
  side.SamplesInside = static_cast<int64_t>(at[12]);
  const double count = at[13];
  at += 14;
  if (!(count >= 0) || count * ContactDoubles > double(end - at))
  {
    return false;
  }
  side.Contacts.resize(static_cast<size_t>(count));
  for (ContactSample& c : side.Contacts)
  {
    std::copy(at, at + 3, c.Point.begin());
    std::copy(at + 3, at + 6, c.Normal.begin());
    c.Depth = at[6];
    c.Triangle = static_cast<int64_t>(at[7]);
    c.Vertex = static_cast<int64_t>(at[8]);
    at += ContactDoubles;
  }
  return true;
}
} // namespace

std::vector<double> PackProximityShare(const ProximityReport& report)
{
  const ProximityResult& c = report.Contact;
  std::vector<double> out = { double(c.ContactA),
    double(c.ContactB),
    c.Separation,
    c.ClosestA[0],
    c.ClosestA[1],
    c.ClosestA[2],
    c.ClosestB[0],
    c.ClosestB[1],
    c.ClosestB[2],
    double(c.ClosestTriangleA),
    double(c.ClosestTriangleB),
    double(c.ContactTests),
    double(c.DistanceTests),
    double(report.PointQueries),
    double(report.InsideEvaluations) };
  PackSide(report.AInB, out);
  PackSide(report.BInA, out);
  return out;
}

bool UnpackProximityShares(const double* data,
  size_t count,
  const ProximityReport& local,
  std::vector<ProximityReport>& shares)
{
  shares.clear();
  const double* at = data;
  const double* end = data + count;
  while (at < end)
  {
    if (end - at < 15)
    {
      return false;
    }
    // What every share computes alike (the region, the step, the point distances) is
    // the local report's.
    ProximityReport share;
    share.Region = local.Region;
    share.Step = local.Step;
    ProximityResult& c = share.Contact;
    c.ContactA = static_cast<int64_t>(at[0]);
    c.ContactB = static_cast<int64_t>(at[1]);
    c.Separation = at[2];
    std::copy(at + 3, at + 6, c.ClosestA.begin());
    std::copy(at + 6, at + 9, c.ClosestB.begin());
    c.ClosestTriangleA = static_cast<int64_t>(at[9]);
    c.ClosestTriangleB = static_cast<int64_t>(at[10]);
    c.ContactTests = static_cast<int64_t>(at[11]);
    c.DistanceTests = static_cast<int64_t>(at[12]);
    share.PointQueries = static_cast<int64_t>(at[13]);
    share.InsideEvaluations = static_cast<int64_t>(at[14]);
    at += 15;
    if (!UnpackSide(at, end, share.AInB) || !UnpackSide(at, end, share.BInA))
    {
      return false;
    }
    if (shares.empty())
    {
      share.DistanceA = local.DistanceA;
      share.DistanceB = local.DistanceB;
    }
    shares.push_back(std::move(share));
  }
  return !shares.empty();
}
} // namespace vtkdf
