#include "LinearFactor/QueryTree.h"

#include "Common/FloatBounds.h"
#include "Common/LargeVector.h"
#include "Common/Vector3.h"
#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <vector>

namespace vtkdf
{
namespace nearest
{
/// MeshSites' face test and unit normal: distinct corners, and twice the area above
/// `degenerate` times the longest side.
bool FaceNormal(const double* x, double degenerate, double normal[3])
{
  const double *a = x, *b = x + 3, *c = x + 6;
  if (SamePoint(a, b) || SamePoint(b, c) || SamePoint(c, a))
  {
    return false;
  }
  double e1[3], e2[3], e3[3];
  for (int k = 0; k < 3; ++k)
  {
    e1[k] = b[k] - a[k], e2[k] = c[k] - a[k], e3[k] = c[k] - b[k];
  }
  double n[3];
  Cross(e1, e2, n);
  const double area2 = std::sqrt(Dot(n, n));
  const double longest =
    std::max(std::sqrt(Dot(e1, e1)), std::max(std::sqrt(Dot(e2, e2)), std::sqrt(Dot(e3, e3))));
  if (!(area2 > degenerate * longest))
  {
    return false;
  }
  for (int k = 0; k < 3; ++k)
  {
    normal[k] = n[k] * (1.0 / area2);
  }
  return true;
}

namespace
{

/// Spreads the 10 low bits of x three bits apart (a Morton code's one axis).
uint32_t SpreadBits(uint32_t x)
{
  x &= 0x3ff;
  x = (x | (x << 16)) & 0x30000ff;
  x = (x | (x << 8)) & 0x300f00f;
  x = (x | (x << 4)) & 0x30c30c3;
  x = (x | (x << 2)) & 0x9249249;
  return x;
}

/// An inner node's box: the union of its children's.
void UniteChildren(LargeVector<Node>& nodes, int32_t slot)
{
  Node& node = nodes[slot];
  const Node &left = nodes[node.First], &right = nodes[node.First + 1];
  for (int a = 0; a < 3; ++a)
  {
    node.Lo[a] = std::min(left.Lo[a], right.Lo[a]);
    node.Hi[a] = std::max(left.Hi[a], right.Hi[a]);
  }
}

} // namespace

/// The corner ids and input cell of primitive i of a mesh: a triangle's, a segment's
/// (a, b, b), a point's (a, a, a), in that order.
struct PrimitiveCorners
{
  const MeshInput& Mesh;
  int64_t Triangles, Segments;

