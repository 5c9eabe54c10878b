#include "LinearFactor/PointDistance.h"

#include "Common/Barycentric.h"
#include "Common/LargeVector.h"
#include "Common/PointTriangleDistance.h"
#include "Common/Vector3.h"
#include "LinearFactor/QueryTree.h"
#include "Winding/WindingCrossings.h"
#include "Winding/WindingNumber.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <mutex>
#include <vector>

namespace vtkdf
{
namespace
{
using nearest::Primitive;
using nearest::QueryTree;

/// The coordinates of `closest` on primitive p, which holds the closest feature of `type`
/// (0 vertex a, 1 edge ab, 2 face).
void Barycentric(const Primitive& p,
  uint8_t type,
  const double* a,
  const double* b,
  const double closest[3],
  double bary[3])
{
  std::fill(bary, bary + 3, 0.0);
  if (type == 2)
  {
    FaceBarycentric(p.X, p.X + 3, p.X + 6, closest, bary);
    return;
  }
  int atA = 0, atB = 0;
  while (atA < 2 && !SamePoint(p.X + 3 * atA, a))
  {
    ++atA;
  }
  double along = 0;
  if (b)
  {
    while (atB < 2 && (atB == atA || !SamePoint(p.X + 3 * atB, b)))
    {
      ++atB;
    }
    along = SegmentParameter(a, b, closest);
    bary[atB] = along;
  }
  bary[atA] += 1 - along;
}

/// Spreads the 16 low bits of x three bits apart (one axis of a 48-bit Morton code).
uint64_t Spread16(uint64_t x)
{
  x &= 0xffff;
  x = (x | (x << 16)) & 0x0000ff0000ffull;
  x = (x | (x << 8)) & 0x00f00f00f00full;
  x = (x | (x << 4)) & 0x0c30c30c30c3ull;
  x = (x | (x << 2)) & 0x249249249249ull;
  return x;
}

/// The points' indices in the Morton order of their positions in the box lo..hi (16 bits
/// an axis; points in one cell in input order), by three 16-bit radix passes.
LargeVector<int64_t> MortonOrder(const double* points,
  int64_t count,
  const double lo[3],
  const double hi[3],
  const ParallelFor& parallelFor)
{
  LargeVector<uint64_t> keys(count), sortedKeys(count);
  LargeVector<int64_t> order(count), sorted(count);
  auto code = [&](int64_t begin, int64_t end)
  {
    for (int64_t i = begin; i < end; ++i)
    {
      uint64_t morton = 0;
      for (int a = 0; a < 3; ++a)
      {
        const double extent = hi[a] - lo[a];
        const double cell =
          extent > 0 ? std::floor((points[3 * i + a] - lo[a]) / extent * 65535.0) : 0.0;
        morton |= Spread16(static_cast<uint64_t>(std::min(65535.0, std::max(0.0, cell))))
          << (2 - a);
      }
      keys[i] = morton;
      order[i] = i;
    }
  };
  parallelFor ? parallelFor(count, 16384, code) : code(0, count);
  std::vector<int64_t> start(65537);
  for (int pass = 0; pass < 3; ++pass)
  {
    const int shift = 16 * pass;
    std::fill(start.begin(), start.end(), 0);
    for (int64_t i = 0; i < count; ++i)
    {
      ++start[((keys[i] >> shift) & 0xffff) + 1];
    }
    for (int b = 0; b < 65536; ++b)
    {
      start[b + 1] += start[b];
    }
    for (int64_t i = 0; i < count; ++i)
    {
      const int64_t to = start[(keys[i] >> shift) & 0xffff]++;
      sortedKeys[to] = keys[i];
      sorted[to] = order[i];
    }
    keys.swap(sortedKeys);
    order.swap(sorted);
  }
  return order;
}

/// The summary of the |distances| (NaN: beyond the cap) in input order, whatever the
/// threads, but for the excluded points.
void Summarize(const LargeVector<double>& magnitude,
  const uint8_t* excluded,
  PointDistanceStatistics& stats)
{
  const int64_t count = static_cast<int64_t>(magnitude.size());
  for (int64_t i = 0; i < count; ++i)
  {
    if (!excluded || !excluded[i])
    {
      stats.Count(magnitude[i], i);
    }
  }
  stats.Finish();
}

} // namespace

struct PointDistanceQueries::Internal
{
  MeshInput Mesh; // in the local frame
  QueryTree Tree;
  // The winding hierarchy, built when first needed (a closed chain's points off the
  // surface never need it).
  mutable WindingNumber Winding;
  mutable std::once_flag WindingOnce;
  const WindingNumber& Hierarchy() const
  {
    std::call_once(
      this->WindingOnce, [this] { this->Winding.Build(this->Mesh.Points, this->Mesh.Triangles); });
    return this->Winding;
  }
  SignMode Sign = SignMode::Unsigned;
  bool WindingBuilt = false;
  bool ClosedChain = false; // the triangles' w is an integer, constant off the surface
  double Scale = 1;         // world = Scale * local, a power of two
  int64_t Triangles = 0, Segments = 0;

