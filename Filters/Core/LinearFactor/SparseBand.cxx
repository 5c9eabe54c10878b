#include "LinearFactor/SparseBand.h"

#include "LinearFactor/LinearFactorScan.h"
#include "LinearFactor/LocalSites.h"
#include "LinearFactor/RangeCulling.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <deque>
#include <new>
#include <utility>

namespace vtkdf
{

int64_t SparseBandField::Bytes() const
{
  int64_t bytes = 0;
  for (const SparseBrick& brick : this->Bricks)
  {
    const int64_t n = brick.Extent.Count();
    bytes += n * (int64_t(sizeof(float)) + 1);
    bytes += brick.ClosestCellId ? n * int64_t(sizeof(int64_t)) : 0;
    bytes += brick.ClosestPoint ? 3 * n * int64_t(sizeof(float)) : 0;
  }
  return bytes;
}

namespace
{
/// A brick's arrays are small: one thread computes each, the bricks run in parallel.
const ParallelFor Serial = [](int64_t n, int64_t, const std::function<void(int64_t, int64_t)>& body)
{
  if (n > 0)
  {
    body(0, n);
  }
};

/// The arrays a thread computes its bricks into (reused: fresh pages cost more than the
/// scan), copied out to blocks of BlockArena.h for the bricks that hold band samples.
struct BrickScratch
{
  std::vector<float> Distance;
  std::vector<uint8_t> Feature;
  std::vector<int64_t> Cells;
  std::vector<float> Points;
};

template<typename T>
BrickArray<T> CopyToBlock(const std::vector<T>& from, int64_t count)
{
  BrickArray<T> block = NewBlockArray<T>(count);
  std::copy(from.begin(), from.begin() + count, block.get());
  return block;
}

/// The grid of bricks over the whole grid.
struct BrickGrid
{
  IndexBox Whole;
  int Size = 32;
  std::array<int, 3> Counts{ { 1, 1, 1 } };

