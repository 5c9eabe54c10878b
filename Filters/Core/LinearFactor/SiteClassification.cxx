#include "LinearFactor/SiteBuilder.h"

namespace vtkdf
{
namespace sites
{
void SiteBuilder::VertexNormals()
{
  const auto& corners = this->Out.FaceCorners;
  // Each face's volume term and corner angles in parallel; the terms then summed in face
  // order (the same sum as a serial loop's).
  LargeVector<double> volumes(this->NumFaces);
  LargeVector<double> cornerAngle(3 * this->NumFaces);
  Run(this->For,
    this->NumFaces,
    4096,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t fi = begin; fi < end; ++fi)
      {
        const auto& f = corners[fi];
        const Vec a = Sub(this->X(f[0]), this->X(0)), b = Sub(this->X(f[1]), this->X(0)),
                  c = Sub(this->X(f[2]), this->X(0));
        volumes[fi] = Dot(a, Cross(b, c));
        for (int k = 0; k < 3; ++k)
        {
          const Vec u = Sub(this->X(f[(k + 1) % 3]), this->X(f[k]));
          const Vec w = Sub(this->X(f[(k + 2) % 3]), this->X(f[k]));
          cornerAngle[3 * fi + k] = std::atan2(Norm(Cross(u, w)), Dot(u, w));
        }
      }
    });
  double volume = 0;
  for (const double term : volumes)
  {
    volume += term;
  }
  const double orientation = volume < 0 ? -1.0 : 1.0;
  this->Out.Orientation = orientation;
  std::vector<Vec> sum(this->NumVertices, Vec{ 0, 0, 0 });
  for (int64_t fi = 0; fi < this->NumFaces; ++fi)
  {
    const auto& f = corners[fi];
    const Vec normal = this->Normal(fi);
    for (int k = 0; k < 3; ++k)
    {
      sum[f[k]] = Add(sum[f[k]], Scale(normal, cornerAngle[3 * fi + k] * orientation));
    }
  }
  // Only the sign of a dot product with it is used: float is enough.
  this->Out.VertexNormals.resize(this->NumVertices);
  for (int64_t v = 0; v < this->NumVertices; ++v)
  {
    for (int a = 0; a < 3; ++a)
    {
      this->Out.VertexNormals[v][a] = static_cast<float>(sum[v][a]);
    }
  }
}

/// Calls visit(first, last, b) for every group of bucket a (records [first, last), edge
/// from a to b) that is not degenerate; returns how many were.
template<typename Visit>
int64_t SiteBuilder::ForEachGroup(int64_t a, const Visit& visit) const
{
  int64_t degenerateGroups = 0;
  for (int64_t e0 = this->EdgeStart[a]; e0 < this->EdgeStart[a + 1];)
  {
    int64_t e1 = e0 + 1;
    while (e1 < this->EdgeStart[a + 1] && this->Edges[e1].B == this->Edges[e0].B)
    {
      ++e1;
    }
    if (Norm(Sub(this->X(this->Edges[e0].B), this->X(a))) <= this->Degenerate)
    {
      ++degenerateGroups;
    }
    else
    {
      visit(e0, e1, this->Edges[e0].B);
    }
    e0 = e1;
  }
  return degenerateGroups;
}

