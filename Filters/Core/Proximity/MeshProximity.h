// MeshProximity: whether two triangle meshes collide, and how far apart they are when they
// do not, decided exactly and independently of any grid, without VTK types. The part of
// Sud et al.'s proximity queries between deformable models ("Interactive 3D distance
// field computation using linear factorization", ACM I3D 2006, section 6.2) that a grid
// cannot settle: contacts smaller than a voxel, and separations larger than the region
// the fields cover.
//
// - Colliding: some pair of triangles has a point in common (orientation predicates,
//   Segment/TriangleCrossings.h: touching and coplanar contact count), or, with none, a
//   model lies inside the other (a vertex of one inside the other by the winding number,
//   Winding/WindingNumber.h: a model wholly inside the other has no intersecting pair).
//   Candidate pairs are those whose boxes meet (a bounding-volume hierarchy over each
//   model, Common/TriangleBoxTree.h).
// - Separation: the smallest distance between the two surfaces and a pair of closest
//   points, from every pair of triangles that a lower bound (the distance of the
//   hierarchies' boxes) does not exclude, nearest pairs of nodes first. Between two
//   triangles that do not intersect it is the least of the six corner-to-triangle and
//   nine edge-to-edge distances, in double precision.
// - Penetration: the largest distance to B's surface over A's surface samples inside B
//   (a barycentric lattice on each triangle, corners included: FaceSamples), each at its
//   exact distance (the nearest triangle through B's hierarchy), with the deepest sample
//   and the direction to its closest point on B: the paper's penetration estimate.
#ifndef vtkdf_MeshProximity_h
#define vtkdf_MeshProximity_h

#include "Common/MeshInput.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace vtkdf
{
struct ProximityOptions
{
  /// Whether a model inside the other (no surface contact) counts as colliding.
  bool Containment = true;
  /// The separation is searched only when the models do not collide.
  bool Separation = true;
  /// A known upper bound of the separation (e.g. from a distance field), HUGE_VAL for
  /// none: it only prunes the search; when it is below the true separation, the result is
  /// still exact.
  double UpperBound = HUGE_VAL;
};

struct ProximityResult
{
  bool Colliding = false;
  /// A pair of triangles (indices into each mesh's Triangles / 3) with a point in
  /// common, -1 when the models collide by containment only or do not collide.
  int64_t ContactA = -1, ContactB = -1;
  bool AInsideB = false, BInsideA = false;

  /// When the models do not collide: the separation, the closest points (on A, on B) and
  /// their triangles.
  double Separation = HUGE_VAL;
  std::array<double, 3> ClosestA{ { 0, 0, 0 } }, ClosestB{ { 0, 0, 0 } };
  int64_t ClosestTriangleA = -1, ClosestTriangleB = -1;

  /// Work done: triangle pairs tested for contact, and for distance.
  int64_t ContactTests = 0, DistanceTests = 0;
};

/// Decides the proximity of meshes a and b (their Triangles; Segments and Vertices are
/// not part of a model's surface here). False with `error` when either has no triangle
/// or a coordinate that is not finite.
bool ComputeMeshProximity(const MeshInput& a,
  const MeshInput& b,
  const ProximityOptions& options,
  ProximityResult& result,
  std::string& error);

/// The points of a triangle's lattice with `step`: with L its longest edge and
/// n = max(1, ceil(L / step)), the points p0 + (i / n)(p1 - p0) + (j / n)(p2 - p0) for
/// i, j >= 0 and i + j <= n (the corners included), in that order of i, then j.
std::vector<std::array<double, 3>> FaceSamples(const double p[9], double step);

struct PenetrationResult
{
  /// The largest distance to B's surface over A's samples inside B, 0 when none is.
  double Depth = 0;
  /// The deepest sample of A, its closest point on B and that point's triangle of B
  /// (-1 when no sample is inside).
  std::array<double, 3> Deepest{ { 0, 0, 0 } }, ClosestOnB{ { 0, 0, 0 } };
  int64_t TriangleB = -1;
  int64_t Samples = 0, SamplesInside = 0;
};

/// The penetration of a into b: FaceSamples(step) of each of a's triangles (step > 0;
/// the corners among them) inside b by b's winding number (|w| > 1/2), at their exact distances to
/// b's triangles. False with `error` on invalid meshes (as ComputeMeshProximity) or step.
bool ComputePenetration(const MeshInput& a,
  const MeshInput& b,
  double step,
  PenetrationResult& result,
  std::string& error);

/// Squared distance between the closed triangles p and q (9 coordinates each) when they
/// do not intersect, with the closest points; the least of the corner-to-triangle and
/// edge-to-edge distances (for intersecting triangles it is not 0: test that first).
double SquaredTriangleDistance(const double p[9], const double q[9], double onP[3], double onQ[3]);
} // namespace vtkdf

#endif
