#include "Proximity/ProximityParts.h"

#include "Common/Vector3.h"
#include "Proximity/ProximityGPU.h"
#include "Segment/TriangleCrossings.h"
#include "Winding/WindingCrossings.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <map>
#include <utility>

namespace vtkdf
{
namespace proximity
{
namespace
{

/// A point whose side of the other model is known, with its exact squared distance to it
/// (0 when not computed).
struct KnownPoint
{
  const double* X;
  double D2;
  bool Inside;
  int64_t Triangle;
};

/// The side of x from a known point y that a ball free of the surface joins to it: one
/// centred at y of radius d_y, or at x of radius d_x (`d2x`, 0 when not known), with a
/// margin far above the roundings of the squared distances.
const KnownPoint* SameSide(const std::vector<KnownPoint>& known, const double x[3], double d2x)
{
  const double shrink = 1 - 1e-9;
  for (auto it = known.rbegin(); it != known.rend(); ++it)
  {
    const double gap2 = (x[0] - it->X[0]) * (x[0] - it->X[0]) +
      (x[1] - it->X[1]) * (x[1] - it->X[1]) + (x[2] - it->X[2]) * (x[2] - it->X[2]);
    if (gap2 < shrink * std::max(it->D2, d2x))
    {
      return &*it;
    }
  }
  return nullptr;
}

bool InRegion(const std::array<double, 6>& region, const double x[3])
{
  for (int k = 0; k < 3; ++k)
  {
    if (x[k] < region[2 * k] || x[k] > region[2 * k + 1])
    {
      return false;
    }
  }
  return true;
}

bool BoxMeetsRegion(const Box& box, const std::array<double, 6>& region)
{
  for (int k = 0; k < 3; ++k)
  {
    if (box.Max[k] < region[2 * k] || box.Min[k] > region[2 * k + 1])
    {
      return false;
    }
  }
  return true;
}

/// Lattice divisions of a triangle for `step` (FaceSamples' n).
int64_t Divisions(const double p[9], double step)
{
  double longest = 0;
  for (int e = 0; e < 3; ++e)
  {
    const double* u = p + 3 * e;
    const double* v = p + 3 * ((e + 1) % 3);
    longest = std::max(longest,
      std::sqrt((u[0] - v[0]) * (u[0] - v[0]) + (u[1] - v[1]) * (u[1] - v[1]) +
        (u[2] - v[2]) * (u[2] - v[2])));
  }
  const double divisions = std::ceil(longest / step);
  return divisions >= 1 ? static_cast<int64_t>(divisions) : 1;
}

void RunFor(const Execution& execution,
  int64_t n,
  int64_t grain,
  const std::function<void(int64_t, int64_t)>& body)
{
  if (execution.For)
  {
    execution.For(n, grain, body);
  }
  else if (n > 0)
  {
    body(0, n);
  }
}

void Keep(PenetrationSide& side, const ContactSample& sample, const double closest[3], int64_t t)
{
  if (sample.Depth > side.Depth || side.TriangleOfOther < 0)
  {
    side.Depth = sample.Depth;
    side.Deepest = sample.Point;
    std::copy(closest, closest + 3, side.ClosestOnOther.begin());
    side.Normal = sample.Normal;
    side.TriangleOfOther = t;
  }
}

ContactSample MakeSample(const double x[3],
  const PointQuery& query,
  int64_t triangle,
  int64_t vertex)
{
  ContactSample sample;
  sample.Point = { { x[0], x[1], x[2] } };
  sample.Depth = std::sqrt(query.D2);
  const Point3 towards{
    { query.Closest[0] - x[0], query.Closest[1] - x[1], query.Closest[2] - x[2] }
  };
  sample.Normal = Unit(towards);
  sample.Triangle = triangle;
  sample.Vertex = vertex;
  return sample;
}

} // namespace

/// The signed distances of `self`'s points to `other` (NaN for the points no triangle
/// uses), with each point's query kept for the penetration. False with `error` when the
/// GPU fails.
bool PointDistances(const ProximityModel::Data& self,
  const ProximityModel::Data& other,
  const OnDevice& gpu,
  const Execution& execution,
  std::vector<double>& distances,
  std::vector<PointQuery>& queries,
  std::string& error)
{
  const int64_t n = static_cast<int64_t>(self.Model.Points.size());
  distances.assign(static_cast<size_t>(n), std::nan(""));
  queries.assign(static_cast<size_t>(n), PointQuery());
  NearestAnswers answers;
  if (gpu.Device && !DeviceNearestToPoints(*gpu.Device, gpu.Self, gpu.Other, answers, error))
  {
    return false;
  }
  RunFor(execution,
    n,
    256,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t i = begin; i < end; ++i)
      {
        if (!self.Used[static_cast<size_t>(i)])
        {
          continue;
        }
        const double* x = self.Model.Points[static_cast<size_t>(i)].data();
        PointQuery query;
        if (gpu.Device)
        {
          query = PointQuery(answers, static_cast<size_t>(i));
          query.Inside = other.Inside(x, query.Closest, query.Triangle, query.D2);
        }
        else
        {
          query = PointQuery(other, x);
        }
        queries[static_cast<size_t>(i)] = query;
        const double distance = std::sqrt(query.D2);
        distances[static_cast<size_t>(i)] = query.Inside ? -distance : distance;
      }
    });
  return true;
}

