// The VTK-free chamfer transform against a breadth-first search with the same
// neighbourhood, on hand-made voxel sets: one voxel, a plane, the grid's corners and
// faces, random sets of several densities; nz = 1, 64, 65, 129, 300 and 66000 (more than
// 2^16 layers);
// every metric, with and without a maximum number of layers (3: within the wavefront's
// first block of eight layers, 11: within the second, 30: beyond what the wavefront
// computes, the sweeps with a limit), unsigned and signed. And the rounding by
// truncation (Common/Rounding.h) that the voxelizer and the scan use, against std::llround,
// std::ceil and std::floor.
#include "Common/Rounding.h"
#include "CoreTest.h"
#include "ThreadFor.h"
#include "Voxels/ChamferTransform.h"
#include "Voxels/VoxelFields.h"

#include <cmath>

#include <cstdio>
#include <deque>
#include <functional>
#include <random>
#include <string>
#include <thread>
#include <vector>

using namespace vtkdf;
using namespace vtkdf::coretest;

namespace
{

/// Layer index of every voxel by breadth-first search from the set voxels.
std::vector<int32_t> Reference(const BitVolume& zero,
  ChamferMetric metric,
  int maxLayers,
  int32_t unreached)
{
  const int nx = zero.Size(0), ny = zero.Size(1), nz = zero.Size(2);
  std::vector<int32_t> d(size_t(nx) * ny * nz, -1);
  std::deque<int64_t> queue;
  for (int z = 0; z < nz; ++z)
  {
    for (int y = 0; y < ny; ++y)
    {
      for (int x = 0; x < nx; ++x)
      {
        if (zero.Get(x, y, z))
        {
          const int64_t at = x + int64_t(nx) * (y + int64_t(ny) * z);
          d[at] = 0;
          queue.push_back(at);
        }
      }
    }
  }
  while (!queue.empty())
  {
    const int64_t at = queue.front();
    queue.pop_front();
    const int x = static_cast<int>(at % nx), y = static_cast<int>((at / nx) % ny);
    const int z = static_cast<int>(at / (int64_t(nx) * ny));
    if (maxLayers > 0 && d[at] >= maxLayers)
    {
      continue;
    }
    for (int dz = -1; dz <= 1; ++dz)
    {
      for (int dy = -1; dy <= 1; ++dy)
      {
        for (int dx = -1; dx <= 1; ++dx)
        {
          const int order = (dx != 0) + (dy != 0) + (dz != 0);
          const bool neighbour = metric == ChamferMetric::Manhattan ? order == 1
            : metric == ChamferMetric::Chessboard18                 ? (order == 1 || order == 2)
                                                                    : order >= 1;
          const int ox = x + dx, oy = y + dy, oz = z + dz;
          if (!neighbour || ox < 0 || oy < 0 || oz < 0 || ox >= nx || oy >= ny || oz >= nz)
          {
            continue;
          }
          const int64_t o = ox + int64_t(nx) * (oy + int64_t(ny) * oz);
          if (d[o] < 0)
          {
            d[o] = d[at] + 1;
            queue.push_back(o);
          }
        }
      }
    }
  }
  for (int32_t& v : d)
  {
    v = v < 0 ? unreached : v;
  }
  return d;
}

/// One run of the family's entry point (as vtkChamferVoxelDistance calls it on masks)
/// against the reference; `inside` (optional) negates its voxels.
void CompareOne(const std::string& name,
  const BitVolume& zero,
  ChamferMetric metric,
  int maxLayers,
  const BitVolume* inside)
{
  const char* metrics[] = { "manhattan", "chessboard18", "chessboard26" };
  const int32_t unreached = maxLayers > 0 ? maxLayers + 1 : INT32_MAX;
  auto expected = Reference(zero, metric, maxLayers, unreached);
  int32_t layers = 0;
  int64_t reached = 0;
  for (int32_t v : expected)
  {
    layers = v != unreached ? std::max(layers, v) : layers;
    reached += v != unreached;
  }
  const int nx = zero.Size(0), ny = zero.Size(1), nz = zero.Size(2);
  for (int z = 0; z < nz && inside; ++z)
  {
    for (int y = 0; y < ny; ++y)
    {
      for (int x = 0; x < nx; ++x)
      {
        int32_t& v = expected[x + int64_t(nx) * (y + int64_t(ny) * z)];
        v = inside->Get(x, y, z) ? -v : v;
      }
    }
  }
  std::vector<int32_t> got(expected.size());
  ChamferRequest request;
  request.Grid.Whole.Hi = { nx - 1, ny - 1, nz - 1 };
  request.Metric = metric;
  request.MaximumLayers = maxLayers;
  request.Signed = inside != nullptr;
  Execution execution;
  execution.For = ThreadFor;
  ChamferReport report;
  std::string error;
  Check(ComputeChamferField(zero, inside, request, nullptr, got.data(), execution, report, error),
    "%s: %s",
    name.c_str(),
    error.c_str());
  const ChamferResult& r = report.Result;
  int64_t wrong = 0, first = -1;
  for (size_t i = 0; i < got.size(); ++i)
  {
    if (got[i] != expected[i])
    {
      first = first < 0 ? int64_t(i) : first;
      ++wrong;
    }
  }
  Check(r.Reached == reached && r.ZeroSet == zero.Count(),
    "%s %s M=%d%s: %lld voxels reached (%lld zero), expected %lld (%lld)",
    name.c_str(),
    metrics[static_cast<int>(metric)],
    maxLayers,
    inside ? " signed" : "",
    (long long)r.Reached,
    (long long)r.ZeroSet,
    (long long)reached,
    (long long)zero.Count());
  Check(!wrong && r.Layers == layers,
    "%s %s M=%d%s: %lld voxels differ (first at %lld: %d, expected %d), layers %d, expected %d",
    name.c_str(),
    metrics[static_cast<int>(metric)],
    maxLayers,
    inside ? " signed" : "",
    (long long)wrong,
    (long long)first,
    first >= 0 ? got[first] : 0,
    first >= 0 ? expected[first] : 0,
    r.Layers,
    layers);
}

/// Every metric, with and without a maximum number of layers, unsigned and with a
/// random half of the voxels inside.
void CompareAll(const std::string& name, const BitVolume& zero, std::mt19937& random)
{
  BitVolume inside(zero.Size(0), zero.Size(1), zero.Size(2));
  for (int z = 0; z < zero.Size(2); ++z)
  {
    for (int y = 0; y < zero.Size(1); ++y)
    {
      for (int x = 0; x < zero.Size(0); ++x)
      {
        if (random() & 1)
        {
          inside.Set(x, y, z);
        }
      }
    }
  }
  for (int m = 0; m < 3; ++m)
  {
    for (int maxLayers : { 0, 3, 11, 30 })
    {
      CompareOne(name, zero, static_cast<ChamferMetric>(m), maxLayers, nullptr);
    }
    CompareOne(name, zero, static_cast<ChamferMetric>(m), 0, &inside);
  }
  std::printf("%-34s %dx%dx%d  %lld zero voxels: ok\n",
    name.c_str(),
    zero.Size(0),
    zero.Size(1),
    zero.Size(2),
    (long long)zero.Count());
}
} // namespace

