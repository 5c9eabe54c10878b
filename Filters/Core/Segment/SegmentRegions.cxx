#include "Segment/SegmentRegions.h"

#include "Common/Vector3.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <map>
#include <mutex>
#include <unordered_map>

namespace vtkdf
{

namespace
{
/// Scales v to unit length; false (v unchanged) when it is 0.
bool Normalize(double* v)
{
  const double length = std::sqrt(Dot(v, v));
  if (!(length > 0))
  {
    return false;
  }
  v[0] /= length, v[1] /= length, v[2] /= length;
  return true;
}

double SegmentDistance2(const double* a, const double* b, const double* c)
{
  const double e[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
  const double f[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
  const double ee = Dot(e, e);
  const double s = ee > 0 ? std::min(1.0, std::max(0.0, Dot(e, f) / ee)) : 0.0;
  const double g[3] = { f[0] - s * e[0], f[1] - s * e[1], f[2] - s * e[2] };
  return Dot(g, g);
}

/// How near in angle the unit direction u is to triangle f's half-plane around its edge
/// (a, b) (unit tangent e): the cosine of the angle, in the plane across the edge.
double EdgeWedgeCosine(const SurfacePatches& patches,
  int64_t f,
  int64_t ka,
  int64_t kb,
  const double* a,
  const double* e,
  const double* u)
{
  int third = 0;
  while (patches.Key(f, third) == ka || patches.Key(f, third) == kb)
  {
    ++third;
  }
  const double* p = patches.Corner(f, third);
  double inward[3] = { p[0] - a[0], p[1] - a[1], p[2] - a[2] };
  const double along = Dot(inward, e);
  for (int i = 0; i < 3; ++i)
  {
    inward[i] -= along * e[i];
  }
  double across[3] = { u[0], u[1], u[2] };
  const double uAlong = Dot(u, e);
  for (int i = 0; i < 3; ++i)
  {
    across[i] -= uAlong * e[i];
  }
  if (!Normalize(inward) || !Normalize(across))
  {
    return -2;
  }
  return Dot(across, inward);
}

/// How near in angle the unit direction u is to triangle f's corner wedge at its corner
/// with key kv: the cosine of the angle between u and the nearest direction in the wedge.
/// When that direction is one of the wedge's edges, `edgeEnd` receives the key of the
/// edge's other end (else -1).
double VertexWedgeCosine(const SurfacePatches& patches,
  int64_t f,
  int64_t kv,
  const double* u,
  int64_t& edgeEnd)
{
  edgeEnd = -1;
  int k = 0;
  while (patches.Key(f, k) != kv)
  {
    ++k;
  }
  const double* v = patches.Corner(f, k);
  const double* p = patches.Corner(f, (k + 1) % 3);
  const double* q = patches.Corner(f, (k + 2) % 3);
  double e1[3] = { p[0] - v[0], p[1] - v[1], p[2] - v[2] };
  double e2[3] = { q[0] - v[0], q[1] - v[1], q[2] - v[2] };
  double n[3];
  if (!Normalize(e1) || !Normalize(e2))
  {
    return -2;
  }
  Cross(e1, e2, n);
  if (!Normalize(n))
  {
    return -2;
  }
  const double un = Dot(u, n);
  const double projection[3] = { u[0] - un * n[0], u[1] - un * n[1], u[2] - un * n[2] };
  double c1[3], c2[3];
  Cross(e1, projection, c1);
  Cross(projection, e2, c2);
  if (Dot(c1, n) >= 0 && Dot(c2, n) >= 0)
  {
    return std::sqrt(std::max(0.0, 1 - un * un)); // the projection lies in the wedge
  }
  const bool first = Dot(u, e1) >= Dot(u, e2);
  edgeEnd = patches.Key(f, first ? (k + 1) % 3 : (k + 2) % 3);
  return first ? Dot(u, e1) : Dot(u, e2);
}
} // namespace

int64_t SideLabel(const SurfacePatches& patches,
  const double p[3],
  const double c[3],
  int64_t triangle,
  int feature,
  std::vector<int64_t>& scratch)
{
  if (triangle < 0 || triangle >= static_cast<int64_t>(patches.Patch.size()) ||
    patches.Patch[triangle] < 0)
  {
    return -1;
  }
  double u[3] = { p[0] - c[0], p[1] - c[1], p[2] - c[2] };
  const bool away = Normalize(u);
  int64_t chosen = triangle;
  // Around an edge (keys ka, kb): the triangle whose half-plane is nearest in angle.
  auto aroundEdge = [&](int64_t ka, int64_t kb, const double* a, const double* b)
  {
    double e[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
    Normalize(e);
    patches.TrianglesAtEdge(ka, kb, scratch);
    double best = -3;
    for (const int64_t f : scratch)
    {
      const double cosine = EdgeWedgeCosine(patches, f, ka, kb, a, e, u);
      if (cosine > best)
      {
        best = cosine;
        chosen = f;
      }
    }
  };
  if (away && feature == 1)
  {
    // The triangle's edge nearest to the closest point.
    int edge = 0;
    double nearest = HUGE_VAL;
    for (int k = 0; k < 3; ++k)
    {
      const double d2 =
        SegmentDistance2(patches.Corner(triangle, k), patches.Corner(triangle, (k + 1) % 3), c);
      if (d2 < nearest)
      {
        nearest = d2;
        edge = k;
      }
    }
    aroundEdge(patches.Key(triangle, edge),
      patches.Key(triangle, (edge + 1) % 3),
      patches.Corner(triangle, edge),
      patches.Corner(triangle, (edge + 1) % 3));
  }
  else if (away && feature == 0)
  {
    // The triangle's corner nearest to the closest point, and every triangle at it.
    int corner = 0;
    double nearest = HUGE_VAL;
    for (int k = 0; k < 3; ++k)
    {
      const double* v = patches.Corner(triangle, k);
      const double g[3] = { v[0] - c[0], v[1] - c[1], v[2] - c[2] };
      if (Dot(g, g) < nearest)
      {
        nearest = Dot(g, g);
        corner = k;
      }
    }
    const int64_t kv = patches.Key(triangle, corner);
    patches.TrianglesAtPoint(kv, scratch);
    double best = -3;
    int64_t bestEnd = -1;
    for (const int64_t f : scratch)
    {
      int64_t end = -1;
      const double cosine = VertexWedgeCosine(patches, f, kv, u, end);
      if (cosine > best)
      {
        best = cosine;
        bestEnd = end;
        chosen = f;
      }
    }
    if (bestEnd >= 0)
    {
      // Nearest to an edge direction, which two or more wedges share: the triangles
      // around that edge decide, as for an edge.
      aroundEdge(kv, bestEnd, patches.Position(kv), patches.Position(bestEnd));
    }
  }
  double n[3];
  patches.Normal(chosen, n);
  // On the sheet (u = 0) or in its plane: the front, by convention.
  const int side = away && Dot(u, n) < 0 ? 1 : 0;
  return 2 * patches.Patch[chosen] + side;
}

namespace
{
/// Each sample's side label (2 patch + side; -1: none) and its patch.
void Label(const SegmentInput& input,
  const ParallelFor& run,
  std::vector<int64_t>& label,
  std::vector<int32_t>& patch)
{
  const SampleGrid& grid = input.Grid;
  const IndexBox& whole = grid.Whole;
  const int n[3] = { whole.Size(0), whole.Size(1), whole.Size(2) };
  const int64_t count = whole.Count();
  label.resize(count);
  patch.assign(count, -1);
  if (input.Labels)
  {
    run(count,
      1 << 16,
      [&](int64_t begin, int64_t end)
      {
        for (int64_t v = begin; v < end; ++v)
        {
          label[v] = input.Labels[v];
          patch[v] = label[v] < 0 ? -1 : static_cast<int32_t>(label[v] / 2);
        }
      });
    return;
  }
  run(n[2],
    1,
    [&](int64_t k0, int64_t k1)
    {
      std::vector<int64_t> scratch;
      for (int64_t k = k0; k < k1; ++k)
      {
        for (int j = 0; j < n[1]; ++j)
        {
          for (int i = 0; i < n[0]; ++i)
          {
            const int64_t v = i + n[0] * (j + int64_t(n[1]) * k);
            const double p[3] = { grid.Coordinate(0, whole.Lo[0] + i),
              grid.Coordinate(1, whole.Lo[1] + j),
              grid.Coordinate(2, whole.Lo[2] + static_cast<int>(k)) };
            label[v] = SideLabel(*input.Patches,
              p,
              input.ClosestPoint + 3 * v,
              input.ClosestTriangle[v],
              input.ClosestFeature[v],
              scratch);
            patch[v] = label[v] < 0 ? -1 : static_cast<int32_t>(label[v] / 2);
          }
        }
      }
    });
}

using LabelPair = std::pair<std::pair<int64_t, int64_t>, int64_t>;

/// The evidence of the samples this piece owns (all of them without a piece): the labels
/// they take and the support of each label pair, adjacent samples with no surface between
/// them. False when an owned sample's neighbour within the whole grid is not among the
/// samples given.
bool CountEvidence(const SegmentInput& input,
  const std::vector<int64_t>& label,
  const ParallelFor& run,
  RegionEvidence& evidence)
{
  const SampleGrid& grid = input.Grid;
  const IndexBox& box = grid.Whole;
  const IndexBox& whole = input.Ownership ? input.WholeGrid : box;
  const int n[3] = { box.Size(0), box.Size(1), box.Size(2) };
  const int64_t stride[3] = { 1, n[0], int64_t(n[0]) * n[1] };
  const int64_t labels = 2 * input.Patches->PatchCount;
  std::vector<uint8_t> present(labels, 0);
  std::unordered_map<uint64_t, int64_t> support;
  int64_t samples = 0;
  bool complete = true;
  std::mutex lock;
  run(n[2],
    1,
    [&](int64_t k0, int64_t k1)
    {
      std::unordered_map<uint64_t, int64_t> local;
      std::vector<uint8_t> seen(labels, 0);
      std::vector<std::pair<int, int>> runs;
      int64_t counted = 0;
      bool ok = true;
      for (int64_t k = k0; k < k1; ++k)
      {
        for (int j = 0; j < n[1]; ++j)
        {
          if (input.Ownership)
          {
            input.Ownership->Runs(box.Lo[1] + j, box.Lo[2] + static_cast<int>(k), runs);
            for (auto& span : runs)
            {
              span.first -= box.Lo[0], span.second -= box.Lo[0];
            }
          }
          else
          {
            runs.assign(1, { 0, n[0] - 1 });
          }
          for (const auto& span : runs)
          {
            for (int i = span.first; i <= span.second; ++i)
            {
              const int64_t v = i + j * stride[1] + k * stride[2];
              const int at[3] = { i, j, static_cast<int>(k) };
              ++counted;
              if (label[v] >= 0)
              {
                seen[label[v]] = 1;
              }
              for (int a = 0; a < 3; ++a)
              {
                if (box.Lo[a] + at[a] + 1 > whole.Hi[a])
                {
                  continue; // the grid's last plane
                }
                if (at[a] + 1 >= n[a])
                {
                  ok = false; // the neighbour was not given
                  continue;
                }
                const int64_t w = v + stride[a];
                if (label[v] == label[w] || label[v] < 0 || label[w] < 0 ||
                  !(double(input.Distance[v]) + input.Distance[w] > grid.Spacing[a] * (1 + 1e-5)))
                {
                  continue;
                }
                const uint64_t lo = static_cast<uint64_t>(std::min(label[v], label[w]));
                const uint64_t hi = static_cast<uint64_t>(std::max(label[v], label[w]));
                ++local[(lo << 32) | hi];
              }
            }
          }
        }
      }
      std::lock_guard<std::mutex> guard(lock);
      for (const auto& entry : local)
      {
        support[entry.first] += entry.second;
      }
      for (int64_t l = 0; l < labels; ++l)
      {
        present[l] |= seen[l];
      }
      samples += counted;
      complete = complete && ok;
    });
  evidence = RegionEvidence();
  evidence.Samples = samples;
  for (int64_t l = 0; l < labels; ++l)
  {
    if (present[l])
    {
      evidence.Labels.push_back(l);
    }
  }
  for (const auto& entry : support)
  {
    evidence.Support[{ static_cast<int64_t>(entry.first >> 32),
      static_cast<int64_t>(entry.first & 0xffffffffu) }] += entry.second;
  }
  return complete;
}

/// The label pairs in the canonical order: most support first, ties by the labels.
std::vector<LabelPair> CanonicalPairs(const RegionEvidence& evidence)
{
  std::vector<LabelPair> pairs(evidence.Support.begin(), evidence.Support.end());
  std::stable_sort(
    pairs.begin(), pairs.end(), [](const auto& x, const auto& y) { return x.second > y.second; });
  return pairs;
}

/// Union-find over labels; each root knows the sides of the patches its set holds, so
/// that a merge that would join the two sides of one patch is refused.
class LabelSets
{
public:
  int64_t Find(int64_t x)
  {
    auto it = this->Parent.find(x);
    if (it == this->Parent.end())
    {
      this->Parent[x] = x;
      this->Sides[x][x / 2] = static_cast<uint8_t>(1 << (x % 2));
      return x;
    }
    int64_t root = x;
    while (this->Parent[root] != root)
    {
      root = this->Parent[root];
    }
    while (this->Parent[x] != root)
    {
      const int64_t next = this->Parent[x];
      this->Parent[x] = root;
      x = next;
    }
    return root;
  }

  /// Merges the sets of labels x and y; false when that would join a patch's two sides.
  /// Nothing to do (true) when they are one set already.
  bool Merge(int64_t x, int64_t y, bool& merged)
  {
    merged = false;
    int64_t a = this->Find(x), b = this->Find(y);
    if (a == b)
    {
      return true;
    }
    auto* small = &this->Sides[a];
    auto* large = &this->Sides[b];
    if (small->size() > large->size())
    {
      std::swap(small, large);
      std::swap(a, b); // a: the smaller set
    }
    for (const auto& s : *small)
    {
      const auto it = large->find(s.first);
      if (it != large->end() && (it->second | s.second) == 3)
      {
        return false;
      }
    }
    for (const auto& s : *small)
    {
      (*large)[s.first] |= s.second;
    }
    this->Sides.erase(a);
    this->Parent[a] = b;
    merged = true;
    return true;
  }

private:
  std::unordered_map<int64_t, int64_t> Parent;
  std::unordered_map<int64_t, std::unordered_map<int64_t, uint8_t>> Sides;
};

/// Regions numbered by their lowest label among the samples (the evidence's labels);
/// each sample's region.
void NumberRegions(const std::vector<int64_t>& label,
  int64_t labels,
  const RegionEvidence& evidence,
  LabelSets& sets,
  const ParallelFor& run,
  SegmentResult& result)
{
  const int64_t count = static_cast<int64_t>(label.size());
  std::unordered_map<int64_t, int32_t> number;    // root -> region
  std::vector<int32_t> regionOfLabel(labels, -1); // labels are dense: below 2 patches
  result.Sides.clear();
  for (const int64_t l : evidence.Labels)
  {
    const int64_t root = sets.Find(l);
    auto it = number.find(root);
    if (it == number.end())
    {
      it = number.emplace(root, static_cast<int32_t>(result.Sides.size())).first;
      result.Sides.emplace_back();
    }
    regionOfLabel[l] = it->second;
    result.Sides[it->second].emplace_back(l / 2, static_cast<int>(l % 2));
  }
  result.RegionCount = static_cast<int32_t>(result.Sides.size());
  result.Region.assign(count, -1);
  run(count,
    1 << 16,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t v = begin; v < end; ++v)
      {
        result.Region[v] = label[v] >= 0 ? regionOfLabel[label[v]] : -1;
      }
    });
}
} // namespace

std::vector<int64_t> RegionEvidence::Pack() const
{
  std::vector<int64_t> words = { this->Samples, static_cast<int64_t>(this->Labels.size()) };
  words.insert(words.end(), this->Labels.begin(), this->Labels.end());
  words.push_back(static_cast<int64_t>(this->Support.size()));
  for (const auto& entry : this->Support)
  {
    words.insert(words.end(), { entry.first.first, entry.first.second, entry.second });
  }
  return words;
}

bool RegionEvidence::Add(const int64_t* words, int64_t count)
{
  if (count < 3 || words[0] < 0 || words[1] < 0 || words[1] > count - 3)
  {
    return false;
  }
  const int64_t labels = words[1];
  const int64_t* label = words + 2;
  const int64_t pairs = words[2 + labels];
  if (pairs < 0 || pairs > (count - 3 - labels) / 3 || 3 + labels + 3 * pairs != count ||
    !std::is_sorted(label, label + labels) ||
    std::any_of(label, label + labels, [](int64_t l) { return l < 0; }))
  {
    return false;
  }
  const int64_t* pair = words + 3 + labels;
  for (int64_t p = 0; p < pairs; ++p)
  {
    const int64_t* entry = pair + 3 * p;
    if (entry[0] < 0 || entry[1] <= entry[0] || entry[2] <= 0)
    {
      return false;
    }
  }
  this->Samples += words[0];
  std::vector<int64_t> merged;
  std::set_union(
    this->Labels.begin(), this->Labels.end(), label, label + labels, std::back_inserter(merged));
  this->Labels = std::move(merged);
  for (int64_t p = 0; p < pairs; ++p)
  {
    const int64_t* entry = pair + 3 * p;
    this->Support[{ entry[0], entry[1] }] += entry[2];
  }
  return true;
}

bool SegmentRegions(const SegmentInput& input,
  SegmentResult& result,
  std::string& error,
  const ParallelFor& parallelFor)
{
  const ParallelFor run = parallelFor
    ? parallelFor
    : ParallelFor([](int64_t total, int64_t, const std::function<void(int64_t, int64_t)>& body)
        { body(0, total); });
  if (input.Ownership &&
    (!input.WholeGrid.Contains(input.Grid.Whole) ||
      !input.Grid.Whole.Contains(input.Ownership->Piece) || !input.Combine))
  {
    error = "a piece's samples must lie in the whole grid and hold the piece, and the "
            "piece needs Combine";
    return false;
  }
  std::vector<int64_t> label;
  Label(input, run, label, result.Patch);
  RegionEvidence evidence;
  if (!CountEvidence(input, label, run, evidence))
  {
    error = "a piece's samples must hold the sample after it along each axis";
    return false;
  }
  if (input.Combine && !input.Combine(evidence, error))
  {
    return false;
  }
  const int64_t labels = 2 * input.Patches->PatchCount;
  const int64_t whole = input.Ownership ? input.WholeGrid.Count() : input.Grid.Whole.Count();
  if (evidence.Samples != whole || (!evidence.Labels.empty() && evidence.Labels.back() >= labels) ||
    (!evidence.Support.empty() && evidence.Support.rbegin()->first.first >= labels))
  {
    error = "the pieces' evidence covers " + std::to_string(evidence.Samples) + " of the " +
      std::to_string(whole) + " samples, or names labels the patches do not have";
    return false;
  }
  LabelSets sets;
  result.Merges = result.Refused = 0;
  for (const auto& entry : CanonicalPairs(evidence))
  {
    if (entry.first.second >= labels)
    {
      error = "the pieces' evidence names labels the patches do not have";
      return false;
    }
    bool merged = false;
    if (!sets.Merge(entry.first.first, entry.first.second, merged))
    {
      ++result.Refused;
    }
    result.Merges += merged;
  }
  NumberRegions(label, labels, evidence, sets, run, result);
  return true;
}

} // namespace vtkdf
