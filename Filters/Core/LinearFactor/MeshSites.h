// MeshSites: a polygon mesh decomposed into the sites of Sud et al. (I3D 2006) (vertices, edges,
// triangles), each with the convex domain that bounds its Voronoi region.
//
// Every domain is an intersection of half-spaces. On a slice it becomes the convex
// polygon that the GPU rasterizes and the CPU scan-converts (SliceDomain.h). Inside its
// domain a site's distance vector is an affine function of the sample position
// (linear factorization), so interpolating it across the polygon is exact.
#ifndef vtkdf_MeshSites_h
#define vtkdf_MeshSites_h

#include "Common/LargeVector.h"
#include "Common/MeshInput.h"
#include "Common/Parallel.h"
#include "LinearFactor/LinearFactorField.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace vtkdf
{
namespace sites
{
class SiteBuilder;
}

enum SiteType : uint8_t
{
  VertexSite = 0,
  EdgeSite = 1,
  FaceSite = 2
};

/// n . (x - anchor) + d >= 0, with n unit, x in world coordinates, anchor the site's
/// Anchor, and the slack already added to d. Relative to the anchor, d is about the
/// size of the site, so float keeps it to 1e-7 of that; the float normal turns the plane
/// by at most 2^-23 rad about the anchor, which the slack covers (see Build). The GPU
/// reads the same float planes.
struct HalfSpace
{
  float N[3];
  float D;
};

/// A site as the scan and Finalize read it, derived from the mesh on demand
/// (MeshSites::Describe); its planes come separately (MeshSites::Planes).
struct Site
{
  uint8_t Type = VertexSite;
  uint8_t Required = 0; // the first Required planes keep the distance formula valid
  int PlaneCount = 0;
  int64_t CellId = -1;              // input cell reported as ClosestCellId
  double Anchor[3] = { 0, 0, 0 };   // a point of the site (vertex, edge start, triangle corner)
  double Axis[3] = { 0, 0, 0 };     // edge: unit tangent; face: unit normal; vertex: unused
  float Normal[3] = { 0, 0, 0 };    // pseudonormal: only the sign of a dot product is used
  float BoundsMin[3] = { 0, 0, 0 }; // the site's box, rounded outward to float
  float BoundsMax[3] = { 0, 0, 0 };
};

/// How many sites got which kind of domain (reported, and checked by the tests).
struct DomainStatistics
{
  int64_t Faces = 0, Edges = 0, Vertices = 0;
  int64_t EdgeWedges = 0;        // edges bounded by incident faces
  int64_t PolarVertices = 0;     // vertices bounded by planes orthogonal to their edges
  int64_t PyramidVertices = 0;   // hyperbolic vertices bounded by Theorem 1's pyramid
  int64_t UnboundedVertices = 0; // vertices whose domain is the whole space
  int64_t DegenerateFaces = 0, DegenerateEdges = 0, MergedPoints = 0;
};

/// The sites of a mesh in a compact form: the merged points, the faces, the edges and
/// the vertices with the indices that tie them together (about 100 bytes a triangle).
/// A site's domain is derived from them when the scan needs it (Describe, Planes), not
/// stored: a fine mesh has ten planes a triangle, and most of them would be written once
/// to fresh memory and read once. Sites are numbered faces first, then edges, then
/// vertices; ties between equally near sites go to the lower number.
class MeshSites
{
public:
  /// Builds sites and domains. `slack` (world units) enlarges every domain so that
  /// neighbouring domains overlap despite rounding; a site's formula is then evaluated
  /// at most `slack` outside its exact region, which bounds the error by `slack`. The
  /// planes are rounded to float (HalfSpace): where they are used up to a distance L
  /// from the mesh, the slack must exceed PlaneRounding * L as well (PlaneSlack).
  /// `parallelFor` (optional) runs the per-site passes in parallel; the result is the
  /// same either way.
  bool Build(const MeshInput& input,
    DomainShape shape,
    double slack,
    std::string& error,
    const ParallelFor& parallelFor = ParallelFor());
  /// The same for a caller that no longer needs the mesh: its arrays are released as
  /// soon as the build has read them (before its own peak).
  bool Build(MeshInput&& input,
    DomainShape shape,
    double slack,
    std::string& error,
    const ParallelFor& parallelFor = ParallelFor());

  /// How far a stored plane may be from the exact one, per unit of distance from the
  /// site's anchor: the float normal's rounding (2^-24 per component), for each of the
  /// two neighbours that share a boundary, with a margin.
  static constexpr double PlaneRounding = 4.0 / (1 << 24);
  /// The slack that keeps neighbouring domains overlapping wherever the planes are used
  /// within `reach` of the mesh: `base` plus what the float planes' rounding needs.
  static double PlaneSlack(double base, double reach) { return base + PlaneRounding * reach; }

  /// How many sites: faces, edges and vertices.
  int64_t Count() const { return this->NumFaces() + this->NumEdges() + this->NumVertices(); }
  bool Empty() const { return this->Count() == 0; }
  int64_t NumFaces() const { return static_cast<int64_t>(this->FaceCells.size()); }
  int64_t NumEdges() const { return static_cast<int64_t>(this->EdgeCells.size()); }
  int64_t NumVertices() const { return static_cast<int64_t>(this->VertexCells.size()); }
  SiteType TypeOf(int64_t s) const
  {
    return s < this->NumFaces() ? FaceSite
                                : (s < this->NumFaces() + this->NumEdges() ? EdgeSite : VertexSite);
  }
  /// The input cell a site reports as its ClosestCellId.
  int64_t CellOf(int64_t s) const;
  /// The point a site's planes are relative to (a corner of the site).
  const double* AnchorOf(int64_t s) const { return this->X(this->AnchorPointOf(s)); }
  /// That point's index in SitePoints (xyz at 3 times it).
  int64_t AnchorPointOf(int64_t s) const
  {
    const int64_t faces = this->NumFaces(), edges = this->NumEdges();
    return s < faces ? this->FaceCorners[s][0]
                     : (s < faces + edges ? this->EdgeEnds[s - faces][0] : s - faces - edges);
  }
  /// The box of site `s`, rounded outward to float (Site::BoundsMin, BoundsMax).
  void BoxOf(int64_t s, float lo[3], float hi[3]) const;
  /// The box of site `s`'s corners in double (BoxOf before its rounding).
  void CornerBounds(int64_t s, double lo[3], double hi[3]) const;
  /// The site `s` without its planes; without its box (`box` false: Site's bounds left
  /// 0) or an edge's pseudonormal (`normal` false: left 0) where the caller needs only
  /// its distance.
  void Describe(int64_t s, Site& site, bool box = true, bool normal = true) const;
  /// The planes of site `s` (described by `site`): at most `capacity` of them (optional
  /// planes beyond that are dropped, which only enlarges the domain); returns how many.
  int Planes(int64_t s, const Site& site, HalfSpace* out, int capacity) const;
  /// The bytes the sites hold.
  size_t Bytes() const;

  std::vector<double> SitePoints; // xyz of every point a cell uses (merged), for range culling
  double Bounds[6] = { 0, 0, 0, 0, 0, 0 };
  DomainStatistics Statistics;

  /// Distance vector from sample x to site s (closest point = x + vector), exact in
  /// double inside the site's domain.
  static void DistanceVector(const Site& s, const double x[3], double out[3])
  {
    double r[3] = { s.Anchor[0] - x[0], s.Anchor[1] - x[1], s.Anchor[2] - x[2] };
    if (s.Type != VertexSite)
    {
      const double along = r[0] * s.Axis[0] + r[1] * s.Axis[1] + r[2] * s.Axis[2];
      for (int a = 0; a < 3; ++a)
      {
        // edge: remove the part along the tangent; face: keep the part along the normal
        r[a] = s.Type == EdgeSite ? r[a] - along * s.Axis[a] : along * s.Axis[a];
      }
    }
    out[0] = r[0];
    out[1] = r[1];
    out[2] = r[2];
  }

private:
  friend class sites::SiteBuilder;
  const double* X(int64_t point) const { return this->SitePoints.data() + 3 * point; }
  void FaceNormal(int64_t f, double normal[3]) const;
  void EdgeTangent(int64_t e, double tangent[3]) const;
  bool Wedge(int64_t e) const;
  void SetPlane(HalfSpace& h, const double n[3], const double* through, const double* anchor) const;

  DomainShape Shape = DomainShape::Auto;
  double Slack = 0;
  double Orientation = 1; // -1 when the faces' signed volume is negative
  // Faces: merged corners, input cell.
  LargeVector<std::array<uint32_t, 3>> FaceCorners;
  LargeVector<int64_t> FaceCells;
  // Edges: merged ends (first < second), smallest input cell, incident faces (ascending).
  LargeVector<std::array<uint32_t, 2>> EdgeEnds;
  LargeVector<int64_t> EdgeCells;
  LargeVector<uint32_t> EdgeFaceStart, EdgeFaces;
  // Vertices: smallest input cell, pseudonormal, domain kind, incident edges (ascending),
  // the sides of the pyramid vertices' domains (DomainShape::Manifold only).
  LargeVector<int64_t> VertexCells;
  LargeVector<std::array<float, 3>> VertexNormals;
  std::vector<uint8_t> VertexDomains;
  LargeVector<uint32_t> VertexEdgeStart, VertexEdges;
  std::vector<std::array<float, 12>> PyramidSides;
};

} // namespace vtkdf

#endif