namespace
{

/// How many of the samples evaluated last in a triangle stay known points.
constexpr size_t RecentSamples = 4;

/// The vertices of `self` in `region` inside `other` (from their queries), into `side`.
void VertexPenetration(const ProximityModel::Data& self,
  const std::vector<PointQuery>& vertexQueries,
  const std::array<double, 6>& region,
  bool keepContacts,
  PenetrationSide& side)
{
  for (size_t i = 0; i < self.Model.Points.size(); ++i)
  {
    const double* x = self.Model.Points[i].data();
    if (!self.Used[i] || !InRegion(region, x))
    {
      continue;
    }
    ++side.Samples;
    const PointQuery& query = vertexQueries[i];
    if (query.Inside)
    {
      ++side.SamplesInside;
      const ContactSample sample = MakeSample(x, query, -1, static_cast<int64_t>(i));
      Keep(side, sample, query.Closest, query.Triangle);
      if (keepContacts)
      {
        side.Contacts.push_back(sample);
      }
    }
  }
}

/// A block's results, merged in order into the side (the report does not depend on the
/// threads).
struct BlockResult
{
  PenetrationSide Side;
  int64_t Queries = 0;  // exact nearest-triangle queries on the CPU
  int64_t Windings = 0; // winding-number evaluations
};

/// The face samples of `self`'s triangles (corners excluded) against `other`: which lie
/// inside, how deep, and the contacts. One instance per Penetrate; Triangle is called
/// from many threads, each with its own scratch.
struct FaceSampler
{
  const ProximityModel::Data& Self;
  const ProximityModel::Data& Other;
  const OnDevice& GPU;
  const NearestAnswers& Answers;           // the batch's nearest triangles (GPU)
  const std::vector<int64_t>& FirstSample; // each triangle's first answer in the batch
  const std::vector<PointQuery>& VertexQueries;
  const std::array<double, 6>& Region;
  double Step;
  bool KeepContacts;
  bool Chain; // the winding-number rule on a closed model: sides chained between samples

  /// The points whose side and distance are known: the corners, then the samples
  /// evaluated last (their coordinates in Recent).
  struct Scratch
  {
    std::vector<KnownPoint> Known;
    std::array<std::array<double, 3>, RecentSamples> Recent;
    size_t RecentNext = 0;
  };

