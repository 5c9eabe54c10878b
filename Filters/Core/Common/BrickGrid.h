// BrickGrid: a grid of samples cut into bricks of Size samples along each axis, with
// neighbouring bricks sharing their boundary samples (brick b holds the samples b * Size
// .. (b + 1) * Size from the grid's first), so that a contour of the bricks has no
// cracks. The sparse band (LinearFactor/SparseBand.h) and its winding sign
// (Winding/BrickWindingSigns.h) share it.
#ifndef vtkdf_BrickGrid_h
#define vtkdf_BrickGrid_h

#include "Common/SampleGrid.h"

#include <algorithm>
#include <array>
#include <cstdint>

namespace vtkdf
{

struct BrickGrid
{
  IndexBox Whole;
  int Size = 32;
  std::array<int, 3> Counts{ { 1, 1, 1 } };

  /// The bricks over `whole` (at least one along each axis).
  static BrickGrid Over(const IndexBox& whole, int size)
  {
    BrickGrid bricks;
    bricks.Whole = whole;
    bricks.Size = size;
    for (int a = 0; a < 3; ++a)
    {
      const int64_t intervals = int64_t(whole.Hi[a]) - whole.Lo[a];
      bricks.Counts[a] = static_cast<int>(std::max<int64_t>(1, (intervals + size - 1) / size));
    }
    return bricks;
  }

  int64_t Total() const { return int64_t(this->Counts[0]) * this->Counts[1] * this->Counts[2]; }
  int64_t Id(int i, int j, int k) const
  {
    return i + int64_t(this->Counts[0]) * (j + int64_t(this->Counts[1]) * k);
  }
  std::array<int, 3> Indices(int64_t id) const
  {
    return { { static_cast<int>(id % this->Counts[0]),
      static_cast<int>((id / this->Counts[0]) % this->Counts[1]),
      static_cast<int>(id / (int64_t(this->Counts[0]) * this->Counts[1])) } };
  }
  /// A brick's samples: its last layer is its neighbour's first.
  IndexBox Extent(const std::array<int, 3>& b) const
  {
    IndexBox box;
    for (int a = 0; a < 3; ++a)
    {
      box.Lo[a] = this->Whole.Lo[a] + b[a] * this->Size;
      box.Hi[a] = static_cast<int>(
        std::min<int64_t>(int64_t(box.Lo[a]) + this->Size, int64_t(this->Whole.Hi[a])));
    }
    return box;
  }
  /// The bricks that hold some sample of [lo, hi] (whole-grid indices, which may lie
  /// beyond the grid) along axis a: [first, last], empty when first > last.
  void Range(int a, int64_t lo, int64_t hi, int& first, int& last) const
  {
    const int64_t l = std::max<int64_t>(lo - this->Whole.Lo[a], 0);
    const int64_t h = hi - this->Whole.Lo[a];
    // Brick b holds samples b * Size .. (b + 1) * Size.
    first = static_cast<int>(std::max<int64_t>(0, (l + this->Size - 1) / this->Size - 1));
    last = static_cast<int>(std::min<int64_t>(this->Counts[a] - 1, h < 0 ? -1 : h / this->Size));
  }
};

} // namespace vtkdf

#endif
