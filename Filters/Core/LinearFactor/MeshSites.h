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

enum SiteType : uint8_t
{
  VertexSite = 0,
  EdgeSite = 1,
  FaceSite = 2
};

/// n . (x - anchor) + d >= 0, with n unit, x in world coordinates, anchor the site's
/// Anchor, and the slack already added to d. Relative to the anchor, d is about the
/// size of the site, so float keeps it to 1e-7 of that; the float normal turns the plane
/// by at most 2^-23 rad about the anchor, which the slack covers (see Build). Float
/// halves the largest array of a fine mesh (10M planes for 871k triangles).
struct HalfSpace
{
  float N[3];
  float D;
};

struct Site
{
  uint8_t Type;
  uint8_t Required; // the first Required planes keep the distance formula valid
  uint16_t PlaneCount;
  uint32_t PlaneBegin;
  int64_t CellId;   // input cell reported as ClosestCellId
  double Anchor[3]; // a point of the site (vertex, edge start, triangle corner)
  double Axis[3];   // edge: unit tangent; face: unit normal; vertex: unused
  // Float is enough for these, and a smaller Site costs less memory traffic (a mesh
  // of 871k triangles has 2.6M sites):
  float Normal[3];                  // pseudonormal: only the sign of a dot product is used
  float BoundsMin[3], BoundsMax[3]; // rounded outward, so the box still holds the site
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

class MeshSites
{
public:
  /// Builds sites and domains. `slack` (world units) enlarges every domain so that
  /// neighbouring domains overlap despite rounding; a site's formula is then evaluated
  /// at most `slack` outside its exact region, which bounds the error by `slack`. The
  /// planes are stored in float (HalfSpace): where they are used up to a distance L
  /// from the mesh, the slack must exceed PlaneRounding * L as well (PlaneSlack).
  /// `parallelFor` (optional) runs the per-site passes in parallel; the result is the
  /// same either way.
  bool Build(const MeshInput& input,
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

  LargeVector<Site> Sites;
  LargeVector<HalfSpace> Planes;
  std::vector<double> SitePoints; // xyz of every point a cell uses (merged), for range culling
  double Bounds[6] = { 0, 0, 0, 0, 0, 0 };
  DomainStatistics Statistics;

  /// Distance vector from sample x to site s (closest point = x + vector), exact in
  /// double inside the site's domain.
  void DistanceVector(const Site& s, const double x[3], double out[3]) const
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
};

} // namespace vtkdf

#endif
