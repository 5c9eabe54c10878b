#include "LinearFactor/NearestTriangleQueries.h"

#include "Common/PointTriangleDistance.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <vector>

namespace vtkdf
{

namespace
{
constexpr int LeafSize = 4;

/// A triangle, segment (b = c) or point (a = b = c) of the mesh, in the tree's order.
struct Primitive
{
  double X[9];  // corners a, b, c
  int64_t Cell; // the input cell
  bool Face;    // a proper triangle (MeshSites' rule): otherwise only its edges count
};

/// A node's box is rounded outward to float; a leaf holds primitives [First, First +
/// Count), an inner node has its children at First and First + 1.
struct Node
{
  float Lo[3], Hi[3];
  int32_t First;
  int32_t Count; // 0 for an inner node
};

double Dot(const double* u, const double* v)
{
  return u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
}

void Cross(const double* u, const double* v, double* w)
{
  w[0] = u[1] * v[2] - u[2] * v[1];
  w[1] = u[2] * v[0] - u[0] * v[2];
  w[2] = u[0] * v[1] - u[1] * v[0];
}

bool SamePoint(const double* u, const double* v)
{
  return u[0] == v[0] && u[1] == v[1] && u[2] == v[2];
}

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

float Below(double v)
{
  const float f = static_cast<float>(v);
  return f <= v ? f : std::nextafter(f, -HUGE_VALF);
}

float Above(double v)
{
  const float f = static_cast<float>(v);
  return f >= v ? f : std::nextafter(f, HUGE_VALF);
}

class QueryTree
{
public:
  bool Build(const MeshInput& mesh, const ParallelFor& parallelFor, std::string& error);

  /// The nearest primitive to p: its index, squared distance, closest point and feature
  /// (TriangleFeature). Exact ties go to the smaller cell, then the smaller index, so the
  /// answer does not depend on `bound2` (an upper bound on the squared distance, or
  /// HUGE_VAL). Returns the number of primitives evaluated; index -1 when none lies
  /// within the bound.
  int64_t Nearest(const double p[3],
    double bound2,
    int64_t& index,
    double& best2,
    double closest[3],
    int& feature) const;

  /// The smallest cell among the primitives with a corner at `a` (and at `b` too, when
  /// given), and the pseudonormal of that vertex or edge: the faces' unit normals, each
  /// weighted by its angle at `a` for a vertex.
  void FeatureCellAndNormal(const double* a,
    const double* b,
    int64_t& cell,
    double normal[3]) const;

  const Primitive& Get(int64_t i) const { return this->Primitives[i]; }
  /// A face's pseudonormal: its unit normal, turned by the mesh's orientation.
  void FaceNormalOf(int64_t i, double normal[3]) const
  {
    for (int k = 0; k < 3; ++k)
    {
      normal[k] = this->FaceNormals[3 * i + k] * this->Orientation;
    }
  }
  double Orientation = 1; // -1 when the faces' signed volume is negative (MeshSites)
  double Degenerate = 0;
  double Tolerance2 = 0; // absolute slack on squared distances (coordinates' rounding)

private:
  void BuildNode(int32_t slot, int32_t begin, int32_t end);
  double BoxDistance2(const Node& node, const double p[3]) const;

