#include "LinearFactor/HausdorffDistance.h"

#include "Common/LargeVector.h"
#include "Common/Vector3.h"
#include "LinearFactor/HausdorffCover.h"
#include "LinearFactor/QueryTree.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <functional>
#include <mutex>
#include <vector>

namespace vtkdf
{
namespace
{
using hausdorff::CornerReach;
using hausdorff::CoverScratch;
using hausdorff::Piece;
using nearest::QueryTree;

/// The midpoints of a piece's sides 01, 12 and 20: where they are, their squared
/// distances and nearest primitives.
struct Midpoints
{
  double X[3][3];
  double D2[3];
  int32_t Near[3];
};

/// The children of `piece` (four, two for a segment) at its `midpoints`.
void Split(const Piece& piece, const Midpoints& midpoints, Piece* children);

/// The point of the source at the largest distance found so far: its squared distance,
/// its position and an order key (the first found wins ties, whatever the threads).
struct Farthest
{
  double D2 = -1;
  double X[3] = { 0, 0, 0 };
  int64_t Key = 0;
  void Offer(double d2, const double x[3], int64_t key)
  {
    if (d2 > this->D2 || (d2 == this->D2 && key < this->Key))
    {
      this->D2 = d2;
      this->Key = key;
      std::copy(x, x + 3, this->X);
    }
  }
};

/// One direction: the source's points and primitives against the target's tree.
class OneSide
{
public:
  OneSide(const MeshInput& source, const QueryTree& target, double slack)
    : Source(source)
    , Target(target)
    , Slack(slack)
    , Cover(target, slack)
  {
  }

  /// Every point's squared distance and nearest primitive (in the order of
  /// `sourceTree`, the source's own tree); Found starts at the farthest used point.
  void QueryPoints(const QueryTree& sourceTree, const ParallelFor& parallelFor);
  /// Refines the source's primitives until every piece's bound is within `tolerance` of
  /// the farthest distance found; false when aborted.
  bool Refine(double tolerance, const Execution& execution, OneSidedHausdorff& side);

  // The source's triangles and segments (its mesh's indices) in its tree's order: the
  // first round's pieces, neighbours in turn.
  std::vector<int64_t> Primitives;
  LargeVector<double> D2;       // per point (NaN: not finite)
  LargeVector<int32_t> Nearest; // per point (-1: none)
  Farthest Found;
  std::atomic<int64_t> Evaluations{ 0 };

private:
  /// The nearest primitive to x with its squared distance, the search bounded by the
  /// distance to primitive `seed` (when >= 0).
  int32_t NearestTo(const double x[3], int64_t seed, double& d2, int64_t& evaluations) const;
  /// Bounds `piece` against `threshold` (local units); returns whether it must be split,
  /// and its bound (a distance) into `upper` otherwise.
  bool Bound(Piece& piece,
    double threshold,
    double& upper,
    int64_t& evaluations,
    CoverScratch& scratch) const;
  /// The midpoints of the piece's sides (one for a segment), queried and offered to
  /// `found` with keys from `key` up.
  void QueryMidpoints(const Piece& piece,
    int64_t key,
    Midpoints& midpoints,
    Farthest& found,
    int64_t& evaluations) const;
  Piece FromPrimitive(int64_t i) const;