  explicit PrimitiveCorners(const MeshInput& mesh)
    : Mesh(mesh)
    , Triangles(static_cast<int64_t>(mesh.Triangles.size() / 3))
    , Segments(static_cast<int64_t>(mesh.Segments.size() / 2))
  {
  }
  int64_t Count() const
  {
    return this->Triangles + this->Segments + int64_t(this->Mesh.Vertices.size());
  }
  void operator()(int64_t i, int64_t c[3], int64_t& cell) const
  {
    const int64_t nt = this->Triangles, ns = this->Segments;
    if (i < nt)
    {
      c[0] = this->Mesh.Triangles[3 * i], c[1] = this->Mesh.Triangles[3 * i + 1];
      c[2] = this->Mesh.Triangles[3 * i + 2];
      cell = this->Mesh.TriangleCells[i];
    }
    else if (i < nt + ns)
    {
      const int64_t s = i - nt;
      c[0] = this->Mesh.Segments[2 * s], c[1] = c[2] = this->Mesh.Segments[2 * s + 1];
      cell = this->Mesh.SegmentCells[s];
    }
    else
    {
      c[0] = c[1] = c[2] = this->Mesh.Vertices[i - nt - ns];
      cell = this->Mesh.VertexCells[i - nt - ns];
    }
  }
};

namespace
{

/// Checks primitives [begin, end)'s corners (existing points, finite coordinates) and
/// widens lo, hi over them; false with `error` at the first bad one.
bool BoundCorners(const PrimitiveCorners& corners,
  int64_t begin,
  int64_t end,
  double lo[3],
  double hi[3],
  std::string& error)
{
  const MeshInput& mesh = corners.Mesh;
  const int64_t numPoints = static_cast<int64_t>(mesh.Points.size() / 3);
  for (int64_t i = begin; i < end; ++i)
  {
    int64_t c[3], cell;
    corners(i, c, cell);
    for (int k = 0; k < 3; ++k)
    {
      if (c[k] < 0 || c[k] >= numPoints)
      {
        error =
          "a cell refers to point " + std::to_string(c[k]) + " of " + std::to_string(numPoints);
        return false;
      }
      const double* x = &mesh.Points[3 * c[k]];
      for (int a = 0; a < 3; ++a)
      {
        if (!std::isfinite(x[a]))
        {
          error = "point " + std::to_string(c[k]) + " has a NaN or infinite coordinate";
          return false;
        }
        lo[a] = std::min(lo[a], x[a]);
        hi[a] = std::max(hi[a], x[a]);
      }
    }
  }
  return true;
}

/// Checks every primitive's corners and bounds them in lo, hi (chunks in parallel: a
/// minimum and a maximum do not depend on the order); false with the first bad one's
/// `error`.
bool BoundUsedPoints(const PrimitiveCorners& corners,
  double lo[3],
  double hi[3],
  const ParallelFor& parallelFor,
  std::string& error)
{
  const int64_t n = corners.Count();
  const int64_t chunk = 65536, chunks = (n + chunk - 1) / chunk;
  std::vector<std::array<double, 6>> bounds(
    chunks, { { HUGE_VAL, HUGE_VAL, HUGE_VAL, -HUGE_VAL, -HUGE_VAL, -HUGE_VAL } });
  std::atomic<bool> bad{ false };
  auto bound = [&](int64_t begin, int64_t end)
  {
    std::string ignored;
    for (int64_t k = begin; k < end; ++k)
    {
      std::array<double, 6>& b = bounds[k];
      if (!BoundCorners(
            corners, k * chunk, std::min(n, (k + 1) * chunk), b.data(), b.data() + 3, ignored))
      {
        bad = true;
      }
    }
  };
  parallelFor ? parallelFor(chunks, 1, bound) : bound(0, chunks);
  for (int a = 0; a < 3; ++a)
  {
    lo[a] = HUGE_VAL;
    hi[a] = -HUGE_VAL;
  }
  if (bad)
  {
    return BoundCorners(corners, 0, n, lo, hi, error); // finds the first bad corner
  }
  for (const std::array<double, 6>& b : bounds)
  {
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = std::min(lo[a], b[a]);
      hi[a] = std::max(hi[a], b[3 + a]);
    }
  }
  return true;
}

/// The primitives as keys (Morton code of the box's centre over the points' box lo..hi,
/// in the high 32 bits; the index in the low ones), sorted by radix.
LargeVector<uint64_t> SortedMortonKeys(const PrimitiveCorners& corners,
  const double lo[3],
  const double hi[3],
  const ParallelFor& parallelFor)
{
  const MeshInput& mesh = corners.Mesh;
  const int64_t n = corners.Count();
  const double extent = std::max({ hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], 1e-300 });
  LargeVector<uint64_t> keys(n);
  auto code = [&](int64_t begin, int64_t end)
  {
    for (int64_t i = begin; i < end; ++i)
    {
      int64_t c[3], cell;
      corners(i, c, cell);
      uint32_t morton = 0;
      for (int a = 0; a < 3; ++a)
      {
        const double x0 = mesh.Points[3 * c[0] + a], x1 = mesh.Points[3 * c[1] + a],
                     x2 = mesh.Points[3 * c[2] + a];
        const double centre = 0.5 * (std::min({ x0, x1, x2 }) + std::max({ x0, x1, x2 }));
        const double cellIndex = std::floor((centre - lo[a]) / extent * 1024);
        morton |= SpreadBits(static_cast<uint32_t>(std::min(1023.0, std::max(0.0, cellIndex))))
          << (2 - a);
      }
      keys[i] = (uint64_t(morton) << 32) | uint64_t(i);
    }
  };
  parallelFor ? parallelFor(n, 8192, code) : code(0, n);
  // Three passes of a stable radix sort on the codes' 10-bit digits, each over fixed
  // chunks of the keys in parallel: chunk c's keys of digit d go after every earlier
  // chunk's of that digit, so the order is the serial sort's on any thread count.
  LargeVector<uint64_t> sorted(n);
  const int64_t chunk = 65536, chunks = (n + chunk - 1) / chunk;
  std::vector<std::array<int64_t, 1024>> start(chunks);
  for (int pass = 0; pass < 3; ++pass)
  {
    const int shift = 32 + 10 * pass;
    auto count = [&](int64_t begin, int64_t end)
    {
      for (int64_t c = begin; c < end; ++c)
      {
        start[c].fill(0);
        for (int64_t i = c * chunk; i < std::min(n, (c + 1) * chunk); ++i)
        {
          ++start[c][(keys[i] >> shift) & 1023];
        }
      }
    };
    parallelFor ? parallelFor(chunks, 1, count) : count(0, chunks);
    int64_t offset = 0;
    for (int d = 0; d < 1024; ++d)
    {
      for (int64_t c = 0; c < chunks; ++c)
      {
        const int64_t size = start[c][d];
        start[c][d] = offset;
        offset += size;
      }
    }
    auto scatter = [&](int64_t begin, int64_t end)
    {
      for (int64_t c = begin; c < end; ++c)
      {
        for (int64_t i = c * chunk; i < std::min(n, (c + 1) * chunk); ++i)
        {
          sorted[start[c][(keys[i] >> shift) & 1023]++] = keys[i];
        }
      }
    };
    parallelFor ? parallelFor(chunks, 1, scatter) : scatter(0, chunks);
    keys.swap(sorted);
  }
  return keys;
}

} // namespace

