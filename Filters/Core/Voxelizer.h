// Voxelizer: boundary and solid voxelization of a triangle mesh into voxel lanes, as in
// paper 001 §4, on the CPU. The voxels are the grid's samples; voxel (i, j, k) is the
// cell of size spacing centred on its sample.
//
// Each of the three views (along x, y and z) rasterizes every triangle onto the plane
// of the other two axes: a lane (the line through a row of sample centres) that meets
// the triangle sets the bit of the voxel holding the meeting point. The rule deciding
// which lanes a triangle covers is exact (vertices snapped to 1/256 of a spacing,
// integer edge functions, top-left rule), so a lane through an edge shared by two
// triangles is counted once, and the GPU pass can reproduce it bit for bit.
// - Boundary: the three views' bits, rotated into z-lanes and OR-ed.
// - Solid: per view, front-facing and back-facing triangles go to separate lanes; the
//   bits of every [front, back] interval are set; the three views are AND-ed, so an open
//   sheet (the paper's leaves) adds no volume.
#ifndef vtkdf_Voxelizer_h
#define vtkdf_Voxelizer_h

#include "BitVolume.h"
#include "MeshSites.h"
#include "Parallel.h"
#include "SampleGrid.h"

#include <string>

namespace vtkdf
{

struct VoxelizeStatistics
{
  int64_t Triangles = 0;          // triangles used
  int64_t FarTriangles = 0;       // ignored: a vertex beyond the snapping range (2^22 cells)
  int64_t FlippedOrientation = 0; // 1 when the mesh's signed volume was negative
};

/// Voxelizes the triangles of `mesh` on the whole of `grid`. Either output may be null.
/// Returns false (and `error`) on invalid input (NaN coordinates, bad point ids).
bool VoxelizeCPU(const MeshInput& mesh,
  const SampleGrid& grid,
  BitVolume* boundary,
  BitVolume* solid,
  const ParallelFor& parallelFor,
  VoxelizeStatistics& statistics,
  std::string& error);

} // namespace vtkdf

#endif
