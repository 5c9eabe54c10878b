// BitVolume: a binary voxel grid stored as voxel lanes (Martinek et al. (VMV 2011) §3): the voxels
// of column (x, y) along z are the bits of one lane, 64 per word, ceil(nz / 64) words per lane.
// Lanes are stored x fastest, then y. Bits past nz in a lane's last word are zero.
#ifndef vtkdf_BitVolume_h
#define vtkdf_BitVolume_h

#include "Common/Parallel.h"
#include "Common/SampleGrid.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace vtkdf
{

class BitVolume
{
public:
  BitVolume() = default;
  BitVolume(int nx, int ny, int nz) { this->Resize(nx, ny, nz); }

  void Resize(int nx, int ny, int nz)
  {
    this->Dims = { { nx, ny, nz } };
    this->Words = (nz + 63) / 64;
    this->Bits.assign(static_cast<size_t>(nx) * ny * this->Words, 0);
  }

  int Size(int a) const { return this->Dims[a]; }
  int WordsPerLane() const { return this->Words; }
  int64_t NumberOfLanes() const { return int64_t(this->Dims[0]) * this->Dims[1]; }

  uint64_t* Lane(int x, int y)
  {
    return this->Bits.data() + (static_cast<size_t>(y) * this->Dims[0] + x) * this->Words;
  }
  const uint64_t* Lane(int x, int y) const
  {
    return this->Bits.data() + (static_cast<size_t>(y) * this->Dims[0] + x) * this->Words;
  }
  bool Get(int x, int y, int z) const { return (this->Lane(x, y)[z >> 6] >> (z & 63)) & 1u; }
  void Set(int x, int y, int z) { this->Lane(x, y)[z >> 6] |= uint64_t(1) << (z & 63); }

  /// 64 bits of lane (x, y) from voxel z on (zero past the lane's end).
  uint64_t Bits64(int x, int y, int z) const
  {
    const uint64_t* lane = this->Lane(x, y);
    const int w = z >> 6, shift = z & 63;
    const uint64_t lo = w < this->Words ? lane[w] : 0;
    const uint64_t hi = w + 1 < this->Words ? lane[w + 1] : 0;
    return shift ? (lo >> shift) | (hi << (64 - shift)) : lo;
  }

  /// The valid bits of a lane's last word.
  uint64_t LastWordMask() const
  {
    const int used = this->Dims[2] - 64 * (this->Words - 1);
    return used >= 64 ? ~uint64_t(0) : ((uint64_t(1) << used) - 1);
  }

  bool Any() const
  {
    for (uint64_t w : this->Bits)
    {
      if (w)
      {
        return true;
      }
    }
    return false;
  }
  int64_t Count() const
  {
    int64_t n = 0;
    for (uint64_t w : this->Bits)
    {
      n += __builtin_popcountll(w);
    }
    return n;
  }

  std::vector<uint64_t>& Data() { return this->Bits; }
  const std::vector<uint64_t>& Data() const { return this->Bits; }

private:
  std::array<int, 3> Dims{ { 0, 0, 0 } };
  int Words = 0;
  std::vector<uint64_t> Bits;
};

/// A 64 x 64 bit matrix transposed in place: afterwards m[r] bit c is the former m[c]
/// bit r (recursive swaps of off-diagonal blocks, 6 rounds).
inline void TransposeBits64(uint64_t m[64])
{
  static const uint64_t masks[6] = { 0x00000000FFFFFFFFull,
    0x0000FFFF0000FFFFull,
    0x00FF00FF00FF00FFull,
    0x0F0F0F0F0F0F0F0Full,
    0x3333333333333333ull,
    0x5555555555555555ull };
  int round = 0;
  for (int j = 32; j != 0; j >>= 1, ++round)
  {
    for (int k = 0; k < 64; ++k)
    {
      if (k & j)
      {
        continue;
      }
      const uint64_t t = ((m[k] >> j) ^ m[k + j]) & masks[round];
      m[k] ^= t << j;
      m[k + j] ^= t;
    }
  }
}

/// Writes the bits of `bits` (the voxels of `grid.Whole`) over `extent`, a sub-extent
/// of it, as bytes 0 or 1, x fastest.
void BitsToBytes(const BitVolume& bits,
  const SampleGrid& grid,
  const IndexBox& extent,
  uint8_t* out,
  const ParallelFor& parallelFor);

} // namespace vtkdf

#endif
