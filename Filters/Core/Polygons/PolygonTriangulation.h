// PolygonTriangulation: the triangles of a polygon (convex or concave, planar or not),
// by ear clipping its projection on its best-fit plane, or why it has none.
//
// The plane is Newell's: its normal is the polygon's area vector (right for concave
// polygons, where three corners may give a reversed normal), through the corners' mean.
// In that plane a polygon is clipped ear by ear, starting at its corner 1, so that a
// convex polygon becomes the fan around its corner 0. An ear is a corner whose triangle
// turns the polygon's way and holds no other corner; a flat corner (collinear with its
// neighbours, or a duplicate point) is clipped as a zero-area triangle, which covers only
// the polygon's own edges. Every triangle keeps the polygon's orientation and uses its
// actual corners, so a polygon that is not planar becomes triangles through its corners
// whose projections tile its projection.
//
// A polygon has no such triangulation when two of its edges cross in that plane (or it
// touches itself so that no ear is left): then Triangulate() returns false and says
// which corners. A fan is never the fallback: on a concave polygon it covers area
// outside the polygon.
#ifndef vtkdf_PolygonTriangulation_h
#define vtkdf_PolygonTriangulation_h

#include <cstdint>
#include <string>
#include <vector>

namespace vtkdf
{

/// A polygon whose corners lie farther than this fraction of its size (its bounding
/// box's diagonal) from its best-fit plane is not planar: it is still triangulated (by
/// the rule above), and the filters warn about it.
constexpr double PolygonPlanarityTolerance = 1e-3;

class PolygonTriangulation
{
public:
  /// Triangulates the polygon of `count` (at least 3) corners `xyz` (3 doubles each).
  /// True: Triangles() holds count - 2 triangles as corner indices (0 to count - 1).
  /// False: Problem() says why there is none. Buffers are reused from call to call.
  bool Triangulate(const double* xyz, int64_t count);

  /// Corner indices, 3 per triangle, in the polygon's orientation.
  const std::vector<int64_t>& Triangles() const { return this->Result; }

  /// The largest distance of a corner from the best-fit plane, over the polygon's size
  /// (0 for a planar polygon); above PolygonPlanarityTolerance it is not planar.
  double Planarity() const { return this->Flatness; }

  /// Why the last Triangulate() failed, as the end of a sentence ("its edges from
  /// corner 1 and from corner 4 cross in its best-fit plane").
  const std::string& Problem() const { return this->Why; }

private:
  bool Project(const double* xyz, int64_t count);
  bool FindCrossing(int64_t count);
  bool ClipEars(int64_t count);

  std::vector<double> Plane; // 2 coordinates per corner in the best-fit plane
  std::vector<int64_t> Next, Previous;
  std::vector<uint8_t> Convex; // per corner: 1 when it turns the polygon's way
  std::vector<int64_t> Edges;  // crossing search: edges by their lowest first coordinate
  std::vector<int64_t> Result;
  double Size = 0;  // bounding box diagonal
  double Noise = 0; // absolute rounding scale of the plane coordinates
  double Flatness = 0;
  std::string Why;
};

} // namespace vtkdf

#endif
