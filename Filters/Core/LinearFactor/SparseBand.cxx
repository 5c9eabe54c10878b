#include "LinearFactor/SparseBand.h"

#include "LinearFactor/LinearFactorScan.h"
#include "LinearFactor/LocalSites.h"
#include "LinearFactor/RangeCulling.h"
#include "Winding/BrickWindingSigns.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <deque>
#include <iterator>
#include <memory>
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
const ParallelFor Serial = SerialFor;

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

/// Every sample's side by the winding number (`inside`, scratch), and the distances
/// signed by it as the dense field signs them; `side` the side of all the samples (-1
/// inside, 1 outside), 0 when they differ.
void WindingSign(const BrickWindingSigns& winding,
  const IndexBox& extent,
  const GridFrame& frame,
  float* distance,
  std::vector<uint8_t>& inside,
  int8_t& side)
{
  const int64_t n = extent.Count();
  inside.resize(n);
  // Unsigned still, in world units: blocks near the surface split without trying.
  winding.Decide(extent, inside.data(), distance, 1 / frame.Scale);
  for (int64_t v = 0; v < n; ++v)
  {
    distance[v] = inside[v] ? -std::fabs(distance[v]) : std::fabs(distance[v]);
  }
  const bool uniform =
    std::all_of(inside.begin(), inside.begin() + n, [&](uint8_t in) { return in == inside[0]; });
  side = uniform ? (inside[0] ? -1 : 1) : 0;
}

/// One brick's field: the dense field's culling, scan and Finalize over its samples with
/// its candidate sites, and the winding sign when `winding` is given. Its BandSamples
/// stay 0 when every sample is beyond the band; its arrays are kept when it has band
/// samples, or samples of both sides (`side` 0; otherwise `side` their side, 0 unsigned).
SparseBrick ComputeBrick(const LocalSites& local,
  const BrickGrid& bricks,
  int64_t id,
  std::vector<uint32_t> candidates,
  const SparseBandRequest& request,
  const BrickWindingSigns* winding,
  int64_t& evaluations,
  int8_t& side)
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
  side = 0;
  if (winding)
  {
    thread_local std::vector<uint8_t> inside;
    WindingSign(*winding, brick.Extent, local.Frame, scratch.Distance.data(), inside, side);
  }
  if (brick.BandSamples > 0 || (winding && side == 0))
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

/// The six sides of the samples each piece shares with its neighbours (SharedFaceSide:
/// 2 a + (step > 0)), at 6 x its number among all pieces, summed over the processes.
std::vector<int8_t> PieceFaceSides(const SparseBandRequest& request,
  int64_t pieces,
  SparseBandField& field)
{
  std::vector<int8_t> faces(static_cast<size_t>(6 * pieces), 0);
  const BrickGrid bricks = BrickGrid::Over(request.Grid.Whole, request.BrickSize);
  for (const SparseBrick& brick : field.Bricks)
  {
    const int32_t piece = field.BrickOf[bricks.Id(brick.Index[0], brick.Index[1], brick.Index[2])];
    for (int a = 0; a < 3; ++a)
    {
      for (int step = -1; step <= 1; step += 2)
      {
        faces[6 * size_t(piece) + 2 * a + (step > 0)] = SharedFaceSide(brick, a, step);
      }
    }
  }
  if (request.Pieces > 1)
  {
    request.SumOverPieces(faces);
  }
  return faces;
}