  /// The index of `source` (in the tree's mesh order) within its cell's run of
  /// triangles, segments or points.
  int64_t SubIndex(int64_t source) const
  {
    const LargeVector<int64_t>* cells = &this->Mesh.TriangleCells;
    int64_t i = source;
    if (source >= this->Triangles + this->Segments)
    {
      cells = &this->Mesh.VertexCells, i = source - this->Triangles - this->Segments;
    }
    else if (source >= this->Triangles)
    {
      cells = &this->Mesh.SegmentCells, i = source - this->Triangles;
    }
    int64_t first = i;
    while (first > 0 && (*cells)[first - 1] == (*cells)[i])
    {
      --first;
    }
    return i - first;
  }
};

PointDistanceQueries::PointDistanceQueries()
  : Impl(new Internal)
{
}

PointDistanceQueries::~PointDistanceQueries() = default;

SignMode PointDistanceQueries::Sign() const
{
  return this->Impl->Sign;
}

int64_t PointDistanceQueries::Primitives() const
{
  const MeshInput& mesh = this->Impl->Mesh;
  return int64_t(mesh.Triangles.size() / 3 + mesh.Segments.size() / 2 + mesh.Vertices.size());
}

bool PointDistanceQueries::Build(MeshInput mesh,
  SignMode sign,
  bool windingValues,
  const ParallelFor& parallelFor,
  std::string& error)
{
  this->Impl.reset(new Internal);
  Internal& in = *this->Impl;
  if (mesh.Empty())
  {
    error = "the mesh has no cell to measure distances to";
    return false;
  }
  // The frame: the mesh scaled by a power of two near its size (exact both ways).
  std::array<double, 6> bounds;
  const int64_t points = static_cast<int64_t>(mesh.Points.size() / 3);
  for (const LargeVector<int64_t>* ids : { &mesh.Triangles, &mesh.Segments, &mesh.Vertices })
  {
    for (const int64_t id : *ids)
    {
      if (id < 0 || id >= points)
      {
        error = "a cell refers to point " + std::to_string(id) + " of " + std::to_string(points);
        return false;
      }
    }
  }
  double size = 0;
  if (UsedPointBounds(mesh, bounds))
  {
    for (int a = 0; a < 3; ++a)
    {
      size = std::max(size, bounds[2 * a + 1] - bounds[2 * a]);
    }
  }
  in.Scale = std::isfinite(size) && size > 0 ? std::ldexp(1.0, std::ilogb(size)) : 1.0;
  GridFrame frame;
  frame.Scale = in.Scale;
  MoveToLocalFrame(mesh, frame, parallelFor);
  in.Mesh = std::move(mesh);
  in.Triangles = static_cast<int64_t>(in.Mesh.Triangles.size() / 3);
  in.Segments = static_cast<int64_t>(in.Mesh.Segments.size() / 2);
  in.Sign = sign;
  if (!in.Tree.Build(in.Mesh, parallelFor, error))
  {
    return false;
  }
  in.WindingBuilt = sign == SignMode::WindingNumber || windingValues;
  if (in.WindingBuilt)
  {
    in.ClosedChain = IsClosedChain(in.Mesh.Points, in.Mesh.Triangles);
  }
  return true;
}

int64_t PointDistanceQueries::Query(const double world[3],
  double cap,
  const double* seed,
  const PointQueryParts& parts,
  PointAnswer& answer,
  const PointAnswer* hint) const
{
  const Internal& in = *this->Impl;
  const QueryTree& tree = in.Tree;
  const double scale = in.Scale;
  const double x[3] = { world[0] / scale, world[1] / scale, world[2] / scale };
  const double localCap = cap / scale;
  const bool banded = std::isfinite(localCap);
  const double capBound2 = banded ? localCap * localCap * (1 + 1e-9) + tree.Tolerance2 : HUGE_VAL;
  double bound2 = capBound2;
  if (seed)
  {
    double r2 = 0;
    for (int a = 0; a < 3; ++a)
    {
      const double d = x[a] - seed[a] / scale;
      r2 += d * d;
    }
    bound2 = std::min(bound2, r2 * (1 + 1e-9) + tree.Tolerance2);
  }
  int64_t index;
  double best2, closest[3];
  int feature = InFace;
  int64_t evaluations = tree.Nearest(x, bound2, index, best2, closest, feature);
  if (index < 0 && bound2 < capBound2)
  {
    // The seed fell short by rounding: search without it.
    evaluations += tree.Nearest(x, capBound2, index, best2, closest, feature);
  }
  // The winding number's side (and value) wherever it is asked for, within the cap or not.
  const bool beyond = index < 0 || (banded && std::sqrt(best2) > localCap);
  const double clearance = beyond ? localCap : std::sqrt(best2);
  double winding = 0;
  bool inside = false;
  if (in.WindingBuilt && (in.Sign == SignMode::WindingNumber || parts.Winding))
  {
    // A closed chain's side from a neighbour (SideFromHint) or the crossings of a ray
    // (an integer w, exact); otherwise, and on the surface, the winding number itself.
    int64_t crossings = 0;
    if (this->SideFromHint(x, clearance, parts, hint, inside))
    {
    }
    else if (in.ClosedChain && !parts.Winding && in.Tree.CrossingCount(x, crossings))
    {
      inside = crossings != 0;
    }
    else
    {
      inside = in.Hierarchy().Inside(x, parts.Winding ? &winding : nullptr);
    }
  }
  answer = PointAnswer();
  answer.Winding = winding;
  answer.Inside = inside;
  answer.Clearance = clearance * scale;
  if (beyond)
  {
    answer.Beyond = true;
    answer.Distance = in.Sign == SignMode::PseudoNormal
      ? NAN
      : (in.Sign == SignMode::WindingNumber && inside ? -cap : cap);
    for (int a = 0; a < 3; ++a)
    {
      answer.Closest[a] = answer.Barycentric[a] = answer.Gradient[a] = NAN;
    }
    return evaluations;
  }
  // The feature: 0 vertex, 1 edge, 2 face (the grid's ClosestFeature).
  const uint8_t type = feature == InFace ? 2 : (feature >= OnEdgeAB ? 1 : 0);
  const Primitive& t = tree.Get(index);
  const int first = feature >= OnEdgeAB ? feature - OnEdgeAB : (feature == InFace ? 0 : feature);
  const double* a = t.X + 3 * first;
  const double* b = type == 1 ? t.X + 3 * ((first + 1) % 3) : nullptr;
  if (type == 0)
  {
    // A vertex's closest point is the vertex itself.
    std::copy(a, a + 3, closest);
  }
  int64_t cell = tree.Cell(index), primitive = index;
  double normal[3] = { 0, 0, 0 };
  const bool wantNormal = in.Sign == SignMode::PseudoNormal || (parts.Gradient && best2 == 0);
  if (type != 2 && (parts.Closest || wantNormal))
  {
    tree.FeatureCellAndNormal(a, b, cell, normal, &primitive);
  }
  else if (type == 2 && wantNormal)
  {
    tree.FaceNormalOf(index, normal);
  }
  double d[3];
  for (int k = 0; k < 3; ++k)
  {
    d[k] = x[k] - closest[k];
  }
  double sign = 1;
  if (in.Sign == SignMode::PseudoNormal)
  {
    sign = Dot(d, normal) < 0 ? -1 : 1;
  }
  else if (in.Sign == SignMode::WindingNumber)
  {
    sign = inside ? -1 : 1;
  }
  const double distance = std::sqrt(best2);
  answer.Distance = sign * distance * scale;
  for (int k = 0; k < 3; ++k)
  {
    answer.Closest[k] = closest[k] * scale;
  }
  if (parts.Closest)
  {
    answer.Cell = cell;
    answer.Feature = type;
    answer.SubTriangle = in.SubIndex(tree.Source(primitive));
    Barycentric(tree.Get(primitive), type, a, b, closest, answer.Barycentric);
  }
  if (parts.Gradient)
  {
    // Along x - closest itself (whose length differs from `distance` by rounding).
    const double length = std::sqrt(Dot(d, d));
    if (distance > 0 && length > 0)
    {
      for (int k = 0; k < 3; ++k)
      {
        answer.Gradient[k] = sign * d[k] / length;
      }
    }
    else
    {
      const double length = std::sqrt(Dot(normal, normal));
      for (int k = 0; k < 3; ++k)
      {
        answer.Gradient[k] = length > 0 ? normal[k] / length : 0.0;
      }
    }
  }
  return evaluations;
}

bool PointDistanceQueries::SideFromHint(const double x[3],
  double clearance,
  const PointQueryParts& parts,
  const PointAnswer* hint,
  bool& inside) const
{
  const Internal& in = *this->Impl;
  if (!hint || !in.ClosedChain || parts.Winding || !(hint->Clearance > 0))
  {
    return false;
  }
  // x and the hint's point, each in a ball that holds no point of the surface: where
  // the balls overlap, the segment between them does not cross it, and w (an integer
  // constant off a closed chain's surface) is the same at both.
  double gap2 = 0;
  for (int a = 0; a < 3; ++a)
  {
    const double d = x[a] - hint->Point[a] / in.Scale;
    gap2 += d * d;
  }
  const double reach =
    (clearance + hint->Clearance / in.Scale) * (1 - 1e-9) - std::sqrt(in.Tree.Tolerance2);
  if (!(reach > 0) || gap2 >= reach * reach)
  {
    return false;
  }
  inside = hint->Inside;
  return true;
}

bool PointDistanceQueries::QueryPoints(const double* points,
  int64_t count,
  double cap,
  const PointDistanceArrays& arrays,
  const Execution& execution,
  PointDistanceStatistics& stats,
  std::string& error,
  const uint8_t* excluded) const
{
  stats = PointDistanceStatistics();
  // The points' box (every coordinate checked first), then their Morton order in it.
  double lo[3] = { HUGE_VAL, HUGE_VAL, HUGE_VAL }, hi[3] = { -HUGE_VAL, -HUGE_VAL, -HUGE_VAL };
  for (int64_t i = 0; i < count; ++i)
  {
    const double* x = points + 3 * i;
    if (!std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(x[2]))
    {
      error = "point " + std::to_string(i) + " has a NaN or infinite coordinate (" +
        FormatNumber(x[0]) + ", " + FormatNumber(x[1]) + ", " + FormatNumber(x[2]) + ")";
      return false;
    }
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = std::min(lo[a], x[a]);
      hi[a] = std::max(hi[a], x[a]);
    }
  }
  if (count == 0)
  {
    return true;
  }
  const LargeVector<int64_t> order = MortonOrder(points, count, lo, hi, execution.For);
  execution.EndStage("order");

