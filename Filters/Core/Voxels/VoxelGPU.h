// VoxelGPU: the voxelizer and the chamfer transform on the GPU (OpenGL 4.5 core with
// GL_ARB_gpu_shader_int64, in HeadlessGL's context). Voxel lanes live in RGBA32UI 2D
// array textures, 128 bits per texel, as many texture slices as a lane needs (Martinek,
// Grosso and Greiner, "Fast and Efficient 3D Chamfer Distance Transform for Polygonal
// Meshes", VMV 2011, section 3); compute shaders set each triangle up and set its bits
// (Shaders/VoxelizeLanes.comp.glsl). The results equal the CPU passes bit for bit (same
// integer and IEEE double arithmetic, see VoxelizerRules.h and Shaders/VoxelizeCommon.glsl).
#ifndef vtkdf_VoxelGPU_h
#define vtkdf_VoxelGPU_h

#include "Common/MeshInput.h"
#include "Common/SampleGrid.h"
#include "GL/HeadlessGL.h"
#include "Voxels/BitVolume.h"
#include "Voxels/ChamferTransform.h"
#include "Voxels/Voxelizer.h"

#include <string>

namespace vtkdf
{

/// Voxelizes on the GPU and reads the masks back (either may be null).
bool VoxelizeGPU(HeadlessGL& context,
  const MeshInput& mesh,
  const SampleGrid& grid,
  BitVolume* boundary,
  BitVolume* solid,
  VoxelizeStatistics& statistics,
  std::string& error);

/// What the GPU chamfer starts from: a mesh (voxelized on the GPU, nothing read back
/// in between) or masks already in lanes.
struct ChamferInput
{
  const MeshInput* Mesh = nullptr; // voxelized on `Grid` when set
  const BitVolume* Boundary = nullptr;
  const BitVolume* Solid = nullptr; // optional, for the sign
  SampleGrid Grid;
};

/// The chamfer transform on the GPU; the layers become the int32 field on the GPU too,
/// read back once into `distance` (negated in the solid when `negateSolid`). The masks
/// a mesh input was voxelized into come back in `boundaryOut` / `solidOut` when given.
bool ChamferGPU(HeadlessGL& context,
  const ChamferInput& input,
  ChamferMetric metric,
  int maximumLayers,
  int32_t unreached,
  bool negateSolid,
  int32_t* distance,
  BitVolume* boundaryOut,
  BitVolume* solidOut,
  ChamferResult& result,
  VoxelizeStatistics& statistics,
  std::string& error,
  const ProgressCallback& progress = ProgressCallback());

} // namespace vtkdf

#endif
