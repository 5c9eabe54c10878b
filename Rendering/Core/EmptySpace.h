// Empty-space leaping for the volume mapper's rays (plain C++, no VTK types).
//
// The grid's cells are grouped in bricks of `size`^3 cells. A brick is occupied when a ray
// slab inside it may contribute to the picture: for surfaces, when one of its cells (or of
// the cells next to it) holds voxels of two regions; for pre-integrated compositing, when
// the transfer function's extinction is not zero over the brick's values (widened by a
// table step, so that every table entry a slab in it reads is zero). Each brick then holds
// its Chebyshev distance, in bricks, to the nearest occupied brick: from a point in a brick
// at distance r the cube of bricks within r - 1 of it is empty, and a ray leaps to where it
// leaves that cube.
#ifndef vtkdf_EmptySpace_h
#define vtkdf_EmptySpace_h

#include <array>
#include <vector>

namespace vtkdf::render
{
/// Bricks a side of a grid of `dims` samples ((dims - 1) cells): ceil(cells / size).
std::array<int, 3> BrickCounts(const int dims[3], int size);

/// Occupied bricks (1) of a field of (distance, region) texel pairs: a cell of the brick,
/// or a cell next to it, holds voxels of two regions.
std::vector<unsigned char> MixedBricks(const float* texels, const int dims[3], int size);

/// Each brick's smallest and largest value over its cells' voxels (those on its far faces
/// included: an interpolated value lies between its cell's eight).
std::vector<std::array<float, 2>> BrickValueRanges(const float* values,
  const int dims[3],
  int size);

/// Occupied bricks (1) for pre-integrated compositing: the extinction `samples` (evenly
/// spaced over [low, high], both ends included, as the table is built from) is not zero
/// everywhere over the brick's value range widened by `margin` on both sides (and the
/// samples around its ends).
std::vector<unsigned char> OpaqueBricks(const std::vector<std::array<float, 2>>& ranges,
  const std::vector<double>& samples,
  double low,
  double high,
  double margin);

/// Per brick, the Chebyshev distance in bricks to the nearest occupied brick (0 for an
/// occupied one), capped at 255 (also where no brick is occupied).
std::vector<unsigned char> LeapDistances(const std::vector<unsigned char>& occupied,
  const std::array<int, 3>& bricks);
} // namespace vtkdf::render

#endif
