#include "Voxels/ChamferPasses.h"

#include <algorithm>
#include <climits>
#include <cstring>
#include <mutex>
#include <type_traits>
#include <vector>

namespace vtkdf
{
namespace chamfer
{
namespace
{
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
} // namespace

ChamferResult PropagateWavefront(const BitVolume& zero,
  ChamferMetric metric,
  int maximumLayers,
  int32_t unreached,
  const BitVolume* inside,
  int32_t* distance,
  const ParallelFor& parallelFor,
  const ProgressCallback& progress)
{
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
} // namespace chamfer
} // namespace vtkdf