/// Sides of the bricks without band samples, flooded over the grid of bricks from the
/// faces they share with the pieces (`faces`: PieceFaceSides).
void FloodBrickSides(const BrickGrid& bricks,
  const std::vector<int8_t>& faces,
  SparseBandField& field)
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
  for (int64_t id = 0; id < bricks.Total(); ++id)
  {
    const int32_t piece = field.BrickOf[id];
    if (piece < 0)
    {
      continue;
    }
    neighbours(id,
      [&](int64_t other, int a, int step)
      {
        if (field.BrickOf[other] < 0 && field.Sides[other] == 0)
        {
          field.Sides[other] = faces[6 * size_t(piece) + 2 * a + (step > 0)];
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

/// The sides and the pieces of all processes on every process: the sides each computed
/// summed (each brick's by one process), the pieces numbered in the order of their index.
/// Returns the number of pieces.
int64_t ShareSides(const SparseBandRequest& request, SparseBandField& field)
{
  std::vector<int8_t> kept(field.Sides.size(), 0);
  const BrickGrid bricks = BrickGrid::Over(request.Grid.Whole, request.BrickSize);
  for (const SparseBrick& brick : field.Bricks)
  {
    kept[bricks.Id(brick.Index[0], brick.Index[1], brick.Index[2])] = 1;
  }
  if (request.Pieces > 1)
  {
    request.SumOverPieces(kept);
    request.SumOverPieces(field.Sides);
  }
  int32_t next = 0;
  for (size_t b = 0; b < kept.size(); ++b)
  {
    field.BrickOf[b] = kept[b] ? next++ : -1;
  }
  return next;
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
  if (request.Pieces < 1 || request.Piece < 0 || request.Piece >= request.Pieces ||
    (request.Pieces > 1 && !request.SumOverPieces))
  {
    error = "Piece " + std::to_string(request.Piece) + " of " + std::to_string(request.Pieces) +
      " is not a piece of a distributed run.";
    return false;
  }
  if (request.BrickSize < 2 || request.BrickSize > 1024)
  {
    error =
      "BrickSize must be between 2 and 1024; it is " + std::to_string(request.BrickSize) + ".";
    return false;
  }
  return true;
}

/// The grid of bricks; false and `error` when it would have too many bricks to index.
bool MakeBrickGrid(const SampleGrid& grid, int size, BrickGrid& bricks, std::string& error)
{
  bricks = BrickGrid::Over(grid.Whole, size);
  const double total =
    double(bricks.Counts[0]) * double(bricks.Counts[1]) * double(bricks.Counts[2]);
  if (total > double(int64_t(1) << 28))
  {
    error = "The grid would have " + FormatNumber(total) +
      " bricks, more than 2^28 bricks: use a larger BrickSize.";
    return false;
  }
  return true;
}

/// Whether the grid of bricks (its sides, pieces, binning offsets, the pieces kept and the
/// winding sign's proven sides: 15 bytes a brick) fits the memory limit.
bool CheckBrickGridMemory(const SparseBandRequest& request,
  const BrickGrid& bricks,
  std::string& error)
{
  const double bytes = 15.0 * double(bricks.Total());
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

namespace
{
/// The bricks `ids` (with their binned sites, or none) in batches in parallel, progress
/// from `from` to `to` and abort between batches: computed[t] and side[t] for ids[t].
/// False when aborted.
bool ComputeBricks(const LocalSites& local,
  const BrickGrid& bricks,
  const std::vector<int64_t>& ids,
  const BrickSites* binned,
  const SparseBandRequest& request,
  const BrickWindingSigns* winding,
  const Execution& execution,
  double from,
  double to,
  std::vector<SparseBrick>& computed,
  std::vector<int8_t>& side,
  int64_t& evaluations)
{
  const int64_t count = static_cast<int64_t>(ids.size());
  computed.resize(ids.size());
  side.assign(ids.size(), 0);
  std::atomic<int64_t> total{ 0 };
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
          const int64_t b = ids[t];
          std::vector<uint32_t> candidates;
          if (binned)
          {
            candidates.assign(binned->Sites.begin() + binned->Start[b],
              binned->Sites.begin() + binned->Start[b + 1]);
          }
          computed[t] = ComputeBrick(
            local, bricks, b, std::move(candidates), request, winding, brickEvaluations, side[t]);
        }
        total += brickEvaluations;
      });
    if (!execution.Report(from + (to - from) * double(batch + 1) / batches))
    {
      return false;
    }
  }
  evaluations += total.load();
  return true;
}

/// The winding sign's sides of the bricks that no site reached (all beyond the band) and
/// this process owns (every Pieces-th): proven by BrickWindingSigns' test, or decided
/// sample by sample; the bricks whose samples differ go to `mixed`. Progress from `from` to `to`;
/// false when aborted.
bool FarWindingSides(const BrickWindingSigns& winding,
  const BrickGrid& bricks,
  const BrickSites& binned,
  const SparseBandRequest& request,
  const Execution& execution,
  double from,
  double to,
  SparseBandField& field,
  std::vector<int64_t>& mixed)
{
  std::vector<int64_t> unproven;
  for (int64_t b = 0; b < bricks.Total(); ++b)
  {
    if (binned.Start[b + 1] == binned.Start[b] && b % request.Pieces == request.Piece)
    {
      const int proven = winding.ProvenSide(b);
      if (proven < 0)
      {
        unproven.push_back(b);
      }
      field.Sides[b] = proven < 0 ? 0 : (proven ? -1 : 1);
    }
  }
  field.WindingBricksDecided = static_cast<int64_t>(unproven.size());
  const int64_t count = static_cast<int64_t>(unproven.size());
  const int64_t batches = std::max<int64_t>(1, std::min<int64_t>(10, count / 16));
  std::vector<int8_t> found(unproven.size(), 0);
  for (int64_t batch = 0; batch < batches; ++batch)
  {
    const int64_t first = count * batch / batches, last = count * (batch + 1) / batches;
    execution.For(last - first,
      1,
      [&](int64_t begin, int64_t end)
      {
        std::vector<uint8_t> inside;
        for (int64_t t = first + begin; t < first + end; ++t)
        {
          const IndexBox box = bricks.Extent(bricks.Indices(unproven[t]));
          inside.resize(box.Count());
          winding.Decide(box, inside.data());
          const bool uniform =
            std::all_of(inside.begin(), inside.end(), [&](uint8_t in) { return in == inside[0]; });
          found[t] = uniform ? (inside[0] ? -1 : 1) : 0;
        }
      });
    if (!execution.Report(from + (to - from) * double(batch + 1) / batches))
    {
      return false;
    }
  }
  for (int64_t t = 0; t < count; ++t)
  {
    field.Sides[unproven[t]] = found[t];
    if (found[t] == 0)
    {
      mixed.push_back(unproven[t]);
    }
  }
  return true;
}

/// The kept bricks (`ids`[t] with computed[t]) into the field, in the order of their ids;
/// the side of each brick left out (ShareSides numbers the pieces).
void KeepBricks(const std::vector<int64_t>& ids,
  std::vector<SparseBrick>& computed,
  const std::vector<int8_t>& side,
  SparseBandField& field)
{
  std::vector<size_t> order;
  for (size_t t = 0; t < ids.size(); ++t)
  {
    if (computed[t].Distance)
    {
      order.push_back(t);
    }
    else
    {
      field.Sides[ids[t]] = side[t];
    }
  }
  std::sort(order.begin(), order.end(), [&](size_t x, size_t y) { return ids[x] < ids[y]; });
  for (const size_t t : order)
  {
    field.BandSamples += computed[t].BandSamples;
    field.Sides[ids[t]] = 0;
    field.Bricks.push_back(std::move(computed[t]));
  }
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
  // This process's share: every Pieces-th brick the band may touch.
  std::vector<int64_t> todo;
  for (int64_t b = 0, reached = 0; b < bricks.Total(); ++b)
  {
    if (binned.Start[b + 1] > binned.Start[b] && reached++ % request.Pieces == request.Piece)
    {
      todo.push_back(b);
    }
  }
  execution.EndStage("bricks");
  // The winding sign: the mesh (moved to the local frame, kept by BuildLocalSites) on the
  // local grid, as the dense field signs it.
  std::unique_ptr<BrickWindingSigns> winding;
  if (request.Sign == SignMode::WindingNumber)
  {
    winding = std::make_unique<BrickWindingSigns>();
    winding->Prepare(mesh.Points, mesh.Triangles, local.Request.Grid, bricks, execution.For);
    execution.EndStage("winding");
  }
  const double scanEnd = winding ? 0.8 : 0.95;
  if (!execution.Report(0.05))
  {
    field.Aborted = true;
    return true;
  }
  std::vector<SparseBrick> computed;
  std::vector<int8_t> side;
  if (!ComputeBricks(local,
        bricks,
        todo,
        &binned,
        request,
        winding.get(),
        execution,
        0.05,
        scanEnd,
        computed,
        side,
        field.Evaluations))
  {
    field.Aborted = true;
    return true;
  }
  KeepBricks(todo, computed, side, field);
  execution.EndStage("scan");
  if (winding)
  {
    // Beyond the band: one side a brick where a test proves it, else sample by sample;
    // a brick whose samples differ becomes a piece without band samples.
    std::vector<int64_t> mixed;
    if (!FarWindingSides(
          *winding, bricks, binned, request, execution, scanEnd, 0.95, field, mixed) ||
      !ComputeBricks(local,
        bricks,
        mixed,
        nullptr,
        request,
        winding.get(),
        execution,
        0.95,
        1,
        computed,
        side,
        field.Evaluations))
    {
      field.Aborted = true;
      return true;
    }
    // Merged with the band's bricks in the order of their ids.
    std::vector<int64_t> ids;
    std::vector<SparseBrick> all;
    std::vector<int8_t> sides;
    for (size_t t = 0; t < field.Bricks.size(); ++t)
    {
      const std::array<int, 3>& b = field.Bricks[t].Index;
      ids.push_back(bricks.Id(b[0], b[1], b[2]));
      all.push_back(std::move(field.Bricks[t]));
      sides.push_back(0);
    }
    ids.insert(ids.end(), mixed.begin(), mixed.end());
    std::move(computed.begin(), computed.end(), std::back_inserter(all));
    sides.insert(sides.end(), side.begin(), side.end());
    field.Bricks.clear();
    field.BandSamples = 0;
    KeepBricks(ids, all, sides, field);
  }
  const int64_t pieces = ShareSides(request, field);
  if (request.Sign == SignMode::PseudoNormal)
  {
    FloodBrickSides(bricks, PieceFaceSides(request, pieces, field), field);
  }
  execution.EndStage("sides");
  return true;
}

} // namespace vtkdf
