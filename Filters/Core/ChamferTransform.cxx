#include "ChamferTransform.h"

#include <algorithm>
#include <climits>
#include <mutex>
#include <type_traits>
#include <vector>

namespace vtkdf
{
namespace
{
struct LaneBox
{
  int X0 = INT_MAX, X1 = INT_MIN, Y0 = INT_MAX, Y1 = INT_MIN;
  bool Empty() const { return X1 < X0; }
  void Add(int x, int y)
  {
    X0 = std::min(X0, x), X1 = std::max(X1, x);
    Y0 = std::min(Y0, y), Y1 = std::max(Y1, y);
  }
  void Merge(const LaneBox& o)
  {
    X0 = std::min(X0, o.X0), X1 = std::max(X1, o.X1);
    Y0 = std::min(Y0, o.Y0), Y1 = std::max(Y1, o.Y1);
  }
  LaneBox Grown(int nx, int ny) const
  {
    LaneBox g;
    if (!this->Empty())
    {
      g.X0 = std::max(0, X0 - 1), g.X1 = std::min(nx - 1, X1 + 1);
      g.Y0 = std::max(0, Y0 - 1), g.Y1 = std::min(ny - 1, Y1 + 1);
    }
    return g;
  }
};

/// Writes `value` at every set bit of a lane.
inline int64_t WriteLane(const uint64_t* lane,
  int words,
  int64_t first,
  int64_t stride,
  int32_t value,
  int32_t* distance)
{
  int64_t count = 0;
  for (int w = 0; w < words; ++w)
  {
    uint64_t bits = lane[w];
    while (bits)
    {
      const int z = 64 * w + __builtin_ctzll(bits);
      bits &= bits - 1;
      distance[first + z * stride] = value;
      ++count;
    }
  }
  return count;
}

/// n(w) of word `w` of a lane: its bits moved one voxel up and one down the lane.
inline uint64_t Shifted(const uint64_t* lane, int w, int words)
{
  return (lane[w] << 1) | (w > 0 ? lane[w - 1] >> 63 : 0) | (lane[w] >> 1) |
    (w + 1 < words ? lane[w + 1] << 63 : 0);
}

/// n'(w) = n(w) | w.
inline uint64_t Wide(const uint64_t* lane, int w, int words)
{
  return lane[w] | Shifted(lane, w, words);
}

/// Word `w` of the next layer's candidates from the lanes around (x, y) in the current
/// layer: `lanes[(dy + 1) * 3 + dx + 1]`, an all-zero lane outside the grid. A template
/// per metric, so that the compiler sees a fixed set of operations.
template<ChamferMetric Metric>
inline uint64_t Candidates(const uint64_t* const lanes[9], int w, int words)
{
  uint64_t v = Shifted(lanes[4], w, words);
  if (Metric == ChamferMetric::Manhattan)
  {
    v |= lanes[1][w] | lanes[3][w] | lanes[5][w] | lanes[7][w];
  }
  else
  {
    v |= Wide(lanes[1], w, words) | Wide(lanes[3], w, words) | Wide(lanes[5], w, words) |
      Wide(lanes[7], w, words);
    if (Metric == ChamferMetric::Chessboard18)
    {
      v |= lanes[0][w] | lanes[2][w] | lanes[6][w] | lanes[8][w];
    }
    else
    {
      v |= Wide(lanes[0], w, words) | Wide(lanes[2], w, words) | Wide(lanes[6], w, words) |
        Wide(lanes[8], w, words);
    }
  }
  return v;
}

template<ChamferMetric Metric>
using MetricTag = std::integral_constant<ChamferMetric, Metric>;

/// One layer over the rows [begin, end) of `region`: writes the new voxels into `next`
/// (and `accumulated`, and `distance`), grows `found`, returns how many were reached.
template<ChamferMetric Metric>
int64_t LayerRows(const BitVolume& current,
  BitVolume& next,
  BitVolume& accumulated,
  const uint64_t* zeroLane,
  const LaneBox& region,
  int64_t begin,
  int64_t end,
  int32_t layer,
  int32_t* distance,
  LaneBox& found)
{
  const int nx = current.Size(0), ny = current.Size(1);
  const int words = current.WordsPerLane();
  const uint64_t lastMask = current.LastWordMask();
  const uint64_t full = ~uint64_t(0);
  const int64_t slice = int64_t(nx) * ny;
  int64_t reached = 0;
  for (int y = region.Y0 + static_cast<int>(begin); y < region.Y0 + end; ++y)
  {
    for (int x = region.X0; x <= region.X1; ++x)
    {
      uint64_t* a = accumulated.Lane(x, y);
      bool saturated = true;
      for (int w = 0; w < words && saturated; ++w)
      {
        saturated = a[w] == (w + 1 == words ? lastMask : full);
      }
      if (saturated)
      {
        continue; // every voxel of the lane has its layer (`next` is clear here)
      }
      const uint64_t* lanes[9];
      for (int dy = -1; dy <= 1; ++dy)
      {
        for (int dx = -1; dx <= 1; ++dx)
        {
          const int ox = x + dx, oy = y + dy;
          const bool inside = ox >= 0 && oy >= 0 && ox < nx && oy < ny;
          lanes[(dy + 1) * 3 + dx + 1] = inside ? current.Lane(ox, oy) : zeroLane;
        }
      }
      uint64_t* out = next.Lane(x, y);
      uint64_t any = 0;
      for (int w = 0; w < words; ++w)
      {
        out[w] = Candidates<Metric>(lanes, w, words) & ~a[w] & (w + 1 == words ? lastMask : full);
        a[w] |= out[w];
        any |= out[w];
      }
      if (any)
      {
        found.Add(x, y);
        reached += WriteLane(out, words, x + int64_t(nx) * y, slice, layer, distance);
      }
    }
  }
  return reached;
}
} // namespace

ChamferResult ChamferPropagate(const BitVolume& zero,
  ChamferMetric metric,
  int maximumLayers,
  int32_t unreached,
  int32_t* distance,
  const ParallelFor& parallelFor,
  const ProgressCallback& progress)
{
  ChamferResult result;
  const int nx = zero.Size(0), ny = zero.Size(1), nz = zero.Size(2);
  const int words = zero.WordsPerLane();
  const int64_t total = int64_t(nx) * ny * nz, slice = int64_t(nx) * ny;
  parallelFor(total,
    1 << 16,
    [&](int64_t begin, int64_t end) { std::fill(distance + begin, distance + end, unreached); });

  // Layer 0: the zero set.
  BitVolume current = zero, next(nx, ny, nz), accumulated = zero;
  LaneBox box;
  for (int y = 0; y < ny; ++y)
  {
    for (int x = 0; x < nx; ++x)
    {
      const uint64_t* lane = zero.Lane(x, y);
      bool any = false;
      for (int w = 0; w < words && !any; ++w)
      {
        any = lane[w] != 0;
      }
      if (any)
      {
        box.Add(x, y);
        result.Reached += WriteLane(lane, words, x + int64_t(nx) * y, slice, 0, distance);
      }
    }
  }
  result.ZeroSet = result.Reached;
  if (box.Empty())
  {
    return result;
  }
  LaneBox written; // the lanes where `next` holds an older layer (cleared before reuse)

  const std::vector<uint64_t> zeroLane(words, 0); // the neighbours outside the grid
  for (int layer = 1; maximumLayers <= 0 || layer <= maximumLayers; ++layer)
  {
    // `next` holds layer - 2 within `written`: clear it there.
    for (int y = written.Y0; y <= written.Y1 && !written.Empty(); ++y)
    {
      std::fill(next.Lane(written.X0, y), next.Lane(written.X1, y) + words, 0);
    }
    const LaneBox region = box.Grown(nx, ny);
    LaneBox found;
    int64_t reached = 0;
    std::mutex merge;
    parallelFor(region.Y1 - region.Y0 + 1,
      4,
      [&](int64_t begin, int64_t end)
      {
        LaneBox localBox;
        int64_t localReached = 0;
        auto rows = [&](auto metricTag)
        {
          return LayerRows<decltype(metricTag)::value>(current,
            next,
            accumulated,
            zeroLane.data(),
            region,
            begin,
            end,
            layer,
            distance,
            localBox);
        };
        switch (metric)
        {
          case ChamferMetric::Manhattan:
            localReached = rows(MetricTag<ChamferMetric::Manhattan>());
            break;
          case ChamferMetric::Chessboard18:
            localReached = rows(MetricTag<ChamferMetric::Chessboard18>());
            break;
          case ChamferMetric::Chessboard26:
            localReached = rows(MetricTag<ChamferMetric::Chessboard26>());
            break;
        }
        std::lock_guard<std::mutex> guard(merge);
        found.Merge(localBox);
        reached += localReached;
      });
    if (found.Empty())
    {
      break;
    }
    result.Layers = layer;
    result.Reached += reached;
    // Now `current` gets layer `layer`, and `next` the previous layer, within `box`.
    std::swap(current, next);
    written = box;
    box = found;
    if (progress && !progress(double(result.Reached) / double(total)))
    {
      result.Aborted = true;
      break;
    }
  }
  return result;
}

} // namespace vtkdf
