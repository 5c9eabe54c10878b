#include "LevelSet/OpenVDBLevelSet.h"

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Prune.h>

#include <algorithm>
#include <exception>
#include <type_traits>

namespace vtkdf
{
namespace
{
openvdb::Coord ToCoord(int i, int j, int k)
{
  return openvdb::Coord(i, j, k);
}

/// The bricks without band samples inside the mesh: inactive tiles at -background. The
/// bricks with band samples are written over them afterwards (they share boundary
/// samples with their neighbours).
void FillInsideBricks(const LevelSetGrid& grid, openvdb::FloatGrid& levelSet)
{
  const std::array<int, 3>& n = grid.BrickCounts;
  for (int64_t id = 0; id < static_cast<int64_t>(grid.Sides.size()); ++id)
  {
    if (grid.Sides[id] >= 0)
    {
      continue;
    }
    const int b[3] = { static_cast<int>(id % n[0]),
      static_cast<int>((id / n[0]) % n[1]),
      static_cast<int>(id / (int64_t(n[0]) * n[1])) };
    const openvdb::Coord lo(b[0] * grid.BrickSize, b[1] * grid.BrickSize, b[2] * grid.BrickSize);
    const openvdb::Coord hi = lo.offsetBy(grid.BrickSize);
    levelSet.tree().fill(openvdb::CoordBBox(lo, hi), -grid.Background, false);
  }
}

/// One brick's samples: the band's active with their distances, the others inactive at
/// the background with their side's sign; closest points active where the band is.
void WriteBrick(const LevelSetBrick& brick,
  float background,
  openvdb::FloatGrid::Accessor& distance,
  openvdb::Vec3SGrid::Accessor* closest,
  int64_t& active)
{
  const IndexBox& e = brick.Extent;
  int64_t at = 0;
  for (int k = e.Lo[2]; k <= e.Hi[2]; ++k)
  {
    for (int j = e.Lo[1]; j <= e.Hi[1]; ++j)
    {
      for (int i = e.Lo[0]; i <= e.Hi[0]; ++i, ++at)
      {
        const openvdb::Coord ijk = ToCoord(i, j, k);
        if (!brick.Hidden[at])
        {
          distance.setValueOn(ijk, brick.Distance[at]);
          ++active;
          if (closest)
          {
            const float* p = brick.ClosestPoint + 3 * at;
            closest->setValueOn(ijk, openvdb::Vec3s(p[0], p[1], p[2]));
          }
        }
        else
        {
          // Outside is the background already, but where a neighbouring brick inside
          // filled the shared samples (a mesh whose sides disagree).
          const float side = brick.Distance[at] < 0 ? -background : background;
          if (distance.getValue(ijk) != side)
          {
            distance.setValueOff(ijk, side);
          }
        }
      }
    }
  }
}

bool WriteOpenVDBLevelSet(const std::string& path,
  const LevelSetGrid& grid,
  const std::vector<LevelSetBrick>& bricks,
  LevelSetSummary& summary,
  std::string& error)
{
  summary = LevelSetSummary();
  for (const LevelSetBrick& brick : bricks)
  {
    if (brick.Extent.Lo[0] < 0 || brick.Extent.Lo[1] < 0 || brick.Extent.Lo[2] < 0)
    {
      error = "A brick starts at a negative sample index: the level set needs the grid's "
              "samples from (0, 0, 0).";
      return false;
    }
  }
  try
  {
    openvdb::initialize();
    openvdb::FloatGrid::Ptr levelSet = openvdb::FloatGrid::create(grid.Background);
    auto transform = openvdb::math::Transform::createLinearTransform(grid.VoxelSize);
    transform->postTranslate(openvdb::Vec3d(grid.Origin[0], grid.Origin[1], grid.Origin[2]));
    levelSet->setTransform(transform);
    levelSet->setGridClass(openvdb::GRID_LEVEL_SET);
    levelSet->setName(grid.Name);
    FillInsideBricks(grid, *levelSet);
    const bool points = !bricks.empty() &&
      std::all_of(bricks.begin(),
        bricks.end(),
        [](const LevelSetBrick& b) { return b.ClosestPoint != nullptr; });
    openvdb::Vec3SGrid::Ptr closest = openvdb::Vec3SGrid::create(openvdb::Vec3s(0, 0, 0));
    closest->setTransform(transform->copy());
    closest->setName("closest_point");
    openvdb::FloatGrid::Accessor distance = levelSet->getAccessor();
    openvdb::Vec3SGrid::Accessor closestAccessor = closest->getAccessor();
    int64_t written = 0;
    for (const LevelSetBrick& brick : bricks)
    {
      WriteBrick(brick, grid.Background, distance, points ? &closestAccessor : nullptr, written);
    }
    // Bricks share their boundary samples: the grid counts each voxel once.
    summary.ActiveVoxels = static_cast<int64_t>(levelSet->activeVoxelCount());
    // Inactive nodes become tiles of their own sign (pruneInactive would make them all
    // +background).
    openvdb::tools::pruneLevelSet(levelSet->tree());
    summary.LeafNodes = static_cast<int64_t>(levelSet->tree().leafCount());
    openvdb::GridPtrVec grids{ levelSet };
    if (points)
    {
      grids.push_back(closest);
    }
    openvdb::io::File file(path);
    file.write(grids);
    file.close();
  }
  catch (const std::exception& failure)
  {
    error = "Cannot write " + path + " (OpenVDB: " + failure.what() + ").";
    return false;
  }
  return true;
}
} // namespace
} // namespace vtkdf

// The module's entry point: a name dlsym can find, a type the caller checks against.
extern "C" __attribute__((visibility("default"))) bool vtkdf_WriteOpenVDBLevelSet(
  const std::string& path,
  const vtkdf::LevelSetGrid& grid,
  const std::vector<vtkdf::LevelSetBrick>& bricks,
  vtkdf::LevelSetSummary& summary,
  std::string& error)
{
  static_assert(std::is_same<decltype(&vtkdf_WriteOpenVDBLevelSet),
    vtkdf::WriteOpenVDBLevelSetFunction>::value);
  return vtkdf::WriteOpenVDBLevelSet(path, grid, bricks, summary, error);
}
