// vtkDistanceFieldMesh: what the filters of this module share on the VTK side: the
// copy of a vtkPolyData into the cores' plain arrays, and the vtkSMPTools loop behind
// the cores' ParallelFor hook. Private to the module (not wrapped).
#ifndef vtkDistanceFieldMesh_h
#define vtkDistanceFieldMesh_h

#include "Voxels/BitVolume.h"
#include "GL/HeadlessGL.h"
#include "LinearFactor/MeshSites.h"
#include "Common/SampleGrid.h"
#include "Voxels/Voxelizer.h"

#include "vtkSmartPointer.h"
#include "vtkType.h"

#include <cstdint>
#include <functional>
#include <string>

class vtkAlgorithm;
class vtkCallbackCommand;
class vtkDataArray;
class vtkDataObject;
class vtkImageData;
class vtkPolyData;

namespace vtkdf
{

/// Bounds (xmin, xmax, ...) of the points that the cells of `input` use. Every point id
/// is checked before its point is read. False and `error` when a cell refers to a point
/// that does not exist, a used point has a NaN or infinite coordinate, or no cell uses a
/// point.
bool UsedPointBounds(vtkPolyData* input, double bounds[6], std::string& error);

/// Copies the mesh into the core's plain arrays (polygons ear-cut into triangles,
/// strips split, polylines into segments), in the local frame of the grid (GridFrame:
/// translated to the grid's origin, divided by a power of two near its spacing), so that
/// the cores see the same numbers at any coordinate scale. Counts the cells it cannot use.
struct MeshConversion
{
  MeshInput Mesh; // local coordinates
  GridFrame Frame;
  SampleGrid Grid;       // the grid, in local coordinates
  double LocalBounds[6]; // of the used points, local coordinates
  vtkIdType ShortPolygons = 0, ShortLines = 0, ShortStrips = 0, EmptyVertices = 0;

  /// False and `error` on invalid input (UsedPointBounds), or when the mesh and `grid`
  /// together cannot carry float32 distances (CheckGrid).
  bool Run(vtkPolyData* input, const SampleGrid& grid, std::string& error);

  /// A sentence naming the cells that were ignored, or "" when none was.
  std::string IgnoredCells() const;

private:
  void AddTriangle(vtkIdType a, vtkIdType b, vtkIdType c, vtkIdType cell);
};

/// The sites of `input` (MeshSites::Build after MeshConversion) for fields on `grid`,
/// in the local frame `conversion.Frame` (`conversion.Grid` is the grid there): the
/// domains' slack is 1e-4 of the smallest spacing plus what the float planes need over
/// the box that holds the mesh and the grid (MeshSites::PlaneSlack). False and `error`
/// on invalid input; `warning` names the cells that were ignored, if any.
bool BuildSites(vtkPolyData* input,
  Culling culling,
  const SampleGrid& grid,
  MeshConversion& conversion,
  MeshSites& sites,
  std::string& warning,
  std::string& error);

/// The point-data array `name` of `image` when it is numeric, has `components`
/// components and one tuple per sample; else null, and `error` says what is wrong.
vtkDataArray* SampleArray(vtkImageData* image,
  const char* name,
  int components,
  std::string& error);

/// Keeps the first error an inner filter reports (the message after "): "), so that the
/// filter that runs it can report it as its own: a caller observes the outer filter.
class InnerErrors
{
public:
  explicit InnerErrors(vtkAlgorithm* inner);
  /// The message, or `fallback` when there was none.
  std::string Message(const char* fallback) const;

private:
  std::string Text;
  vtkSmartPointer<vtkCallbackCommand> Command;
};

/// The warning for cells a voxelizer ignores (vertices, lines, unusable cells), or "".
std::string TrianglesOnly(const MeshConversion& conversion);
/// The warning for triangles too far from the grid, or "".
std::string FarTriangles(const VoxelizeStatistics& statistics);

/// Voxelizes the triangles of `input` on `grid` (either output may be null), on the GPU
/// when `gpu` is given (in the local frame of the grid: the same bits at any scale). Returns false
/// with `error` on invalid input or a GPU failure; `warning` names what was ignored, if anything.
bool VoxelizeMesh(vtkPolyData* input,
  const SampleGrid& grid,
  HeadlessGL* gpu,
  BitVolume* boundary,
  BitVolume* solid,
  std::string& error,
  std::string& warning);

/// Writes the bits of `bits` over `extent` (a sub-extent of `grid.Whole`) as uint8 0/1.
void BitsToMask(const BitVolume& bits,
  const SampleGrid& grid,
  const IndexBox& extent,
  uint8_t* out);

/// Gives `array` `tuples` tuples; throws std::bad_alloc when VTK could not allocate
/// them (it then reports and leaves the array short, which must not be written).
void AllocateTuples(vtkDataArray* array, vtkIdType tuples);

/// The GPU context for a filter's Backend (0 Auto, 1 GPU, 2 CPU): `gl` is the context
/// (Backend GPU: any, even a software rasterizer; Auto: a hardware-accelerated one) or
/// null for the CPU. False, with `error`, when Backend is GPU and there is no context.
bool ChooseContext(int backend, HeadlessGL*& gl, std::string& error);

/// The RequestData of a filter whose work is `compute`: a failure (0) leaves `output`
/// empty and says so in the error code (UserError, else NoError), for callers that do not
/// observe ErrorEvent. `setErrorCode` is the filter's own (protected) SetErrorCode.
int RunOrEmpty(vtkDataObject* output,
  const std::function<int()>& compute,
  const std::function<void(unsigned long)>& setErrorCode);

/// vtkSMPTools::For behind the cores' ParallelFor hook. An exception thrown by `body`
/// (std::bad_alloc) stops the remaining chunks and is rethrown here, on the calling
/// thread, whatever the SMP backend (a std::thread backend would otherwise terminate).
void SMPFor(int64_t n, int64_t grain, const std::function<void(int64_t, int64_t)>& body);

} // namespace vtkdf

#endif
