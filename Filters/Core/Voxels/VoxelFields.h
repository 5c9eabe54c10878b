// VoxelFields: the entry points of the voxel family, after M. Martinek, R. Grosso and
// G. Greiner, "Fast and Efficient 3D Chamfer Distance Transform for Polygonal Meshes",
// Vision, Modeling, and Visualization (VMV), 2011: the boundary and solid voxelization
// of a mesh into bit lanes (Voxelizer, VoxelGPU) and the wavefront chamfer distance
// transform (ChamferTransform, VoxelGPU), on the CPU or the GPU with the same bits.
#ifndef vtkdf_VoxelFields_h
#define vtkdf_VoxelFields_h

#include "Common/MeshInput.h"
#include "Common/Parallel.h"
#include "Common/SampleGrid.h"
#include "Voxels/BitVolume.h"
#include "Voxels/ChamferTransform.h"

#include <cstdint>
#include <functional>
#include <string>

namespace vtkdf
{
class HeadlessGL;

struct VoxelReport
{
  /// Triangles too far from the grid to be snapped, and what was ignored (vertex and
  /// line cells have no area), as sentences for a warning ("" when nothing was).
  std::string Warning;
  int64_t FarTriangles = 0;
};

/// Voxelizes the triangles of `mesh` (world coordinates; moved into the grid's local
/// frame, so the bits are the same at any scale) on the whole of `grid` (world), on the
/// GPU when `gl` is given. Either mask may be null. False and `error` on invalid input
/// or when the GPU fails ("The GPU voxelizer (renderer) failed: ...").
bool VoxelizeMesh(MeshInput mesh,
  const SampleGrid& grid,
  HeadlessGL* gl,
  BitVolume* boundary,
  BitVolume* solid,
  const Execution& execution,
  VoxelReport& report,
  std::string& error);

struct ChamferRequest
{
  SampleGrid Grid; // world; its Whole extent is the voxels
  ChamferMetric Metric = ChamferMetric::Manhattan;
  int MaximumLayers = 0; // 0: every layer
  bool Signed = false;   // negative in the solid
  /// The value of the voxels no layer reached.
  int32_t Unreached() const
  {
    return this->MaximumLayers > 0 ? this->MaximumLayers + 1 : INT32_MAX;
  }
};

struct ChamferReport
{
  ChamferResult Result;
  VoxelReport Voxels;
};

/// The chamfer field of a mesh: voxelized (the boundary; the solid when Signed), then
/// propagated, into `distance` (the grid's voxels, x fastest). On the GPU the masks stay
/// there; they come back into `boundary` and `solid` when `keepMasks` (on the CPU they
/// always do). Stages voxelize and propagate; progress of the propagation from 0.1 to 0.95.
/// False and `error` on invalid input, an empty zero set, or a GPU failure.
bool ComputeChamferField(MeshInput mesh,
  const ChamferRequest& request,
  HeadlessGL* gl,
  int32_t* distance,
  BitVolume& boundary,
  BitVolume& solid,
  bool keepMasks,
  const Execution& execution,
  ChamferReport& report,
  std::string& error);

/// The chamfer field from masks already in lanes (`solid` may be null: unsigned).
bool ComputeChamferField(const BitVolume& boundary,
  const BitVolume* solid,
  const ChamferRequest& request,
  HeadlessGL* gl,
  int32_t* distance,
  const Execution& execution,
  ChamferReport& report,
  std::string& error);

/// Where ComputeChamferPiece writes: called with each box of voxels it computes (a
/// later call replaces an earlier one's values), returns room for the box's voxels, x
/// fastest.
using ChamferOutput = std::function<int32_t*(const IndexBox& box)>;

/// The chamfer field on `piece` alone, from the masks of the whole grid
/// (request.Grid.Whole), equal there to the whole grid's field: a voxel at distance
/// d <= MaximumLayers from the zero set has a shortest path to it inside the box its
/// distance spans (every step of every metric moves each coordinate by at most one, and
/// the steps of a path can be reordered to move monotonically), so MaximumLayers voxels
/// around the piece decide it. Without a limit, the piece and a margin of 16 voxels are
/// propagated with that many layers, and the margin doubled until every voxel of the
/// piece is reached; a box over a quarter of the grid is not tried (the whole grid then,
/// so that the tries cost at most half of it). `computed` is the box of the last call to
/// `output`, which holds the piece. report.Result is the last propagation's;
/// report.Voxels is left as it is. False and `error` on an empty zero set or a GPU failure.
bool ComputeChamferPiece(const BitVolume& boundary,
  const BitVolume* solid,
  const IndexBox& piece,
  const ChamferRequest& request,
  HeadlessGL* gl,
  const ChamferOutput& output,
  IndexBox& computed,
  const Execution& execution,
  ChamferReport& report,
  std::string& error);

} // namespace vtkdf

#endif