  const MeshInput& Source;
  const QueryTree& Target;
  const double Slack;
  const hausdorff::CoverBound Cover; // the third bound (HausdorffCover.h)
};

int32_t OneSide::NearestTo(const double x[3], int64_t seed, double& d2, int64_t& evaluations) const
{
  double bound2 = HUGE_VAL;
  if (seed >= 0)
  {
    bound2 = this->Target.Distance2(seed, x) * (1 + 1e-9) + this->Target.Tolerance2;
    ++evaluations;
  }
  int64_t index;
  double closest[3];
  int feature;
  evaluations += this->Target.Nearest(x, bound2, index, d2, closest, feature);
  if (index < 0 && bound2 < HUGE_VAL)
  {
    evaluations += this->Target.Nearest(x, HUGE_VAL, index, d2, closest, feature);
  }
  if (index < 0)
  {
    d2 = NAN;
  }
  return static_cast<int32_t>(index);
}

void OneSide::QueryPoints(const QueryTree& sourceTree, const ParallelFor& parallelFor)
{
  const int64_t count = static_cast<int64_t>(this->Source.Points.size() / 3);
  this->D2 = LargeVector<double>(count);
  this->Nearest = LargeVector<int32_t>(count);
  // The points in the order the source's own tree holds its primitives (Morton order):
  // each query is then bounded by a near neighbour's nearest primitive and walks the
  // nodes the previous one walked. Points no cell uses come last.
  LargeVector<int64_t> order(count);
  std::vector<uint8_t> seen(static_cast<size_t>(count), 0);
  int64_t placed = 0;
  const int64_t triangles = static_cast<int64_t>(this->Source.Triangles.size() / 3);
  const int64_t segments = static_cast<int64_t>(this->Source.Segments.size() / 2);
  auto place = [&](int64_t id)
  {
    if (!seen[id])
    {
      seen[id] = 1;
      order[placed++] = id;
    }
  };
  for (int64_t i = 0; i < sourceTree.Size(); ++i)
  {
    const int64_t source = sourceTree.Source(i);
    if (source < triangles + segments)
    {
      this->Primitives.push_back(source);
    }
    if (source < triangles)
    {
      for (int c = 0; c < 3; ++c)
      {
        place(this->Source.Triangles[3 * source + c]);
      }
    }
    else if (source < triangles + segments)
    {
      place(this->Source.Segments[2 * (source - triangles)]);
      place(this->Source.Segments[2 * (source - triangles) + 1]);
    }
    else
    {
      place(this->Source.Vertices[source - triangles - segments]);
    }
  }
  for (int64_t id = 0; id < count; ++id)
  {
    place(id);
  }
  auto query = [&](int64_t begin, int64_t end)
  {
    int64_t evaluations = 0;
    int64_t previous = -1;
    for (int64_t k = begin; k < end; ++k)
    {
      const int64_t i = order[k];
      this->Nearest[i] =
        this->NearestTo(&this->Source.Points[3 * i], previous, this->D2[i], evaluations);
      previous = this->Nearest[i];
    }
    this->Evaluations += evaluations;
  };
  parallelFor ? parallelFor(count, 1024, query) : query(0, count);
  auto use = [&](const LargeVector<int64_t>& ids)
  {
    for (const int64_t id : ids)
    {
      this->Found.Offer(this->D2[id], &this->Source.Points[3 * id], id);
    }
  };
  use(this->Source.Triangles);
  use(this->Source.Segments);
  use(this->Source.Vertices);
}

Piece OneSide::FromPrimitive(int64_t i) const
{
  const int64_t triangles = static_cast<int64_t>(this->Source.Triangles.size() / 3);
  int64_t ids[3];
  Piece piece;
  piece.Segment = i >= triangles;
  if (piece.Segment)
  {
    const int64_t s = i - triangles;
    ids[0] = this->Source.Segments[2 * s];
    ids[1] = ids[2] = this->Source.Segments[2 * s + 1];
  }
  else
  {
    std::copy(&this->Source.Triangles[3 * i], &this->Source.Triangles[3 * i] + 3, ids);
  }
  for (int c = 0; c < 3; ++c)
  {
    std::copy(
      &this->Source.Points[3 * ids[c]], &this->Source.Points[3 * ids[c]] + 3, piece.X + 3 * c);
    piece.D2[c] = this->D2[ids[c]];
    piece.Near[c] = this->Nearest[ids[c]];
  }
  piece.Near[3] = -1;
  return piece;
}

bool OneSide::Bound(Piece& piece,
  double threshold,
  double& upper,
  int64_t& evaluations,
  CoverScratch& scratch) const
{
  const int corners = piece.Segment ? 2 : 3;
  // The distance is 1-Lipschitz: no point of the piece is farther than its farthest
  // corner's distance plus the piece's reach from its corners. Free, and on a piece far
  // below the threshold usually enough.
  const double lipschitz = std::sqrt(std::max(std::max(piece.D2[0], piece.D2[1]), piece.D2[2])) +
    CornerReach(piece) * (1 + 1e-12) + this->Slack;
  if (lipschitz <= threshold)
  {
    upper = lipschitz;
    return false;
  }
  // Then the primitives nearest to the corners (and the parent's best): on a smooth
  // pair of surfaces one of them nearly always bounds the piece.
  double worst2 = HUGE_VAL;
  int32_t best = -1;
  const double enough2 = threshold > 0 ? threshold * threshold : -1;
  for (int k = 0; k < 4 && worst2 > enough2; ++k)
  {
    const int32_t candidate = piece.Near[k];
    if (candidate < 0 || std::find(piece.Near, piece.Near + k, candidate) != piece.Near + k)
    {
      continue;
    }
    double farthest = 0;
    for (int c = 0; c < corners && farthest < worst2; ++c)
    {
      farthest = std::max(farthest, this->Target.Distance2(candidate, piece.X + 3 * c));
      ++evaluations;
    }
    if (farthest < worst2)
    {
      worst2 = farthest;
      best = candidate;
    }
  }
  // The faces nearest to the corners often cover the piece together where no one of
  // them bounds it alone (a piece across an edge of the target); else the faces near it.
  double cover = HUGE_VAL;
  piece.Near[3] = best;
  if (worst2 > enough2 &&
    ((this->Cover(piece, threshold, true, cover, scratch) && cover <= threshold) ||
      (this->Cover(piece, threshold, false, cover, scratch) && cover <= threshold)))
  {
    piece.Near[3] = best;
    upper = std::min(lipschitz, cover);
    return false;
  }
  if (worst2 > enough2)
  {
    int64_t index;
    double found2;
    evaluations += this->Target.NearestToAll(piece.X, corners, worst2, enough2, index, found2);
    if (index >= 0)
    {
      worst2 = found2;
      best = static_cast<int32_t>(index);
    }
  }
  piece.Near[3] = best;
  upper = std::min(std::min(lipschitz, cover), std::sqrt(worst2) + this->Slack);
  return !(worst2 <= enough2);
}

void OneSide::QueryMidpoints(const Piece& piece,
  int64_t key,
  Midpoints& midpoints,
  Farthest& found,
  int64_t& evaluations) const
{
  const int edges = piece.Segment ? 1 : 3;
  for (int e = 0; e < edges; ++e)
  {
    const double* u = piece.X + 3 * e;
    const double* v = piece.X + 3 * ((e + 1) % 3);
    double* x = midpoints.X[e];
    for (int a = 0; a < 3; ++a)
    {
      x[a] = 0.5 * (u[a] + v[a]);
    }
    midpoints.Near[e] = this->NearestTo(x, piece.Near[3], midpoints.D2[e], evaluations);
    found.Offer(midpoints.D2[e], x, key + e);
  }
}

void Split(const Piece& piece, const Midpoints& midpoints, Piece* children)
{
  // Corners 0-2, then the midpoints of edges 01, 12, 20 (only 01 for a segment).
  auto corner = [&](int at, Piece& child, int c)
  {
    const double* x = at < 3 ? piece.X + 3 * at : midpoints.X[at - 3];
    std::copy(x, x + 3, child.X + 3 * c);
    child.D2[c] = at < 3 ? piece.D2[at] : midpoints.D2[at - 3];
    child.Near[c] = at < 3 ? piece.Near[at] : midpoints.Near[at - 3];
  };
  auto add = [&](int i, int j, int k)
  {
    Piece& child = *children++;
    child.Segment = piece.Segment;
    corner(i, child, 0);
    corner(j, child, 1);
    corner(k, child, 2);
    child.Near[3] = piece.Near[3];
  };
  if (piece.Segment)
  {
    add(0, 3, 3);
    add(3, 1, 1);
    return;
  }
  add(0, 3, 5);
  add(3, 1, 4);
  add(5, 4, 2);
  add(3, 4, 5);
}

bool OneSide::Refine(double tolerance, const Execution& execution, OneSidedHausdorff& side)
{
  const int64_t primitives = static_cast<int64_t>(this->Primitives.size());
  // The round's pieces (the first round reads the primitives), the next round's, and per
  // piece of the round whether it is split, the primitive that bounded it best, its
  // place among the pieces split and where its children go: reused round after round.
  std::vector<Piece> pieces, next;
  std::vector<uint8_t> split;
  std::vector<int32_t> best;
  std::vector<int64_t> ranks, offsets;
  std::vector<Midpoints> midpoints;
  double upper = -HUGE_VAL;
  // The order in which points are found, for ties: the points, then each round's.
  int64_t keys = static_cast<int64_t>(this->D2.size());
  // Halving a piece 64 times leaves it below any coordinate's resolution.
  constexpr int MaximumRounds = 64;
  std::mutex merge;
  const ParallelFor& parallelFor = execution.For;
  auto loop = [&](int64_t n, int64_t grain, const std::function<void(int64_t, int64_t)>& body)
  { parallelFor ? parallelFor(n, grain, body) : body(0, n); };
  int round = 0;
  for (; round < MaximumRounds; ++round)
  {
    const bool first = round == 0;
    const int64_t count = first ? primitives : static_cast<int64_t>(pieces.size());
    if (count == 0)
    {
      break;
    }
    auto pieceAt = [&](int64_t i)
    {
      Piece piece = first ? this->FromPrimitive(this->Primitives[i]) : pieces[i];
      if (!split.empty() && split[i])
      {
        piece.Near[3] = best[i];
      }
      return piece;
    };
    const bool last = round + 1 == MaximumRounds;
    double roundUpper = upper;
    // Bounds the pieces [begin, end) that `todo` selects against `threshold`.
    auto bound = [&](int64_t begin, int64_t end, double threshold, bool again)
    {
      double chunkUpper = -HUGE_VAL;
      int64_t evaluations = 0;
      CoverScratch scratch;
      for (int64_t i = begin; i < end; ++i)
      {
        if (again && !split[i])
        {
          continue;
        }
        Piece piece = pieceAt(i);
        double pieceUpper;
        const bool cut = this->Bound(piece, threshold, pieceUpper, evaluations, scratch) && !last;
        best[i] = piece.Near[3];
        split[i] = cut;
        if (!cut)
        {
          chunkUpper = std::max(chunkUpper, pieceUpper);
        }
      }
      this->Evaluations += evaluations;
      std::lock_guard<std::mutex> lock(merge);
      roundUpper = std::max(roundUpper, chunkUpper);
    };
    // 1. Every piece against the farthest distance of the rounds before.
    split.assign(count, 0);
    best.resize(count);
    double threshold = std::sqrt(this->Found.D2) + tolerance - 2 * this->Slack;
    loop(count, 256, [&](int64_t b, int64_t e) { bound(b, e, threshold, false); });
    // 2. The midpoints of the pieces that fail, which may raise the farthest distance.
    ranks.resize(count + 1);
    ranks[0] = 0;
    for (int64_t i = 0; i < count; ++i)
    {
      ranks[i + 1] = ranks[i] + split[i];
    }
    midpoints.resize(ranks[count]);
    Farthest roundFound = this->Found;
    loop(count,
      64,
      [&](int64_t begin, int64_t end)
      {
        Farthest found;
        int64_t evaluations = 0;
        for (int64_t i = begin; i < end; ++i)
        {
          if (split[i])
          {
            this->QueryMidpoints(pieceAt(i), keys + 4 * i, midpoints[ranks[i]], found, evaluations);
          }
        }
        this->Evaluations += evaluations;
        std::lock_guard<std::mutex> lock(merge);
        if (found.D2 >= 0)
        {
          roundFound.Offer(found.D2, found.X, found.Key);
        }
      });
    this->Found = roundFound;
    // 3. Those pieces again, against what their midpoints found; the rest are split.
    const double raised = std::sqrt(this->Found.D2) + tolerance - 2 * this->Slack;
    if (raised > threshold)
    {
      loop(count, 256, [&](int64_t b, int64_t e) { bound(b, e, raised, true); });
    }
    offsets.resize(count + 1);
    offsets[0] = 0;
    for (int64_t i = 0; i < count; ++i)
    {
      offsets[i + 1] = offsets[i] + (split[i] ? (pieceAt(i).Segment ? 2 : 4) : 0);
    }
    next.resize(offsets[count]);
    loop(count,
      256,
      [&](int64_t begin, int64_t end)
      {
        for (int64_t i = begin; i < end; ++i)
        {
          if (split[i])
          {
            Split(pieceAt(i), midpoints[ranks[i]], next.data() + offsets[i]);
          }
        }
      });
    side.Pieces += count;
    keys += 4 * count;
    pieces.swap(next);
    split.clear();
    upper = roundUpper;
    if (!execution.Report(1 - std::ldexp(1.0, -(round + 1))))
    {
      return false;
    }
  }
  side.Rounds = round;
  const double farthest = std::sqrt(std::max(0.0, this->Found.D2));
  side.Lower = std::max(0.0, farthest - this->Slack);
  // Vertex cells and the corners themselves are within the farthest distance found.
  side.Upper = std::max(upper, farthest + this->Slack);
  return true;
}

/// The frame's scale: a power of two near the size of both meshes' used points.
double FrameScale(const std::array<double, 6>& a, const std::array<double, 6>& b, double& diagonal)
{
  double size = 0, extent[3];
  for (int k = 0; k < 3; ++k)
  {
    const double lo = std::min(a[2 * k], b[2 * k]), hi = std::max(a[2 * k + 1], b[2 * k + 1]);
    extent[k] = hi - lo;
    size = std::max(size, extent[k]);
  }
  // hypot: the squares of coordinates beyond 1e154 would overflow.
  diagonal = std::hypot(std::hypot(extent[0], extent[1]), extent[2]);
  return std::isfinite(size) && size > 0 ? std::ldexp(1.0, std::ilogb(size)) : 1.0;
}

/// The world-unit answer of one side.
void Finish(const OneSide& side, const QueryTree& target, double scale, OneSidedHausdorff& answer)
{
  answer.Distance = std::sqrt(std::max(0.0, side.Found.D2)) * scale;
  answer.Lower *= scale;
  answer.Upper *= scale;
  answer.Evaluations = side.Evaluations;
  int64_t index;
  double d2, closest[3];
  int feature;
  target.Nearest(side.Found.X, HUGE_VAL, index, d2, closest, feature);
  for (int a = 0; a < 3; ++a)
  {
    answer.From[a] = side.Found.X[a] * scale;
    answer.To[a] = closest[a] * scale;
  }
}

void WorldDistances(const OneSide& side, double scale, double* out)
{
  if (!out)
  {
    return;
  }
  for (size_t i = 0; i < side.D2.size(); ++i)
  {
    out[i] = std::sqrt(side.D2[i]) * scale;
  }
}

} // namespace

bool ComputeHausdorffDistance(MeshInput a,
  MeshInput b,
  const HausdorffOptions& options,
  const Execution& execution,
  HausdorffResult& result,
  std::string& error)
{
  result = HausdorffResult();
  if (!(options.RelativeError > 0) || !std::isfinite(options.RelativeError))
  {
    error = "the relative error must be finite and positive";
    return false;
  }
  for (const MeshInput* mesh : { &a, &b })
  {
    const int64_t points = static_cast<int64_t>(mesh->Points.size() / 3);
    for (const LargeVector<int64_t>* ids : { &mesh->Triangles, &mesh->Segments, &mesh->Vertices })
    {
      for (const int64_t id : *ids)
      {
        if (id < 0 || id >= points)
        {
          error = std::string("mesh ") + (mesh == &a ? "A" : "B") + ": a cell refers to point " +
            std::to_string(id) + " of " + std::to_string(points);
          return false;
        }
      }
    }
  }
  std::array<double, 6> boundsA, boundsB;
  if (!UsedPointBounds(a, boundsA) || !UsedPointBounds(b, boundsB))
  {
    error = std::string("mesh ") + (a.Empty() ? "A" : "B") + " has no cell";
    return false;
  }
  const double scale = FrameScale(boundsA, boundsB, result.Diagonal);
  result.Tolerance = options.RelativeError * result.Diagonal;
  GridFrame frame;
  frame.Scale = scale;
  MoveToLocalFrame(a, frame, execution.For);
  MoveToLocalFrame(b, frame, execution.For);
  QueryTree treeA, treeB;
  if (!treeA.Build(a, execution.For, error))
  {
    error = "mesh A: " + error;
    return false;
  }
  if (!treeB.Build(b, execution.For, error))
  {
    error = "mesh B: " + error;
    return false;
  }
  if (!std::isfinite(result.Diagonal))
  {
    error = "the meshes' box is too large for double precision to measure its diagonal";
    return false;
  }
  execution.EndStage("trees");
  // What the rounding of a computed distance can reach (the trees' slack on squared
  // distances near zero is its square).
  const double slack = std::sqrt(std::max(treeA.Tolerance2, treeB.Tolerance2));
  const double tolerance = result.Tolerance / scale;
  if (!(tolerance > 8 * slack))
  {
    error = "the requested accuracy (" + std::to_string(result.Tolerance) +
      ") is below what double precision resolves at these coordinates; ask for a relative "
      "error of at least " +
      std::to_string(8 * slack * scale / result.Diagonal);
    return false;
  }

  OneSide aToB(a, treeB, slack), bToA(b, treeA, slack);
  aToB.QueryPoints(treeA, execution.For);
  bToA.QueryPoints(treeB, execution.For);
  execution.EndStage("points");
  if (!execution.Report(0.2))
  {
    result.Aborted = true;
    return true;
  }
  if (!aToB.Refine(tolerance, execution.Part(0.2, 0.6), result.AToB) ||
    !bToA.Refine(tolerance, execution.Part(0.6, 1.0), result.BToA))
  {
    result.Aborted = true;
    return true;
  }
  execution.EndStage("refine");
  Finish(aToB, treeB, scale, result.AToB);
  Finish(bToA, treeA, scale, result.BToA);
  WorldDistances(aToB, scale, options.DistanceA);
  WorldDistances(bToA, scale, options.DistanceB);
  result.Lower = std::max(result.AToB.Lower, result.BToA.Lower);
  result.Upper = std::max(result.AToB.Upper, result.BToA.Upper);
  return true;
}

} // namespace vtkdf
