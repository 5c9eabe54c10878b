#include "Voxels/ChamferTransform.h"

#include <algorithm>
#include <climits>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <type_traits>
#include <vector>

namespace vtkdf
{
namespace
{
// The row loops are compiled twice on x86-64: for the generic target (SSE2, two
// words per operation) and for AVX2 (four), chosen once at run time (the environment
// variable VTKDF_DISABLE_AVX2 forces the generic one, which is how its test runs on a
// machine with AVX2). Each loop body is an always-inlined function, so both versions
// come from the same source.
#if defined(__GNUC__) && defined(__x86_64__)
#define VTKDF_HAVE_AVX2_CLONES 1
#define VTKDF_INLINE inline __attribute__((always_inline))
bool HaveAVX2()
{
  static const bool has =
    __builtin_cpu_supports("avx2") && std::getenv("VTKDF_DISABLE_AVX2") == nullptr;
  return has;
}
#else
#define VTKDF_INLINE inline
#endif

/// The lanes [X0, X1] of one row (empty when X1 < X0).
struct LaneRange
{
  int X0 = INT_MAX, X1 = INT_MIN;
  bool Empty() const { return X1 < X0; }
  void Merge(const LaneRange& o) { X0 = std::min(X0, o.X0), X1 = std::max(X1, o.X1); }
};

/// n(w) of word i of a lane: its bits moved one voxel up and one down the lane.
/// `below` and `above` are all ones where the lane has a word below / above word i (the
/// carries between words), zero at the lane's ends; the words i - 1 and i + 1 are read
/// in any case, so they must exist.
VTKDF_INLINE uint64_t Along(const uint64_t* p, int64_t i, uint64_t below, uint64_t above)
{
  return (p[i] << 1) | (p[i] >> 1) | ((p[i - 1] >> 63) & below) | ((p[i + 1] << 63) & above);
}

/// n'(w) = n(w) | w.
VTKDF_INLINE uint64_t Wide(const uint64_t* p, int64_t i, uint64_t below, uint64_t above)
{
  return p[i] | Along(p, i, below, above);
}

/// Word i of the next layer's candidates, from the rows y - 1, y, y + 1 of the current
/// layer (`up`, `mid`, `down`, lanes of `W` words side by side). A template per metric,
/// so that the row loop is a fixed sequence of word operations the compiler vectorizes.
template<ChamferMetric Metric>
VTKDF_INLINE uint64_t Candidates(const uint64_t* up,
  const uint64_t* mid,
  const uint64_t* down,
  int64_t i,
  int64_t W,
  uint64_t below,
  uint64_t above)
{
  uint64_t v = Along(mid, i, below, above);
  if (Metric == ChamferMetric::Manhattan)
  {
    return v | mid[i - W] | mid[i + W] | up[i] | down[i];
  }
  v |= Wide(mid, i - W, below, above) | Wide(mid, i + W, below, above) | Wide(up, i, below, above) |
    Wide(down, i, below, above);
  if (Metric == ChamferMetric::Chessboard18)
  {
    return v | up[i - W] | up[i + W] | down[i - W] | down[i + W];
  }
  return v | Wide(up, i - W, below, above) | Wide(up, i + W, below, above) |
    Wide(down, i - W, below, above) | Wide(down, i + W, below, above);
}

constexpr int LowBits = 3;

template<ChamferMetric Metric>
using MetricTag = std::integral_constant<ChamferMetric, Metric>;

/// What the propagation keeps between layers.
struct Wavefront
{
  int NX, NY, NZ, W;
  BitVolume Current, Next;
  BitVolume Accumulated; // every voxel reached; the bits past nz are set
  // Bit k of every reached voxel's layer index. The low `LowBits` planes are written as
  // each layer is found; the others once per block of 2^LowBits layers, from the voxels
  // reached since `BlockStart` (a copy of Accumulated), so that a layer touches few planes.
  std::vector<BitVolume> Planes;
  BitVolume BlockStart;
  std::vector<uint64_t> Below, Above; // per word of a row: the carry masks of Along
  std::vector<uint64_t> ZeroRow;      // the rows outside the grid
  // Per row, the lanes where Current and Next may hold bits, and where the layers of
  // the present block were found.
  std::vector<LaneRange> CurrentRows, NextRows, BlockRows;
};

/// The candidates of words [begin, end) of a row whose lanes all have both x neighbours
/// in the row (and the words around those): the new voxels go to `out` and `acc`. The
/// rows are separate __restrict parameters (not a struct of pointers, not copied into
/// __restrict locals): GCC 12 vectorizes the loop only then.
template<ChamferMetric Metric>
VTKDF_INLINE void InnerRowLoop(const uint64_t* __restrict up,
  const uint64_t* __restrict mid,
  const uint64_t* __restrict down,
  const uint64_t* __restrict below,
  const uint64_t* __restrict above,
  uint64_t* __restrict acc,
  uint64_t* __restrict out,
  int64_t begin,
  int64_t end,
  int64_t W)
{
  for (int64_t i = begin; i < end; ++i)
  {
    const uint64_t o = Candidates<Metric>(up, mid, down, i, W, below[i], above[i]) & ~acc[i];
    out[i] = o;
    acc[i] |= o;
  }
}

/// plane[i] |= added[i] for i in [begin, end].
VTKDF_INLINE void OrRowLoop(uint64_t* __restrict plane,
  const uint64_t* __restrict added,
  int64_t begin,
  int64_t end)
{
  for (int64_t i = begin; i <= end; ++i)
  {
    plane[i] |= added[i];
  }
}

#ifdef VTKDF_HAVE_AVX2_CLONES
template<ChamferMetric Metric>
__attribute__((target("avx2"))) void InnerRowAVX2(const uint64_t* up,
  const uint64_t* mid,
  const uint64_t* down,
  const uint64_t* below,
  const uint64_t* above,
  uint64_t* acc,
  uint64_t* out,
  int64_t begin,
  int64_t end,
  int64_t W)
{
  InnerRowLoop<Metric>(up, mid, down, below, above, acc, out, begin, end, W);
}

__attribute__((target("avx2"))) void OrRowAVX2(uint64_t* plane,
  const uint64_t* added,
  int64_t begin,
  int64_t end)
{
  OrRowLoop(plane, added, begin, end);
}
#endif

template<ChamferMetric Metric>
void InnerRow(const uint64_t* up,
  const uint64_t* mid,
  const uint64_t* down,
  const uint64_t* below,
  const uint64_t* above,
  uint64_t* acc,
  uint64_t* out,
  int64_t begin,
  int64_t end,
  int64_t W)
{
#ifdef VTKDF_HAVE_AVX2_CLONES
  if (HaveAVX2())
  {
    InnerRowAVX2<Metric>(up, mid, down, below, above, acc, out, begin, end, W);
    return;
  }
#endif
  InnerRowLoop<Metric>(up, mid, down, below, above, acc, out, begin, end, W);
}

void OrRow(uint64_t* plane, const uint64_t* added, int64_t begin, int64_t end)
{
#ifdef VTKDF_HAVE_AVX2_CLONES
  if (HaveAVX2())
  {
    OrRowAVX2(plane, added, begin, end);
    return;
  }
#endif
  OrRowLoop(plane, added, begin, end);
}

/// The number of bits set in `set` and not in `except` over n words (the popcnt
/// instruction where the CPU has it: the generic x86-64 build calls a library function
/// per word).
inline int64_t CountNewBitsGeneric(const uint64_t* set, const uint64_t* except, int64_t n)
{
  int64_t count = 0;
  for (int64_t i = 0; i < n; ++i)
  {
    count += __builtin_popcountll(set[i] & ~except[i]);
  }
  return count;
}
#if defined(__GNUC__) && defined(__x86_64__)
__attribute__((target("popcnt"))) int64_t CountNewBitsPopcnt(const uint64_t* set,
  const uint64_t* except,
  int64_t n)
{
  return CountNewBitsGeneric(set, except, n);
}
#endif
int64_t CountNewBits(const uint64_t* set, const uint64_t* except, int64_t n)
{
#if defined(__GNUC__) && defined(__x86_64__)
  static const bool popcnt = __builtin_cpu_supports("popcnt");
  if (popcnt)
  {
    return CountNewBitsPopcnt(set, except, n);
  }
#endif
  return CountNewBitsGeneric(set, except, n);
}

/// One layer on the rows [y0 + begin, y0 + end): the new voxels go into `Next`, are
/// added to `Accumulated` and, bit by bit of `layer`, to the low planes. A row's
/// candidates lie in its lanes next to the current layer's lanes of rows y - 1, y, y + 1;
/// the rest of the row of `Next` is cleared where it held a layer. Returns how many rows
/// have new voxels.
template<ChamferMetric Metric>
int64_t LayerRows(Wavefront& f, int y0, int64_t begin, int64_t end, int32_t layer)
{
  const int nx = f.NX, ny = f.NY;
  const int64_t W = f.W;
  const uint64_t* below = f.Below.data();
  const uint64_t* above = f.Above.data();
  std::vector<uint64_t> pad(3 * (3 * W + 2), 0);
  int64_t rowsReached = 0;
  for (int y = y0 + static_cast<int>(begin); y < y0 + end; ++y)
  {
    uint64_t* out = f.Next.Lane(0, y);
    LaneRange region = f.CurrentRows[y];
    region.Merge(y > 0 ? f.CurrentRows[y - 1] : LaneRange());
    region.Merge(y + 1 < ny ? f.CurrentRows[y + 1] : LaneRange());
    if (!region.Empty())
    {
      region.X0 = std::max(0, region.X0 - 1), region.X1 = std::min(nx - 1, region.X1 + 1);
    }
    // `Next` holds layer - 2 in NextRows[y]: what the region does not overwrite is cleared.
    const LaneRange stale = f.NextRows[y];
    if (!stale.Empty())
    {
      // Kept: lanes [cut0, cut1], overwritten below.
      const int cut0 =
        region.Empty() ? stale.X1 + 1 : std::clamp(region.X0, stale.X0, stale.X1 + 1);
      const int cut1 = region.Empty() ? stale.X1 : std::min(stale.X1, region.X1);
      std::fill(out + stale.X0 * W, out + cut0 * W, 0);
      std::fill(out + std::max(cut0, cut1 + 1) * W, out + (stale.X1 + 1) * W, 0);
    }
    f.NextRows[y] = LaneRange();
    if (region.Empty())
    {
      continue;
    }
    const uint64_t* up = y > 0 ? f.Current.Lane(0, y - 1) : f.ZeroRow.data();
    const uint64_t* mid = f.Current.Lane(0, y);
    const uint64_t* down = y + 1 < ny ? f.Current.Lane(0, y + 1) : f.ZeroRow.data();
    uint64_t* acc = f.Accumulated.Lane(0, y);
    // Lanes 0, 1, nx - 2 and nx - 1 read words beyond their row: they are computed from
    // copies with zero lanes around them. The lanes between run in one flat loop.
    const int inner0 = std::max(region.X0, 2), inner1 = std::min(region.X1, nx - 3);
    InnerRow<Metric>(up, mid, down, below, above, acc, out, inner0 * W, (inner1 + 1) * W, W);
    for (int x = region.X0; x <= region.X1; ++x)
    {
      if (x >= inner0 && x <= inner1)
      {
        x = inner1;
        continue;
      }
      // Rows of the padded copy: a zero word, lanes x - 1, x, x + 1, a zero word.
      const uint64_t* rows[3] = { up, mid, down };
      uint64_t* copy[3];
      for (int r = 0; r < 3; ++r)
      {
        copy[r] = pad.data() + r * (3 * W + 2);
        for (int dx = -1; dx <= 1; ++dx)
        {
          const bool inside = x + dx >= 0 && x + dx < nx;
          for (int64_t w = 0; w < W; ++w)
          {
            copy[r][1 + (dx + 1) * W + w] = inside ? rows[r][(x + dx) * W + w] : 0;
          }
        }
      }
      for (int64_t w = 0; w < W; ++w)
      {
        const int64_t i = x * W + w;
        const uint64_t o =
          Candidates<Metric>(copy[0], copy[1], copy[2], 1 + W + w, W, below[i], above[i]) & ~acc[i];
        out[i] = o;
        acc[i] |= o;
      }
    }
    // The words [lo, hi] of the row hold all its new voxels.
    int64_t lo = region.X0 * W, hi = (region.X1 + 1) * W - 1;
    while (lo <= hi && !out[lo])
    {
      ++lo;
    }
    while (hi > lo && !out[hi])
    {
      --hi;
    }
    if (lo > hi)
    {
      // `out` is zero: nothing is left in this row of `Next`.
      continue;
    }
    // The low bits of the layer index, one bit plane at a time.
    for (int k = 0; k < LowBits; ++k)
    {
      if ((layer >> k) & 1)
      {
        OrRow(f.Planes[k].Lane(0, y), out, lo, hi);
      }
    }
    ++rowsReached;
    LaneRange found;
    found.X0 = static_cast<int>(lo / W), found.X1 = static_cast<int>(hi / W);
    f.NextRows[y] = found;
    f.BlockRows[y].Merge(found);
  }
  return rowsReached;
}

/// The end of a block of layers: the voxels reached since `BlockStart` get the block's
/// bits of their layer index (`block` = layer >> LowBits) in the high planes, within the
/// lanes where the block's layers were found (BlockRows, then reset), and `BlockStart`
/// catches up. Returns how many voxels the block reached.
int64_t EndBlock(Wavefront& f, int32_t block, const ParallelFor& parallelFor)
{
  const int64_t W = f.W;
  int64_t reached = 0;
  std::mutex merge;
  parallelFor(f.NY,
    4,
    [&](int64_t begin, int64_t end)
    {
      int64_t count = 0;
      for (int y = static_cast<int>(begin); y < end; ++y)
      {
        const LaneRange lanes = f.BlockRows[y];
        f.BlockRows[y] = LaneRange();
        if (lanes.Empty())
        {
          continue;
        }
        const uint64_t* __restrict now = f.Accumulated.Lane(0, y);
        uint64_t* __restrict before = f.BlockStart.Lane(0, y);
        const int64_t lo = lanes.X0 * W, hi = (lanes.X1 + 1) * W;
        count += CountNewBits(now + lo, before + lo, hi - lo);
        for (int k = LowBits; (int32_t(1) << k) <= (block << LowBits); ++k)
        {
          if (((block << LowBits) >> k) & 1)
          {
            uint64_t* __restrict plane = f.Planes[k].Lane(0, y);
            for (int64_t i = lo; i < hi; ++i)
            {
              plane[i] |= now[i] & ~before[i];
            }
          }
        }
        std::copy(now + lo, now + hi, before + lo);
      }
      std::lock_guard<std::mutex> guard(merge);
      reached += count;
    });
  return reached;
}

/// 256 bytes spread to bits: byte j of Spread[b] is bit j of b.
struct ByteSpread
{
  uint64_t Table[256];
  ByteSpread()
  {
    for (int b = 0; b < 256; ++b)
    {
      Table[b] = 0;
      for (int j = 0; j < 8; ++j)
      {
        Table[b] |= uint64_t((b >> j) & 1) << (8 * j);
      }
    }
  }
};

/// The layer indices of the rows (y, w) = (task / W, task % W) for task in [begin, end),
/// from the bit planes, written x fastest: 64 lanes by 64 voxels of every plane are
/// transposed at a time, so that each output row is written once, in order (the lanes
/// run along z, the array along x).
VTKDF_INLINE void WriteDistancesLoop(const Wavefront& f,
  const BitVolume* inside,
  int32_t unreached,
  int32_t* distance,
  int64_t begin,
  int64_t end)
{
  static const ByteSpread spread;
  const int nx = f.NX, nz = f.NZ, W = f.W;
  const int planes = static_cast<int>(f.Planes.size());
  const int64_t slice = int64_t(nx) * f.NY;
  // Tiles: the planes, then the reached voxels, then the inside voxels.
  std::vector<uint64_t> tiles((planes + 2) * 64);
  uint64_t* reachedTile = tiles.data() + planes * 64;
  uint64_t* insideTile = reachedTile + 64;
  for (int64_t task = begin; task < end; ++task)
  {
    const int y = static_cast<int>(task / W), w = static_cast<int>(task % W);
    const int rows = std::min(64, nz - 64 * w);
    for (int x0 = 0; x0 < nx; x0 += 64)
    {
      const int columns = std::min(64, nx - x0);
      auto load = [&](const BitVolume& v, uint64_t* tile)
      {
        for (int c = 0; c < 64; ++c)
        {
          tile[c] = c < columns ? v.Lane(x0 + c, y)[w] : 0;
        }
        TransposeBits64(tile);
      };
      for (int k = 0; k < planes; ++k)
      {
        load(f.Planes[k], tiles.data() + 64 * k);
      }
      load(f.Accumulated, reachedTile);
      if (inside)
      {
        load(*inside, insideTile);
      }
      for (int r = 0; r < rows; ++r)
      {
        // Bytes per voxel of the row: the low and the high eight planes, reached,
        // inside; spread from the tiles eight voxels at a time.
        alignas(16) uint8_t low[64], high[64], reached[64], negative[64];
        for (int c0 = 0; c0 < 64; c0 += 8)
        {
          auto bytesOf = [&](const uint64_t* tile) { return spread.Table[(tile[r] >> c0) & 255]; };
          uint64_t lowBytes = 0, highBytes = 0;
          for (int k = 0; k < std::min(planes, 8); ++k)
          {
            lowBytes |= bytesOf(tiles.data() + 64 * k) << k;
          }
          for (int k = 8; k < std::min(planes, 16); ++k)
          {
            highBytes |= bytesOf(tiles.data() + 64 * k) << (k - 8);
          }
          const uint64_t reachedBytes = bytesOf(reachedTile);
          const uint64_t negativeBytes = inside ? bytesOf(insideTile) : 0;
          std::memcpy(low + c0, &lowBytes, 8);
          std::memcpy(high + c0, &highBytes, 8);
          std::memcpy(reached + c0, &reachedBytes, 8);
          std::memcpy(negative + c0, &negativeBytes, 8);
        }
        alignas(16) int32_t value[64];
        for (int c = 0; c < 64; ++c)
        {
          value[c] = low[c] | (high[c] << 8);
        }
        for (int k = 16; k < planes; ++k) // more than 2^16 layers
        {
          for (int c = 0; c < 64; ++c)
          {
            value[c] |= static_cast<int32_t>((tiles[64 * k + r] >> c) & 1) << k;
          }
        }
        int32_t* row = distance + x0 + y * int64_t(nx) + (64 * w + r) * slice;
        for (int c = 0; c < columns; ++c)
        {
          const int32_t v = reached[c] ? value[c] : unreached;
          row[c] = negative[c] ? -v : v;
        }
      }
    }
  }
}

#ifdef VTKDF_HAVE_AVX2_CLONES
__attribute__((target("avx2"))) void WriteDistancesAVX2(const Wavefront& f,
  const BitVolume* inside,
  int32_t unreached,
  int32_t* distance,
  int64_t begin,
  int64_t end)
{
  WriteDistancesLoop(f, inside, unreached, distance, begin, end);
}
#endif

/// The int32 layer indices of every voxel (negated inside), from the bit planes.
void WriteDistances(const Wavefront& f,
  const BitVolume* inside,
  int32_t unreached,
  int32_t* distance,
  const ParallelFor& parallelFor)
{
  parallelFor(int64_t(f.NY) * f.W,
    1,
    [&](int64_t begin, int64_t end)
    {
#ifdef VTKDF_HAVE_AVX2_CLONES
      if (HaveAVX2())
      {
        WriteDistancesAVX2(f, inside, unreached, distance, begin, end);
        return;
      }
#endif
      WriteDistancesLoop(f, inside, unreached, distance, begin, end);
    });
}

/// The Manhattan field is the L1 distance transform of the zero set (its layers beyond a
/// limit unreached), which is separable: the distance along z to the nearest zero voxel
/// of the lane, then min over x' of (|x - x'| + that), then the same over y'. Two passes
/// over the output instead of one per layer. Pass 1, a row y of lanes at a time (the
/// lanes of a row lie side by side): the z and x transforms in a buffer of the row's
/// lanes, then written into the row y of every z-slice, each value doubled and its inside
/// bit added (the y transform keeps each voxel's own bit: min(e, ((e' >> 1) + 1) << 1 |
/// (e & 1)) compares the distances alone). Pass 2, a z-slice at a time (in cache): the y
/// transform, and each value decoded (unreached beyond the limit) and signed. The layer
/// indices are the wavefront's, bit for bit: a voxel's layer is its L1 distance to the
/// zero set.
constexpr int32_t Far = int32_t(1) << 29; // beyond any distance on a grid of int extents

/// Along z, for every lane x of row y: the distance to the lane's nearest zero voxel (Far
/// where the lane has none), into `lanes` (x-major: lane x's z run). The zero voxels are
/// found a word at a time (most words hold none), and each run between two of them is
/// filled in one loop the compiler vectorizes.
VTKDF_INLINE void LaneDistances(const BitVolume& zero, int y, int32_t* lanes)
{
  const int nx = zero.Size(0), nz = zero.Size(2), words = zero.WordsPerLane();
  const uint64_t last = zero.LastWordMask(); // the bits past nz are not voxels
  for (int x = 0; x < nx; ++x)
  {
    const uint64_t* lane = zero.Lane(x, y);
    int32_t* __restrict d = lanes + int64_t(x) * nz;
    int32_t previous = -1; // the last zero voxel so far
    for (int w = 0; w < words; ++w)
    {
      for (uint64_t bits = lane[w] & (w + 1 < words ? ~uint64_t(0) : last); bits != 0;
           bits &= bits - 1)
      {
        const int32_t z = 64 * w + __builtin_ctzll(bits);
        if (previous < 0)
        {
          for (int32_t k = 0; k < z; ++k)
          {
            d[k] = z - k;
          }
        }
        else
        {
          for (int32_t k = previous + 1; k < z; ++k)
          {
            d[k] = std::min(k - previous, z - k);
          }
        }
        d[z] = 0;
        previous = z;
      }
    }
    if (previous < 0)
    {
      std::fill(d, d + nz, Far);
    }
    else
    {
      for (int32_t k = previous + 1; k < nz; ++k)
      {
        d[k] = k - previous;
      }
    }
  }
}

/// Writes the lanes' z runs (x-major, nz each) into row y of every slice, in tiles of
/// 16 x 16: the runs read across, the output rows written along, whole cache lines at a
/// time (a lane's run written down the slices would touch one line per value). With
/// `Encoded`, each value doubled plus the voxel's bit of `inside` (optional).
template<bool Encoded>
VTKDF_INLINE void WriteLaneRows(const int32_t* lanes,
  const BitVolume* inside,
  int nx,
  int nz,
  int64_t slice,
  int64_t y,
  int32_t* distance)
{
  for (int z0 = 0; z0 < nz; z0 += 16)
  {
    const int z1 = std::min(nz, z0 + 16);
    for (int x0 = 0; x0 < nx; x0 += 16)
    {
      const int x1 = std::min(nx, x0 + 16);
      for (int z = z0; z < z1; ++z)
      {
        int32_t* __restrict out = distance + z * slice + y * nx;
        const int32_t* __restrict d = lanes + z;
        if (!Encoded)
        {
          for (int x = x0; x < x1; ++x)
          {
            out[x] = d[int64_t(x) * nz];
          }
          continue;
        }
        const int word = z >> 6, shift = z & 63;
        for (int x = x0; x < x1; ++x)
        {
          const int32_t bit = inside
            ? static_cast<int32_t>((inside->Lane(x, static_cast<int>(y))[word] >> shift) & 1)
            : 0;
          out[x] = (d[int64_t(x) * nz] << 1) | bit;
        }
      }
    }
  }
}

VTKDF_INLINE void ManhattanRowsLoop(const BitVolume& zero,
  const BitVolume* inside,
  int32_t* distance,
  int64_t begin,
  int64_t end)
{
  const int nx = zero.Size(0), ny = zero.Size(1), nz = zero.Size(2);
  const int64_t slice = int64_t(nx) * ny;
  std::vector<int32_t> lanes(static_cast<size_t>(nx) * nz); // x-major: lane x's z run
  for (int64_t y = begin; y < end; ++y)
  {
    LaneDistances(zero, static_cast<int>(y), lanes.data());
    // Along x: forward and backward, a whole lane at a time.
    for (int x = 1; x < nx; ++x)
    {
      const int32_t* __restrict previous = lanes.data() + int64_t(x - 1) * nz;
      int32_t* __restrict current = lanes.data() + int64_t(x) * nz;
      for (int z = 0; z < nz; ++z)
      {
        current[z] = std::min(current[z], previous[z] + 1);
      }
    }
    for (int x = nx - 2; x >= 0; --x)
    {
      const int32_t* __restrict previous = lanes.data() + int64_t(x + 1) * nz;
      int32_t* __restrict current = lanes.data() + int64_t(x) * nz;
      for (int z = 0; z < nz; ++z)
      {
        current[z] = std::min(current[z], previous[z] + 1);
      }
    }
    // Into row y of every slice, doubled, with the inside bit.
    WriteLaneRows<true>(lanes.data(), inside, nx, nz, slice, y, distance);
  }
}

VTKDF_INLINE void ManhattanSlicesLoop(int nx,
  int ny,
  int32_t limit,
  int32_t unreached,
  int32_t* distance,
  int64_t begin,
  int64_t end,
  int32_t& largest,
  int64_t& reached)
{
  const int64_t slice = int64_t(nx) * ny;
  int32_t top = largest;
  for (int64_t z = begin; z < end; ++z)
  {
    int32_t* s = distance + z * slice;
    for (int pass = 0; pass < 2; ++pass)
    {
      for (int k = 1; k < ny; ++k)
      {
        const int y = pass == 0 ? k : ny - 1 - k;
        const int32_t* __restrict previous = s + int64_t(pass == 0 ? y - 1 : y + 1) * nx;
        int32_t* __restrict current = s + int64_t(y) * nx;
        for (int x = 0; x < nx; ++x)
        {
          const int32_t e = current[x];
          const int32_t candidate = ((((previous[x] >> 1) + 1) << 1) | (e & 1));
          current[x] = std::min(e, candidate);
        }
      }
    }
    // Decoded and signed, branch-free so that it vectorizes.
    for (int y = 0; y < ny; ++y)
    {
      int32_t* __restrict row = s + int64_t(y) * nx;
      int32_t count = 0;
      for (int x = 0; x < nx; ++x)
      {
        const int32_t e = row[x];
        const int32_t layer = e >> 1;
        const int32_t near = -static_cast<int32_t>(layer <= limit); // all ones when reached
        top = std::max(top, layer & near);
        count -= near;
        const int32_t value = (layer & near) | (unreached & ~near);
        const int32_t negate = -(e & 1);
        row[x] = (value ^ negate) - negate;
      }
      reached += count;
    }
  }
  largest = top;
}

#ifdef VTKDF_HAVE_AVX2_CLONES
__attribute__((target("avx2"))) void ManhattanRowsAVX2(const BitVolume& zero,
  const BitVolume* inside,
  int32_t* distance,
  int64_t begin,
  int64_t end)
{
  ManhattanRowsLoop(zero, inside, distance, begin, end);
}

__attribute__((target("avx2"))) void ManhattanSlicesAVX2(int nx,
  int ny,
  int32_t limit,
  int32_t unreached,
  int32_t* distance,
  int64_t begin,
  int64_t end,
  int32_t& largest,
  int64_t& reached)
{
  ManhattanSlicesLoop(nx, ny, limit, unreached, distance, begin, end, largest, reached);
}
#endif

/// The Manhattan field (a non-empty zero set), separably; the layers beyond `limit`
/// unreached. Each pass runs in batches of rows or slices, with progress (and abort)
/// between them.
ChamferResult SeparableManhattan(const BitVolume& zero,
  const BitVolume* inside,
  int32_t limit,
  int32_t unreached,
  int32_t* distance,
  const ParallelFor& parallelFor,
  const ProgressCallback& progress,
  int64_t zeroSet)
{
  ChamferResult result;
  result.ZeroSet = zeroSet;
  const int nx = zero.Size(0), ny = zero.Size(1), nz = zero.Size(2);
  constexpr int Batches = 8;
  std::mutex merge;
  for (int pass = 0; pass < 2; ++pass)
  {
    const int64_t total = pass == 0 ? ny : nz;
    for (int batch = 0; batch < Batches; ++batch)
    {
      const int64_t first = total * batch / Batches, last = total * (batch + 1) / Batches;
      parallelFor(last - first,
        1,
        [&](int64_t begin, int64_t end)
        {
          begin += first, end += first;
          if (pass == 0)
          {
#ifdef VTKDF_HAVE_AVX2_CLONES
            if (HaveAVX2())
            {
              ManhattanRowsAVX2(zero, inside, distance, begin, end);
              return;
            }
#endif
            ManhattanRowsLoop(zero, inside, distance, begin, end);
            return;
          }
          int32_t largest = 0;
          int64_t reached = 0;
#ifdef VTKDF_HAVE_AVX2_CLONES
          if (HaveAVX2())
          {
            ManhattanSlicesAVX2(nx, ny, limit, unreached, distance, begin, end, largest, reached);
          }
          else
#endif
          {
            ManhattanSlicesLoop(nx, ny, limit, unreached, distance, begin, end, largest, reached);
          }
          std::lock_guard<std::mutex> guard(merge);
          result.Layers = std::max(result.Layers, largest);
          result.Reached += reached;
        });
      if (progress && !progress(double(pass * Batches + batch + 1) / (2 * Batches)))
      {
        result.Aborted = true;
        return result;
      }
    }
  }
  return result;
}

/// The chessboard fields (18 and 26 neighbours) in three sweeps of the output instead of
/// one pass per layer (a limit only leaves the layers beyond it unreached). A voxel's
/// layer index is the fewest steps from the zero set, each to a neighbour of the metric.
/// A shortest path can be taken monotone (no step moves a coordinate away from the end
/// point; with 18 neighbours, a displacement (a, b, c), a >= b >= c >= 0, takes max(a,
/// ceil((a + b + c) / 2)) steps of (1, 1, 0), (1, 0, 1), (0, 1, 1) and (1, 0, 0)), and
/// the steps of a monotone path can be reordered without leaving the box between its
/// ends, so without leaving the grid: first the steps along z alone, then those that
/// move x (and maybe z), then those that move y (and maybe x and z). Each class is a
/// sweep along its axis, forward then backward, in which a voxel takes min(its value, a
/// neighbour's in the previous lane or plane + 1):
///   pass 1, a row y of lanes at a time: the distance along z to each lane's nearest zero
///   voxel, then the x sweeps across the row's lanes (their z runs side by side), written
///   into row y of every slice;
///   pass 2, y ascending: every row (y, z) from the rows y - 1;
///   pass 3, y descending: every row (y, z) from the rows y + 1, then signed and written.
/// Every value is the length of a path and the reordered shortest paths are among them:
/// the layer indices are the wavefront's, bit for bit. Passes 2 and 3 are parallel over
/// z within each y.

/// An x step across lanes of nz voxels: current[z] = min(current[z], the least of
/// previous[z - 1..z + 1] + 1) (an x step may also move z by one in both metrics).
VTKDF_INLINE void ChessboardLaneStep(const int32_t* __restrict previous,
  int32_t* __restrict current,
  int nz)
{
  if (nz == 1)
  {
    current[0] = std::min(current[0], previous[0] + 1);
    return;
  }
  current[0] = std::min(current[0], std::min(previous[0], previous[1]) + 1);
  for (int z = 1; z < nz - 1; ++z)
  {
    current[z] =
      std::min(current[z], std::min(std::min(previous[z - 1], previous[z]), previous[z + 1]) + 1);
  }
  current[nz - 1] = std::min(current[nz - 1], std::min(previous[nz - 2], previous[nz - 1]) + 1);
}

/// Pass 1 for rows [begin, end).
VTKDF_INLINE void ChessboardRowsLoop(const BitVolume& zero,
  int32_t* distance,
  int64_t begin,
  int64_t end)
{
  const int nx = zero.Size(0), ny = zero.Size(1), nz = zero.Size(2);
  const int64_t slice = int64_t(nx) * ny;
  std::vector<int32_t> lanes(static_cast<size_t>(nx) * nz); // x-major: lane x's z run
  for (int64_t y = begin; y < end; ++y)
  {
    LaneDistances(zero, static_cast<int>(y), lanes.data());
    for (int x = 1; x < nx; ++x)
    {
      ChessboardLaneStep(lanes.data() + int64_t(x - 1) * nz, lanes.data() + int64_t(x) * nz, nz);
    }
    for (int x = nx - 2; x >= 0; --x)
    {
      ChessboardLaneStep(lanes.data() + int64_t(x + 1) * nz, lanes.data() + int64_t(x) * nz, nz);
    }
    WriteLaneRows<false>(lanes.data(), nullptr, nx, nz, slice, y, distance);
  }
}

/// The least value among the metric's neighbours, in the rows of the previous y, of each
/// voxel of a row (y, z): `below`, `at`, `above` are the rows z - 1, z, z + 1 of that y
/// (at the grid's ends the row itself). Chessboard26: x - 1..x + 1 of all three;
/// Chessboard18 (a step moves one coordinate besides y at most): x - 1..x + 1 of `at` and
/// x of the others. `column` is scratch; nx ints each.
template<ChamferMetric Metric>
VTKDF_INLINE void NeighbourLeast(const int32_t* __restrict below,
  const int32_t* __restrict at,
  const int32_t* __restrict above,
  int32_t* __restrict column,
  int32_t* __restrict least,
  int nx)
{
  for (int x = 0; x < nx; ++x)
  {
    column[x] = Metric == ChamferMetric::Chessboard26
      ? std::min(std::min(below[x], at[x]), above[x])
      : std::min(below[x], above[x]);
  }
  const int32_t* across = Metric == ChamferMetric::Chessboard26 ? column : at;
  if (nx == 1)
  {
    least[0] = std::min(column[0], at[0]);
    return;
  }
  least[0] = std::min(std::min(column[0], at[0]), across[1]);
  for (int x = 1; x < nx - 1; ++x)
  {
    least[x] = std::min(std::min(column[x], at[x]), std::min(across[x - 1], across[x + 1]));
  }
  least[nx - 1] = std::min(std::min(column[nx - 1], at[nx - 1]), across[nx - 2]);
}

/// row[x] = min(row[x], least[x] + 1).
VTKDF_INLINE void StepRow(const int32_t* __restrict least, int32_t* __restrict row, int nx)
{
  for (int x = 0; x < nx; ++x)
  {
    row[x] = std::min(row[x], least[x] + 1);
  }
}

/// The same step, the raw values into `raw` and the row finished: `unreached` beyond
/// `limit`, negated where negate[x] is -1 (else 0); the largest layer into `top`.
/// Returns the voxels reached. Branch-free, so that it vectorizes.
VTKDF_INLINE int32_t StepAndFinishRow(const int32_t* __restrict least,
  const int32_t* __restrict negate,
  int32_t limit,
  int32_t unreached,
  int32_t* __restrict row,
  int32_t* __restrict raw,
  int nx,
  int32_t& top)
{
  int32_t largest = top, count = 0;
  for (int x = 0; x < nx; ++x)
  {
    const int32_t e = std::min(row[x], least[x] + 1);
    raw[x] = e;
    const int32_t near = -static_cast<int32_t>(e <= limit); // all ones when reached
    largest = std::max(largest, e & near);
    count -= near;
    const int32_t value = (e & near) | (unreached & ~near);
    row[x] = (value ^ negate[x]) - negate[x];
  }
  top = largest;
  return count;
}

/// One y step of the chessboard sweep: the rows (y, z) of the output `Distance`, from
/// the rows of the previous y (row z at Previous + z * PreviousStride). Forward (pass 2):
/// in place. Backward (pass 3): each row's raw values also go to row z of `Raw` (z-major,
/// the next step's Previous), and the row is written finished: Unreached beyond Limit,
/// negated at the voxels of `Inside` (optional).
struct ChessboardYStep
{
  const int32_t* Previous;
  int64_t PreviousStride;
  int32_t* Distance;
  int Y, NX, NY, NZ;
  int32_t* Raw;
  const BitVolume* Inside;
  int32_t Limit; // the layers beyond it unreached
  int32_t Unreached;
};

/// The step for rows z in [begin, end); a backward step counts what it writes into
/// `largest` (the largest layer) and `reached`.
template<ChamferMetric Metric, bool Backward>
VTKDF_INLINE void ChessboardYStepLoop(const ChessboardYStep& step,
  int64_t begin,
  int64_t end,
  int32_t& largest,
  int64_t& reached)
{
  const int nx = step.NX, y = step.Y;
  const int64_t slice = int64_t(nx) * step.NY, stride = step.PreviousStride;
  std::vector<int32_t> scratch(3 * static_cast<size_t>(nx));
  int32_t* column = scratch.data();
  int32_t* least = column + nx;
  int32_t* negate = least + nx; // -1 inside, else 0
  int32_t top = largest;
  int64_t count = 0;
  for (int64_t z = begin; z < end; ++z)
  {
    const int32_t* at = step.Previous + z * stride;
    NeighbourLeast<Metric>(
      z > 0 ? at - stride : at, at, z + 1 < step.NZ ? at + stride : at, column, least, nx);
    int32_t* row = step.Distance + z * slice + int64_t(y) * nx;
    if (!Backward)
    {
      StepRow(least, row, nx);
      continue;
    }
    if (step.Inside)
    {
      const int word = static_cast<int>(z >> 6), shift = static_cast<int>(z & 63);
      for (int x = 0; x < nx; ++x)
      {
        negate[x] = -static_cast<int32_t>((step.Inside->Lane(x, y)[word] >> shift) & 1);
      }
    }
    count +=
      StepAndFinishRow(least, negate, step.Limit, step.Unreached, row, step.Raw + z * nx, nx, top);
  }
  largest = top;
  reached += count;
}

#ifdef VTKDF_HAVE_AVX2_CLONES
__attribute__((target("avx2"))) void ChessboardRowsAVX2(const BitVolume& zero,
  int32_t* distance,
  int64_t begin,
  int64_t end)
{
  ChessboardRowsLoop(zero, distance, begin, end);
}

template<ChamferMetric Metric, bool Backward>
__attribute__((target("avx2"))) void ChessboardYStepAVX2(const ChessboardYStep& step,
  int64_t begin,
  int64_t end,
  int32_t& largest,
  int64_t& reached)
{
  ChessboardYStepLoop<Metric, Backward>(step, begin, end, largest, reached);
}
#endif

/// Runs a y step over every row (y, z), parallel over z, in tasks of about 2048 voxels
/// (at 256^3, 26 tasks a step: enough for 16 threads).
template<ChamferMetric Metric, bool Backward>
void RunChessboardYStep(const ChessboardYStep& step,
  const ParallelFor& parallelFor,
  std::mutex& merge,
  ChamferResult& result)
{
  parallelFor(step.NZ,
    std::max<int64_t>(1, 2048 / step.NX),
    [&](int64_t begin, int64_t end)
    {
      int32_t largest = 0;
      int64_t reached = 0;
#ifdef VTKDF_HAVE_AVX2_CLONES
      if (HaveAVX2())
      {
        ChessboardYStepAVX2<Metric, Backward>(step, begin, end, largest, reached);
      }
      else
#endif
      {
        ChessboardYStepLoop<Metric, Backward>(step, begin, end, largest, reached);
      }
      if (Backward)
      {
        std::lock_guard<std::mutex> guard(merge);
        result.Layers = std::max(result.Layers, largest);
        result.Reached += reached;
      }
    });
}

template<ChamferMetric Metric>
ChamferResult SweepChessboard(const BitVolume& zero,
  const BitVolume* inside,
  int32_t limit,
  int32_t unreached,
  int32_t* distance,
  const ParallelFor& parallelFor,
  const ProgressCallback& progress,
  int64_t zeroSet)
{
  ChamferResult result;
  result.ZeroSet = zeroSet;
  const int nx = zero.Size(0), ny = zero.Size(1), nz = zero.Size(2);
  const int64_t slice = int64_t(nx) * ny;
  constexpr int Batches = 8;
  // Progress after each eighth of a pass's rows.
  auto report = [&](int pass, int y0, int y1)
  {
    const int64_t b0 = int64_t(y0) * Batches / ny, b1 = int64_t(y1) * Batches / ny;
    return b0 == b1 || !progress || progress(double(pass * Batches + b1) / (3 * Batches));
  };
  std::mutex merge;
  // Pass 1: the z and x steps, a batch of rows of lanes at a time.
  for (int batch = 0; batch < Batches; ++batch)
  {
    const int64_t first = int64_t(ny) * batch / Batches, last = int64_t(ny) * (batch + 1) / Batches;
    parallelFor(last - first,
      1,
      [&](int64_t begin, int64_t end)
      {
#ifdef VTKDF_HAVE_AVX2_CLONES
        if (HaveAVX2())
        {
          ChessboardRowsAVX2(zero, distance, first + begin, first + end);
          return;
        }
#endif
        ChessboardRowsLoop(zero, distance, first + begin, first + end);
      });
    if (progress && !progress(double(batch + 1) / (3 * Batches)))
    {
      result.Aborted = true;
      return result;
    }
  }
  // Pass 2: the y steps forward, in place.
  for (int y = 1; y < ny; ++y)
  {
    const ChessboardYStep step = { distance + int64_t(y - 1) * nx,
      slice,
      distance,
      y,
      nx,
      ny,
      nz,
      nullptr,
      nullptr,
      limit,
      unreached };
    RunChessboardYStep<Metric, false>(step, parallelFor, merge, result);
    if (!report(1, y, y + 1))
    {
      result.Aborted = true;
      return result;
    }
  }
  // Pass 3: the y steps backward, from the raw values of the next y (`next`, a plane of
  // rows z-major), each row finished as it is stepped. The last row has no step: it
  // takes one from a plane of Far, which changes nothing.
  std::vector<int32_t> next(static_cast<size_t>(nx) * nz, Far), current(next.size());
  for (int y = ny - 1; y >= 0; --y)
  {
    const ChessboardYStep step = {
      next.data(), nx, distance, y, nx, ny, nz, current.data(), inside, limit, unreached
    };
    RunChessboardYStep<Metric, true>(step, parallelFor, merge, result);
    std::swap(next, current);
    if (!report(2, ny - y - 1, ny - y))
    {
      result.Aborted = true;
      return result;
    }
  }
  return result;
}
} // namespace

ChamferResult ChamferPropagate(const BitVolume& zero,
  ChamferMetric metric,
  int maximumLayers,
  int32_t unreached,
  const BitVolume* inside,
  int32_t* distance,
  const ParallelFor& parallelFor,
  const ProgressCallback& progress)
{
  // The sweeps pass over the whole array a fixed number of times, the wavefront over the
  // lanes it reaches once a layer: the separable Manhattan transform is the faster from
  // the first layer on, the chessboard sweeps beyond about WavefrontLayers layers
  // (measured on the bunny's boundary: the wavefront as fast at 16 layers at 512^3, at 24
  // at 256^3). Same bits either way, the layers beyond a limit unreached.
  constexpr int WavefrontLayers = 24;
  if (metric == ChamferMetric::Manhattan || maximumLayers <= 0 || maximumLayers > WavefrontLayers)
  {
    const int64_t zeroSet = zero.Count();
    // No path is as long as Far: the limit stops below it.
    const int32_t limit = maximumLayers > 0 ? std::min(maximumLayers, Far - 1) : Far - 1;
    if (zeroSet > 0)
    {
      switch (metric)
      {
        case ChamferMetric::Manhattan:
          return SeparableManhattan(
            zero, inside, limit, unreached, distance, parallelFor, progress, zeroSet);
        case ChamferMetric::Chessboard18:
          return SweepChessboard<ChamferMetric::Chessboard18>(
            zero, inside, limit, unreached, distance, parallelFor, progress, zeroSet);
        case ChamferMetric::Chessboard26:
          return SweepChessboard<ChamferMetric::Chessboard26>(
            zero, inside, limit, unreached, distance, parallelFor, progress, zeroSet);
      }
    }
  }
  ChamferResult result;
  Wavefront f;
  f.NX = zero.Size(0), f.NY = zero.Size(1), f.NZ = zero.Size(2), f.W = zero.WordsPerLane();
  const int nx = f.NX, ny = f.NY, W = f.W;
  const int64_t total = int64_t(nx) * ny * f.NZ;
  f.Current = zero;
  f.Next.Resize(nx, ny, f.NZ);
  f.Accumulated = zero;
  f.ZeroRow.assign(int64_t(nx) * W, 0);
  f.Below.resize(int64_t(nx) * W);
  f.Above.resize(int64_t(nx) * W);
  for (int64_t i = 0; i < int64_t(nx) * W; ++i)
  {
    f.Below[i] = i % W > 0 ? ~uint64_t(0) : 0;
    f.Above[i] = i % W + 1 < W ? ~uint64_t(0) : 0;
  }
  const uint64_t padding = ~zero.LastWordMask();

  // Layer 0: the zero set, and the lanes of each row that hold it.
  f.CurrentRows.assign(ny, LaneRange());
  f.NextRows.assign(ny, LaneRange());
  f.BlockRows.assign(ny, LaneRange());
  int rows0 = ny, rows1 = -1; // the rows where `Current` or `Next` may hold bits
  for (int y = 0; y < ny; ++y)
  {
    uint64_t* row = f.Accumulated.Lane(0, y);
    for (int x = 0; x < nx; ++x)
    {
      bool any = false;
      for (int w = 0; w < W; ++w)
      {
        any = any || row[x * W + w] != 0;
      }
      row[x * W + W - 1] |= padding; // never candidates
      if (any)
      {
        f.CurrentRows[y].Merge(LaneRange{ x, x });
        rows0 = std::min(rows0, y), rows1 = std::max(rows1, y);
      }
    }
  }
  // Block 0 starts with nothing reached (the bits past nz aside), so that its end counts
  // the zero set too.
  f.BlockStart.Resize(nx, ny, f.NZ);
  for (int64_t lane = 0; lane < int64_t(nx) * ny; ++lane)
  {
    f.BlockStart.Data()[lane * W + W - 1] = padding;
  }
  f.BlockRows = f.CurrentRows;
  result.ZeroSet = CountNewBits(
    zero.Data().data(), f.BlockStart.Data().data(), static_cast<int64_t>(zero.Data().size()));

  for (int layer = 1; result.ZeroSet > 0 && (maximumLayers <= 0 || layer <= maximumLayers); ++layer)
  {
    for (int k = static_cast<int>(f.Planes.size()); (int32_t(1) << k) <= layer; ++k)
    {
      f.Planes.emplace_back(nx, ny, f.NZ);
    }
    // Rows next to the current layer get candidates; rows of `Next` holding an older
    // layer get cleared.
    const int y0 = std::max(0, rows0 - 1), y1 = std::min(ny - 1, rows1 + 1);
    int64_t rowsReached = 0;
    std::mutex merge;
    parallelFor(y1 - y0 + 1,
      4,
      [&](int64_t begin, int64_t end)
      {
        auto rows = [&](auto metricTag)
        { return LayerRows<decltype(metricTag)::value>(f, y0, begin, end, layer); };
        int64_t localRows = 0;
        switch (metric)
        {
          case ChamferMetric::Manhattan:
            localRows = rows(MetricTag<ChamferMetric::Manhattan>());
            break;
          case ChamferMetric::Chessboard18:
            localRows = rows(MetricTag<ChamferMetric::Chessboard18>());
            break;
          case ChamferMetric::Chessboard26:
            localRows = rows(MetricTag<ChamferMetric::Chessboard26>());
            break;
        }
        std::lock_guard<std::mutex> guard(merge);
        rowsReached += localRows;
      });
    // Now `Current` gets layer `layer`, and `Next` the previous one.
    std::swap(f.Current, f.Next);
    std::swap(f.CurrentRows, f.NextRows);
    rows0 = y0, rows1 = y1;
    if (rowsReached == 0)
    {
      break;
    }
    result.Layers = layer;
    // The block's voxels are counted at its end, and progress reported then.
    if (((layer + 1) & ((1 << LowBits) - 1)) == 0)
    {
      result.Reached += EndBlock(f, layer >> LowBits, parallelFor);
      if (progress && !progress(double(result.Reached) / double(total)))
      {
        result.Aborted = true;
        return result;
      }
    }
  }
  if (((result.Layers + 1) & ((1 << LowBits) - 1)) != 0)
  {
    result.Reached += EndBlock(f, result.Layers >> LowBits, parallelFor); // a block left open
  }
  WriteDistances(f, inside, unreached, distance, parallelFor);
  return result;
}

} // namespace vtkdf