bool QueryTree::Build(const MeshInput& mesh, const ParallelFor& parallelFor, std::string& error)
{
  const PrimitiveCorners corners(mesh);
  const int64_t n = corners.Count();
  this->Triangles = corners.Triangles;
  if (n >= std::numeric_limits<int32_t>::max())
  {
    error = "the mesh has " + std::to_string(n) + " cells, more than 2^31 - 1";
    return false;
  }
  if (mesh.Points.size() / 3 > std::numeric_limits<uint32_t>::max())
  {
    error =
      "the mesh has " + std::to_string(mesh.Points.size() / 3) + " points, more than 2^32 - 1";
    return false;
  }
  double lo[3], hi[3];
  if (!BoundUsedPoints(corners, lo, hi, parallelFor, error))
  {
    return false;
  }
  if (n == 0)
  {
    return true;
  }
  const double diagonal = std::hypot(hi[0] - lo[0], std::hypot(hi[1] - lo[1], hi[2] - lo[2]));
  this->Degenerate = 1e-10 * (diagonal > 0 ? diagonal : 1.0);
  const double magnitude = std::max({ std::fabs(lo[0]),
    std::fabs(lo[1]),
    std::fabs(lo[2]),
    std::fabs(hi[0]),
    std::fabs(hi[1]),
    std::fabs(hi[2]) });
  // Squared distances computed from coordinates of this size are off by about
  // (magnitude * 2^-52)^2 near zero: a thousand times that is slack enough.
  this->Tolerance2 = std::pow(1e3 * std::numeric_limits<double>::epsilon() * (1 + magnitude), 2);
  this->GatherPrimitives(corners, SortedMortonKeys(corners, lo, hi, parallelFor), parallelFor);
  this->Orientation = this->FacesVolume(lo) < 0 ? -1.0 : 1.0;
  this->BuildNodes(static_cast<int32_t>(n), parallelFor);
  this->Codes = LargeVector<uint32_t>(); // only the build needs them
  this->Widen();
  this->Margin = 1e-12 * (1 + magnitude);
  this->FrameLeaves(parallelFor);
  return true;
}