// A group lies in one bucket (the records of one smaller point), so the buckets are
// counted, then written, in parallel; edges are numbered in bucket order, as a serial
// loop would.
bool SiteBuilder::GroupEdges(std::string& error)
{
  const int64_t nv = this->NumVertices;
  std::vector<int64_t> groupStart(nv + 1, 0);
  std::atomic<int64_t> degenerateEdges{ 0 };
  Run(this->For,
    nv,
    4096,
    [&](int64_t begin, int64_t end)
    {
      int64_t local = 0;
      for (int64_t a = begin; a < end; ++a)
      {
        int64_t count = 0;
        local += this->ForEachGroup(a, [&](int64_t, int64_t, int64_t) { ++count; });
        groupStart[a + 1] = count;
      }
      degenerateEdges += local;
    });
  this->Out.Statistics.DegenerateEdges = degenerateEdges.load();
  for (int64_t v = 0; v < nv; ++v)
  {
    groupStart[v + 1] += groupStart[v];
  }
  this->NumEdges = groupStart[nv];
  const int64_t numSites = this->NumFaces + this->NumEdges + nv;
  if (numSites >= int64_t(UINT32_MAX) || 2 * this->NumEdges >= int64_t(UINT32_MAX))
  {
    error = "the mesh has " + std::to_string(numSites) + " sites, more than 2^32 - 1";
    return false;
  }
  MeshSites& out = this->Out;
  out.EdgeEnds.resize(this->NumEdges);
  out.EdgeCells.resize(this->NumEdges);
  out.EdgeFaceStart.resize(this->NumEdges + 1);
  out.EdgeFaceStart[0] = 0;
  std::vector<std::atomic<int64_t>> vertexEdgeCount(nv + 1); // value-initialized: zeros
  // The faces of every edge are its records' that have one: they come first in a group
  // (sorted by Source).
  auto groupFaces = [this](int64_t first, int64_t last)
  {
    int64_t faces = 0;
    for (int64_t r = first; r < last; ++r)
    {
      faces += this->IsFaceRecord(this->Edges[r]);
    }
    return faces;
  };
  // Every edge with its number e: the buckets in parallel, each numbering its groups from
  // the bucket's first edge.
  auto forEachEdge = [&](const auto& visit)
  {
    Run(this->For,
      nv,
      4096,
      [&](int64_t begin, int64_t end)
      {
        for (int64_t a = begin; a < end; ++a)
        {
          int64_t e = groupStart[a];
          this->ForEachGroup(
            a, [&](int64_t first, int64_t last, int64_t b) { visit(e++, first, last, a, b); });
        }
      });
  };
  forEachEdge(
    [&](int64_t e, int64_t first, int64_t last, int64_t a, int64_t b)
    {
      int64_t cell = INT64_MAX;
      for (int64_t r = first; r < last; ++r)
      {
        cell = std::min(cell, this->RecordCell(this->Edges[r]));
      }
      out.EdgeCells[e] = cell;
      out.EdgeEnds[e] = { static_cast<uint32_t>(a), static_cast<uint32_t>(b) };
      out.EdgeFaceStart[e + 1] = static_cast<uint32_t>(groupFaces(first, last));
      vertexEdgeCount[a + 1].fetch_add(1, std::memory_order_relaxed);
      vertexEdgeCount[b + 1].fetch_add(1, std::memory_order_relaxed);
    });
  uint64_t edgeFaces = 0;
  for (int64_t e = 0; e < this->NumEdges; ++e)
  {
    edgeFaces += out.EdgeFaceStart[e + 1];
    if (edgeFaces >= UINT32_MAX)
    {
      error = "the mesh's edges have more than 2^32 - 1 faces in all";
      return false;
    }
    out.EdgeFaceStart[e + 1] = static_cast<uint32_t>(edgeFaces);
  }
  out.EdgeFaces.resize(edgeFaces);
  forEachEdge(
    [&](int64_t e, int64_t first, int64_t, int64_t, int64_t)
    {
      uint32_t at = out.EdgeFaceStart[e];
      for (int64_t r = first; r < first + this->EdgeFaceCount(e); ++r)
      {
        out.EdgeFaces[at++] = this->Edges[r].Source;
      }
    });
  LargeVector<EdgeRecord>().swap(this->Edges);
  std::vector<int64_t>().swap(this->LooseCells);
  std::vector<int64_t>().swap(this->EdgeStart);

  // The edges of every vertex, contiguous per vertex, in edge order. Filled in
  // parallel, then each vertex's few sorted.
  out.VertexEdgeStart.resize(nv + 1);
  out.VertexEdgeStart[0] = 0;
  for (int64_t v = 0; v < nv; ++v)
  {
    out.VertexEdgeStart[v + 1] = static_cast<uint32_t>(
      out.VertexEdgeStart[v] + vertexEdgeCount[v + 1].load(std::memory_order_relaxed));
  }
  std::vector<std::atomic<int64_t>>& vertexEdgeFill = vertexEdgeCount; // the next free entry
  for (int64_t v = 0; v < nv; ++v)
  {
    vertexEdgeFill[v].store(out.VertexEdgeStart[v], std::memory_order_relaxed);
  }
  out.VertexEdges.resize(out.VertexEdgeStart[nv]);
  Run(this->For,
    this->NumEdges,
    4096,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t e = begin; e < end; ++e)
      {
        for (int side = 0; side < 2; ++side)
        {
          const int64_t at =
            vertexEdgeFill[out.EdgeEnds[e][side]].fetch_add(1, std::memory_order_relaxed);
          out.VertexEdges[at] = static_cast<uint32_t>(e);
        }
      }
    });
  std::vector<int64_t> vertexEdgeStart(out.VertexEdgeStart.begin(), out.VertexEdgeStart.end());
  SortBuckets(out.VertexEdges, vertexEdgeStart, std::less<uint32_t>(), this->For);
  return true;
}