  /// Triangle t's samples (batchTriangle: the batch's first triangle, for the answers).
  void Triangle(int64_t t, int64_t batchTriangle, BlockResult& result, Scratch& scratch) const
  {
    if (!BoxMeetsRegion(this->Self.Tree->Boxes()[static_cast<size_t>(t)], this->Region))
    {
      return;
    }
    double p[9];
    this->Self.Model.Corners(static_cast<size_t>(t), p);
    const int64_t n = Divisions(p, this->Step);
    // The corners are known points; the samples evaluated last join them.
    std::vector<KnownPoint>& known = scratch.Known;
    known.clear();
    for (const size_t id : this->Self.Model.Triangles[static_cast<size_t>(t)])
    {
      const PointQuery& corner = this->VertexQueries[id];
      known.push_back(
        { this->Self.Model.Points[id].data(), corner.D2, corner.Inside, corner.Triangle });
    }
    int64_t hint = known[0].Triangle;
    // The triangle's samples in the GPU's answers, in the lattice's order.
    size_t answer = this->GPU.Device
      ? static_cast<size_t>(this->FirstSample[static_cast<size_t>(t - batchTriangle)])
      : 0;
    for (int64_t i = 0; i <= n; ++i)
    {
      for (int64_t j = 0; i + j <= n; ++j)
      {
        if ((i == 0 && j == 0) || i == n || j == n)
        {
          continue; // a corner: a vertex, already counted
        }
        const size_t answerIndex = answer++;
        const double u = double(i) / n, v = double(j) / n;
        const double x[3] = { p[0] + u * (p[3] - p[0]) + v * (p[6] - p[0]),
          p[1] + u * (p[4] - p[1]) + v * (p[7] - p[1]),
          p[2] + u * (p[5] - p[2]) + v * (p[8] - p[2]) };
        if (!InRegion(this->Region, x))
        {
          continue;
        }
        ++result.Side.Samples;
        PointQuery query;
        const bool decided = this->Chain
          ? this->ChainedQuery(x, answerIndex, result, scratch, query)
          : this->FreshQuery(x, answerIndex, result, scratch, hint, query);
        if (decided || !query.Inside)
        {
          continue;
        }
        ++result.Side.SamplesInside;
        const ContactSample sample = MakeSample(x, query, t, -1);
        Keep(result.Side, sample, query.Closest, query.Triangle);
        if (this->KeepContacts)
        {
          result.Side.Contacts.push_back(sample);
        }
      }
    }
  }

  /// Without the contacts' list only the deepest matters: an inside sample whose distance
  /// cannot exceed the deepest so far (by the triangle inequality from a known point,
  /// d(x) <= d(y) + |x - y|) needs no exact distance.
  bool CannotDeepen(const double x[3], const PenetrationSide& part, const Scratch& scratch) const
  {
    if (this->KeepContacts || part.TriangleOfOther < 0)
    {
      return false;
    }
    double bound = HUGE_VAL;
    for (const KnownPoint& y : scratch.Known)
    {
      const double gap2 = (x[0] - y.X[0]) * (x[0] - y.X[0]) + (x[1] - y.X[1]) * (x[1] - y.X[1]) +
        (x[2] - y.X[2]) * (x[2] - y.X[2]);
      bound = std::min(bound, std::sqrt(y.D2) + std::sqrt(gap2));
    }
    return bound * (1 + 1e-12) <= part.Depth;
  }

  /// A closed chain: the side from a known point joined by a ball free of the surface,
  /// else the winding number; the distance only when needed. True when the sample is
  /// settled without a query (outside, or inside but no deeper); else `query` holds it.
  bool ChainedQuery(const double x[3],
    size_t answerIndex,
    BlockResult& result,
    Scratch& scratch,
    PointQuery& query) const
  {
    std::vector<KnownPoint>& known = scratch.Known;
    const KnownPoint* same = SameSide(known, x, 0);
    if (same && !same->Inside)
    {
      return true;
    }
    if (same && this->CannotDeepen(x, result.Side, scratch))
    {
      ++result.Side.SamplesInside;
      return true;
    }
    query = this->GPU.Device ? PointQuery(this->Answers, answerIndex)
                             : PointQuery(this->Other, x, known.back().Triangle);
    result.Queries += this->GPU.Device ? 0 : 1;
    same = same ? same : SameSide(known, x, query.D2);
    if (same)
    {
      query.Inside = same->Inside;
    }
    else
    {
      query.Inside = this->Other.Winding.Inside(x);
      ++result.Windings;
    }
    if (known.size() == 3 + RecentSamples)
    {
      known.erase(known.begin() + 3); // the corners stay
    }
    known.push_back({ nullptr, query.D2, query.Inside, query.Triangle });
    std::copy(x, x + 3, scratch.Recent[scratch.RecentNext].data());
    known.back().X = scratch.Recent[scratch.RecentNext].data();
    scratch.RecentNext = (scratch.RecentNext + 1) % scratch.Recent.size();
    return false;
  }