  int64_t Total() const { return int64_t(this->Counts[0]) * this->Counts[1] * this->Counts[2]; }
  int64_t Id(int i, int j, int k) const
  {
    return i + int64_t(this->Counts[0]) * (j + int64_t(this->Counts[1]) * k);
  }
  std::array<int, 3> Indices(int64_t id) const
  {
    return { { static_cast<int>(id % this->Counts[0]),
      static_cast<int>((id / this->Counts[0]) % this->Counts[1]),
      static_cast<int>(id / (int64_t(this->Counts[0]) * this->Counts[1])) } };
  }
  /// A brick's samples: its last layer is its neighbour's first.
  IndexBox Extent(const std::array<int, 3>& b) const
  {
    IndexBox box;
    for (int a = 0; a < 3; ++a)
    {
      box.Lo[a] = this->Whole.Lo[a] + b[a] * this->Size;
      box.Hi[a] = static_cast<int>(
        std::min<int64_t>(int64_t(box.Lo[a]) + this->Size, int64_t(this->Whole.Hi[a])));
    }
    return box;
  }
  /// The bricks that hold some sample of [lo, hi] (whole-grid indices) along axis a.
  void Range(int a, int lo, int hi, int& first, int& last) const
  {
    const int64_t l = int64_t(lo) - this->Whole.Lo[a], h = int64_t(hi) - this->Whole.Lo[a];
    // Brick b holds samples b * Size .. (b + 1) * Size.
    first = static_cast<int>(std::max<int64_t>(0, (l + this->Size - 1) / this->Size - 1));
    last = static_cast<int>(std::min<int64_t>(this->Counts[a] - 1, h / this->Size));
  }
};

/// Every brick's candidate sites (ascending): those whose band region reaches it.
struct BrickSites
{
  std::vector<int64_t> Start; // per brick, one more than the bricks
  std::vector<uint32_t> Sites;
};

/// The samples of the whole grid within `cap` of a site's box (RangeCulling::Region's
/// band, over the whole grid); false when none.
bool BandRegion(const MeshSites& sites,
  int64_t s,
  const SampleGrid& grid,
  double cap,
  IndexBox& region)
{
  float lo[3], hi[3];
  sites.BoxOf(s, lo, hi);
  for (int a = 0; a < 3; ++a)
  {
    const double l = (lo[a] - cap - grid.Origin[a]) / grid.Spacing[a];
    const double h = (hi[a] + cap - grid.Origin[a]) / grid.Spacing[a];
    region.Lo[a] = static_cast<int>(std::min(std::max(std::ceil(l), -2e9), 2e9));
    region.Hi[a] = static_cast<int>(std::min(std::max(std::floor(h), -2e9), 2e9));
  }
  region = region.Intersect(grid.Whole);
  return !region.Empty();
}

/// Whether a face site's plane lies farther than `reach` from every sample of `box` (its
/// samples' coordinates): then so does the face, which cannot be the nearest site of a
/// band sample there.
bool PlaneMisses(const MeshSites& sites,
  int64_t s,
  const SampleGrid& grid,
  const IndexBox& box,
  double reach)
{
  Site face;
  sites.Describe(s, face, false, false);
  double centre = 0, radius = 0;
  for (int a = 0; a < 3; ++a)
  {
    const double lo = grid.Coordinate(a, box.Lo[a]), hi = grid.Coordinate(a, box.Hi[a]);
    centre += face.Axis[a] * (0.5 * (lo + hi) - face.Anchor[a]);
    radius += std::fabs(face.Axis[a]) * 0.5 * (hi - lo);
  }
  return std::fabs(centre) - radius > reach;
}

/// Bins every site into the bricks its band region reaches (less those a face's plane
/// keeps beyond the band): the pairs found in parallel, then counted and placed by brick
/// in the order of the sites.
void BinSites(const MeshSites& sites,
  const SampleGrid& grid,
  const BrickGrid& bricks,
  double cap,
  const ParallelFor& parallelFor,
  BrickSites& out)
{
  struct Pair
  {
    int64_t Brick;
    uint32_t Site;
  };
  // The plane test's margin covers its rounding: a face within the band stays.
  const double reach = cap + 1e-6 * (cap + grid.MinSpacing() * bricks.Size);
  const int64_t numSites = sites.Count();
  const int64_t chunks = std::max<int64_t>(1, std::min<int64_t>(256, numSites / 4096));
  std::vector<std::vector<Pair>> found(chunks);
  parallelFor(chunks,
    1,
    [&](int64_t first, int64_t last)
    {
      for (int64_t chunk = first; chunk < last; ++chunk)
      {
        for (int64_t s = numSites * chunk / chunks; s < numSites * (chunk + 1) / chunks; ++s)
        {
          IndexBox region;
          if (!BandRegion(sites, s, grid, cap, region))
          {
            continue;
          }
          int lo[3], hi[3];
          for (int a = 0; a < 3; ++a)
          {
            bricks.Range(a, region.Lo[a], region.Hi[a], lo[a], hi[a]);
          }
          const bool face = sites.TypeOf(s) == FaceSite;
          const bool several = lo[0] < hi[0] || lo[1] < hi[1] || lo[2] < hi[2];
          for (int k = lo[2]; k <= hi[2]; ++k)
          {
            for (int j = lo[1]; j <= hi[1]; ++j)
            {
              for (int i = lo[0]; i <= hi[0]; ++i)
              {
                if (face && several &&
                  PlaneMisses(sites, s, grid, bricks.Extent({ { i, j, k } }), reach))
                {
                  continue;
                }
                found[chunk].push_back({ bricks.Id(i, j, k), static_cast<uint32_t>(s) });
              }
            }
          }
        }
      }
    });
  out.Start.assign(bricks.Total() + 1, 0);
  for (const std::vector<Pair>& pairs : found)
  {
    for (const Pair& pair : pairs)
    {
      ++out.Start[pair.Brick + 1];
    }
  }
  for (int64_t b = 0; b < bricks.Total(); ++b)
  {
    out.Start[b + 1] += out.Start[b];
  }
  out.Sites.resize(out.Start.back());
  std::vector<int64_t> fill(out.Start.begin(), out.Start.end() - 1);
  for (std::vector<Pair>& pairs : found)
  {
    for (const Pair& pair : pairs)
    {
      out.Sites[fill[pair.Brick]++] = pair.Site;
    }
    pairs = std::vector<Pair>();
  }
}

/// One brick's field: the dense field's culling, scan and Finalize over its samples with
/// its candidate sites. Its BandSamples stay 0 when every sample is beyond the band.
SparseBrick ComputeBrick(const LocalSites& local,
  const BrickGrid& bricks,
  int64_t id,
  std::vector<uint32_t> candidates,
  const SparseBandRequest& request,
  int64_t& evaluations)
{
  SparseBrick brick;
  brick.Index = bricks.Indices(id);
  brick.Extent = bricks.Extent(brick.Index);
  LocalFieldRequest piece = local.Request;
  piece.Extent = brick.Extent;
  RangeCulling range;
  range.Build(local.Sites, piece.Grid, piece.Extent, piece.MaximumDistance, Serial, &candidates);
  candidates = std::vector<uint32_t>(); // released before the brick's own arrays
  // One buffer a thread, reused from brick to brick: fresh pages cost more than the scan.
  thread_local NearestSiteBuffer nearest;
  const int64_t n = piece.Extent.Count();
  nearest.Reset(n);
  evaluations +=
    ScanSitesCPU(local.Sites, range, piece, nearest, Serial, ProgressCallback()).Evaluations;
  range = RangeCulling();
  thread_local BrickScratch scratch;
  scratch.Distance.resize(n);
  scratch.Feature.resize(n);
  scratch.Cells.resize(request.ClosestCellId ? n : 0);
  scratch.Points.resize(request.ClosestPoint ? 3 * n : 0);
  LocalFieldArrays arrays;
  arrays.Frame = local.Frame;
  arrays.Distance = scratch.Distance.data();
  arrays.Signed = request.Sign == SignMode::PseudoNormal;
  arrays.ClosestCellId = request.ClosestCellId ? scratch.Cells.data() : nullptr;
  arrays.ClosestFeature = scratch.Feature.data();
  arrays.ClosestPoint = request.ClosestPoint ? scratch.Points.data() : nullptr;
  Finalize(local.Sites, piece, nearest, arrays, Serial);
  brick.BandSamples = static_cast<int64_t>(
    n - std::count(scratch.Feature.begin(), scratch.Feature.begin() + n, uint8_t(255)));
  if (brick.BandSamples > 0)
  {
    brick.Distance = CopyToBlock(scratch.Distance, n);
    brick.ClosestFeature = CopyToBlock(scratch.Feature, n);
    if (request.ClosestCellId)
    {
      brick.ClosestCellId = CopyToBlock(scratch.Cells, n);
    }
    if (request.ClosestPoint)
    {
      brick.ClosestPoint = CopyToBlock(scratch.Points, 3 * n);
    }
  }
  return brick;
}

/// The side of the samples that `brick` shares with its neighbour one step along axis
/// `a` (`step` -1 or 1): those samples are all beyond the band when the neighbour holds
/// none, and a signed brick has flooded a side onto every one of them.
int8_t SharedFaceSide(const SparseBrick& brick, int a, int step)
{
  const IndexBox& e = brick.Extent;
  const int64_t nx = e.Size(0), ny = e.Size(1);
  IndexBox face = e;
  face.Lo[a] = face.Hi[a] = step > 0 ? e.Hi[a] : e.Lo[a];
  for (int k = face.Lo[2]; k <= face.Hi[2]; ++k)
  {
    for (int j = face.Lo[1]; j <= face.Hi[1]; ++j)
    {
      for (int i = face.Lo[0]; i <= face.Hi[0]; ++i)
      {
        const int64_t at = (i - e.Lo[0]) + nx * ((j - e.Lo[1]) + ny * int64_t(k - e.Lo[2]));
        if (brick.ClosestFeature[at] == 255)
        {
          return brick.Distance[at] < 0 ? -1 : 1;
        }
      }
    }
  }
  return 0;
}

/// Sides of the bricks without band samples, flooded over the grid of bricks from the
/// faces they share with the bricks that have some.
void FloodBrickSides(const BrickGrid& bricks, SparseBandField& field)
{
  std::deque<int64_t> queue;
  auto neighbours = [&](int64_t id, const auto& visit)
  {
    const std::array<int, 3> b = bricks.Indices(id);
    for (int a = 0; a < 3; ++a)
    {
      for (int step = -1; step <= 1; step += 2)
      {
        std::array<int, 3> o = b;
        o[a] += step;
        if (o[a] >= 0 && o[a] < bricks.Counts[a])
        {
          visit(bricks.Id(o[0], o[1], o[2]), a, step);
        }
      }
    }
  };
  for (const SparseBrick& brick : field.Bricks)
  {
    const int64_t id = bricks.Id(brick.Index[0], brick.Index[1], brick.Index[2]);
    neighbours(id,
      [&](int64_t other, int a, int step)
      {
        if (field.BrickOf[other] < 0 && field.Sides[other] == 0)
        {
          field.Sides[other] = SharedFaceSide(brick, a, step);
          if (field.Sides[other] != 0)
          {
            queue.push_back(other);
          }
        }
      });
  }
  while (!queue.empty())
  {
    const int64_t id = queue.front();
    queue.pop_front();
    neighbours(id,
      [&](int64_t other, int, int)
      {
        if (field.BrickOf[other] < 0 && field.Sides[other] == 0)
        {
          field.Sides[other] = field.Sides[id];
          queue.push_back(other);
        }
      });
  }
}

bool CheckRequest(const SparseBandRequest& request, std::string& error)
{
  const double accuracy = 1e-3 * request.Grid.MinSpacing();
  if (!(std::isfinite(request.BandWidth) && request.BandWidth >= accuracy))
  {
    error = "The band's half-width (" + FormatNumber(request.BandWidth) +
      ") must be finite and at least 1e-3 of the smallest spacing (" + FormatNumber(accuracy) +
      ").";
    return false;
  }
  if (request.BrickSize < 2 || request.BrickSize > 1024)
  {
    error =
      "BrickSize must be between 2 and 1024; it is " + std::to_string(request.BrickSize) + ".";
    return false;
  }
  if (request.Sign == SignMode::WindingNumber)
  {
    error = "The sparse band is unsigned or signed by pseudonormals; the winding number's sign "
            "needs the dense field (vtkLinearFactorDistanceField with MaximumDistance).";
    return false;
  }
  return true;
}

/// The grid of bricks; false and `error` when it would have too many bricks to index.
bool MakeBrickGrid(const SampleGrid& grid, int size, BrickGrid& bricks, std::string& error)
{
  bricks.Whole = grid.Whole;
  bricks.Size = size;
  double total = 1;
  for (int a = 0; a < 3; ++a)
  {
    const int64_t intervals = int64_t(grid.Whole.Hi[a]) - grid.Whole.Lo[a];
    bricks.Counts[a] = static_cast<int>(std::max<int64_t>(1, (intervals + size - 1) / size));
    total *= bricks.Counts[a];
  }
  if (total > double(int64_t(1) << 28))
  {
    error = "The grid would have " + FormatNumber(total) +
      " bricks, more than 2^28 bricks: use a larger BrickSize.";
    return false;
  }
  return true;
}

/// Whether the grid of bricks (its sides, pieces and binning offsets: 13 bytes a brick)
/// fits the memory limit.
bool CheckBrickGridMemory(const SparseBandRequest& request,
  const BrickGrid& bricks,
  std::string& error)
{
  const double bytes = 13.0 * double(bricks.Total());
  if (request.MemoryLimit > 0 && bytes > request.MemoryLimit)
  {
    error = "The grid of " + std::to_string(bricks.Total()) + " bricks needs " +
      FormatNumber(bytes / 1048576.0) + " MiB, above the memory limit (" +
      FormatNumber(request.MemoryLimit / 1048576.0) + " MiB): use a larger BrickSize.";
    return false;
  }
  return true;
}

/// Whether the bricks the band may touch fit the memory limit.
bool CheckBrickMemory(const SparseBandRequest& request,
  const BrickSites& binned,
  const BrickGrid& bricks,
  int64_t& candidates,
  std::string& error)
{
  candidates = 0;
  for (int64_t b = 0; b < bricks.Total(); ++b)
  {
    candidates += binned.Start[b + 1] > binned.Start[b];
  }
  const double perSample = 5 + (request.ClosestCellId ? 8 : 0) + (request.ClosestPoint ? 12 : 0);
  const double samples = std::pow(double(request.BrickSize) + 1, 3);
  const double bytes = double(candidates) * samples * perSample;
  if (request.MemoryLimit > 0 && bytes > request.MemoryLimit)
  {
    error = "The " + std::to_string(candidates) + " bricks the band may touch need up to " +
      FormatNumber(bytes / 1048576.0) + " MiB, above the memory limit (" +
      FormatNumber(request.MemoryLimit / 1048576.0) + " MiB).";
    return false;
  }
  return true;
}
} // namespace

bool ComputeSparseBand(MeshInput mesh,
  const SparseBandRequest& request,
  const Execution& execution,
  SparseBandField& field,
  std::string& error)
{
  field = SparseBandField();
  field.BrickSize = request.BrickSize;
  BrickGrid bricks;
  if (!CheckRequest(request, error) ||
    !MakeBrickGrid(request.Grid, request.BrickSize, bricks, error) ||
    !CheckBrickGridMemory(request, bricks, error))
  {
    return false;
  }
  field.BrickCounts = bricks.Counts;
  field.Sides.assign(bricks.Total(), 0);
  field.BrickOf.assign(bricks.Total(), -1);
  LinearFactorRequest dense;
  dense.Grid = request.Grid;
  dense.Extent = request.Grid.Whole;
  dense.Domains = request.Domains;
  dense.Sign = request.Sign;
  dense.MaximumDistance = request.BandWidth;
  LocalSites local;
  if (!BuildLocalSites(mesh, dense, false, execution.For, local, error))
  {
    return false;
  }
  if (local.Sites.Empty())
  {
    field.NoUsableCell = true;
    return true;
  }
  execution.EndStage("sites");
  BrickSites binned;
  BinSites(
    local.Sites, local.Request.Grid, bricks, local.Request.MaximumDistance, execution.For, binned);
  if (!CheckBrickMemory(request, binned, bricks, field.CandidateBricks, error))
  {
    return false;
  }
  std::vector<int64_t> todo;
  for (int64_t b = 0; b < bricks.Total(); ++b)
  {
    if (binned.Start[b + 1] > binned.Start[b])
    {
      todo.push_back(b);
    }
  }
  execution.EndStage("bricks");
  if (!execution.Report(0.05))
  {
    field.Aborted = true;
    return true;
  }

  // Batches of bricks in parallel, progress and abort between them.
  std::vector<SparseBrick> computed(todo.size());
  std::atomic<int64_t> evaluations{ 0 };
  const int64_t count = static_cast<int64_t>(todo.size());
  const int64_t batches = std::max<int64_t>(1, std::min<int64_t>(20, count / 16));
  for (int64_t batch = 0; batch < batches; ++batch)
  {
    const int64_t first = count * batch / batches, last = count * (batch + 1) / batches;
    execution.For(last - first,
      1,
      [&](int64_t begin, int64_t end)
      {
        int64_t brickEvaluations = 0;
        for (int64_t t = first + begin; t < first + end; ++t)
        {
          const int64_t b = todo[t];
          std::vector<uint32_t> candidates(
            binned.Sites.begin() + binned.Start[b], binned.Sites.begin() + binned.Start[b + 1]);
          computed[t] =
            ComputeBrick(local, bricks, b, std::move(candidates), request, brickEvaluations);
        }
        evaluations += brickEvaluations;
      });
    if (!execution.Report(0.05 + 0.9 * double(batch + 1) / batches))
    {
      field.Aborted = true;
      return true;
    }
  }
  binned = BrickSites();
  for (int64_t t = 0; t < count; ++t)
  {
    if (computed[t].BandSamples > 0)
    {
      field.BandSamples += computed[t].BandSamples;
      field.BrickOf[todo[t]] = static_cast<int32_t>(field.Bricks.size());
      field.Bricks.push_back(std::move(computed[t]));
    }
  }
  field.Evaluations = evaluations.load();
  execution.EndStage("scan");
  if (request.Sign == SignMode::PseudoNormal)
  {
    FloodBrickSides(bricks, field);
    execution.EndStage("sides");
  }
  return true;
}

} // namespace vtkdf