void QueryTree::GatherPrimitives(const PrimitiveCorners& corners,
  const LargeVector<uint64_t>& keys,
  const ParallelFor& parallelFor)
{
  const MeshInput& mesh = corners.Mesh;
  const int64_t n = corners.Count();
  this->Corners.resize(n);
  this->Cells.resize(n);
  this->Sources.resize(n);
  this->Faces.resize(n);
  this->Codes.resize(n);
  // The sorted order first (sequential), then each primitive read in the mesh's order,
  // where consecutive cells share points and cache lines, and written to its place: a
  // gather in the sorted order would chase two random reads a primitive.
  LargeVector<uint32_t> place(n);
  auto order = [&](int64_t begin, int64_t end)
  {
    for (int64_t i = begin; i < end; ++i)
    {
      this->Sources[i] = static_cast<uint32_t>(keys[i] & 0xffffffffu);
      this->Codes[i] = static_cast<uint32_t>(keys[i] >> 32);
      place[this->Sources[i]] = static_cast<uint32_t>(i);
    }
  };
  parallelFor ? parallelFor(n, 8192, order) : order(0, n);
  auto gather = [&](int64_t begin, int64_t end)
  {
    for (int64_t source = begin; source < end; ++source)
    {
      const uint32_t i = place[source];
      int64_t c[3];
      corners(source, c, this->Cells[i]);
      this->Corners[i] = {
        static_cast<uint32_t>(c[0]), static_cast<uint32_t>(c[1]), static_cast<uint32_t>(c[2])
      };
      double normal[3];
      Primitive t;
      for (int k = 0; k < 3; ++k)
      {
        std::copy(&mesh.Points[3 * c[k]], &mesh.Points[3 * c[k]] + 3, t.X + 3 * k);
      }
      this->Faces[i] = source < corners.Triangles && FaceNormal(t.X, this->Degenerate, normal);
    }
  };
  parallelFor ? parallelFor(n, 8192, gather) : gather(0, n);
  // The points in the order the sorted primitives first use them: a leaf's corners then
  // share cache lines, as they would if the tree held them itself.
  const int64_t numPoints = static_cast<int64_t>(mesh.Points.size() / 3);
  LargeVector<uint32_t> renumber(numPoints);
  std::fill(renumber.begin(), renumber.end(), std::numeric_limits<uint32_t>::max());
  uint32_t next = 0;
  for (CornerIds& c : this->Corners)
  {
    for (uint32_t& id : c)
    {
      uint32_t& to = renumber[id];
      if (to == std::numeric_limits<uint32_t>::max())
      {
        to = next++;
      }
      id = to;
    }
  }
  this->Points.resize(3 * int64_t(next));
  auto copy = [&](int64_t begin, int64_t end)
  {
    for (int64_t p = begin; p < end; ++p)
    {
      if (renumber[p] != std::numeric_limits<uint32_t>::max())
      {
        std::copy(
          &mesh.Points[3 * p], &mesh.Points[3 * p] + 3, &this->Points[3 * int64_t(renumber[p])]);
      }
    }
  };
  parallelFor ? parallelFor(numPoints, 1 << 14, copy) : copy(0, numPoints);
}

double QueryTree::FacesVolume(const double lo[3]) const
{
  double volume = 0;
  for (int64_t i = 0; i < this->Size(); ++i)
  {
    if (this->Faces[i])
    {
      const double *pa = this->Corner(i, 0), *pb = this->Corner(i, 1), *pc = this->Corner(i, 2);
      double a[3], b[3], c[3], bc[3];
      for (int k = 0; k < 3; ++k)
      {
        a[k] = pa[k] - lo[k], b[k] = pb[k] - lo[k], c[k] = pc[k] - lo[k];
      }
      Cross(b, c, bc);
      volume += Dot(a, bc);
    }
  }
  return volume;
}

