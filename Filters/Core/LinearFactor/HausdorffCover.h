// HausdorffCover: the pieces of triangles that the Hausdorff distance refines
// (HausdorffDistance.cxx) and two of the bounds on their distance to a target mesh: the
// reach from a piece's corners, and the covering bound by the target's faces over it.
// Private to the linear-factorization family.
#ifndef vtkdf_HausdorffCover_h
#define vtkdf_HausdorffCover_h

#include "LinearFactor/QueryTree.h"

#include <cstdint>
#include <vector>

namespace vtkdf
{
namespace hausdorff
{
/// A piece of a source triangle (or segment: C == B) still to be bounded: its corners,
/// their squared distances to the target and nearest primitives, and the primitive that
/// bounded its parent best (candidates for its own bound).
struct Piece
{
  double X[9];
  double D2[3];
  int32_t Near[4];
  bool Segment;
};

/// The largest distance from a point of the piece to its nearest corner: half a
/// segment's length; a triangle's circumradius where no angle is obtuse, else (the
/// triangle then lies in the disk on its longest side) that side over the square root
/// of two.
double CornerReach(const Piece& piece);

/// The covering bound of a piece T against the target's faces near it, S. Seen along
/// T's normal n, where the projections of S cover T, every point p of T lies below or
/// above a point q of some face t of S, and |p - q| is q's height over T's plane, at most
/// the largest height of t's corners (or of t's plane along n at T's corners): the
/// distance from p to the target is at most the largest such height of the faces whose
/// projections meet T. S covers T when no edge
/// of S's boundary (the directed edges, in the projection's counterclockwise order, that
/// no other face of S runs the other way) meets T's projection, and a face's projection
/// holds T's centroid: the number of faces over a point then only changes across S's
/// boundary, so it is at least one all over T. Where the target is a fine mesh of a
/// smooth surface and the piece is larger than its faces, no single face bounds the
/// piece (the corner bound) but their heights do. Buffers reused piece after piece.
struct CoverScratch
{
  struct Face
  {
    double U[3][2];     // the projected corners, counterclockwise
    const double* X[3]; // the corners, in the same order
    double Height;      // how far T's part below or above it can be (FaceHeight)
  };
  struct Edge
  {
    uint64_t Key;       // a hash of the corners' coordinates, the same both ways
    const double* From; // the lexicographically smaller corner
    const double* To;
    bool Forward; // whether the face runs the edge from From to To
  };
  std::vector<int32_t> Found;
  std::vector<Face> Faces;
  std::vector<Edge> Edges;
};

struct PieceFrame; // a triangle piece's frame (HausdorffCover.cxx)

/// The covering bound (see CoverScratch) against the faces of `target`; `slack` is what
/// the rounding of a computed distance can reach (local units).
class CoverBound
{
public:
  CoverBound(const nearest::QueryTree& target, double slack)
    : Target(target)
    , Slack(slack)
  {
  }

  /// The bound of a triangle piece by the faces nearest to its corners when `nearest`,
  /// else by the faces near it (those that could hold it below `threshold`); false when
  /// they do not cover it.
  bool operator()(const Piece& piece,
    double threshold,
    bool nearest,
    double& bound,
    CoverScratch& scratch) const;

private:
  /// The faces of the target nearest to the piece's corners (`nearest`) or near it,
  /// projected into scratch.Faces (counterclockwise, with their heights) and their edges
  /// into scratch.Edges; `margin` what the projections' rounding cannot reach. False
  /// when there are too many faces.
  bool ProjectFaces(const Piece& piece,
    const PieceFrame& frame,
    double threshold,
    bool nearest,
    CoverScratch& scratch,
    double& margin) const;
  /// How far the part of the piece below or above the face x can be from it.
  double FaceHeight(const Piece& piece, const PieceFrame& frame, const double* x) const;

  const nearest::QueryTree& Target;
  const double Slack;
};
} // namespace hausdorff
} // namespace vtkdf

#endif
