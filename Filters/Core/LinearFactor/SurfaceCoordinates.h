// SurfaceCoordinates: where on the mesh each grid sample's closest point lies (the
// triangle of its cell and the barycentric coordinates there) and the field's gradient,
// from the closest cells the field found, on either route. A pass after the field: one
// distance a primitive of the closest cell per sample (one for a triangle mesh), and a
// point query for the samples that lie on the surface itself, whose gradient is the
// closest feature's pseudonormal (PointDistance.h's rules).
#ifndef vtkdf_SurfaceCoordinates_h
#define vtkdf_SurfaceCoordinates_h

#include "Common/MeshInput.h"
#include "Common/Parallel.h"
#include "Common/SampleGrid.h"

#include <cstdint>
#include <string>

namespace vtkdf
{

/// Where the pass writes; any pointer may be null. Per sample of the extent, x fastest.
struct SurfaceCoordinateArrays
{
  /// The index of the closest point's triangle within its cell's triangles (segments,
  /// points), as the module splits the cell; -1 beyond the band.
  int64_t* ClosestSubTriangle = nullptr;
  float* ClosestBarycentric = nullptr; // 3 per sample: the coordinates on that triangle
  /// 3 per sample: the unit vector from the closest point to the sample times the
  /// distance's sign; on the surface, the closest feature's unit pseudonormal.
  float* Gradient = nullptr;
};

/// The pass over `extent` of `grid`, with `mesh` and `grid` in one frame (the field's
/// local frame: the answers do not depend on it). `cells` are the field's ClosestCellId
/// (-1: beyond the band, where every output is -1 or NaN); `distance` its signed
/// Distance (its sign bit signs the gradient; null: unsigned). False and `error` when the
/// mesh is invalid for the point queries of the samples on the surface.
bool ComputeSurfaceCoordinates(const MeshInput& mesh,
  const SampleGrid& grid,
  const IndexBox& extent,
  const int64_t* cells,
  const float* distance,
  const SurfaceCoordinateArrays& arrays,
  const ParallelFor& parallelFor,
  std::string& error);

} // namespace vtkdf

#endif
