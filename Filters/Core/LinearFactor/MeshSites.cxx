#include "LinearFactor/MeshSites.h"

#include "Common/FloatBounds.h"
#include "LinearFactor/SiteBuilder.h"

namespace vtkdf
{
namespace sites
{
void SiteBuilder::Finish()
{
  std::vector<std::vector<int64_t>>().swap(this->VertexFaces);
  this->Out.VertexCells.resize(this->NumVertices);
  for (int64_t v = 0; v < this->NumVertices; ++v)
  {
    this->Out.VertexCells[v] = this->VertexCell[v].load(std::memory_order_relaxed);
  }
  std::vector<std::atomic<int64_t>>().swap(this->VertexCell);
}

void SiteBuilder::CountDomains()
{
  DomainStatistics& statistics = this->Out.Statistics;
  statistics.Faces = this->NumFaces;
  statistics.Edges = this->NumEdges;
  statistics.Vertices = this->NumVertices;
  for (int64_t e = 0; e < this->NumEdges; ++e)
  {
    statistics.EdgeWedges += this->Out.Wedge(e) && this->EdgeFaceCount(e) > 0;
  }
  for (const uint8_t domain : this->Out.VertexDomains)
  {
    statistics.PolarVertices += domain == Polar;
    statistics.PyramidVertices += domain == Pyramid;
    statistics.UnboundedVertices += domain == Unbounded;
  }
}
} // namespace sites

namespace
{
bool BuildSites(MeshSites& out,
  const MeshInput& in,
  MeshInput* release,
  DomainShape shape,
  double slack,
  std::string& error,
  const ParallelFor& parallelFor)
{
  out = MeshSites();
  sites::SiteBuilder builder(in, shape, slack, parallelFor, out);
  if (!builder.MergePoints(error))
  {
    return false;
  }
  if (builder.Empty())
  {
    return true;
  }
  if (!builder.CollectFacesAndEdges(error, release))
  {
    return false;
  }
  builder.VertexNormals();
  if (!builder.GroupEdges(error))
  {
    return false;
  }
  builder.ClassifyVertices();
  builder.Finish();
  builder.CountDomains();
  return true;
}
} // namespace

bool MeshSites::Build(const MeshInput& in,
  DomainShape shape,
  double slack,
  std::string& error,
  const ParallelFor& parallelFor)
{
  return BuildSites(*this, in, nullptr, shape, slack, error, parallelFor);
}

bool MeshSites::Build(MeshInput&& in,
  DomainShape shape,
  double slack,
  std::string& error,
  const ParallelFor& parallelFor)
{
  return BuildSites(*this, in, &in, shape, slack, error, parallelFor);
}

int64_t MeshSites::CellOf(int64_t s) const
{
  const int64_t faces = this->NumFaces(), edges = this->NumEdges();
  return s < faces
    ? this->FaceCells[s]
    : (s < faces + edges ? this->EdgeCells[s - faces] : this->VertexCells[s - faces - edges]);
}

/// The unit normal of face f, as the build computed it.
void MeshSites::FaceNormal(int64_t f, double normal[3]) const
{
  const auto& c = this->FaceCorners[f];
  const sites::Vec e1 = sites::Sub(this->X(c[1]), this->X(c[0]));
  const sites::Vec e2 = sites::Sub(this->X(c[2]), this->X(c[0]));
  const sites::Vec n = sites::Cross(e1, e2);
  const double scale = 1.0 / sites::Norm(n);
  for (int a = 0; a < 3; ++a)
  {
    normal[a] = n[a] * scale;
  }
}

/// The unit tangent of edge e, from its first end to its second.
void MeshSites::EdgeTangent(int64_t e, double tangent[3]) const
{
  const sites::Vec t = sites::Sub(this->X(this->EdgeEnds[e][1]), this->X(this->EdgeEnds[e][0]));
  const double scale = 1.0 / sites::Norm(t);
  for (int a = 0; a < 3; ++a)
  {
    tangent[a] = t[a] * scale;
  }
}

/// Whether edge e's domain is bounded by its faces too (a wedge), or only by its ends.
bool MeshSites::Wedge(int64_t e) const
{
  return this->Shape == DomainShape::Auto ||
    (this->Shape == DomainShape::Manifold &&
      this->EdgeFaceStart[e + 1] - this->EdgeFaceStart[e] == 2);
}

/// The plane through `through` with normal n, relative to the site's anchor. The offset
/// is computed from the rounded normal, so the stored plane still passes through it.
void MeshSites::SetPlane(HalfSpace& h,
  const double n[3],
  const double* through,
  const double* anchor) const
{
  for (int a = 0; a < 3; ++a)
  {
    h.N[a] = static_cast<float>(n[a]);
  }
  h.D = static_cast<float>(-(h.N[0] * (through[0] - anchor[0]) + h.N[1] * (through[1] - anchor[1]) +
                             h.N[2] * (through[2] - anchor[2])) +
    this->Slack);
}

namespace
{
/// Starts a site's box at its anchor.
/// The corner of face `corners` that is neither a nor b.
uint32_t ThirdCorner(const std::array<uint32_t, 3>& corners, uint32_t a, uint32_t b)
{
  uint32_t c = corners[0];
  for (int k = 0; k < 3; ++k)
  {
    if (corners[k] != a && corners[k] != b)
    {
      c = corners[k];
    }
  }
  return c;
}
} // namespace

void MeshSites::CornerBounds(int64_t s, double lo[3], double hi[3]) const
{
  const int64_t faces = this->NumFaces(), edges = this->NumEdges();
  uint32_t points[3] = { 0, 0, 0 };
  int count = 1;
  if (s < faces)
  {
    std::copy(this->FaceCorners[s].begin(), this->FaceCorners[s].end(), points);
    count = 3;
  }
  else if (s < faces + edges)
  {
    std::copy(this->EdgeEnds[s - faces].begin(), this->EdgeEnds[s - faces].end(), points);
    count = 2;
  }
  else
  {
    points[0] = static_cast<uint32_t>(s - faces - edges);
  }
  for (int a = 0; a < 3; ++a)
  {
    lo[a] = hi[a] = this->X(points[0])[a];
    for (int k = 1; k < count; ++k)
    {
      lo[a] = std::min(lo[a], this->X(points[k])[a]);
      hi[a] = std::max(hi[a], this->X(points[k])[a]);
    }
  }
}

void MeshSites::BoxOf(int64_t s, float lo[3], float hi[3]) const
{
  // The corners' bounds in double, rounded once: the rounding is monotonic, so this is
  // the box of the rounded corners.
  double dlo[3], dhi[3];
  this->CornerBounds(s, dlo, dhi);
  for (int a = 0; a < 3; ++a)
  {
    lo[a] = FloatBelow(dlo[a]);
    hi[a] = FloatAbove(dhi[a]);
  }
}

// Faces: the triangle prism (three planes through the edges, orthogonal to the
// triangle), required for the plane-distance formula to be exact.
// Edges: the slab between the end planes (required), then one plane per incident face:
// a point on the face side of that plane is closer to the face.
// Vertices: the planes orthogonal to their edges (Polar), or the four sides of Theorem
// 1's pyramid (Pyramid), or none.
void MeshSites::Describe(int64_t s, Site& site, bool box, bool normal) const
{
  // Every field set once, in its branch (no zeroing of the whole site first: samples
  // describe their sites millions of times).
  const int64_t faces = this->NumFaces(), edges = this->NumEdges();
  if (s < faces)
  {
    const auto& c = this->FaceCorners[s];
    site.Type = FaceSite;
    site.CellId = this->FaceCells[s];
    std::copy(this->X(c[0]), this->X(c[0]) + 3, site.Anchor);
    this->FaceNormal(s, site.Axis);
    for (int a = 0; a < 3; ++a)
    {
      site.Normal[a] = static_cast<float>(site.Axis[a] * this->Orientation);
    }
    site.Required = 3;
    site.PlaneCount = 3;
  }
  else if (s < faces + edges)
  {
    const int64_t e = s - faces;
    site.Type = EdgeSite;
    site.CellId = this->EdgeCells[e];
    std::copy(this->X(this->EdgeEnds[e][0]), this->X(this->EdgeEnds[e][0]) + 3, site.Anchor);
    this->EdgeTangent(e, site.Axis);
    // The pseudonormal: the sum of the faces' normals.
    sites::Vec pseudo{ 0, 0, 0 };
    for (uint32_t i = this->EdgeFaceStart[e]; normal && i < this->EdgeFaceStart[e + 1]; ++i)
    {
      sites::Vec n;
      this->FaceNormal(this->EdgeFaces[i], n.data());
      pseudo = sites::Add(pseudo, sites::Scale(n, this->Orientation));
    }
    for (int a = 0; a < 3; ++a)
    {
      site.Normal[a] = static_cast<float>(pseudo[a]);
    }
    site.Required = 2;
    site.PlaneCount = 2 +
      (this->Wedge(e) ? static_cast<int>(this->EdgeFaceStart[e + 1] - this->EdgeFaceStart[e]) : 0);
  }
  else
  {
    const int64_t v = s - faces - edges;
    site.Type = VertexSite;
    site.CellId = this->VertexCells[v];
    std::copy(this->X(v), this->X(v) + 3, site.Anchor);
    std::fill(site.Axis, site.Axis + 3, 0.0);
    site.Required = 0;
    std::copy(this->VertexNormals[v].begin(), this->VertexNormals[v].end(), site.Normal);
    site.PlaneCount = this->VertexDomains[v] == sites::Polar
      ? static_cast<int>(this->VertexEdgeStart[v + 1] - this->VertexEdgeStart[v])
      : (this->VertexDomains[v] == sites::Pyramid ? 4 : 0);
  }
  if (box)
  {
    this->BoxOf(s, site.BoundsMin, site.BoundsMax);
  }
  else
  {
    std::fill(site.BoundsMin, site.BoundsMin + 3, 0.0f);
    std::fill(site.BoundsMax, site.BoundsMax + 3, 0.0f);
  }
}

int MeshSites::Planes(int64_t s, const Site& site, HalfSpace* out, int capacity) const
{
  const int count = std::min(site.PlaneCount, capacity);
  const int64_t faces = this->NumFaces(), edges = this->NumEdges();
  if (s < faces)
  {
    const auto& c = this->FaceCorners[s];
    for (int k = 0; k < count; ++k)
    {
      const double* a = this->X(c[k]);
      const sites::Vec e = sites::Sub(this->X(c[(k + 1) % 3]), a);
      sites::Vec m = sites::Cross({ site.Axis[0], site.Axis[1], site.Axis[2] }, e);
      m = sites::Scale(m, 1.0 / sites::Norm(m));
      if (sites::Dot(m, sites::Sub(this->X(c[(k + 2) % 3]), a)) < 0)
      {
        m = sites::Scale(m, -1.0);
      }
      this->SetPlane(out[k], m.data(), a, site.Anchor);
    }
  }
  else if (s < faces + edges)
  {
    const int64_t e = s - faces;
    const uint32_t a = this->EdgeEnds[e][0], b = this->EdgeEnds[e][1];
    const double* t = site.Axis;
    const double back[3] = { -t[0], -t[1], -t[2] };
    const HalfSpace* end = out + count;
    HalfSpace* at = out;
    if (at < end)
    {
      this->SetPlane(*at++, t, this->X(a), site.Anchor);
    }
    if (at < end)
    {
      this->SetPlane(*at++, back, this->X(b), site.Anchor);
    }
    for (uint32_t i = this->EdgeFaceStart[e]; at < end && i < this->EdgeFaceStart[e + 1]; ++i)
    {
      const uint32_t c = ThirdCorner(this->FaceCorners[this->EdgeFaces[i]], a, b);
      const sites::Vec ac = sites::Sub(this->X(c), this->X(a));
      const sites::Vec tv{ t[0], t[1], t[2] };
      sites::Vec m = sites::Sub(ac.data(), sites::Scale(tv, sites::Dot(ac, tv)).data());
      m = sites::Scale(m, -1.0 / sites::Norm(m));
      this->SetPlane(*at++, m.data(), this->X(a), site.Anchor);
    }
  }
  else
  {
    const int64_t v = s - faces - edges;
    if (this->VertexDomains[v] == sites::Polar)
    {
      // (x - p) . u <= 0 for every edge direction u away from the vertex.
      for (int k = 0; k < count; ++k)
      {
        const uint32_t e = this->VertexEdges[this->VertexEdgeStart[v] + k];
        double u[3];
        this->EdgeTangent(e, u);
        const double sign = this->EdgeEnds[e][0] == v ? -1.0 : 1.0;
        const double n[3] = { u[0] * sign, u[1] * sign, u[2] * sign };
        this->SetPlane(out[k], n, this->X(v), site.Anchor);
      }
    }
    else if (this->VertexDomains[v] == sites::Pyramid)
    {
      for (int k = 0; k < count; ++k)
      {
        const float* w = &this->PyramidSides[v][3 * k];
        const double n[3] = { w[0], w[1], w[2] };
        this->SetPlane(out[k], n, this->X(v), site.Anchor);
      }
    }
  }
  return count;
}

size_t MeshSites::Bytes() const
{
  auto bytes = [](const auto& v) { return v.capacity() * sizeof(v[0]); };
  return bytes(this->SitePoints) + bytes(this->FaceCorners) + bytes(this->FaceCells) +
    bytes(this->EdgeEnds) + bytes(this->EdgeCells) + bytes(this->EdgeFaceStart) +
    bytes(this->EdgeFaces) + bytes(this->VertexCells) + bytes(this->VertexNormals) +
    bytes(this->VertexDomains) + bytes(this->VertexEdgeStart) + bytes(this->VertexEdges) +
    bytes(this->PyramidSides);
}

} // namespace vtkdf
