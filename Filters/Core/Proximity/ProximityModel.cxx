#include "Proximity/ProximityParts.h"

#include "Common/Vector3.h"
#include "Winding/WindingCrossings.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace vtkdf
{

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
    const Point3 n = proximity::Unit(
      { { u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0] } });
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
} // namespace vtkdf
