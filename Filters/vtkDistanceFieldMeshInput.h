// vtkDistanceFieldMeshInput: a vtkPolyData copied into the cores' MeshInput. Private to
// the module (not wrapped).
#ifndef vtkDistanceFieldMeshInput_h
#define vtkDistanceFieldMeshInput_h

#include "Common/MeshInput.h"
#include "Common/SampleGrid.h"

#include "vtkType.h"

#include <string>

class vtkPolyData;

namespace vtkdf
{

/// Bounds (xmin, xmax, ...) of the points that the cells of `input` use. Every point id
/// is checked before its point is read. False and `error` when a cell refers to a point
/// that does not exist, a used point has a NaN or infinite coordinate, or no cell uses a
/// point.
bool UsedPointBounds(vtkPolyData* input, double bounds[6], std::string& error);

/// What a copy could not use, and the polygons it triangulated by the rule for polygons
/// that are not planar.
struct MeshCopyReport
{
  vtkIdType ShortPolygons = 0, ShortLines = 0, ShortStrips = 0, EmptyVertices = 0;
  vtkIdType NonPlanarPolygons = 0;
  vtkIdType FarthestNonPlanarCell = -1; // the polygon farthest from its plane
  double FarthestPlanarity = 0;         // its distance from the plane over its size
  /// Sentences naming them, or "" when there are none.
  std::string Warnings() const;
};

/// Copies `input` into `mesh`: every point (world coordinates, in double) and the cells
/// in the filters' numbering (vertices, lines, polygons, strips; polygons triangulated by
/// PolygonTriangulation, strips split, polylines into segments), with `bounds`
/// (UsedPointBounds) as its Bounds. Polygons are triangulated in `frame`, the one the
/// cores compute in, so that a mesh and grid scaled by 2^k are cut alike. False and
/// `error` (naming the cell) when a polygon has no triangulation along its edges.
bool CopyMesh(vtkPolyData* input,
  const double bounds[6],
  const GridFrame& frame,
  MeshInput& mesh,
  MeshCopyReport& report,
  std::string& error);

} // namespace vtkdf

#endif