  const bool wantFeature = arrays.ClosestPoint || arrays.ClosestCellId ||
    arrays.ClosestSubTriangle || arrays.ClosestBarycentric || arrays.ClosestFeature;
  PointQueryParts parts;
  parts.Closest = wantFeature;
  parts.Gradient = arrays.Gradient != nullptr;
  parts.Winding = arrays.WindingNumber != nullptr;
  // Every answer's |distance| (NaN beyond the cap) for the summary.
  LargeVector<double> magnitude(count);
  std::atomic<int64_t> evaluations{ 0 };
  // Runs of points in Morton order, each point seeded with the previous one's closest
  // point.
  constexpr int64_t Run = 256;
  const int64_t runs = (count + Run - 1) / Run;
  auto queryRuns = [&](int64_t runBegin, int64_t runEnd)
  {
    int64_t work = 0;
    for (int64_t r = runBegin; r < runEnd; ++r)
    {
      double previous[3];
      bool seeded = false;
      PointAnswer last;
      bool haveLast = false;
      for (int64_t k = r * Run; k < std::min(count, (r + 1) * Run); ++k)
      {
        const int64_t i = order[k];
        PointAnswer answer;
        work += this->Query(points + 3 * i,
          cap,
          seeded ? previous : nullptr,
          parts,
          answer,
          haveLast ? &last : nullptr);
        std::copy(points + 3 * i, points + 3 * i + 3, answer.Point);
        last = answer;
        haveLast = true;
        if (!answer.Beyond)
        {
          std::copy(answer.Closest, answer.Closest + 3, previous);
          seeded = true;
        }
        if (arrays.Distance)
        {
          arrays.Distance[i] = answer.Distance;
        }
        magnitude[i] = answer.Beyond ? NAN : std::fabs(answer.Distance);
        if (arrays.ClosestPoint)
        {
          std::copy(answer.Closest, answer.Closest + 3, arrays.ClosestPoint + 3 * i);
        }
        if (arrays.ClosestCellId)
        {
          arrays.ClosestCellId[i] = answer.Cell;
        }
        if (arrays.ClosestSubTriangle)
        {
          arrays.ClosestSubTriangle[i] = answer.SubTriangle;
        }
        if (arrays.ClosestBarycentric)
        {
          std::copy(answer.Barycentric, answer.Barycentric + 3, arrays.ClosestBarycentric + 3 * i);
        }
        if (arrays.ClosestFeature)
        {
          arrays.ClosestFeature[i] = answer.Feature;
        }
        if (arrays.Gradient)
        {
          std::copy(answer.Gradient, answer.Gradient + 3, arrays.Gradient + 3 * i);
        }
        if (arrays.WindingNumber)
        {
          arrays.WindingNumber[i] = answer.Winding;
        }
      }
    }
    evaluations += work;
  };
  const int64_t batches = std::min<int64_t>(runs, 64);
  for (int64_t batch = 0; batch < batches; ++batch)
  {
    const int64_t begin = runs * batch / batches, end = runs * (batch + 1) / batches;
    if (execution.For)
    {
      execution.For(end - begin, 1, [&](int64_t b, int64_t e) { queryRuns(begin + b, begin + e); });
    }
    else
    {
      queryRuns(begin, end);
    }
    if (!execution.Report(double(batch + 1) / batches))
    {
      stats.Aborted = true;
      return true;
    }
  }
  stats.Evaluations = evaluations.load();
  execution.EndStage("queries");

  Summarize(magnitude, excluded, stats);
  if (arrays.Magnitude)
  {
    std::copy(magnitude.begin(), magnitude.end(), arrays.Magnitude);
  }
  return true;
}

} // namespace vtkdf
