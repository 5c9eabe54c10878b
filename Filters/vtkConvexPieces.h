// vtkConvexPieces: the convex pieces of a filter input, for vtkUnionClosestPoint and
// vtkPenetrationDepth: a vtkPolyData's connected components (or the cells of each value
// of a cell-data array of piece ids), or a composite's leaves, each checked to be a
// closed convex polytope or replaced by its convex hull (qhull). Private to the module
// (not wrapped).
#ifndef vtkConvexPieces_h
#define vtkConvexPieces_h

#include "Union/UnionClosestPoint.h"

#include <string>
#include <vector>

class vtkDataObject;

namespace vtkdf
{

struct ConvexPieceInput
{
  std::vector<ConvexPiece> Pieces;
  /// The diagonal of the box of every piece (the tolerances are relative to it).
  double Diagonal = 0;
  /// The absolute tolerance of what touches, for the queries: 1e-9 of the diagonal.
  double Tolerance = 0;
  /// The absolute tolerance of the convexity check: 1e-9 of the diagonal for double
  /// points, 1e-6 for float points (a convex mesh stored in float has corners up to a
  /// few float roundings outside its faces' planes).
  double ConvexityTolerance = 0;
  /// How many pieces were replaced by their hulls (UseConvexHulls).
  int Hulls = 0;

  /// Reads the pieces of `input` (a vtkPolyData or a vtkCompositeDataSet of them), in the
  /// order the filters document: a vtkPolyData's connected components (cells sharing a
  /// point id) in the order of their lowest cell id, or with `pieceArray` the cells of
  /// each value of that cell-data array, or a composite's leaves in traversal order. A
  /// piece that is not closed and convex is an error naming it, or with `useHulls` is
  /// replaced by its convex hull. False and `error` on bad input (no polygons, a bad point
  /// id, a NaN coordinate, a missing array, a flat piece).
  bool Read(vtkDataObject* input, const std::string& pieceArray, bool useHulls, std::string& error);
};

} // namespace vtkdf

#endif
