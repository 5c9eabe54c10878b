#include "ChamferTransform.h"

#include <algorithm>
#include <climits>
#include <mutex>

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
  const uint64_t lastMask = zero.LastWordMask();
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

  const bool faceWide = metric != ChamferMetric::Manhattan;        // n' on face neighbours
  const bool diagonals = metric != ChamferMetric::Manhattan;       // edge lanes at all
  const bool diagonalWide = metric == ChamferMetric::Chessboard26; // n' on them
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
        const uint64_t full = ~uint64_t(0);
        // n(w) of word `w` of a lane: its bits moved one voxel up and one down.
        auto shifted = [words](const uint64_t* lane, int w)
        {
          return (lane[w] << 1) | (w > 0 ? lane[w - 1] >> 63 : 0) | (lane[w] >> 1) |
            (w + 1 < words ? lane[w + 1] << 63 : 0);
        };
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
            // The neighbouring lanes that contribute, and whether as w or n'(w).
            const uint64_t* neighbours[8];
            bool wide[8];
            int count = 0;
            for (int dy = -1; dy <= 1; ++dy)
            {
              for (int dx = -1; dx <= 1; ++dx)
              {
                const int ox = x + dx, oy = y + dy;
                const bool diagonal = dx != 0 && dy != 0;
                if ((dx == 0 && dy == 0) || ox < 0 || oy < 0 || ox >= nx || oy >= ny ||
                  (diagonal && !diagonals))
                {
                  continue;
                }
                neighbours[count] = current.Lane(ox, oy);
                wide[count++] = diagonal ? diagonalWide : faceWide;
              }
            }
            const uint64_t* centre = current.Lane(x, y);
            uint64_t* out = next.Lane(x, y);
            bool any = false;
            for (int w = 0; w < words; ++w)
            {
              uint64_t v = shifted(centre, w);
              for (int n = 0; n < count; ++n)
              {
                v |= neighbours[n][w] | (wide[n] ? shifted(neighbours[n], w) : 0);
              }
              out[w] = v & ~a[w] & (w + 1 == words ? lastMask : full);
              a[w] |= out[w];
              any = any || out[w] != 0;
            }
            if (any)
            {
              localBox.Add(x, y);
              localReached += WriteLane(out, words, x + int64_t(nx) * y, slice, layer, distance);
            }
          }
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
