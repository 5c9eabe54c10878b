// UnionClosestPoint: the exact closest point to a point O on the boundary of a union of
// convex polytopes (Kim et al.'s query, on the CPU in double precision), without building
// the union and without VTK types.
//
// The boundary of M = union of M_i lies on the pieces' faces. A point x of face f (of
// piece i, outward normal n) is on it unless the union continues beyond x: unless some
// other piece j holds x + e n for small e > 0. On f's plane those points form a convex
// polygon S_j (M_j's section, where a plane of M_j that faces like n counts only strictly
// inside, so a piece touching f from inside does not cover it, and one sharing the face
// from outside does: two unit cubes side by side give 0.5 from (0.9, 0.5,
// 0.5), not 0.1). So the boundary part of f is R_f = f minus the union of the S_j, and
// the answer is the nearest point of all R_f. On a face's plane the nearest point of R_f
// to O's projection P is P itself when no S_j holds it, else it lies on the boundary of
// R_f: on an edge of f where no S_j covers the face's side of it, or on an edge of some
// S_j (inside f) where no other S_k covers its outer side; each such edge loses an
// interval to each covering polygon, and the nearest point of what is left is a clamp.
// Faces are visited in the order of their distance from O and the search stops at the
// first face farther than the best point found. A tolerance (Tolerance, absolute) decides
// what touches.
#ifndef vtkdf_UnionClosestPoint_h
#define vtkdf_UnionClosestPoint_h

#include "Common/Parallel.h"

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace vtkdf
{

/// One convex polytope: its faces as convex polygons (corners counter-clockwise seen from
/// outside) and, per face, the outward unit normal and offset (inside: n . x <= d).
struct ConvexPiece
{
  std::vector<std::vector<double>> Faces; // xyz of each face's corners
  std::vector<double> Planes;             // nx ny nz d per face
  double Lo[3] = { 0, 0, 0 }, Hi[3] = { 0, 0, 0 };
  /// A ball inside the piece: its corners' centroid and the distance to the nearest face
  /// plane (a quick test that a face lies inside the piece).
  double Centre[3] = { 0, 0, 0 };
  double InnerRadius = 0;

  /// From points and faces (point ids per face, any orientation): orients each face
  /// outward, computes planes and bounds; false and `error` when the piece is not
  /// convex (a corner outside a face's plane by more than `tolerance`), is open (an edge
  /// not used by exactly two faces), or is flat.
  bool Build(const std::vector<double>& points,
    const std::vector<std::vector<int64_t>>& faces,
    double tolerance,
    std::string& error);

  /// The distinct corners (xyz triples, sorted).
  std::vector<double> Corners() const;
};

/// Merges the corners of a piece's `faces` that lie within `tolerance` of each other
/// (exported hulls repeat points a rounding apart: an STL file does not share them), each
/// into the lowest id of its cluster, and drops the faces left with fewer than three
/// distinct corners (the zero-area slivers between repeated points). Faces
/// keep their order; a face's consecutive repeats become one corner. Returns how many
/// points were merged into another.
int64_t MergeNearCorners(const std::vector<double>& points,
  std::vector<std::vector<int64_t>>& faces,
  double tolerance);

struct UnionAnswer
{
  double Distance = 0; // to the boundary: negative inside the union
  double Closest[3] = { 0, 0, 0 };
  int64_t Piece = -1; // the piece whose face holds the closest point
  bool Inside = false;
  int64_t FacesVisited = 0;
};

class UnionClosestPoint
{
public:
  std::vector<ConvexPiece> Pieces;
  double Tolerance = 1e-9;
  /// A parallel loop over a query's faces (serial when empty: the caller may already run
  /// queries in parallel).
  ParallelFor For;

  /// The closest point on the union's boundary to `o`. With a `bound`, only faces nearer
  /// than it are searched: when no boundary point is nearer, the answer has Piece -1.
  UnionAnswer Query(const double o[3], double bound = HUGE_VAL) const;
  /// Whether piece `i` holds `x` (closed, within Tolerance).
  bool PieceContains(size_t i, const double x[3]) const;
  /// Whether `x` lies in the union (closed, within Tolerance).
  bool Contains(const double x[3]) const;
};

} // namespace vtkdf

#endif
