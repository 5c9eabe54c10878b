// MeshInput: a polygon mesh as every core takes it, points and cells as plain arrays (no
// VTK types), in world coordinates. The cores that sample it on a grid move it into the
// grid's local frame themselves (SampleGrid.h, GridFrame).
#ifndef vtkdf_MeshInput_h
#define vtkdf_MeshInput_h

#include "Common/LargeVector.h"
#include "Common/Parallel.h"
#include "Common/SampleGrid.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace vtkdf
{

struct MeshInput
{
  // LargeVector: a fine mesh's arrays are large and written once, by the conversion from
  // the host's data (not zero-filled first; in 2 MiB pages where the kernel has them).
  LargeVector<double> Points; // xyz, 3 per point
  // Triangles (polygons and strips already split into triangles), with the cell they came from.
  LargeVector<int64_t> Triangles; // 3 point ids each
  LargeVector<int64_t> TriangleCells;
  LargeVector<int64_t> Segments; // 2 point ids each (lines, polyline pieces)
  LargeVector<int64_t> SegmentCells;
  LargeVector<int64_t> Vertices; // point ids of vertex cells
  LargeVector<int64_t> VertexCells;
  /// Bounds (xmin, xmax, ...) of the points the input's cells use, as whoever built the
  /// mesh found them (UsedPointBounds, or the filter's own pass over its input, which
  /// also counts the points of cells it could not use).
  std::array<double, 6> Bounds{ { 0, -1, 0, -1, 0, -1 } };

  /// Whether the mesh has no triangle, segment or vertex.
  bool Empty() const { return Triangles.empty() && Segments.empty() && Vertices.empty(); }
};

/// The bounds of the points that the mesh's triangles, segments and vertices use; false
/// when they use none.
inline bool UsedPointBounds(const MeshInput& mesh, std::array<double, 6>& bounds)
{
  bounds = { { HUGE_VAL, -HUGE_VAL, HUGE_VAL, -HUGE_VAL, HUGE_VAL, -HUGE_VAL } };
  bool any = false;
  auto use = [&](const LargeVector<int64_t>& ids)
  {
    for (const int64_t id : ids)
    {
      const double* x = &mesh.Points[3 * id];
      for (int a = 0; a < 3; ++a)
      {
        bounds[2 * a] = std::fmin(bounds[2 * a], x[a]);
        bounds[2 * a + 1] = std::fmax(bounds[2 * a + 1], x[a]);
      }
      any = true;
    }
  };
  use(mesh.Triangles);
  use(mesh.Segments);
  use(mesh.Vertices);
  return any;
}

/// Moves the mesh's points into `frame` (GridFrame::ToLocal, coordinate by coordinate),
/// with `parallelFor` when given.
inline void MoveToLocalFrame(MeshInput& mesh,
  const GridFrame& frame,
  const ParallelFor& parallelFor = ParallelFor())
{
  auto move = [&](int64_t begin, int64_t end)
  {
    for (int64_t i = begin; i < end; ++i)
    {
      for (int a = 0; a < 3; ++a)
      {
        mesh.Points[3 * i + a] = frame.ToLocal(a, mesh.Points[3 * i + a]);
      }
    }
  };
  const int64_t count = static_cast<int64_t>(mesh.Points.size() / 3);
  if (parallelFor)
  {
    parallelFor(count, 4096, move);
  }
  else
  {
    move(0, count);
  }
}

} // namespace vtkdf

#endif
