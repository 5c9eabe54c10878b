#include "LinearFactor/QueryTree.h"

#include "Common/FloatBounds.h"
#include "Common/LargeVector.h"
#include "Common/MinMax.h"
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
  double n[3], area2;
  if (!IsProperFace(x, degenerate, n, area2))
  {
    return false;
  }
  for (int k = 0; k < 3; ++k)
  {
    normal[k] = n[k] * (1.0 / area2);
  }
  return true;
}

bool IsProperFace(const double* x, double degenerate, double n[3], double& area2)
{
  const double *a = x, *b = x + 3, *c = x + 6;
  return !SamePoint(a, b) && !SamePoint(b, c) && !SamePoint(c, a) &&
    ProperFace(a, b, c, degenerate, n, area2);
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
  this->BuildWideNodes(static_cast<int32_t>(n), parallelFor);
  this->Codes = LargeVector<uint32_t>(); // only the build needs them
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
      Primitive t;
      for (int k = 0; k < 3; ++k)
      {
        std::copy(&mesh.Points[3 * c[k]], &mesh.Points[3 * c[k]] + 3, t.X + 3 * k);
      }
      double n[3], area2;
      this->Faces[i] = source < corners.Triangles && IsProperFace(t.X, this->Degenerate, n, area2);
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

/// Primitives [Begin, End) in the tree's order: a node of the binary tree that splits
/// ranges by SplitCodes down to leaves of at most LeafSize primitives.
struct Range
{
  int32_t Begin, End;
  bool Leaf() const { return this->End - this->Begin <= LeafSize; }
};

/// The children of the wide node at `range`: the binary node's children, each inner one
/// replaced by its own two (a leaf root is its own only child).
int WideChildren(const LargeVector<uint32_t>& codes, const Range& range, Range kids[4])
{
  if (range.Leaf())
  {
    kids[0] = range;
    return 1;
  }
  const int32_t split = SplitCodes(codes, range.Begin, range.End);
  int count = 0;
  for (const Range half : { Range{ range.Begin, split }, Range{ split, range.End } })
  {
    if (half.Leaf())
    {
      kids[count++] = half;
      continue;
    }
    const int32_t quarter = SplitCodes(codes, half.Begin, half.End);
    kids[count++] = Range{ half.Begin, quarter };
    kids[count++] = Range{ quarter, half.End };
  }
  return count;
}

/// How many wide nodes and leaves the subtree of the wide node at `range` holds.
struct WideSize
{
  int32_t Wide = 0, Leaves = 0;
};
WideSize CountWide(const LargeVector<uint32_t>& codes, const Range& range)
{
  WideSize size{ 1, 0 };
  Range kids[4];
  const int count = WideChildren(codes, range, kids);
  for (int k = 0; k < count; ++k)
  {
    if (kids[k].Leaf())
    {
      ++size.Leaves;
      continue;
    }
    const WideSize below = CountWide(codes, kids[k]);
    size.Wide += below.Wide;
    size.Leaves += below.Leaves;
  }
  return size;
}

/// Writes the wide nodes and leaves of a subtree into arrays sized for them: a node's
/// inner children at consecutive slots, then their subtrees in turn (depth first).
struct WideFill
{
  const QueryTree& Tree;
  const LargeVector<uint32_t>& Codes;
  WideNode* Wide;
  Leaf* Leaves;
  int32_t NextWide, NextLeaf;
  /// Children whose ranges hold at most this many primitives are left to other fills
  /// (Deferred: the node's slot and child), unless it is 0.
  int32_t Defer = 0;
  std::vector<std::array<int32_t, 4>>* Deferred = nullptr; // slot, child, begin, end

  /// The leaf of `range` at slot `at`, its box rounded outward to float once from the
  /// corners' double bounds (the rounding is monotonic: the box of rounded corners).
  void MakeLeaf(const Range& range, int32_t at, float lo[3], float hi[3]) const
  {
    double dlo[3] = { HUGE_VAL, HUGE_VAL, HUGE_VAL }, dhi[3] = { -HUGE_VAL, -HUGE_VAL, -HUGE_VAL };
    for (int32_t i = range.Begin; i < range.End; ++i)
    {
      for (int k = 0; k < 3; ++k)
      {
        const double* x = this->Tree.Corner(i, k);
        for (int a = 0; a < 3; ++a)
        {
          dlo[a] = std::min(dlo[a], x[a]);
          dhi[a] = std::max(dhi[a], x[a]);
        }
      }
    }
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = FloatBelow(dlo[a]), hi[a] = FloatAbove(dhi[a]);
    }
    Leaf leaf{};
    leaf.First = range.Begin, leaf.Count = range.End - range.Begin;
    this->Leaves[at] = leaf;
  }

  /// Fills the wide node at `slot` for `range` and its subtree; its box into lo, hi (the
  /// union of its children's).
  void Fill(const Range& range, int32_t slot, float lo[3], float hi[3])
  {
    Range kids[4];
    const int count = WideChildren(this->Codes, range, kids);
    WideNode& node = this->Wide[slot];
    for (int k = 0; k < 4; ++k)
    {
      node.First[k] = 0, node.Count[k] = -1;
      for (int a = 0; a < 3; ++a)
      {
        node.Lo[a][k] = HUGE_VALF, node.Hi[a][k] = -HUGE_VALF;
      }
    }
    for (int k = 0; k < count; ++k)
    {
      if (kids[k].Leaf())
      {
        node.First[k] = this->NextLeaf++, node.Count[k] = kids[k].End - kids[k].Begin;
      }
      else if (kids[k].End - kids[k].Begin <= this->Defer)
      {
        this->Deferred->push_back({ slot, k, kids[k].Begin, kids[k].End });
        node.Count[k] = 0;
      }
      else
      {
        node.First[k] = this->NextWide++, node.Count[k] = 0;
      }
    }
    for (int k = 0; k < count; ++k)
    {
      float klo[3], khi[3];
      if (kids[k].Leaf())
      {
        this->MakeLeaf(kids[k], node.First[k], klo, khi);
      }
      else if (kids[k].End - kids[k].Begin <= this->Defer)
      {
        continue; // its box once its fill has run
      }
      else
      {
        this->Fill(kids[k], node.First[k], klo, khi);
      }
      for (int a = 0; a < 3; ++a)
      {
        node.Lo[a][k] = klo[a], node.Hi[a][k] = khi[a];
      }
    }
    UniteBoxes(node, lo, hi);
  }

  static void UniteBoxes(const WideNode& node, float lo[3], float hi[3])
  {
    for (int a = 0; a < 3; ++a)
    {
      lo[a] =
        std::min(std::min(node.Lo[a][0], node.Lo[a][1]), std::min(node.Lo[a][2], node.Lo[a][3]));
      hi[a] =
        std::max(std::max(node.Hi[a][0], node.Hi[a][1]), std::max(node.Hi[a][2], node.Hi[a][3]));
    }
  }
};

} // namespace

