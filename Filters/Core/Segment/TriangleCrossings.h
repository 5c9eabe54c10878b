// TriangleCrossings: which triangles of a soup intersect, exactly, without VTK types.
//
// Candidate pairs are the triangles whose bounding boxes meet (closed boxes), found by a
// bounding-volume hierarchy joined with itself; each candidate is then decided by
// orientation predicates alone (Segment/ExactPredicates.h), so that touching, coplanar
// and nearly coplanar triangles are decided as they are, not as rounding has them.
#ifndef vtkdf_TriangleCrossings_h
#define vtkdf_TriangleCrossings_h

#include <array>
#include <cstddef>
#include <functional>
#include <vector>

namespace vtkdf
{
using Point3 = std::array<double, 3>;
using TriangleCorners = std::array<size_t, 3>;

/// Whether the closed triangles p and q (corners xyz, neither collinear) have a point
/// in common.
bool TrianglesIntersect(const Point3 p[3], const Point3 q[3]);

/// Calls `report(i, k)` (i < k) once for every pair of `triangles` (corner ids into
/// `points`, none collinear) whose closed bounding boxes meet, in an order that depends
/// only on the input.
void ForEachOverlappingPair(const std::vector<Point3>& points,
  const std::vector<TriangleCorners>& triangles,
  const std::function<void(size_t, size_t)>& report);
} // namespace vtkdf

#endif
