#include "Voxels/ChamferPasses.h"

#include <algorithm>
#include <mutex>
#include <vector>

namespace vtkdf
{
namespace chamfer
{
namespace
{
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

ChamferResult SweepOutput(const BitVolume& zero,
  ChamferMetric metric,
  const BitVolume* inside,
  int32_t limit,
  int32_t unreached,
  int32_t* distance,
  const ParallelFor& parallelFor,
  const ProgressCallback& progress,
  int64_t zeroSet)
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
      break;
  }
  return SweepChessboard<ChamferMetric::Chessboard26>(
    zero, inside, limit, unreached, distance, parallelFor, progress, zeroSet);
}
} // namespace chamfer
} // namespace vtkdf
