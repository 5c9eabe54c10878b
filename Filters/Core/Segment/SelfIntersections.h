// SelfIntersections: cuts a triangle soup along the curves where its triangles cross
// without sharing an edge, so that the crossings become edges used by four triangles
// (junction lines, SurfacePatches), without VTK types.
//
// A teapot's spout passes through its body: the two surfaces cross but share no edge,
// so SurfacePatches sees one patch for the spout and one for the body, and the pocket
// inside the body and outside the spout belongs to both the spout's outer side and the
// body's inner side. Cut, the spout's part inside the body is a patch of its own and
// the crossing a junction line, as Yamazaki et al.'s segmentation expects.
//
// The crossings are found by the project's own code (Segment/TriangleCrossings.h: a
// bounding-volume hierarchy and exact predicates). The cut is CGAL's autorefinement
// (Segment/CrossingRefinement.h), group by group: only the crossing triangles go to
// CGAL. Triangles without area and repeats of a triangle are passed through uncut. A
// build without CGAL (DF_USE_CGAL=OFF, BSD-compatible dependencies only) finds and
// counts the crossings the same way and leaves every group uncut.
#ifndef vtkdf_SelfIntersections_h
#define vtkdf_SelfIntersections_h

#include "Common/LargeVector.h"
#include <cstdint>
#include <string>
#include <vector>

namespace vtkdf
{

struct SelfIntersectionCut
{
  /// The cut soup: xyz per point, 3 point ids per triangle, each triangle in the
  /// orientation of the input triangle it lies in (Parent).
  LargeVector<double> Points;
  LargeVector<int64_t> Triangles;
  std::vector<int64_t> Parent;
  /// Input triangles that were cut, and whether any was (when none was, the output
  /// arrays are empty and the input stands).
  int64_t CutTriangles = 0;
  bool Cut() const { return this->CutTriangles > 0; }
  /// Groups of crossing triangles (joined by crossings and shared points), each refined
  /// on its own; those left uncut (refused by CGAL, or every group in a build without
  /// it), how many triangles they hold, and why (CGAL's first message, or the build).
  int64_t CrossingGroups = 0;
  int64_t FailedGroups = 0;
  int64_t FailedTriangles = 0;
  std::string FailedMessage;
};

/// Cuts `triangles` (3 ids each into `points`, xyz) along their crossings: triangles
/// that share no point and intersect. Neighbours that also cross elsewhere (a fold
/// through its own fan) are not found. A group that cannot be cut is counted in `out`
/// (FailedGroups) and left uncut.
void CutSelfIntersections(const LargeVector<double>& points,
  const LargeVector<int64_t>& triangles,
  SelfIntersectionCut& out);

} // namespace vtkdf

#endif