  std::vector<Primitive> Primitives;
  std::vector<uint32_t> Codes;
  std::vector<Node> Nodes;
  std::vector<double> FaceNormals; // 3 per primitive (zeros for non-faces)
};

bool QueryTree::Build(const MeshInput& mesh, const ParallelFor& parallelFor, std::string& error)
{
  const int64_t numPoints = static_cast<int64_t>(mesh.Points.size() / 3);
  const int64_t nt = static_cast<int64_t>(mesh.Triangles.size() / 3);
  const int64_t ns = static_cast<int64_t>(mesh.Segments.size() / 2);
  const int64_t nv = static_cast<int64_t>(mesh.Vertices.size());
  const int64_t n = nt + ns + nv;
  if (n >= std::numeric_limits<int32_t>::max())
  {
    error = "the mesh has " + std::to_string(n) + " cells, more than 2^31 - 1";
    return false;
  }
  // Corner ids of primitive i: a triangle's, a segment's (a, b, b), a point's (a, a, a).
  auto corners = [&](int64_t i, int64_t c[3], int64_t& cell)
  {
    if (i < nt)
    {
      c[0] = mesh.Triangles[3 * i], c[1] = mesh.Triangles[3 * i + 1];
      c[2] = mesh.Triangles[3 * i + 2];
      cell = mesh.TriangleCells[i];
    }
    else if (i < nt + ns)
    {
      const int64_t s = i - nt;
      c[0] = mesh.Segments[2 * s], c[1] = c[2] = mesh.Segments[2 * s + 1];
      cell = mesh.SegmentCells[s];
    }
    else
    {
      c[0] = c[1] = c[2] = mesh.Vertices[i - nt - ns];
      cell = mesh.VertexCells[i - nt - ns];
    }
  };
  // Validate, and bound the used points.
  double lo[3] = { HUGE_VAL, HUGE_VAL, HUGE_VAL }, hi[3] = { -HUGE_VAL, -HUGE_VAL, -HUGE_VAL };
  for (int64_t i = 0; i < n; ++i)
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

  // Morton codes of the boxes' centres over the points' box, sorted by radix.
  const double extent = std::max({ hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], 1e-300 });
  std::vector<uint64_t> keys(n);
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
  {
    std::vector<uint64_t> sorted(n);
    for (int pass = 0; pass < 3; ++pass)
    {
      const int shift = 32 + 10 * pass;
      std::vector<int64_t> start(1025, 0);
      for (const uint64_t k : keys)
      {
        ++start[((k >> shift) & 1023) + 1];
      }
      for (int b = 0; b < 1024; ++b)
      {
        start[b + 1] += start[b];
      }
      for (const uint64_t k : keys)
      {
        sorted[start[(k >> shift) & 1023]++] = k;
      }
      keys.swap(sorted);
    }
  }
  this->Primitives.resize(n);
  this->Codes.resize(n);
  this->FaceNormals.assign(3 * n, 0.0);
  auto gather = [&](int64_t begin, int64_t end)
  {
    for (int64_t i = begin; i < end; ++i)
    {
      Primitive& p = this->Primitives[i];
      int64_t c[3];
      corners(static_cast<int64_t>(keys[i] & 0xffffffffu), c, p.Cell);
      for (int k = 0; k < 3; ++k)
      {
        std::copy(&mesh.Points[3 * c[k]], &mesh.Points[3 * c[k]] + 3, p.X + 3 * k);
      }
      const bool triangle = static_cast<int64_t>(keys[i] & 0xffffffffu) < nt;
      p.Face = triangle && FaceNormal(p.X, this->Degenerate, &this->FaceNormals[3 * i]);
      this->Codes[i] = static_cast<uint32_t>(keys[i] >> 32);
    }
  };
  parallelFor ? parallelFor(n, 8192, gather) : gather(0, n);
  // The faces' signed volume, in a fixed order (the same sum on any thread count).
  double volume = 0;
  for (int64_t i = 0; i < n; ++i)
  {
    const Primitive& p = this->Primitives[i];
    if (p.Face)
    {
      double a[3], b[3], c[3], bc[3];
      for (int k = 0; k < 3; ++k)
      {
        a[k] = p.X[k] - lo[k], b[k] = p.X[3 + k] - lo[k], c[k] = p.X[6 + k] - lo[k];
      }
      Cross(b, c, bc);
      volume += Dot(a, bc);
    }
  }
  this->Orientation = volume < 0 ? -1.0 : 1.0;
  this->Nodes.reserve(2 * (n / LeafSize + 1));
  this->Nodes.emplace_back();
  this->BuildNode(0, 0, static_cast<int32_t>(n));
  return true;
}

void QueryTree::BuildNode(int32_t slot, int32_t begin, int32_t end)
{
  if (end - begin <= LeafSize)
  {
    Node& leaf = this->Nodes[slot];
    for (int a = 0; a < 3; ++a)
    {
      leaf.Lo[a] = HUGE_VALF, leaf.Hi[a] = -HUGE_VALF;
    }
    for (int32_t i = begin; i < end; ++i)
    {
      for (int k = 0; k < 9; ++k)
      {
        leaf.Lo[k % 3] = std::min(leaf.Lo[k % 3], Below(this->Primitives[i].X[k]));
        leaf.Hi[k % 3] = std::max(leaf.Hi[k % 3], Above(this->Primitives[i].X[k]));
      }
    }
    leaf.First = begin;
    leaf.Count = end - begin;
    return;
  }
  // Split where the highest bit in which the range's codes differ turns on (the middle
  // when they are all equal).
  int32_t split = begin + (end - begin) / 2;
  const uint32_t first = this->Codes[begin], last = this->Codes[end - 1];
  if (first != last)
  {
    const uint32_t bit = 1u << (31 - __builtin_clz(first ^ last));
    split = static_cast<int32_t>(std::partition_point(this->Codes.begin() + begin,
                                   this->Codes.begin() + end,
                                   [bit](uint32_t c) { return (c & bit) == 0; }) -
      this->Codes.begin());
  }
  const int32_t left = static_cast<int32_t>(this->Nodes.size());
  this->Nodes.emplace_back();
  this->Nodes.emplace_back();
  this->BuildNode(left, begin, split);
  this->BuildNode(left + 1, split, end);
  Node& node = this->Nodes[slot];
  for (int a = 0; a < 3; ++a)
  {
    node.Lo[a] = std::min(this->Nodes[left].Lo[a], this->Nodes[left + 1].Lo[a]);
    node.Hi[a] = std::max(this->Nodes[left].Hi[a], this->Nodes[left + 1].Hi[a]);
  }
  node.First = left;
  node.Count = 0;
}

double QueryTree::BoxDistance2(const Node& node, const double p[3]) const
{
  double d2 = 0;
  for (int a = 0; a < 3; ++a)
  {
    const double gap = std::max(0.0, std::max(node.Lo[a] - p[a], p[a] - node.Hi[a]));
    d2 += gap * gap;
  }
  // Rounded down: a lower bound on the squared distance to anything in the box.
  return d2 * (1 - 8 * std::numeric_limits<double>::epsilon());
}

int64_t QueryTree::Nearest(const double p[3],
  double bound2,
  int64_t& index,
  double& best2,
  double closest[3],
  int& feature) const
{
  index = -1;
  best2 = bound2;
  int64_t evaluations = 0;
  if (this->Nodes.empty())
  {
    return 0;
  }
  // A box is skipped when even its nearest point is farther than the best so far by more
  // than rounding could explain, so that exact ties are always seen.
  auto reach = [this](double d2) { return d2 * (1 + 1e-9) + this->Tolerance2; };
  int32_t stack[128];
  int depth = 0;
  stack[depth++] = 0;
  while (depth > 0)
  {
    const Node& node = this->Nodes[stack[--depth]];
    if (node.Count > 0)
    {
      for (int32_t i = node.First; i < node.First + node.Count; ++i)
      {
        const Primitive& t = this->Primitives[i];
        double on[3];
        int where;
        const double d2 = t.Face
          ? SquaredDistanceToTriangle(p, t.X, t.X + 3, t.X + 6, on, &where)
          : SquaredDistanceToTriangleEdges(p, t.X, t.X + 3, t.X + 6, on, &where);
        ++evaluations;
        const bool better = index < 0
          ? d2 <= best2
          : (d2 < best2 ||
              (d2 == best2 &&
                (t.Cell < this->Primitives[index].Cell ||
                  (t.Cell == this->Primitives[index].Cell && i < index))));
        if (better)
        {
          index = i;
          best2 = d2;
          std::copy(on, on + 3, closest);
          feature = where;
        }
      }
      continue;
    }
    const double limit = reach(best2);
    const int32_t a = node.First, b = node.First + 1;
    const double da = this->BoxDistance2(this->Nodes[a], p);
    const double db = this->BoxDistance2(this->Nodes[b], p);
    // Nearest child on top of the stack (popped first).
    const int32_t nearChild = da <= db ? a : b, farChild = da <= db ? b : a;
    const double nearD = std::min(da, db), farD = std::max(da, db);
    if (farD <= limit && depth < 127)
    {
      stack[depth++] = farChild;
    }
    if (nearD <= limit && depth < 127)
    {
      stack[depth++] = nearChild;
    }
  }
  return evaluations;
}

void QueryTree::FeatureCellAndNormal(const double* a,
  const double* b,
  int64_t& cell,
  double normal[3]) const
{
  cell = std::numeric_limits<int64_t>::max();
  normal[0] = normal[1] = normal[2] = 0;
  int32_t stack[128];
  int depth = 0;
  stack[depth++] = 0;
  while (depth > 0)
  {
    const Node& node = this->Nodes[stack[--depth]];
    if (node.Lo[0] > a[0] || node.Hi[0] < a[0] || node.Lo[1] > a[1] || node.Hi[1] < a[1] ||
      node.Lo[2] > a[2] || node.Hi[2] < a[2])
    {
      continue;
    }
    if (node.Count == 0)
    {
      if (depth < 126)
      {
        stack[depth++] = node.First + 1;
        stack[depth++] = node.First;
      }
      continue;
    }
    for (int32_t i = node.First; i < node.First + node.Count; ++i)
    {
      const Primitive& t = this->Primitives[i];
      int atA = -1;
      bool hasB = !b;
      for (int k = 0; k < 3; ++k)
      {
        atA = atA < 0 && SamePoint(t.X + 3 * k, a) ? k : atA;
        hasB = hasB || SamePoint(t.X + 3 * k, b);
      }
      if (atA < 0 || !hasB)
      {
        continue;
      }
      cell = std::min(cell, t.Cell);
      if (!t.Face)
      {
        continue;
      }
      const double* n = &this->FaceNormals[3 * i];
      double weight = 1;
      if (!b)
      {
        // The face's angle at the vertex, as MeshSites computes it.
        const double* x = t.X + 3 * atA;
        const double* next = t.X + 3 * ((atA + 1) % 3);
        const double* prev = t.X + 3 * ((atA + 2) % 3);
        double u[3], w[3], uw[3];
        for (int k = 0; k < 3; ++k)
        {
          u[k] = next[k] - x[k], w[k] = prev[k] - x[k];
        }
        Cross(u, w, uw);
        weight = std::atan2(std::sqrt(Dot(uw, uw)), Dot(u, w));
      }
      for (int k = 0; k < 3; ++k)
      {
        normal[k] += n[k] * weight * this->Orientation;
      }
    }
  }
}
} // namespace

