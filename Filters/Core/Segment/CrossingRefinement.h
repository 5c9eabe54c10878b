// CrossingRefinement: cuts one group of crossing triangles along their crossings with
// CGAL's autorefinement (Polygon_mesh_processing::experimental::autorefine, exact
// predicates), without VTK types. Built only with DF_USE_CGAL (CGAL's Polygon Mesh
// Processing is GPL-3.0-or-later; its exact numbers need GMP and MPFR).
#ifndef vtkdf_CrossingRefinement_h
#define vtkdf_CrossingRefinement_h

#include "Segment/SelfIntersections.h"
#include "Segment/TriangleCrossings.h"

#include <cstdint>
#include <vector>

namespace vtkdf
{
/// Refines the group `polygons` (corner ids into `points`, one point per position;
/// `triangle`: each one's input triangle) so that no two of its triangles cross in their
/// interiors, and appends the pieces to `out` (Points, Triangles in the orientation of
/// their input triangle, Parent); marks in `wasCut` the input triangles it cut. Throws
/// std::exception, with CGAL's message, when CGAL cannot refine the group (a halfedge
/// mesh it cannot build, a failed check); `out` may then hold part of the group.
void RefineCrossingGroup(const std::vector<Point3>& points,
  const std::vector<TriangleCorners>& polygons,
  const std::vector<int64_t>& triangle,
  std::vector<uint8_t>& wasCut,
  SelfIntersectionCut& out);
} // namespace vtkdf

#endif