void QueryTree::BuildWideNodes(int32_t n, const ParallelFor& parallelFor)
{
  // The top wide nodes here, down to children of at most 1/64 of the primitives, into
  // small arrays; those children's subtrees counted, then filled in parallel at slots that
  // follow from the counts: the same arrays on any number of threads.
  std::vector<WideNode> topWide(1);
  std::vector<Leaf> topLeaves;
  std::vector<std::array<int32_t, 4>> deferred;
  {
    // A top node other than the root holds more than n / 64 primitives (or the whole tree
    // is at the top when n < 64 * LeafSize, at most n nodes): at most 64 on each of the
    // wide tree's at most 32 levels, each with at most 4 leaves.
    topWide.resize(64 * 32 + 1);
    topLeaves.resize(4 * topWide.size());
    WideFill top{ *this, this->Codes, topWide.data(), topLeaves.data(), 1, 0 };
    top.Defer = std::max<int32_t>(LeafSize, n / 64);
    top.Deferred = &deferred;
    float lo[3], hi[3];
    top.Fill(Range{ 0, n }, 0, lo, hi);
    topWide.resize(top.NextWide);
    topLeaves.resize(top.NextLeaf);
  }
  const int64_t tasks = static_cast<int64_t>(deferred.size());
  std::vector<WideSize> sizes(tasks);
  auto count = [&](int64_t begin, int64_t end)
  {
    for (int64_t t = begin; t < end; ++t)
    {
      sizes[t] = CountWide(this->Codes, Range{ deferred[t][2], deferred[t][3] });
    }
  };
  parallelFor ? parallelFor(tasks, 1, count) : count(0, tasks);
  std::vector<WideSize> offsets(tasks);
  WideSize total{ static_cast<int32_t>(topWide.size()), static_cast<int32_t>(topLeaves.size()) };
  for (int64_t t = 0; t < tasks; ++t)
  {
    offsets[t] = total;
    total.Wide += sizes[t].Wide;
    total.Leaves += sizes[t].Leaves;
  }
  this->WideNodes.resize(total.Wide);
  this->Leaves.resize(total.Leaves);
  std::copy(topWide.begin(), topWide.end(), this->WideNodes.begin());
  std::copy(topLeaves.begin(), topLeaves.end(), this->Leaves.begin());
  auto fill = [&](int64_t begin, int64_t end)
  {
    for (int64_t t = begin; t < end; ++t)
    {
      WideFill below{ *this,
        this->Codes,
        this->WideNodes.data(),
        this->Leaves.data(),
        offsets[t].Wide + 1,
        offsets[t].Leaves };
      float lo[3], hi[3];
      below.Fill(Range{ deferred[t][2], deferred[t][3] }, offsets[t].Wide, lo, hi);
      WideNode& parent = this->WideNodes[deferred[t][0]];
      const int k = deferred[t][1];
      parent.First[k] = offsets[t].Wide;
      for (int a = 0; a < 3; ++a)
      {
        parent.Lo[a][k] = lo[a], parent.Hi[a][k] = hi[a];
      }
    }
  };
  parallelFor ? parallelFor(tasks, 1, fill) : fill(0, tasks);
  // The top nodes' boxes of deferred children's ancestors, children (later slots) first.
  for (size_t w = topWide.size(); w-- > 0;)
  {
    WideNode& node = this->WideNodes[w];
    for (int k = 0; k < 4; ++k)
    {
      if (node.Count[k] == 0 && node.First[k] < static_cast<int32_t>(topWide.size()))
      {
        float lo[3], hi[3];
        WideFill::UniteBoxes(this->WideNodes[node.First[k]], lo, hi);
        for (int a = 0; a < 3; ++a)
        {
          node.Lo[a][k] = lo[a], node.Hi[a][k] = hi[a];
        }
      }
    }
  }
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
    const double gap = Max(0.0, std::fabs(along) - double(leaf.Extent[k]));
    d2 += gap * gap;
  }
  // The float axes are orthonormal within 1e-6 (so a sum of squared projections exceeds
  // the squared distance by at most that much), and the extents were widened past the
  // projections' rounding: a lower bound on the squared distance to the leaf.
  return d2 * (1 - 1e-5);
}

} // namespace nearest
} // namespace vtkdf
