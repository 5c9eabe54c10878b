// PenetrationDepth: the penetration depth of two solids given as unions of convex pieces
// (Kim et al., JGT 2002, Algorithm 3.1), without VTK types.
//
// P and Q intersect when 0 is in P - Q = {p - q}, and translating Q by t separates them
// (up to touching) exactly when t is outside the interior of P - Q: the penetration depth
// is the distance from the origin to the boundary of P - Q, and the translation is the
// closest boundary point. For P = union of P_i and Q = union of Q_j, P - Q is the union of
// the convex sums P_i - Q_j, each the convex hull (qhull) of its corners' differences, so
// the answer is UnionClosestPoint's query at the origin. When P and Q do not intersect,
// the same query gives their separation distance, and the translation that brings Q into
// contact.
//
// Pairs whose sums cannot reach the answer are skipped before their hulls are built: any
// bound U of the answer (the distance from the origin to the boundary of the box holding
// every sum when the origin is inside the union; else the farthest corner of a sum's box)
// makes a sum whose box lies farther than U irrelevant, as it cannot meet the ball of
// radius U around the origin, where the boundary point lies.
#ifndef vtkdf_PenetrationDepth_h
#define vtkdf_PenetrationDepth_h

#include "Common/Parallel.h"
#include "Union/UnionClosestPoint.h"
#include "Union/UnionClosestPointGPU.h"

#include <cstdint>
#include <string>
#include <vector>

namespace vtkdf
{

struct PenetrationAnswer
{
  bool Intersecting = false;
  /// The distance from the origin to the boundary of P - Q: the penetration depth when
  /// intersecting, the separation distance otherwise.
  double Distance = 0;
  /// The translation of Q: to separate (intersecting) or to touch (not intersecting).
  double Translation[3] = { 0, 0, 0 };
  /// The pair (i of P, j of Q) whose sum holds the closest boundary point.
  int64_t PieceP = -1, PieceQ = -1;
  int64_t PairsTotal = 0, PairsKept = 0;
  int64_t FacesVisited = 0;
  /// The GPU's upper bound of Distance, which the exact search started from (HUGE_VAL
  /// on the CPU, or when the GPU found none).
  double Estimate = HUGE_VAL;
};

class PenetrationDepth
{
public:
  /// Tolerance (absolute) for the sums' convexity and for what touches.
  double Tolerance = 1e-9;
  /// The parallel loop over pairs for their hulls (serial when empty).
  ParallelFor For;
  /// A distributed run's share: BuildSums builds the hulls of block `Share` of `Shares`
  /// consecutive blocks of the kept pairs only (every share agrees on which are kept).
  int Share = 0, Shares = 1;

  /// The sums P_i - Q_j that can matter (this share's, when Shares > 1), as pieces of a
  /// union, with their pairs; the query origin is `origin` (O_Q - O_P; the origin when P
  /// and Q share a frame). False and `error` when a sum has no three-dimensional hull
  /// (cannot happen for three-dimensional pieces) or qhull fails; then `pairs` ends with
  /// the pair that failed.
  bool BuildSums(const std::vector<ConvexPiece>& p,
    const std::vector<ConvexPiece>& q,
    const double origin[3],
    UnionClosestPoint& sums,
    std::vector<std::pair<int64_t, int64_t>>& pairs,
    int64_t& total,
    std::string& error) const;

  /// The answer for P and Q (convex pieces each), from `origin`: on the CPU, or with `gl`
  /// with the GPU's bound (QueryUnionGPU with `settings`): the same answer.
  bool Compute(const std::vector<ConvexPiece>& p,
    const std::vector<ConvexPiece>& q,
    const double origin[3],
    PenetrationAnswer& answer,
    std::string& error,
    HeadlessGL* gl = nullptr,
    const UnionGPUSettings& settings = UnionGPUSettings()) const;

  /// The answer from sums already built (every share's, in share order), as Compute
  /// gives it; `total` is BuildSums' count of pairs. Sets the sums' Tolerance and For.
  bool Query(UnionClosestPoint& sums,
    const std::vector<std::pair<int64_t, int64_t>>& pairs,
    int64_t total,
    const double origin[3],
    PenetrationAnswer& answer,
    std::string& error,
    HeadlessGL* gl = nullptr,
    const UnionGPUSettings& settings = UnionGPUSettings()) const;
};

/// One share's sums as doubles, for a distributed run to gather: its pairs and pieces
/// (faces, planes, box, inner ball), every value exact; `built` false packs the failure
/// (the last pair, the one whose hull failed).
std::vector<double> PackSums(bool built,
  const std::vector<ConvexPiece>& sums,
  const std::vector<std::pair<int64_t, int64_t>>& pairs);

/// Appends the `shares` shares packed one after another in `data` to `sums` and
/// `pairs`, in order; false and `error` when a share packed a failure (named by its pair
/// and share) or the data are not `shares` such shares.
bool UnpackSums(const double* data,
  size_t size,
  int shares,
  std::vector<ConvexPiece>& sums,
  std::vector<std::pair<int64_t, int64_t>>& pairs,
  std::string& error);

} // namespace vtkdf

#endif
