// Voxelizer: boundary and solid voxelization of a triangle mesh into voxel lanes, as in
// Martinek et al. (VMV 2011) §4, on the CPU. The voxels are the grid's samples; voxel (i, j, k) is
// the cell of size spacing centred on its sample.
//
// Three views (along x, y and z) rasterize triangles onto the plane of the other two
// axes; a lane is the line through a row of sample centres.
// - Boundary: every voxel whose centre lies within half a cell diagonal of a triangle
//   (degenerate triangles included, as the segments or points they are). Each triangle
//   goes to the one view its plane faces most, where its footprint grown by that
//   distance gives candidate voxels that the exact point-triangle distance decides
//   (VoxelizerRules.h, BoundaryTriangle). The views' bits, rotated into z-lanes, are
//   OR-ed.
// - Solid: per view, a lane that meets a triangle gets the crossing's half-voxel bin;
//   the rule deciding which lanes a triangle covers is exact (vertices snapped to 1/256
//   of a spacing, integer edge functions, top-left rule), so a lane through an edge
//   shared by two triangles is counted once. Front-facing and back-facing triangles go
//   to separate lanes; the bits of every [front, back] interval are set; the three views
//   are AND-ed, so an open sheet (the paper's leaves) adds no volume.
// The GPU pass (VoxelGPU) repeats both rules and sets the same bits.
#ifndef vtkdf_Voxelizer_h
#define vtkdf_Voxelizer_h

#include "Common/MeshInput.h"
#include "Common/Parallel.h"
#include "Common/SampleGrid.h"
#include "Voxels/BitVolume.h"

#include <string>

namespace vtkdf
{

struct VoxelizeStatistics
{
  int64_t Triangles = 0;    // triangles used
  int64_t FarTriangles = 0; // ignored by the solid: a vertex beyond the snapping range (2^22 cells)
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
