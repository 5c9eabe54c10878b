#include "LinearFactor/MeshSites.h"

#include "Common/FloatBounds.h"
#include "LinearFactor/SiteBuilder.h"

namespace vtkdf
{
namespace sites
{
int SiteBuilder::EdgePlanes(int64_t e) const
{
  const bool wedge = this->Mode == DomainShape::Auto ||
    (this->Mode == DomainShape::Manifold && this->EdgeGroups[e].Faces == 2);
  return 2 + (wedge ? this->EdgeGroups[e].Faces : 0);
}

int SiteBuilder::VertexPlanes(int64_t v) const
{
  return this->Domain[v] == Polar
    ? static_cast<int>(this->VertexEdgeOffsets[v + 1] - this->VertexEdgeOffsets[v])
    : (this->Domain[v] == Pyramid ? 4 : 0);
}

/// The plane through `through` with normal n, relative to the site's anchor. The offset
/// is computed from the rounded normal, so the stored plane still passes through it.
void SiteBuilder::SetPlane(uint32_t at, const Vec& n, const double* through, const double* anchor)
{
  HalfSpace& h = this->Out.Planes[at];
  for (int a = 0; a < 3; ++a)
  {
    h.N[a] = static_cast<float>(n[a]);
  }
  h.D = static_cast<float>(-(h.N[0] * (through[0] - anchor[0]) + h.N[1] * (through[1] - anchor[1]) +
                             h.N[2] * (through[2] - anchor[2])) +
    this->Slack);
}

Site& SiteBuilder::InitSite(int64_t index, uint8_t type, int64_t cell, const double* anchor)
{
  Site& s = this->Out.Sites[index];
  s = Site{};
  s.Type = type;
  s.CellId = cell;
  s.PlaneBegin = this->PlaneBegin[index];
  s.PlaneCount = static_cast<uint16_t>(this->PlaneBegin[index + 1] - this->PlaneBegin[index]);
  for (int a = 0; a < 3; ++a)
  {
    s.Anchor[a] = anchor[a];
    s.BoundsMin[a] = FloatBelow(anchor[a]);
    s.BoundsMax[a] = FloatAbove(anchor[a]);
  }
  return s;
}

/// Grows a site's box to hold x.
void Grow(Site& s, const double* x)
{
  for (int a = 0; a < 3; ++a)
  {
    s.BoundsMin[a] = std::min(s.BoundsMin[a], FloatBelow(x[a]));
    s.BoundsMax[a] = std::max(s.BoundsMax[a], FloatAbove(x[a]));
  }
}

bool SiteBuilder::WriteSites(std::string& error)
{
  // Plane counts first, then every site and its planes written in place, in parallel.
  const int64_t numSites = this->NumFaces + this->NumEdges + this->NumVertices;
  this->PlaneBegin.assign(numSites + 1, 0);
  for (int64_t i = 0; i < numSites; ++i)
  {
    const int64_t count = i < this->NumFaces ? 3
      : i < this->NumFaces + this->NumEdges
      ? this->EdgePlanes(i - this->NumFaces)
      : this->VertexPlanes(i - this->NumFaces - this->NumEdges);
    const uint64_t next = uint64_t(this->PlaneBegin[i]) + count;
    if (next > UINT32_MAX)
    {
      error = "the mesh needs more than 2^32 domain planes";
      return false;
    }
    this->PlaneBegin[i + 1] = static_cast<uint32_t>(next);
  }
  this->Out.Sites.resize(numSites);
  this->Out.Planes.resize(this->PlaneBegin[numSites]);
  this->WriteFaceSites();
  this->WriteEdgeSites();
  this->WriteVertexSites();
  return true;
}

/// Face sites: the triangle prism (three planes through the edges, orthogonal to the
/// triangle), required for the plane-distance formula to be exact.
void SiteBuilder::WriteFaceSites()
{
  Run(this->For,
    this->NumFaces,
    1024,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t fi = begin; fi < end; ++fi)
      {
        const FaceRecord& f = this->Faces[fi];
        Site& s = this->InitSite(fi, FaceSite, f.Cell, this->X(f.P[0]));
        for (int k = 0; k < 3; ++k)
        {
          const double* a = this->X(f.P[k]);
          const Vec e = Sub(this->X(f.P[(k + 1) % 3]), a);
          Vec m = Cross(f.Normal, e);
          m = Scale(m, 1.0 / Norm(m));
          if (Dot(m, Sub(this->X(f.P[(k + 2) % 3]), a)) < 0)
          {
            m = Scale(m, -1.0);
          }
          this->SetPlane(s.PlaneBegin + k, m, a, s.Anchor);
          Grow(s, this->X(f.P[k]));
        }
        for (int a = 0; a < 3; ++a)
        {
          s.Axis[a] = f.Normal[a];
          s.Normal[a] = static_cast<float>(f.Normal[a] * this->Orientation);
        }
        s.Required = 3;
      }
    });
}

