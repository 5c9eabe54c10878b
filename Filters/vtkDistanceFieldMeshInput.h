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

/// The cells a copy could not use.
struct IgnoredCells
{
  vtkIdType ShortPolygons = 0, ShortLines = 0, ShortStrips = 0, EmptyVertices = 0;
  /// A sentence naming them, or "" when there are none.
  std::string Sentence() const;
};

/// Copies `input` into `mesh`: every point (world coordinates, in double) and the cells
/// in the filters' numbering (vertices, lines, polygons, strips; polygons ear-cut into
/// triangles, strips split, polylines into segments), with `bounds` (UsedPointBounds) as
/// its Bounds. The ear-cut runs in `frame`, the one the cores compute in, so that a mesh
/// and grid scaled by 2^k are cut alike.
void CopyMesh(vtkPolyData* input,
  const double bounds[6],
  const GridFrame& frame,
  MeshInput& mesh,
  IgnoredCells& ignored);

} // namespace vtkdf

#endif
