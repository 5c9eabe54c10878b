// The volume mapper's empty-space bricks against brute force on random grids of uneven
// sizes (bricks cut by the grid's end): the leap distances are each brick's Chebyshev
// distance to the nearest occupied one (capped at 255, also with none occupied), so that
// the cube of bricks within d - 1 holds no occupied brick and the one within d does; mixed
// bricks are those with a two-region cell in or next to them; value ranges are the
// extremes over each brick's cells' voxels; a brick is transparent only if every transfer
// sample around its widened range is zero, and occupied only if one a sample further is not.
#include "CoreTest.h"
#include "EmptySpace.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

using namespace vtkdf::coretest;

namespace
{
size_t Index(const int dims[3], int i, int j, int k)
{
  return i + static_cast<size_t>(dims[0]) * (j + static_cast<size_t>(dims[1]) * k);
}

void TestLeapDistances(std::mt19937& random)
{
  const std::array<std::array<int, 3>, 4> shapes = {
    { { 1, 1, 1 }, { 7, 5, 3 }, { 13, 1, 9 }, { 300, 2, 1 } }
  };
  for (const auto& bricks : shapes)
  {
    const size_t count = static_cast<size_t>(bricks[0]) * bricks[1] * bricks[2];
    for (const double density : { 0.0, 0.003, 0.05, 0.5 })
    {
      std::bernoulli_distribution occupiedAt(density);
      std::vector<unsigned char> occupied(count);
      for (auto& o : occupied)
      {
        o = occupiedAt(random) ? 1 : 0;
      }
      const std::vector<unsigned char> leaps = vtkdf::render::LeapDistances(occupied, bricks);
      int wrong = 0;
      for (int k = 0; k < bricks[2]; ++k)
      {
        for (int j = 0; j < bricks[1]; ++j)
        {
          for (int i = 0; i < bricks[0]; ++i)
          {
            int nearest = 255;
            for (int kk = 0; kk < bricks[2]; ++kk)
            {
              for (int jj = 0; jj < bricks[1]; ++jj)
              {
                for (int ii = 0; ii < bricks[0]; ++ii)
                {
                  if (occupied[Index(bricks.data(), ii, jj, kk)])
                  {
                    nearest = std::min(
                      nearest, std::max({ std::abs(ii - i), std::abs(jj - j), std::abs(kk - k) }));
                  }
                }
              }
            }
            wrong += leaps[Index(bricks.data(), i, j, k)] != nearest;
          }
        }
      }
      Check(wrong == 0,
        "leap distances: %d of %zu bricks differ from brute force (%dx%dx%d, %.3f)",
        wrong,
        count,
        bricks[0],
        bricks[1],
        bricks[2],
        density);
    }
  }
}

void TestMixedAndRanges(std::mt19937& random)
{
  const int size = 4;
  const std::array<std::array<int, 3>, 3> shapes = { { { 2, 2, 2 }, { 10, 7, 13 }, { 17, 9, 5 } } };
  for (const auto& dims : shapes)
  {
    const size_t n = static_cast<size_t>(dims[0]) * dims[1] * dims[2];
    // Regions in blobs (mostly one region, a few others) and random values.
    std::uniform_real_distribution<float> value(-3, 5);
    std::bernoulli_distribution other(0.02);
    std::vector<float> texels(2 * n), values(n);
    for (size_t v = 0; v < n; ++v)
    {
      texels[2 * v] = value(random);
      texels[2 * v + 1] = other(random) ? 2.0f : 0.0f;
      values[v] = value(random);
    }
    const std::array<int, 3> bricks = vtkdf::render::BrickCounts(dims.data(), size);
    const std::vector<unsigned char> mixed =
      vtkdf::render::MixedBricks(texels.data(), dims.data(), size);
    const auto ranges = vtkdf::render::BrickValueRanges(values.data(), dims.data(), size);
    int wrongMixed = 0, wrongRange = 0;
    for (int bk = 0; bk < bricks[2]; ++bk)
    {
      for (int bj = 0; bj < bricks[1]; ++bj)
      {
        for (int bi = 0; bi < bricks[0]; ++bi)
        {
          // Brute force: the brick's cells and their neighbours; its cells' voxels.
          bool expectMixed = false;
          float lo = 1e30f, hi = -1e30f;
          for (int k = 0; k + 1 < dims[2]; ++k)
          {
            for (int j = 0; j + 1 < dims[1]; ++j)
            {
              for (int i = 0; i + 1 < dims[0]; ++i)
              {
                const bool inBrick = i / size == bi && j / size == bj && k / size == bk;
                const bool nextTo =
                  std::abs(i - std::clamp(i, bi * size, bi * size + size - 1)) <= 1 &&
                  std::abs(j - std::clamp(j, bj * size, bj * size + size - 1)) <= 1 &&
                  std::abs(k - std::clamp(k, bk * size, bk * size + size - 1)) <= 1;
                bool cellMixed = false;
                for (int c = 0; c < 8; ++c)
                {
                  const size_t v =
                    Index(dims.data(), i + (c & 1), j + ((c >> 1) & 1), k + (c >> 2));
                  cellMixed =
                    cellMixed || texels[2 * v + 1] != texels[2 * Index(dims.data(), i, j, k) + 1];
                  if (inBrick)
                  {
                    lo = std::min(lo, values[v]);
                    hi = std::max(hi, values[v]);
                  }
                }
                expectMixed = expectMixed || (nextTo && cellMixed);
              }
            }
          }
          const size_t b = Index(bricks.data(), bi, bj, bk);
          wrongMixed += (mixed[b] != 0) != expectMixed;
          wrongRange += ranges[b][0] != lo || ranges[b][1] != hi;
        }
      }
    }
    Check(wrongMixed == 0 && wrongRange == 0,
      "%dx%dx%d: %d mixed bricks and %d ranges differ from brute force",
      dims[0],
      dims[1],
      dims[2],
      wrongMixed,
      wrongRange);
  }
}

void TestOpaque(std::mt19937& random)
{
  // Extinction zero but for a few runs; ranges anywhere over [low, high].
  const double low = -2, high = 6;
  const int count = 993;
  std::vector<double> samples(count, 0.0);
  for (const int start : { 100, 400, 401, 990 })
  {
    for (int m = start; m < std::min(count, start + (start == 400 ? 1 : 7)); ++m)
    {
      samples[m] = 0.5;
    }
  }
  const double h = (high - low) / (count - 1), margin = 3.5 * h;
  std::uniform_real_distribution<double> at(low, high), width(0, 40 * h);
  std::vector<std::array<float, 2>> ranges(4000);
  for (auto& r : ranges)
  {
    const double a = at(random);
    r = { static_cast<float>(a), static_cast<float>(std::min(high, a + width(random))) };
  }
  ranges.push_back({ static_cast<float>(low), static_cast<float>(low) });
  ranges.push_back({ static_cast<float>(high), static_cast<float>(high) });
  const std::vector<unsigned char> occupied =
    vtkdf::render::OpaqueBricks(ranges, samples, low, high, margin);
  int unsound = 0, loose = 0, opaque = 0;
  for (size_t b = 0; b < ranges.size(); ++b)
  {
    bool near = false, further = false;
    for (int m = 0; m < count; ++m)
    {
      const double x = low + m * h;
      near = near ||
        (samples[m] != 0 && x >= ranges[b][0] - margin - h && x <= ranges[b][1] + margin + h);
      further = further ||
        (samples[m] != 0 && x >= ranges[b][0] - margin - 2.5 * h &&
          x <= ranges[b][1] + margin + 2.5 * h);
    }
    unsound += near && !occupied[b];
    loose += occupied[b] && !further;
    opaque += occupied[b];
  }
  std::printf("transfer: %d of %zu ranges occupied\n", opaque, ranges.size());
  Check(unsound == 0 && loose == 0 && opaque > 100 && opaque < 3900,
    "opaque bricks: %d transparent with a nonzero sample in reach, %d occupied without one",
    unsound,
    loose);
}
} // namespace

int main()
{
  std::mt19937 random(7);
  TestLeapDistances(random);
  TestMixedAndRanges(random);
  TestOpaque(random);
  return Verdict();
}
