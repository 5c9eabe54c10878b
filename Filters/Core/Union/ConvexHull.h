// ConvexHull: the convex hull of a point set as triangles, by qhull (libqhull_r, the
// reentrant C library), for vtkUnionClosestPoint's UseConvexHulls. No VTK types.
#ifndef vtkdf_ConvexHull_h
#define vtkdf_ConvexHull_h

#include <cstdint>
#include <string>
#include <vector>

namespace vtkdf
{

/// The hull of `points` (xyz triples) as triangles of point indices (any orientation),
/// into `faces`; `corners` counts the points on the hull. False, with `error` saying
/// why (qhull's message: fewer than four points, all in one plane, ...), when there is no
/// three-dimensional hull.
bool ConvexHull(const std::vector<double>& points,
  std::vector<std::vector<int64_t>>& faces,
  int64_t& corners,
  std::string& error);

} // namespace vtkdf

#endif