/// Edge sites: the slab between the end planes (required), then one plane per incident
/// face: a point on the face side of that plane is closer to the face.
void SiteBuilder::WriteEdgeSites()
{
  Run(this->For,
    this->NumEdges,
    1024,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t e = begin; e < end; ++e)
      {
        const int64_t a = this->EdgeEnds[e][0], b = this->EdgeEnds[e][1];
        const Vec& t = this->EdgeGroups[e].Tangent;
        Site& s =
          this->InitSite(this->NumFaces + e, EdgeSite, this->EdgeGroups[e].Cell, this->X(a));
        Grow(s, this->X(b));
        uint32_t at = s.PlaneBegin;
        this->SetPlane(at++, t, this->X(a), s.Anchor);
        this->SetPlane(at++, Scale(t, -1.0), this->X(b), s.Anchor);
        s.Required = 2;
        const bool wedge = s.PlaneCount > 2;
        Vec pseudo{ 0, 0, 0 };
        for (int i = 0; i < this->EdgeGroups[e].Faces; ++i)
        {
          const FaceRecord& f = this->Faces[this->EdgeFace(e, i)];
          pseudo = Add(pseudo, Scale(f.Normal, this->Orientation));
          if (wedge)
          {
            int64_t c = f.P[0];
            for (int k = 0; k < 3; ++k)
            {
              if (f.P[k] != a && f.P[k] != b)
              {
                c = f.P[k];
              }
            }
            const Vec ac = Sub(this->X(c), this->X(a));
            Vec m = Sub(ac.data(), Scale(t, Dot(ac, t)).data());
            m = Scale(m, -1.0 / Norm(m));
            this->SetPlane(at++, m, this->X(a), s.Anchor);
          }
        }
        for (int k = 0; k < 3; ++k)
        {
          s.Axis[k] = t[k];
          s.Normal[k] = static_cast<float>(pseudo[k]);
        }
      }
    });
}

void SiteBuilder::WriteVertexSites()
{
  Run(this->For,
    this->NumVertices,
    1024,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t v = begin; v < end; ++v)
      {
        Site& s = this->InitSite(this->NumFaces + this->NumEdges + v,
          VertexSite,
          this->VertexCell[v].load(std::memory_order_relaxed),
          this->X(v));
        s.Required = 0;
        for (int a = 0; a < 3; ++a)
        {
          s.Normal[a] = static_cast<float>(this->VertexNormal[v][a]);
        }
        uint32_t at = s.PlaneBegin;
        if (this->Domain[v] == Polar)
        {
          for (const auto& eu : this->IncidentEdges(v))
          {
            this->SetPlane(at++, Scale(this->Away(eu), -1.0), this->X(v), s.Anchor);
          }
        }
        else if (this->Domain[v] == Pyramid)
        {
          for (const Vec& w : this->PyramidSides[v])
          {
            this->SetPlane(at++, w, this->X(v), s.Anchor);
          }
        }
      }
    });
}

void SiteBuilder::CountDomains()
{
  DomainStatistics& statistics = this->Out.Statistics;
  statistics.Faces = this->NumFaces;
  statistics.Edges = this->NumEdges;
  statistics.Vertices = this->NumVertices;
  for (int64_t e = 0; e < this->NumEdges; ++e)
  {
    statistics.EdgeWedges += this->EdgePlanes(e) > 2;
  }
  for (int64_t v = 0; v < this->NumVertices; ++v)
  {
    statistics.PolarVertices += this->Domain[v] == Polar;
    statistics.PyramidVertices += this->Domain[v] == Pyramid;
    statistics.UnboundedVertices += this->Domain[v] == Unbounded;
  }
}
} // namespace sites

bool MeshSites::Build(const MeshInput& in,
  DomainShape shape,
  double slack,
  std::string& error,
  const ParallelFor& parallelFor)
{
  this->Sites.clear();
  this->Planes.clear();
  this->SitePoints.clear();
  this->Statistics = DomainStatistics();
  sites::SiteBuilder builder(in, shape, slack, parallelFor, *this);
  if (!builder.MergePoints(error))
  {
    return false;
  }
  if (builder.Empty())
  {
    return true;
  }
  builder.CollectFacesAndEdges();
  builder.VertexNormals();
  builder.GroupEdges();
  builder.ClassifyVertices();
  if (!builder.WriteSites(error))
  {
    return false;
  }
  builder.CountDomains();
  return true;
}

} // namespace vtkdf
