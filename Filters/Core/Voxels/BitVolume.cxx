#include "Voxels/BitVolume.h"

#include <algorithm>

namespace vtkdf
{

void BitsToBytes(const BitVolume& bits,
  const SampleGrid& grid,
  const IndexBox& extent,
  uint8_t* out,
  const ParallelFor& parallelFor)
{
  // Tiles of 64 lanes (x) by 64 voxels (z), transposed so that each row of bits runs
  // along x, the order of the output.
  const int nx = extent.Size(0), ny = extent.Size(1), nz = extent.Size(2);
  const int zBlocks = (nz + 63) / 64;
  parallelFor(int64_t(ny) * zBlocks,
    1,
    [&](int64_t begin, int64_t end)
    {
      uint64_t tile[64];
      for (int64_t id = begin; id < end; ++id)
      {
        const int j = static_cast<int>(id % ny), z0 = 64 * static_cast<int>(id / ny);
        const int y = extent.Lo[1] + j - grid.Whole.Lo[1];
        const int zLane = extent.Lo[2] + z0 - grid.Whole.Lo[2];
        for (int x0 = 0; x0 < nx; x0 += 64)
        {
          for (int r = 0; r < 64; ++r)
          {
            tile[r] =
              x0 + r < nx ? bits.Bits64(extent.Lo[0] + x0 + r - grid.Whole.Lo[0], y, zLane) : 0;
          }
          TransposeBits64(tile);
          for (int c = 0; c < 64 && z0 + c < nz; ++c)
          {
            uint8_t* row = out + (int64_t(z0 + c) * ny + j) * nx + x0;
            const int count = std::min(64, nx - x0);
            for (int b = 0; b < count; ++b)
            {
              row[b] = static_cast<uint8_t>((tile[c] >> b) & 1u);
            }
          }
        }
      }
    });
}

} // namespace vtkdf