namespace
{
/// Where a range of codes splits: where the highest bit in which they differ turns on
/// (the middle when they are all equal).
int32_t SplitCodes(const LargeVector<uint32_t>& codes, int32_t begin, int32_t end)
{
  const uint32_t first = codes[begin], last = codes[end - 1];
  if (first == last)
  {
    return begin + (end - begin) / 2;
  }
  const uint32_t bit = 1u << (31 - __builtin_clz(first ^ last));
  return static_cast<int32_t>(
    std::partition_point(
      codes.begin() + begin, codes.begin() + end, [bit](uint32_t c) { return (c & bit) == 0; }) -
    codes.begin());
}

/// Builds the subtree of primitives [begin, end) at nodes[slot], its descendants
/// appended to `nodes` (children after their parent, siblings side by side).
void BuildSubtree(LargeVector<Node>& nodes,
  const LargeVector<uint32_t>& codes,
  const QueryTree& tree,
  int32_t slot,
  int32_t begin,
  int32_t end)
{
  if (end - begin <= LeafSize)
  {
    // The corners' bounds in double, then rounded outward once (the rounding is
    // monotonic: the same box as rounding every corner).
    double lo[3] = { HUGE_VAL, HUGE_VAL, HUGE_VAL }, hi[3] = { -HUGE_VAL, -HUGE_VAL, -HUGE_VAL };
    for (int32_t i = begin; i < end; ++i)
    {
      for (int k = 0; k < 3; ++k)
      {
        const double* x = tree.Corner(i, k);
        for (int a = 0; a < 3; ++a)
        {
          lo[a] = std::min(lo[a], x[a]);
          hi[a] = std::max(hi[a], x[a]);
        }
      }
    }
    Node& leaf = nodes[slot];
    for (int a = 0; a < 3; ++a)
    {
      leaf.Lo[a] = FloatBelow(lo[a]), leaf.Hi[a] = FloatAbove(hi[a]);
    }
    leaf.First = begin;
    leaf.Count = end - begin;
    return;
  }
  const int32_t split = SplitCodes(codes, begin, end);
  const int32_t left = static_cast<int32_t>(nodes.size());
  nodes.emplace_back();
  nodes.emplace_back();
  BuildSubtree(nodes, codes, tree, left, begin, split);
  BuildSubtree(nodes, codes, tree, left + 1, split, end);
  nodes[slot].First = left;
  nodes[slot].Count = 0;
  UniteChildren(nodes, slot);
}

} // namespace

