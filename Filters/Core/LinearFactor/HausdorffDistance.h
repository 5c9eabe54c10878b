// HausdorffDistance: the Hausdorff distance between two polygon meshes, certified to a
// requested accuracy, without VTK types.
//
// The one-sided distance from A to B is the largest, over every point of A's triangles,
// segments and vertices (their interiors too, not only the vertices), of the exact
// distance to B. It lies in an interval [Lower, Upper]:
//   - Lower is the distance at a point of A whose distance was computed exactly: A's
//     vertices first, then the midpoints of the sub-triangles below;
//   - Upper bounds every point of A: for a triangle T of A and a primitive t of B, the
//     distance to t is a convex function, so over T it is largest at a corner, and every
//     point of T is within U(T) = min over t of (max over T's corners of |corner - t|) of
//     B. A triangle whose U(T) exceeds Lower + the requested error is cut into four at
//     its edges' midpoints (a segment into two), each half as wide, until every piece's
//     U is within it (Tang, Lee and Kim, "Interactive Hausdorff distance computation for
//     general polygonal models", ACM Transactions on Graphics 28(3), 2009, bound the
//     distance of a triangle the same way; so does CGAL's bounded-error Hausdorff).
// U(T) is found by the nearest-primitive tree of B (QueryTree::NearestToAll), first
// among the primitives nearest to T's corners, then by a search that stops as soon as a
// primitive is within the requested error. The pieces are refined a round at a time,
// every piece of a round against the Lower of the rounds before it, so the result does
// not depend on the number of threads.
//
// The distances are computed in double precision in a frame scaled by a power of two
// (exact); both ends of the interval are widened by the rounding that computation can
// make (a thousand times the unit roundoff of the coordinates' magnitude), so a
// tolerance below that is refused.
#ifndef vtkdf_HausdorffDistance_h
#define vtkdf_HausdorffDistance_h

#include "Common/MeshInput.h"
#include "Common/Parallel.h"

#include <cstdint>
#include <string>

namespace vtkdf
{

/// One direction's answer, in world units.
struct OneSidedHausdorff
{
  /// The largest distance found at a point, and the certified interval around it.
  double Distance = 0;
  double Lower = 0, Upper = 0;
  /// The point of the source mesh where Distance was found, and its closest point on the
  /// target.
  double From[3] = { 0, 0, 0 };
  double To[3] = { 0, 0, 0 };
  int64_t Pieces = 0;      // sub-triangles and sub-segments refined
  int64_t Rounds = 0;      // rounds of refinement
  int64_t Evaluations = 0; // primitive distances computed
};

struct HausdorffResult
{
  OneSidedHausdorff AToB, BToA;
  /// The symmetric distance's interval: the larger of the two one-sided ones.
  double Lower = 0, Upper = 0;
  /// The diagonal of the box of both meshes' used points, and the requested
  /// Upper - Lower (RelativeError times that diagonal).
  double Diagonal = 0, Tolerance = 0;
  bool Aborted = false;
};

struct HausdorffOptions
{
  double RelativeError = 1e-6;
  /// When set, each of the meshes' points' distance to the other mesh (all points, also
  /// those no cell uses), in the order of their Points.
  double* DistanceA = nullptr;
  double* DistanceB = nullptr;
};

/// The Hausdorff distance between meshes a and b (both ways). False and `error` when a
/// mesh has no cell, a cell refers to a point that does not exist, a used point is not
/// finite, or the requested error is below what double precision resolves at the
/// meshes' coordinates. Progress and abort between rounds.
bool ComputeHausdorffDistance(MeshInput a,
  MeshInput b,
  const HausdorffOptions& options,
  const Execution& execution,
  HausdorffResult& result,
  std::string& error);

} // namespace vtkdf

#endif