int main()
{
  std::mt19937 random(7);
  struct Dims
  {
    int X, Y, Z;
  };
  for (const Dims d : { Dims{ 9, 7, 1 },
         Dims{ 6, 5, 64 },
         Dims{ 5, 6, 65 },
         Dims{ 4, 5, 129 },
         Dims{ 3, 4, 300 },
         Dims{ 13, 11, 17 },
         Dims{ 70, 6, 130 } })
  {
    const std::string size =
      std::to_string(d.X) + "x" + std::to_string(d.Y) + "x" + std::to_string(d.Z);
    {
      BitVolume v(d.X, d.Y, d.Z);
      v.Set(d.X / 2, d.Y / 2, d.Z / 2);
      CompareAll("single voxel " + size, v, random);
    }
    {
      BitVolume v(d.X, d.Y, d.Z);
      v.Set(d.X - 1, 0, d.Z - 1);
      CompareAll("corner voxel " + size, v, random);
    }
    {
      BitVolume v(d.X, d.Y, d.Z);
      for (int y = 0; y < d.Y; ++y)
      {
        for (int z = 0; z < d.Z; ++z)
        {
          v.Set(d.X / 3, y, z); // a plane x = const
        }
      }
      CompareAll("plane " + size, v, random);
    }
    {
      BitVolume v(d.X, d.Y, d.Z);
      for (int c = 0; c < 8; ++c)
      {
        v.Set(c & 1 ? d.X - 1 : 0, c & 2 ? d.Y - 1 : 0, c & 4 ? d.Z - 1 : 0);
      }
      CompareAll("corners " + size, v, random);
    }
    {
      BitVolume v(d.X, d.Y, d.Z);
      for (int x = 0; x < d.X; ++x)
      {
        for (int y = 0; y < d.Y; ++y)
        {
          v.Set(x, y, 0); // the face z = 0
        }
      }
      CompareAll("face z=0 " + size, v, random);
    }
    {
      BitVolume v(d.X, d.Y, d.Z);
      std::uniform_int_distribution<int> rx(0, d.X - 1), ry(0, d.Y - 1), rz(0, d.Z - 1);
      for (int n = 0; n < 3; ++n)
      {
        v.Set(rx(random), ry(random), rz(random));
      }
      CompareAll("random sparse " + size, v, random);
    }
  }
  {
    // Random sets of several densities on odd sizes: many shortest paths meet, and the
    // sweeps of the metrics without a layer limit must still give the breadth-first
    // search's layers.
    for (const Dims d : { Dims{ 31, 29, 67 }, Dims{ 65, 3, 40 }, Dims{ 2, 70, 33 } })
    {
      for (int per : { 40, 400, 4000 })
      {
        BitVolume v(d.X, d.Y, d.Z);
        std::uniform_int_distribution<int> pick(0, per - 1);
        for (int z = 0; z < d.Z; ++z)
        {
          for (int y = 0; y < d.Y; ++y)
          {
            for (int x = 0; x < d.X; ++x)
            {
              if (pick(random) == 0)
              {
                v.Set(x, y, z);
              }
            }
          }
        }
        v.Set(d.X - 1, d.Y / 2, 0); // never empty (the field needs a zero set)
        CompareAll("random 1/" + std::to_string(per) + " " + std::to_string(d.X) + "x" +
            std::to_string(d.Y) + "x" + std::to_string(d.Z),
          v,
          random);
      }
    }
  }
  {
    // More than 2^16 layers: the layer indices need more than two bytes.
    BitVolume line(1, 2, 66000);
    line.Set(0, 0, 0);
    CompareOne(
      "one voxel at the end of a line 1x2x66000", line, ChamferMetric::Manhattan, 0, nullptr);
    // The largest limit there is: every layer, and unreached voxels hold INT32_MAX.
    for (int m = 0; m < 3; ++m)
    {
      CompareOne("one voxel at the end of a line 1x2x66000",
        line,
        static_cast<ChamferMetric>(m),
        INT32_MAX - 1,
        nullptr);
    }
  }
  {
    BitVolume empty(4, 4, 4);
    std::vector<int32_t> out(64);
    const ChamferResult r = ChamferPropagate(
      empty, ChamferMetric::Manhattan, 0, -7, nullptr, out.data(), ThreadFor, nullptr);
    bool all = r.Reached == 0;
    for (int32_t v : out)
    {
      all = all && v == -7;
    }
    Check(all, "an empty zero set must leave every voxel unreached");
  }
  {
    // The snapped vertices' range (SnapRange * Subpixel = 2^30): halfway cases, their
    // neighbours one ulp away, and random values.
    std::vector<double> values = { 0.0,
      -0.0,
      0.5,
      -0.5,
      1.5,
      -1.5,
      2.5,
      -2.5,
      0.49999999999999994,
      -0.49999999999999994,
      1073741823.5,
      -1073741823.5 };
    for (double h = 0.5; h < 1 << 30; h += 1.0)
    {
      values.push_back(h);
      values.push_back(std::nextafter(h, 0.0));
      values.push_back(std::nextafter(h, HUGE_VAL));
      values.push_back(-values[values.size() - 2]);
      if (h > 64)
      {
        h = h * 1.7 + 0.5 - std::fmod(h * 1.7, 1.0); // the next halfway value, sparser
      }
    }
    std::uniform_real_distribution<double> uniform(-1073741824.0, 1073741824.0);
    for (int i = 0; i < 100000; ++i)
    {
      values.push_back(uniform(random));
    }
    int wrong = 0;
    for (const double x : values)
    {
      wrong += RoundHalfAway(x) != std::llround(x);
    }
    Check(
      wrong == 0, "RoundHalfAway differs from llround on %d of %zu values", wrong, values.size());
    // Ceil and floor on an int's range: integers, their neighbours one ulp away, halves.
    std::vector<double> small = { 0.0, -0.0, 0.5, -0.5, 1.0, -1.0, 2147483646.5, -2147483647.5 };
    for (int i = -70000; i <= 70000; i += 7)
    {
      for (const double x : { double(i),
             std::nextafter(double(i), -HUGE_VAL),
             std::nextafter(double(i), HUGE_VAL),
             i + 0.5 })
      {
        small.push_back(x);
      }
    }
    std::uniform_real_distribution<double> wide(-2147483647.0, 2147483647.0);
    for (int i = 0; i < 100000; ++i)
    {
      small.push_back(wide(random));
    }
    wrong = 0;
    for (const double x : small)
    {
      wrong += CeilToInt(x) != static_cast<int>(std::ceil(x));
      wrong += FloorToInt(x) != static_cast<int>(std::floor(x));
    }
    Check(wrong == 0, "CeilToInt or FloorToInt differ from ceil and floor %d times", wrong);
  }
  return Verdict();
}
