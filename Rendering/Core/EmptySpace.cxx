#include "EmptySpace.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace vtkdf::render
{
std::array<int, 3> BrickCounts(const int dims[3], int size)
{
  std::array<int, 3> bricks;
  for (int a = 0; a < 3; ++a)
  {
    bricks[a] = std::max(1, (dims[a] - 1 + size - 1) / size);
  }
  return bricks;
}

namespace
{
size_t BrickIndex(const std::array<int, 3>& bricks, int i, int j, int k)
{
  return static_cast<size_t>(i) +
    static_cast<size_t>(bricks[0]) * (static_cast<size_t>(j) + static_cast<size_t>(bricks[1]) * k);
}
} // namespace

std::vector<unsigned char> MixedBricks(const float* texels, const int dims[3], int size)
{
  const std::array<int, 3> bricks = BrickCounts(dims, size);
  const int cells[3] = { dims[0] - 1, dims[1] - 1, dims[2] - 1 };
  const auto region = [&](int i, int j, int k)
  {
    return texels[2 * (i + static_cast<size_t>(dims[0]) * (j + static_cast<size_t>(dims[1]) * k)) +
      1];
  };
  std::vector<unsigned char> occupied(static_cast<size_t>(bricks[0]) * bricks[1] * bricks[2], 0);
  for (int k = 0; k < cells[2]; ++k)
  {
    for (int j = 0; j < cells[1]; ++j)
    {
      for (int i = 0; i < cells[0]; ++i)
      {
        const float r = region(i, j, k);
        bool mixed = false;
        for (int c = 1; c < 8 && !mixed; ++c)
        {
          mixed = region(i + (c & 1), j + ((c >> 1) & 1), k + (c >> 2)) != r;
        }
        if (!mixed)
        {
          continue;
        }
        // The bricks of this cell and of its neighbours.
        for (int dk = -1; dk <= 1; ++dk)
        {
          for (int dj = -1; dj <= 1; ++dj)
          {
            for (int di = -1; di <= 1; ++di)
            {
              const int ci = i + di, cj = j + dj, ck = k + dk;
              if (ci >= 0 && cj >= 0 && ck >= 0 && ci < cells[0] && cj < cells[1] && ck < cells[2])
              {
                occupied[BrickIndex(bricks, ci / size, cj / size, ck / size)] = 1;
              }
            }
          }
        }
      }
    }
  }
  return occupied;
}

std::vector<std::array<float, 2>> BrickValueRanges(const float* values, const int dims[3], int size)
{
  const std::array<int, 3> bricks = BrickCounts(dims, size);
  std::vector<std::array<float, 2>> ranges(static_cast<size_t>(bricks[0]) * bricks[1] * bricks[2]);
  for (int bk = 0; bk < bricks[2]; ++bk)
  {
    for (int bj = 0; bj < bricks[1]; ++bj)
    {
      for (int bi = 0; bi < bricks[0]; ++bi)
      {
        float lo = values[0], hi = values[0];
        bool first = true;
        // The voxels of the brick's cells: size + 1 a side, clipped to the grid.
        for (int k = bk * size; k <= std::min((bk + 1) * size, dims[2] - 1); ++k)
        {
          for (int j = bj * size; j <= std::min((bj + 1) * size, dims[1] - 1); ++j)
          {
            const float* row =
              values + static_cast<size_t>(dims[0]) * (j + static_cast<size_t>(dims[1]) * k);
            for (int i = bi * size; i <= std::min((bi + 1) * size, dims[0] - 1); ++i)
            {
              lo = first ? row[i] : std::min(lo, row[i]);
              hi = first ? row[i] : std::max(hi, row[i]);
              first = false;
            }
          }
        }
        ranges[BrickIndex(bricks, bi, bj, bk)] = { lo, hi };
      }
    }
  }
  return ranges;
}

std::vector<unsigned char> OpaqueBricks(const std::vector<std::array<float, 2>>& ranges,
  const std::vector<double>& samples,
  double low,
  double high,
  double margin)
{
  // nonzero[m]: how many of samples[0, m) are not zero.
  const int count = static_cast<int>(samples.size());
  std::vector<int> nonzero(samples.size() + 1, 0);
  for (int m = 0; m < count; ++m)
  {
    nonzero[m + 1] = nonzero[m] + (samples[m] != 0 ? 1 : 0);
  }
  const double perSample = count > 1 ? (count - 1) / (high - low) : 0;
  std::vector<unsigned char> occupied(ranges.size(), 0);
  for (size_t b = 0; b < ranges.size(); ++b)
  {
    // The samples around [lo - margin, hi + margin], one more each side.
    const double first = std::floor((ranges[b][0] - margin - low) * perSample) - 1;
    const double last = std::ceil((ranges[b][1] + margin - low) * perSample) + 1;
    const int m0 = static_cast<int>(std::clamp(first, 0.0, count - 1.0));
    const int m1 = static_cast<int>(std::clamp(last, 0.0, count - 1.0));
    occupied[b] = nonzero[m1 + 1] - nonzero[m0] > 0 ? 1 : 0;
  }
  return occupied;
}

std::vector<unsigned char> LeapDistances(const std::vector<unsigned char>& occupied,
  const std::array<int, 3>& bricks)
{
  // The chessboard distance transform: two raster scans with unit steps to the 26
  // neighbours (the 13 already visited in each scan's order) are exact for it.
  std::vector<int> distance(occupied.size());
  for (size_t b = 0; b < occupied.size(); ++b)
  {
    distance[b] = occupied[b] ? 0 : 255;
  }
  const auto scan = [&](int sign)
  {
    const int nx = bricks[0], ny = bricks[1], nz = bricks[2];
    for (int kk = 0; kk < nz; ++kk)
    {
      const int k = sign > 0 ? kk : nz - 1 - kk;
      for (int jj = 0; jj < ny; ++jj)
      {
        const int j = sign > 0 ? jj : ny - 1 - jj;
        for (int ii = 0; ii < nx; ++ii)
        {
          const int i = sign > 0 ? ii : nx - 1 - ii;
          int& d = distance[BrickIndex(bricks, i, j, k)];
          for (int dk = -1; dk <= 0; ++dk)
          {
            for (int dj = -1; dj <= 1; ++dj)
            {
              for (int di = -1; di <= 1; ++di)
              {
                // The neighbours before this brick in the scan's order.
                if (dk == 0 && (dj > 0 || (dj == 0 && di >= 0)))
                {
                  continue;
                }
                const int ni = i + sign * di, nj = j + sign * dj, nk = k + sign * dk;
                if (ni >= 0 && nj >= 0 && nk >= 0 && ni < nx && nj < ny && nk < nz)
                {
                  d = std::min(d, distance[BrickIndex(bricks, ni, nj, nk)] + 1);
                }
              }
            }
          }
        }
      }
    }
  };
  scan(1);
  scan(-1);
  std::vector<unsigned char> leap(occupied.size());
  for (size_t b = 0; b < occupied.size(); ++b)
  {
    leap[b] = static_cast<unsigned char>(std::min(distance[b], 255));
  }
  return leap;
}
} // namespace vtkdf::render
