// OpenVDBLevelSet: a narrow band in bricks (SparseBand.h) written as an OpenVDB level set,
// the sparse format of Houdini, Blender and the other VFX tools (K. Museth, "VDB:
// High-Resolution Sparse Volumes with Dynamic Topology", ACM Transactions on Graphics
// 32(3), 2013).
//
// A FloatGrid of class level set: its voxel (i, j, k) is the grid's sample (i, j, k)
// (the transform: voxel size the spacing, translated to the grid's origin); the band's
// samples are its active voxels, with their distances in world units; every other voxel
// and tile is inactive, at plus the background (the band's half-width) outside and minus
// it inside, by the sides of the bricks: the convention tools that read level sets
// expect. Closest points, when given, go to a Vec3SGrid of the same voxels beside it.
#ifndef vtkdf_OpenVDBLevelSet_h
#define vtkdf_OpenVDBLevelSet_h

#include "Common/SampleGrid.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace vtkdf
{

/// A brick of the band: its samples (global indices, x fastest) and arrays.
struct LevelSetBrick
{
  IndexBox Extent;
  const float* Distance = nullptr;     // world units, signed
  const uint8_t* Hidden = nullptr;     // non-zero: beyond the band
  const float* ClosestPoint = nullptr; // optional, 3 per sample
};

struct LevelSetGrid
{
  std::array<double, 3> Origin{ { 0, 0, 0 } }; // the sample (0, 0, 0)
  double VoxelSize = 1;                        // the spacing, the same on every axis
  float Background = 1;                        // the band's half-width, world units
  std::string Name = "surface";
  /// The sides of the bricks without band samples (-1 inside; BrickCounts of BrickSize
  /// samples from the sample (0, 0, 0)); empty: every such voxel outside.
  std::vector<int8_t> Sides;
  std::array<int, 3> BrickCounts{ { 0, 0, 0 } };
  int BrickSize = 0;
};

/// What a write put in the file.
struct LevelSetSummary
{
  int64_t ActiveVoxels = 0;
  int64_t LeafNodes = 0;
};

/// The family is a module of its own, loaded when a first .vdb is written (dlopen); its
/// one entry point is this symbol, of this type: it writes `bricks` as a level set (and
/// their closest points as a Vec3SGrid named "closest_point" when every brick has them)
/// to `path`. False and `error` when the file cannot be written or the grid cannot be a
/// VDB's (a voxel index beyond 32 bits).
constexpr const char* WriteOpenVDBLevelSetSymbol = "vtkdf_WriteOpenVDBLevelSet";
using WriteOpenVDBLevelSetFunction = bool (*)(const std::string& path,
  const LevelSetGrid& grid,
  const std::vector<LevelSetBrick>& bricks,
  LevelSetSummary& summary,
  std::string& error);

} // namespace vtkdf

#endif