  /// Each sample alone: the winding number decides before the distance is needed; the
  /// pseudonormal rule after it. True when settled without a query, as ChainedQuery.
  bool FreshQuery(const double x[3],
    size_t answerIndex,
    BlockResult& result,
    const Scratch& scratch,
    int64_t& hint,
    PointQuery& query) const
  {
    const bool winding = this->Other.Rule == InsideRule::WindingNumber;
    if (winding)
    {
      ++result.Windings;
      if (!this->Other.Winding.Inside(x))
      {
        return true;
      }
      if (this->CannotDeepen(x, result.Side, scratch))
      {
        ++result.Side.SamplesInside;
        return true;
      }
    }
    query =
      this->GPU.Device ? PointQuery(this->Answers, answerIndex) : PointQuery(this->Other, x, hint);
    result.Queries += this->GPU.Device ? 0 : 1;
    hint = query.Triangle;
    query.Inside = winding || this->Other.Inside(x, query.Closest, query.Triangle, query.D2);
    return false;
  }
};
/// The GPU's batch from block batchBegin on: blocks (of blockSize triangles from block
/// firstBlock) up to `budget` samples and one block more, with each triangle's first
/// sample in `firstSample`. Returns the block after the batch.
int64_t DeviceBatch(const ProximityModel::Data& self,
  const std::array<double, 6>& region,
  double step,
  int64_t firstBlock,
  int64_t blockSize,
  int64_t batchBegin,
  int64_t blocks,
  int64_t budget,
  SampleBatch& batch,
  std::vector<int64_t>& firstSample)
{
  const int64_t triangles = static_cast<int64_t>(self.Model.Triangles.size());
  batch.Items.clear();
  batch.Samples = 0;
  firstSample.clear();
  int64_t batchEnd = batchBegin;
  for (; batchEnd < blocks && (batchEnd == batchBegin || batch.Samples < budget); ++batchEnd)
  {
    const int64_t end = std::min(triangles, (firstBlock + batchEnd + 1) * blockSize);
    for (int64_t t = (firstBlock + batchEnd) * blockSize; t < end; ++t)
    {
      firstSample.push_back(batch.Samples);
      if (!BoxMeetsRegion(self.Tree->Boxes()[static_cast<size_t>(t)], region))
      {
        continue;
      }
      double p[9];
      self.Model.Corners(static_cast<size_t>(t), p);
      const int64_t n = Divisions(p, step);
      const int64_t count = (n + 1) * (n + 2) / 2 - 3;
      if (count > 0)
      {
        batch.Items.insert(batch.Items.end(),
          { static_cast<int32_t>(t),
            static_cast<int32_t>(batch.Samples),
            static_cast<int32_t>(n),
            0 });
        batch.Samples += count;
      }
    }
  }
  return batchEnd;
}

} // namespace

