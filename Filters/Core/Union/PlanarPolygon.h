// PlanarPolygon: convex polygons in a face's plane, clipped by half-planes: how a convex
// piece's faces are built (ConvexPiece.cxx) and how the union query cuts a face by the
// other pieces (UnionClosestPoint.cxx). Private to the union family.
#ifndef vtkdf_PlanarPolygon_h
#define vtkdf_PlanarPolygon_h

#include <vector>

namespace vtkdf
{
namespace planar
{
struct V2
{
  double X, Y;
};

/// a . y <= B on a face's plane (2D coordinates).
struct HalfPlane
{
  double A[2];
  double B;
};

/// A convex polygon whose edge k (corner k to k + 1) comes from constraint Source[k]
/// (-1: the face's own edges).
struct Polygon
{
  std::vector<V2> Corners;
  std::vector<int> Source;
};

/// `in` cut by `h`: the corners where a . y <= B, each new edge from constraint `id`.
Polygon Clip(const Polygon& in, const HalfPlane& h, int id);
} // namespace planar
} // namespace vtkdf

#endif