/// The unit direction of edge e away from its end v.
Vec SiteBuilder::Away(int64_t v, int64_t e) const
{
  double t[3];
  this->Out.EdgeTangent(e, t);
  const double sign = this->Out.EdgeEnds[e][0] == v ? 1.0 : -1.0;
  return { t[0] * sign, t[1] * sign, t[2] * sign };
}

EdgeSpan SiteBuilder::IncidentEdges(int64_t v) const
{
  return EdgeSpan{ this->Out.VertexEdges.data() + this->Out.VertexEdgeStart[v],
    static_cast<size_t>(this->Out.VertexEdgeStart[v + 1] - this->Out.VertexEdgeStart[v]) };
}

void SiteBuilder::ClassifyVertices()
{
  const int64_t nv = this->NumVertices;
  if (this->Mode == DomainShape::Manifold)
  {
    this->VertexFaces.resize(nv);
    for (int64_t f = 0; f < this->NumFaces; ++f)
    {
      for (int k = 0; k < 3; ++k)
      {
        this->VertexFaces[this->Out.FaceCorners[f][k]].push_back(f);
      }
    }
    this->Out.PyramidSides.resize(nv);
  }
  this->Out.VertexDomains.assign(nv, Unbounded);
  Run(this->For,
    nv,
    1024,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t v = begin; v < end; ++v)
      {
        this->Out.VertexDomains[v] = this->Classify(v);
      }
    });
}

uint8_t SiteBuilder::Classify(int64_t v)
{
  const EdgeSpan incident = this->IncidentEdges(v);
  if (this->Mode != DomainShape::Manifold)
  {
    return this->Mode == DomainShape::Auto && !incident.empty() ? Polar : Unbounded;
  }
  // Manifold culling: only where the faces around v form one closed fan.
  if (!this->ClosedFan(v, incident))
  {
    return Unbounded;
  }
  // Convex or concave vertex (every incident edge bends the same way): the polytope
  // spanned by the face normals, i.e. the planes orthogonal to the edges.
  int convex = 0, concave = 0;
  for (const uint32_t e : incident)
  {
    const auto& f1 = this->Out.FaceCorners[this->EdgeFace(e, 1)];
    const int64_t a = this->Out.EdgeEnds[e][0], b = this->Out.EdgeEnds[e][1];
    int64_t c1 = f1[0];
    for (int k = 0; k < 3; ++k)
    {
      if (f1[k] != a && f1[k] != b)
      {
        c1 = f1[k];
      }
    }
    const Vec n0 = Scale(this->Normal(this->EdgeFace(e, 0)), this->Out.Orientation);
    const double bend = Dot(n0, Sub(this->X(c1), this->X(a)));
    convex += bend <= 0;
    concave += bend >= 0;
  }
  if (convex == static_cast<int>(incident.size()) || concave == static_cast<int>(incident.size()))
  {
    return Polar;
  }
  return this->PyramidAround(v, incident) ? Pyramid : Unbounded;
}

