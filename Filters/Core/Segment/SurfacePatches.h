// SurfacePatches: a triangle mesh split into patches along its junction lines and
// boundaries (Yamazaki et al., SMI 2003, section 3.3.2, step 1), without VTK types.
//
// Points at the same position are one point (soups share no ids). Two triangles are in
// one patch when they are connected across edges used by exactly two triangles whose
// orientations agree there, once each triangle has been flipped or not so that its patch
// is consistently oriented. A patch that cannot be (a Moebius strip, two triangles
// facing each other across an edge in the wrong order) is cut along the edges where the
// orientations disagree: CutEdges counts them. Edges used by one triangle are
// boundaries, by three or more junctions; triangles with fewer than three distinct
// points (no area) belong to no patch.
#ifndef vtkdf_SurfacePatches_h
#define vtkdf_SurfacePatches_h

#include "Common/LargeVector.h"
#include <cstdint>
#include <vector>

namespace vtkdf
{

class SurfacePatches
{
public:
  /// `points`: xyz; `triangles`: 3 point ids each.
  void Build(const LargeVector<double>& points, const LargeVector<int64_t>& triangles);

  int64_t PatchCount = 0;
  int64_t CutEdges = 0;
  std::vector<int64_t> Patch;   // per triangle, -1 for a triangle without area
  std::vector<uint8_t> Flipped; // per triangle: its patch's orientation is its reverse

  /// The unit normal of triangle t in its patch's orientation.
  void Normal(int64_t t, double n[3]) const;
  /// The triangles (with a patch) that use point p (any id of that position).
  void TrianglesAtPoint(int64_t p, std::vector<int64_t>& out) const;
  /// The triangles (with a patch) that use both points a and b.
  void TrianglesAtEdge(int64_t a, int64_t b, std::vector<int64_t>& out) const;
  /// The position of triangle t's corner k.
  const double* Corner(int64_t t, int k) const
  {
    return &(*this->Points)[3 * this->Ids[3 * t + k]];
  }
  /// The position of point p (any id).
  const double* Position(int64_t p) const { return &(*this->Points)[3 * p]; }
  /// The merged id of triangle t's corner k (equal for equal positions).
  int64_t Key(int64_t t, int k) const { return this->Keys[this->Ids[3 * t + k]]; }

  /// Flat int copies for the GPU (Shaders/SideLabel.comp.glsl): per triangle its three
  /// corner keys, its patch and whether it is flipped; per key where its triangles start
  /// in `corners` (one more entry than keys), then those triangles, ascending. False
  /// when an id does not fit an int.
  bool Flatten(std::vector<int32_t>& triangles, std::vector<int32_t>& corners) const;
  /// The points Build was given (xyz per id), and how many triangle entries Flatten's
  /// `corners` holds after its starts.
  const LargeVector<double>* PointArray() const { return this->Points; }
  int64_t CornerCount() const { return static_cast<int64_t>(this->CornerTriangles.size()); }

private:
  // Build's steps.
  struct Link
  {
    int64_t A, B; // the two triangles of a manifold edge
    bool Same;    // they run the edge the same way: one must be flipped
  };
  void MergePositions();
  std::vector<uint8_t> TrianglesWithArea() const;
  void IndexCorners(const std::vector<uint8_t>& valid);
  std::vector<Link> Links(const std::vector<uint8_t>& valid) const;
  void Orient(const std::vector<uint8_t>& valid, const std::vector<Link>& links);

  const LargeVector<double>* Points = nullptr;
  LargeVector<int64_t> Ids;         // the triangles' point ids
  std::vector<int64_t> Keys;        // per point: the lowest id of its position
  std::vector<int64_t> CornerStart; // per key: first entry in CornerTriangles
  std::vector<int64_t> CornerTriangles;
};

} // namespace vtkdf

#endif