bool PreferSampleQueries(const MeshInput& mesh, const SampleGrid& wholeGrid)
{
  const double primitives = double(mesh.Triangles.size() / 3) + double(mesh.Segments.size() / 2) +
    double(mesh.Vertices.size());
  return primitives >= 3.0 * double(wholeGrid.Whole.Count());
}

bool QueryNearestTriangles(const MeshInput& mesh,
  const FieldRequest& request,
  const FieldArrays& arrays,
  const Execution& execution,
  ScanStatistics& stats,
  std::string& error)
{
  stats = ScanStatistics();
  QueryTree tree;
  if (!tree.Build(mesh, execution.For, error))
  {
    return false;
  }
  const IndexBox& ext = request.Extent;
  const SampleGrid& grid = request.Grid;
  const int64_t nx = ext.Size(0), ny = ext.Size(1), rows = ny * ext.Size(2);
  stats.Samples = ext.Count();
  const GridFrame& frame = arrays.Frame;
  const bool wantFeature = arrays.ClosestCellId || arrays.Signed;
  std::atomic<int64_t> evaluations{ 0 };
  // Rows are independent: each is walked in x, every sample seeded with the previous
  // sample's closest point (the distance to it bounds the next one's).
  auto queryRows = [&](int64_t rowBegin, int64_t rowEnd)
  {
    int64_t count = 0;
    for (int64_t row = rowBegin; row < rowEnd; ++row)
    {
      const double y = grid.Coordinate(1, ext.Lo[1] + static_cast<int>(row % ny));
      const double z = grid.Coordinate(2, ext.Lo[2] + static_cast<int>(row / ny));
      double previous[3] = { 0, 0, 0 };
      bool seeded = false;
      for (int64_t at = row * nx, i = ext.Lo[0]; at < (row + 1) * nx; ++at, ++i)
      {
        const double x[3] = { grid.Coordinate(0, static_cast<int>(i)), y, z };
        double bound2 = HUGE_VAL;
        if (seeded)
        {
          double r2 = 0;
          for (int a = 0; a < 3; ++a)
          {
            r2 += (x[a] - previous[a]) * (x[a] - previous[a]);
          }
          bound2 = r2 * (1 + 1e-9) + tree.Tolerance2;
        }
        int64_t index;
        double best2, closest[3];
        int feature = InFace;
        count += tree.Nearest(x, bound2, index, best2, closest, feature);
        if (index < 0)
        {
          // The seed fell short by rounding: search without it.
          count += tree.Nearest(x, HUGE_VAL, index, best2, closest, feature);
        }
        std::copy(closest, closest + 3, previous);
        seeded = true;
        const Primitive& t = tree.Get(index);
        // The feature: 0 vertex, 1 edge, 2 face (the site types).
        const uint8_t type = feature == InFace ? 2 : (feature >= OnEdgeAB ? 1 : 0);
        int64_t cell = t.Cell;
        double normal[3] = { 0, 0, 0 };
        if (wantFeature && type != 2)
        {
          const int first = feature >= OnEdgeAB ? feature - OnEdgeAB : feature;
          const double* a = t.X + 3 * first;
          const double* b = type == 1 ? t.X + 3 * ((first + 1) % 3) : nullptr;
          tree.FeatureCellAndNormal(a, b, cell, normal);
        }
        double d[3];
        for (int a = 0; a < 3; ++a)
        {
          d[a] = closest[a] - x[a];
        }
        if (arrays.Distance)
        {
          float value = static_cast<float>(std::sqrt(best2) * frame.Scale);
          if (arrays.Signed)
          {
            if (type == 2)
            {
              tree.FaceNormalOf(index, normal);
            }
            const double s = d[0] * normal[0] + d[1] * normal[1] + d[2] * normal[2];
            value = s > 0 ? -value : value;
          }
          arrays.Distance[at] = value;
        }
        if (arrays.ClosestCellId)
        {
          arrays.ClosestCellId[at] = cell;
        }
        if (arrays.ClosestFeature)
        {
          arrays.ClosestFeature[at] = type;
        }
        if (arrays.ClosestPoint)
        {
          for (int a = 0; a < 3; ++a)
          {
            arrays.ClosestPoint[3 * at + a] = static_cast<float>(frame.ToWorld(a, closest[a]));
          }
        }
      }
    }
    evaluations += count;
  };
  // Batches of rows report progress (and may abort) between them.
  const int64_t batches = std::min<int64_t>(rows, 64);
  for (int64_t batch = 0; batch < batches; ++batch)
  {
    const int64_t begin = rows * batch / batches, end = rows * (batch + 1) / batches;
    if (execution.For)
    {
      execution.For(end - begin, 1, [&](int64_t b, int64_t e) { queryRows(begin + b, begin + e); });
    }
    else
    {
      queryRows(begin, end);
    }
    if (!execution.Report(double(batch + 1) / batches))
    {
      stats.Aborted = true;
      break;
    }
  }
  stats.Evaluations = evaluations.load();
  return true;
}

} // namespace vtkdf
