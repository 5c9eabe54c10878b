// SegmentContour: the interfaces of a segmented distance field as triangles (Yamazaki et al. (SMI
// 2003), section 3.3: eqs. 5-7), keeping boundaries and junctions, without VTK types.
//
// A grid edge between samples a and b (spacing w) holds an interface point when their
// regions differ and 0 < d_a + d_b <= w (1 + Tolerance) (eq. 7, the equality allowed: a
// sheet halfway between two samples gives exactly w), at t = d_a / (d_a + d_b) from a
// (eq. 6). Per cell of 2x2x2 samples:
// - two regions and an interface on every edge between them: marching cubes with the
//   caller's case table (bit v set where corner v is in the lower region), so that a
//   closed surface (two regions) gives what marching cubes gives at 0 on its signed
//   field;
// - otherwise (three or more regions, a junction; or an edge suppressed by eq. 7, a
//   boundary): a vertex at the mean of the cell's interface points, and on each face a
//   segment between its two points when they separate the same two regions, else from
//   each of its points to a face vertex at their mean; each segment and the cell vertex
//   make a triangle. Junction lines are where several sheets share those vertices.
// Every triangle separates two regions (Pairs, lower first) and faces the higher one.
// Where a marching-cubes cell shares an ambiguous face (four points, two regions) with a
// cell of the second kind, the two may disagree on that face: a crack of less than a
// cell, rare (only next to a junction or a boundary).
//
// With the samples' closest points (Hermite data: the tangent plane through each
// sample's closest point, normal to the direction to it), vertices follow the surface's
// features as in dual contouring and extended marching cubes: the vertex of a junction or
// boundary cell goes to the point nearest the cell's tangent planes (a least-squares
// point, pulled weakly towards the mean of the interface points so that it stays put
// along the directions the planes leave free), which puts it on the junction line or on
// the open rim rather than inside the sheets; and a marching-cubes cell whose tangent
// planes differ by more than FeatureAngle (an apex, a crease) has its one surface piece
// replaced by a fan around that point, with the same border, so the neighbours still
// match. The points stay within the cell grown by one spacing (a sharp apex may lie past
// the last cell that holds samples of its inside).
#ifndef vtkdf_SegmentContour_h
#define vtkdf_SegmentContour_h

#include "Common/Parallel.h"
#include "Common/SampleGrid.h"

#include <cstdint>
#include <vector>

namespace vtkdf
{

struct ContourInput
{
  SampleGrid Grid; // the samples: Grid.Whole, x fastest
  const float* Distance = nullptr;
  const int32_t* Region = nullptr;
  /// Marching cubes' triangle table: for each of the 256 cases, up to 5 triangles as
  /// edge indices, -1 after the last. Corners 0-7 are (0,0,0) (1,0,0) (1,1,0) (0,1,0)
  /// (0,0,1) (1,0,1) (1,1,1) (0,1,1); edges 0-11 join corners 0-1 1-2 3-2 0-3 4-5 5-6 7-6
  /// 4-7 0-4 1-5 3-7 2-6; bit v of the case is set where corner v is above the value.
  const int (*Cases)[16] = nullptr;
  double Tolerance = 1e-5;
  /// Optional: each sample's closest point on the surface (xyz, the grid's frame).
  const double* ClosestPoint = nullptr;
  /// Tangent planes that differ by more than this (degrees) make a feature.
  double FeatureAngle = 30;
};

struct ContourResult
{
  std::vector<double> Points;     // xyz
  std::vector<int64_t> Triangles; // 3 point ids each
  std::vector<int32_t> Pairs;     // per triangle: the lower and the higher region
  int64_t MarchingCells = 0;      // cells done by the case table
  int64_t OtherCells = 0;         // junction and boundary cells
  int64_t FeatureCells = 0;       // marching-cubes cells fanned around a feature point
};

/// The surface of the segmented field `input`, cell by cell. Progress by slices of
/// cells; false when `execution` aborts (`result` is then empty).
bool ContourSegmented(const ContourInput& input, ContourResult& result, const Execution& execution);

} // namespace vtkdf

#endif