void QueryTree::BuildNodes(int32_t n, const ParallelFor& parallelFor)
{
  // The top levels here, down to subtrees of at most 1/64 of the primitives (or leaves);
  // the subtrees in parallel, each in its own array, then appended in order: the same
  // tree on any number of threads.
  struct Subtree
  {
    int32_t Slot, Begin, End;
    LargeVector<Node> Nodes;
  };
  std::vector<Subtree> subtrees;
  const int32_t small = std::max<int32_t>(LeafSize, n / 64);
  this->Nodes.assign(1, Node{});
  std::vector<int32_t> inner; // top nodes that are split here, parents first
  std::vector<std::array<int32_t, 3>> pending{ { 0, 0, n } };
  while (!pending.empty())
  {
    const auto range = pending.back();
    pending.pop_back();
    if (range[2] - range[1] <= small)
    {
      subtrees.push_back(Subtree{ range[0], range[1], range[2], {} });
      continue;
    }
    const int32_t split = SplitCodes(this->Codes, range[1], range[2]);
    const int32_t left = static_cast<int32_t>(this->Nodes.size());
    this->Nodes.emplace_back();
    this->Nodes.emplace_back();
    this->Nodes[range[0]].First = left;
    this->Nodes[range[0]].Count = 0;
    inner.push_back(range[0]);
    pending.push_back({ left + 1, split, range[2] });
    pending.push_back({ left, range[1], split });
  }
  auto build = [&](int64_t begin, int64_t end)
  {
    for (int64_t k = begin; k < end; ++k)
    {
      Subtree& t = subtrees[k];
      t.Nodes.reserve(2 * static_cast<size_t>((t.End - t.Begin) / LeafSize + 1));
      t.Nodes.emplace_back();
      BuildSubtree(t.Nodes, this->Codes, *this, 0, t.Begin, t.End);
    }
  };
  parallelFor ? parallelFor(static_cast<int64_t>(subtrees.size()), 1, build)
              : build(0, static_cast<int64_t>(subtrees.size()));
  size_t total = this->Nodes.size();
  for (const Subtree& t : subtrees)
  {
    total += t.Nodes.size() - 1;
  }
  this->Nodes.reserve(total);
  for (const Subtree& t : subtrees)
  {
    // Node j > 0 of the subtree goes to offset + j - 1; its root to t.Slot.
    const int32_t offset = static_cast<int32_t>(this->Nodes.size());
    auto place = [offset](Node node)
    {
      if (node.Count == 0)
      {
        node.First += offset - 1;
      }
      return node;
    };
    this->Nodes[t.Slot] = place(t.Nodes[0]);
    for (size_t j = 1; j < t.Nodes.size(); ++j)
    {
      this->Nodes.push_back(place(t.Nodes[j]));
    }
  }
  for (size_t k = inner.size(); k-- > 0;)
  {
    UniteChildren(this->Nodes, inner[k]);
  }
}

void QueryTree::Widen()
{
  this->WideNodes.clear();
  this->Leaves.clear();
  if (this->Nodes.empty())
  {
    return;
  }
  // Wide node w gathers binary node b's children, each inner one replaced by its own two.
  std::vector<std::pair<int32_t, int32_t>> pending{ { 0, 0 } }; // (b, w)
  // About a third as many wide nodes as binary ones, and half as many leaves.
  this->WideNodes.reserve(this->Nodes.size() / 3 + 1);
  this->Leaves.reserve(this->Nodes.size() / 2 + 1);
  this->WideNodes.emplace_back();
  while (!pending.empty())
  {
    const auto [b, w] = pending.back();
    pending.pop_back();
    int32_t kids[4], count = 0;
    const Node& node = this->Nodes[b];
    if (node.Count > 0)
    {
      kids[count++] = b; // a leaf root
    }
    else
    {
      for (const int32_t child : { node.First, node.First + 1 })
      {
        const Node& c = this->Nodes[child];
        if (c.Count > 0)
        {
          kids[count++] = child;
        }
        else
        {
          kids[count++] = c.First;
          kids[count++] = c.First + 1;
        }
      }
    }
    for (int k = 0; k < 4; ++k)
    {
      WideNode& wide = this->WideNodes[w];
      if (k >= count)
      {
        for (int a = 0; a < 3; ++a)
        {
          wide.Lo[a][k] = HUGE_VALF, wide.Hi[a][k] = -HUGE_VALF;
        }
        wide.First[k] = 0, wide.Count[k] = -1;
        continue;
      }
      const Node& c = this->Nodes[kids[k]];
      for (int a = 0; a < 3; ++a)
      {
        wide.Lo[a][k] = c.Lo[a], wide.Hi[a][k] = c.Hi[a];
      }
      if (c.Count > 0)
      {
        wide.First[k] = static_cast<int32_t>(this->Leaves.size()), wide.Count[k] = c.Count;
        Leaf leaf{};
        leaf.First = c.First, leaf.Count = c.Count;
        this->Leaves.push_back(leaf);
      }
      else
      {
        const int32_t slot = static_cast<int32_t>(this->WideNodes.size());
        this->WideNodes.emplace_back(); // invalidates `wide`
        this->WideNodes[w].First[k] = slot, this->WideNodes[w].Count[k] = 0;
        pending.emplace_back(kids[k], slot);
      }
    }
  }
  this->Nodes.clear();
  this->Nodes.shrink_to_fit();
}

