// TriangleCrossings: which triangles of a soup intersect, exactly, without VTK types.
//
// Candidate pairs are the triangles whose bounding boxes meet (closed boxes), found by a
// bounding-volume hierarchy joined with itself; each candidate is then decided by
// orientation predicates alone (Predicates/ExactPredicates.h), so that touching, coplanar
// and nearly coplanar triangles are decided as they are, not as rounding has them.
#ifndef vtkdf_TriangleCrossings_h
#define vtkdf_TriangleCrossings_h

#include "Common/TriangleBoxTree.h"

#include <cstddef>
#include <functional>
#include <vector>

namespace vtkdf
{
/// Whether the closed triangles p and q (corners xyz, neither collinear) have a point
/// in common.
bool TrianglesIntersect(const Point3 p[3], const Point3 q[3]);

/// Whether the closed segment ab (a = b: a point) and the closed triangle t (corners not
/// collinear) have a point in common, exactly.
bool SegmentIntersectsTriangle(const Point3& a, const Point3& b, const Point3 t[3]);

/// Whether the closed segments ab and cd (either may be a point) have a point in
/// common, exactly.
bool SegmentsIntersect(const Point3& a, const Point3& b, const Point3& c, const Point3& d);

/// Whether the closed triangles p and q have a point in common, exactly, for any
/// corners: a triangle whose corners are collinear (or repeated) is the union of its
/// edges.
bool ClosedTrianglesIntersect(const Point3 p[3], const Point3 q[3]);

/// Calls `report(i, k)` (i < k) once for every pair of `triangles` (corner ids into
/// `points`, none collinear) whose closed bounding boxes meet, in an order that depends
/// only on the input.
void ForEachOverlappingPair(const std::vector<Point3>& points,
  const std::vector<TriangleCorners>& triangles,
  const std::function<void(size_t, size_t)>& report);
} // namespace vtkdf

#endif