/// Whether the faces around v form one closed fan: every incident edge has two faces, as
/// many as the faces around v, and a walk around them visits each once.
bool SiteBuilder::ClosedFan(int64_t v, const EdgeSpan& incident) const
{
  const auto& fan = this->VertexFaces[v];
  bool closed = !incident.empty() && fan.size() == incident.size();
  for (const uint32_t e : incident)
  {
    closed = closed && this->EdgeFaceCount(e) == 2;
  }
  if (!closed)
  {
    return false;
  }
  size_t steps = 0;
  int64_t edge = incident[0], face = this->EdgeFace(edge, 0);
  const int64_t startFace = face;
  do
  {
    ++steps;
    int64_t next = -1;
    for (const uint32_t e : incident)
    {
      if (e != edge && (this->EdgeFace(e, 0) == face || this->EdgeFace(e, 1) == face))
      {
        next = e;
      }
    }
    if (next < 0)
    {
      return false;
    }
    edge = next;
    face = this->EdgeFace(edge, 0) == face ? this->EdgeFace(edge, 1) : this->EdgeFace(edge, 0);
  } while (face != startFace && steps <= fan.size());
  return steps == fan.size();
}

/// A hyperbolic vertex (Theorem 1): the cone about the mean normal n_a whose half-angle
/// is the largest angle between n_a and a face normal, circumscribed by a square pyramid
/// (PyramidSides[v], in float as the planes store it); false when there is none or it does
/// not hold the exact domain.
bool SiteBuilder::PyramidAround(int64_t v, const EdgeSpan& incident)
{
  const auto& fan = this->VertexFaces[v];
  Vec na{ 0, 0, 0 };
  for (int64_t f : fan)
  {
    na = Add(na, this->Normal(f));
  }
  const double nal = Norm(na);
  double cosTheta = 1;
  if (nal > 0)
  {
    na = Scale(na, 1.0 / nal);
    for (int64_t f : fan)
    {
      cosTheta = std::min(cosTheta, Dot(na, this->Normal(f)));
    }
  }
  if (!(nal > 0 && cosTheta > 1e-6)) // theta >= pi/2: no pyramid
  {
    return false;
  }
  const double sinTheta = std::sqrt(std::max(0.0, 1 - cosTheta * cosTheta));
  Vec b1 = std::fabs(na[0]) < 0.9 ? Vec{ 1, 0, 0 } : Vec{ 0, 1, 0 };
  b1 = Sub(b1.data(), Scale(na, Dot(b1, na)).data());
  b1 = Scale(b1, 1.0 / Norm(b1));
  const Vec b2 = Cross(na, b1);
  // The cone's tangent planes along +-b1, +-b2: a square pyramid containing the cone.
  std::array<Vec, 4> sides;
  const Vec directions[4] = { b1, Scale(b1, -1), b2, Scale(b2, -1) };
  for (int i = 0; i < 4; ++i)
  {
    sides[i] = Sub(Scale(na, sinTheta).data(), Scale(directions[i], cosTheta).data());
    for (int a = 0; a < 3; ++a)
    {
      this->Out.PyramidSides[v][3 * i + a] = static_cast<float>(sides[i][a]);
    }
  }
  // Theorem 1 is stated for saddles; check that the exact domain (the cone of
  // directions y with y.u <= 0 for every edge u) really lies in the pyramid.
  bool pyramid = true;
  double rank = 0;
  for (size_t i = 0; i < incident.size(); ++i)
  {
    for (size_t j = i + 1; j < incident.size(); ++j)
    {
      const Vec r = Cross(this->Away(v, incident[i]), this->Away(v, incident[j]));
      for (const uint32_t e : incident)
      {
        rank = std::max(rank, std::fabs(Dot(r, this->Away(v, e))));
      }
      for (double sign : { 1.0, -1.0 })
      {
        const Vec ray = Scale(r, sign);
        bool inDomain = Norm(ray) > 1e-12;
        for (const uint32_t e : incident)
        {
          inDomain = inDomain && Dot(ray, this->Away(v, e)) <= 1e-12;
        }
        for (const Vec& w : sides)
        {
          pyramid = pyramid && (!inDomain || Dot(ray, w) >= -1e-12);
        }
      }
    }
  }
  return pyramid && rank > 1e-9;
}
} // namespace sites
} // namespace vtkdf