void QueryTree::FrameLeaves(const ParallelFor& parallelFor)
{
  auto frame = [&](int64_t begin, int64_t end)
  {
    for (int64_t l = begin; l < end; ++l)
    {
      Leaf& leaf = this->Leaves[l];
      // The mean normal (area-weighted), and two axes across it.
      double n[3] = { 0, 0, 0 }, lo[3] = { HUGE_VAL, HUGE_VAL, HUGE_VAL },
             hi[3] = { -HUGE_VAL, -HUGE_VAL, -HUGE_VAL };
      for (int32_t i = leaf.First; i < leaf.First + leaf.Count; ++i)
      {
        const double* x[3] = { this->Corner(i, 0), this->Corner(i, 1), this->Corner(i, 2) };
        double e1[3], e2[3], c[3];
        for (int a = 0; a < 3; ++a)
        {
          e1[a] = x[1][a] - x[0][a], e2[a] = x[2][a] - x[0][a];
          for (int k = 0; k < 3; ++k)
          {
            lo[a] = std::min(lo[a], x[k][a]), hi[a] = std::max(hi[a], x[k][a]);
          }
        }
        Cross(e1, e2, c);
        for (int a = 0; a < 3; ++a)
        {
          n[a] += c[a];
        }
      }
      double length = std::sqrt(Dot(n, n));
      double axes[3][3] = { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
      if (length > 0 && std::isfinite(length))
      {
        double u[3] = { 0, n[2], -n[1] };
        if (std::fabs(n[0]) >= 0.5 * length)
        {
          u[0] = -n[2], u[1] = 0, u[2] = n[0];
        }
        const double ul = std::sqrt(Dot(u, u));
        for (int a = 0; a < 3; ++a)
        {
          axes[0][a] = n[a] / length, axes[1][a] = u[a] / ul;
        }
        Cross(axes[0], axes[1], axes[2]);
      }
      // Extents from the stored (float) centre and axes, widened past rounding.
      for (int a = 0; a < 3; ++a)
      {
        leaf.Centre[a] = static_cast<float>(0.5 * (lo[a] + hi[a]));
        for (int k = 0; k < 3; ++k)
        {
          leaf.Axes[k][a] = static_cast<float>(axes[k][a]);
        }
      }
      for (int k = 0; k < 3; ++k)
      {
        double extent = 0;
        for (int32_t i = leaf.First; i < leaf.First + leaf.Count; ++i)
        {
          for (int c = 0; c < 3; ++c)
          {
            double along = 0;
            for (int a = 0; a < 3; ++a)
            {
              along += (this->Corner(i, c)[a] - double(leaf.Centre[a])) * double(leaf.Axes[k][a]);
            }
            extent = std::max(extent, std::fabs(along));
          }
        }
        leaf.Extent[k] = FloatAbove(extent * (1 + 1e-6) + this->Margin);
      }
    }
  };
  const int64_t count = static_cast<int64_t>(this->Leaves.size());
  parallelFor ? parallelFor(count, 4096, frame) : frame(0, count);
}

double QueryTree::LeafDistance2(const Leaf& leaf, const double p[3]) const
{
  double d2 = 0;
  for (int k = 0; k < 3; ++k)
  {
    double along = 0;
    for (int a = 0; a < 3; ++a)
    {
      along += (p[a] - double(leaf.Centre[a])) * double(leaf.Axes[k][a]);
    }
    const double gap = std::max(0.0, std::fabs(along) - double(leaf.Extent[k]));
    d2 += gap * gap;
  }
  // The float axes are orthonormal within 1e-6 (so a sum of squared projections exceeds
  // the squared distance by at most that much), and the extents were widened past the
  // projections' rounding: a lower bound on the squared distance to the leaf.
  return d2 * (1 - 1e-5);
}

} // namespace nearest
} // namespace vtkdf