/// The penetration of `self` into `other`: its vertices (from their queries) and face
/// samples in `region` inside `other`. False with `error` when the GPU fails.
bool Penetrate(const ProximityModel::Data& self,
  const ProximityModel::Data& other,
  const OnDevice& gpu,
  const std::vector<PointQuery>& vertexQueries,
  const std::array<double, 6>& region,
  double step,
  bool keepContacts,
  int share,
  int shares,
  const Execution& execution,
  PenetrationSide& side,
  int64_t& queries,
  int64_t& windings,
  std::string& error)
{
  side = PenetrationSide();
  // The vertices are the first share's; the blocks of triangles are split in order.
  if (share == 0)
  {
    VertexPenetration(self, vertexQueries, region, keepContacts, side);
  }
  // The face samples other than the corners, in blocks of triangles whose results are
  // merged in order: the report does not depend on the threads.
  const int64_t triangles = static_cast<int64_t>(self.Model.Triangles.size());
  const int64_t blockSize = 64;
  const int64_t allBlocks = (triangles + blockSize - 1) / blockSize;
  const int64_t firstBlock = allBlocks * share / shares;
  const int64_t blocks = allBlocks * (share + 1) / shares - firstBlock;
  std::vector<BlockResult> results(static_cast<size_t>(blocks));
  // On the CPU, every block at once, each sample's nearest triangle searched when it is
  // needed. On the GPU, batches of blocks: the nearest triangles of all the batch's
  // samples first (FirstSample: each triangle's first in the answers), then the blocks.
  SampleBatch batch;
  NearestAnswers answers;
  std::vector<int64_t> firstSample;
  const FaceSampler sampler{ self,
    other,
    gpu,
    answers,
    firstSample,
    vertexQueries,
    region,
    step,
    keepContacts,
    other.Rule == InsideRule::WindingNumber && other.Closed };
  // A batch holds blocks up to DeviceBatchSamples (and one block more).
  const int64_t batchBudget = gpu.Device ? DeviceBatchSamples(*gpu.Device) : 0;
  for (int64_t batchBegin = 0, batchEnd = 0; batchBegin < blocks; batchBegin = batchEnd)
  {
    batchEnd = blocks;
    const int64_t batchTriangle = (firstBlock + batchBegin) * blockSize;
    if (gpu.Device)
    {
      batchEnd = DeviceBatch(self,
        region,
        step,
        firstBlock,
        blockSize,
        batchBegin,
        blocks,
        batchBudget,
        batch,
        firstSample);
      if (batch.Samples > 0 &&
        !DeviceNearestToSamples(*gpu.Device, gpu.Self, gpu.Other, batch, answers, error))
      {
        return false;
      }
      queries += batch.Samples;
    }
    RunFor(execution,
      batchEnd - batchBegin,
      1,
      [&, batchBegin](int64_t first, int64_t last)
      {
        FaceSampler::Scratch scratch;
        scratch.Known.reserve(3 + RecentSamples);
        for (int64_t block = batchBegin + first; block < batchBegin + last; ++block)
        {
          const int64_t end = std::min(triangles, (firstBlock + block + 1) * blockSize);
          for (int64_t t = (firstBlock + block) * blockSize; t < end; ++t)
          {
            sampler.Triangle(t, batchTriangle, results[static_cast<size_t>(block)], scratch);
          }
        }
      });
  }
  for (const BlockResult& result : results)
  {
    const PenetrationSide& part = result.Side;
    side.Samples += part.Samples;
    side.SamplesInside += part.SamplesInside;
    queries += result.Queries;
    windings += result.Windings;
    if (part.TriangleOfOther >= 0 && (part.Depth > side.Depth || side.TriangleOfOther < 0))
    {
      side.Depth = part.Depth;
      side.Deepest = part.Deepest;
      side.ClosestOnOther = part.ClosestOnOther;
      side.Normal = part.Normal;
      side.TriangleOfOther = part.TriangleOfOther;
    }
    side.Contacts.insert(side.Contacts.end(), part.Contacts.begin(), part.Contacts.end());
  }
  return true;
}

/// Face samples (corners excluded) that `self`'s triangles meeting `region` would take.
double CountFaceSamples(const ProximityModel::Data& self,
  const std::array<double, 6>& region,
  double step)
{
  double count = 0;
  for (size_t t = 0; t < self.Model.Triangles.size(); ++t)
  {
    if (BoxMeetsRegion(self.Tree->Boxes()[t], region))
    {
      double p[9];
      self.Model.Corners(t, p);
      const double n = static_cast<double>(Divisions(p, step));
      count += (n + 1) * (n + 2) / 2 - 3;
    }
  }
  return count;
}
} // namespace proximity
} // namespace vtkdf
