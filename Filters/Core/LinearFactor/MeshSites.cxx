#include "LinearFactor/MeshSites.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <numeric>

namespace vtkdf
{
namespace
{

/// The largest float <= x and the smallest float >= x.
float FloatBelow(double x)
{
  const float f = static_cast<float>(x);
  return f > x ? std::nextafter(f, -HUGE_VALF) : f;
}
float FloatAbove(double x)
{
  const float f = static_cast<float>(x);
  return f < x ? std::nextafter(f, HUGE_VALF) : f;
}
using Vec = std::array<double, 3>;

Vec Sub(const double* a, const double* b)
{
  return { a[0] - b[0], a[1] - b[1], a[2] - b[2] };
}
double Dot(const Vec& a, const Vec& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
Vec Cross(const Vec& a, const Vec& b)
{
  return { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
}
double Norm(const Vec& a)
{
  return std::sqrt(Dot(a, a));
}
Vec Scale(const Vec& a, double s)
{
  return { a[0] * s, a[1] * s, a[2] * s };
}
Vec Add(const Vec& a, const Vec& b)
{
  return { a[0] + b[0], a[1] + b[1], a[2] + b[2] };
}

struct EdgeRecord
{
  int64_t A, B; // canonical point ids, A < B
  int64_t Face; // non-degenerate face index, or -1
  int64_t Cell; // input cell
};

/// An edge at a vertex: its index, and +1 where its tangent points away from the vertex,
/// -1 where it points towards it.
struct VertexEdge
{
  int64_t Edge;
  double Sign;
};
struct VertexEdgeSpan
{
  const VertexEdge* First = nullptr;
  size_t Count = 0;
  const VertexEdge* begin() const { return First; }
  const VertexEdge* end() const { return First + Count; }
  size_t size() const { return Count; }
  bool empty() const { return Count == 0; }
  const VertexEdge& operator[](size_t i) const { return First[i]; }
};

/// parallelFor when the caller gave one, else a plain loop.
void Run(const ParallelFor& parallelFor,
  int64_t n,
  int64_t grain,
  const std::function<void(int64_t, int64_t)>& body)
{
  if (n <= 0)
  {
    return;
  }
  if (parallelFor)
  {
    parallelFor(n, grain, body);
  }
  else
  {
    body(0, n);
  }
}

struct FaceRecord
{
  int64_t P[3];
  int64_t Cell;
  Vec Normal;
};

/// The bits of x (21 of them) moved to every third position: one axis of a Morton code.
uint64_t SpreadBits(uint64_t x)
{
  x &= 0x1fffff;
  x = (x | x << 32) & 0x1f00000000ffffull;
  x = (x | x << 16) & 0x1f0000ff0000ffull;
  x = (x | x << 8) & 0x100f00f00f00f00full;
  x = (x | x << 4) & 0x10c30c30c30c30c3ull;
  x = (x | x << 2) & 0x1249249249249249ull;
  return x;
}

/// Sorts each bucket [offsets[b], offsets[b + 1]) of `items` by `before`, in parallel.
template<typename Items, typename Before>
void SortBuckets(Items& items,
  const std::vector<int64_t>& offsets,
  const Before& before,
  const ParallelFor& parallelFor)
{
  Run(parallelFor,
    static_cast<int64_t>(offsets.size()) - 1,
    4096,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t b = begin; b < end; ++b)
      {
        std::sort(items.begin() + offsets[b], items.begin() + offsets[b + 1], before);
      }
    });
}

/// A point's position on the Morton curve, and its input id.
struct CurveKey
{
  uint64_t Code;
  int64_t Id;
};

/// Sorts `items` by `before` (a strict total order: the result does not depend on the
/// schedule): runs sorted in parallel, then merged pairwise, level by level.
template<typename T, typename Before>
void ParallelSort(std::vector<T>& items, const Before& before, const ParallelFor& parallelFor)
{
  const int64_t n = static_cast<int64_t>(items.size());
  int64_t runs = 1;
  while (parallelFor && runs < 16 && n / (2 * runs) >= 16384)
  {
    runs *= 2;
  }
  auto bound = [&](int64_t run) { return n * run / runs; };
  Run(parallelFor,
    runs,
    1,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t r = begin; r < end; ++r)
      {
        std::sort(items.begin() + bound(r), items.begin() + bound(r + 1), before);
      }
    });
  std::vector<T> merged(runs > 1 ? n : 0);
  for (int64_t width = 1; width < runs; width *= 2)
  {
    Run(parallelFor,
      runs / (2 * width),
      1,
      [&](int64_t begin, int64_t end)
      {
        for (int64_t pair = begin; pair < end; ++pair)
        {
          const int64_t lo = bound(2 * pair * width), mid = bound((2 * pair + 1) * width);
          const int64_t hi = bound((2 * pair + 2) * width);
          std::merge(items.begin() + lo,
            items.begin() + mid,
            items.begin() + mid,
            items.begin() + hi,
            merged.begin() + lo,
            before);
        }
      });
    items.swap(merged);
  }
}
} // namespace

bool MeshSites::Build(const MeshInput& in,
  Culling culling,
  double slack,
  std::string& error,
  const ParallelFor& parallelFor)
{
  this->Sites.clear();
  this->Planes.clear();
  this->SitePoints.clear();
  this->Statistics = DomainStatistics();
  const int64_t numPoints = static_cast<int64_t>(in.Points.size() / 3);
  const double* P = in.Points.data();

  // --- Points that cells use, merged when their coordinates are identical, so that
  // polygon soups and duplicated points still get their topology (and tight domains).
  std::vector<char> used(numPoints, 0);
  auto markUsed = [&](const std::vector<int64_t>& ids) -> bool
  {
    for (int64_t id : ids)
    {
      if (id < 0 || id >= numPoints)
      {
        error = "a cell refers to point " + std::to_string(id) + " of " + std::to_string(numPoints);
        return false;
      }
      used[id] = 1;
    }
    return true;
  };
  if (!markUsed(in.Triangles) || !markUsed(in.Segments) || !markUsed(in.Vertices))
  {
    return false;
  }
  std::vector<int64_t> order;
  for (int64_t i = 0; i < numPoints; ++i)
  {
    if (used[i])
    {
      for (int a = 0; a < 3; ++a)
      {
        if (!std::isfinite(P[3 * i + a]))
        {
          error = "point " + std::to_string(i) + " has a NaN or infinite coordinate";
          return false;
        }
      }
      order.push_back(i);
    }
  }
  if (order.empty())
  {
    return true;
  }
  // Sort the points along a Morton curve (identical points stay adjacent, so they
  // merge below): sites, planes and every later pass then walk memory in space order,
  // which matters for large polygon soups whose input order is arbitrary.
  {
    double lo[3], hi[3];
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = hi[a] = P[3 * order[0] + a];
    }
    for (int64_t id : order)
    {
      for (int a = 0; a < 3; ++a)
      {
        lo[a] = std::min(lo[a], P[3 * id + a]);
        hi[a] = std::max(hi[a], P[3 * id + a]);
      }
    }
    const double side = std::max(hi[0] - lo[0], std::max(hi[1] - lo[1], hi[2] - lo[2]));
    // 21 bits per axis. Points a denormal distance apart (side below 2^-1003) would
    // overflow the scale: they take the division instead.
    const double scale = side > 0 ? 2097151.0 / side : 0.0;
    const bool finiteScale = std::isfinite(scale);
    std::vector<CurveKey> keys(order.size());
    Run(parallelFor,
      static_cast<int64_t>(order.size()),
      4096,
      [&](int64_t begin, int64_t end)
      {
        for (int64_t i = begin; i < end; ++i)
        {
          const double* x = P + 3 * order[i];
          uint64_t code = 0;
          for (int a = 0; a < 3; ++a)
          {
            const double cell =
              finiteScale ? (x[a] - lo[a]) * scale : (x[a] - lo[a]) / side * 2097151.0;
            code |= SpreadBits(static_cast<uint64_t>(std::min(cell, 2097151.0))) << a;
          }
          keys[i] = { code, order[i] };
        }
      });
    // The curve, then the coordinates (identical points end up adjacent), then the id.
    ParallelSort(
      keys,
      [P](const CurveKey& x, const CurveKey& y)
      {
        if (x.Code != y.Code)
        {
          return x.Code < y.Code;
        }
        const double *px = P + 3 * x.Id, *py = P + 3 * y.Id;
        return std::lexicographical_compare(px, px + 3, py, py + 3) ||
          (std::equal(px, px + 3, py) && x.Id < y.Id);
      },
      parallelFor);
    for (size_t i = 0; i < keys.size(); ++i)
    {
      order[i] = keys[i].Id;
    }
  }
  std::vector<int64_t> canonical(numPoints, -1);
  std::vector<int64_t> merged; // canonical index -> input point id
  for (size_t k = 0; k < order.size(); ++k)
  {
    const int64_t id = order[k];
    if (k > 0 && std::equal(P + 3 * id, P + 3 * id + 3, P + 3 * order[k - 1]))
    {
      canonical[id] = canonical[order[k - 1]];
      ++this->Statistics.MergedPoints;
    }
    else
    {
      canonical[id] = static_cast<int64_t>(merged.size());
      merged.push_back(id);
    }
  }
  const int64_t nv = static_cast<int64_t>(merged.size());
  // The merged points, contiguous in curve order: every later pass reads them there.
  this->SitePoints.resize(3 * nv);
  for (int64_t c = 0; c < nv; ++c)
  {
    std::copy(P + 3 * merged[c], P + 3 * merged[c] + 3, &this->SitePoints[3 * c]);
  }
  const double* points = this->SitePoints.data();
  auto X = [points](int64_t c) { return points + 3 * c; };
  for (int a = 0; a < 3; ++a)
  {
    this->Bounds[2 * a] = X(0)[a];
    this->Bounds[2 * a + 1] = X(0)[a];
  }
  for (int64_t c = 0; c < nv; ++c)
  {
    for (int a = 0; a < 3; ++a)
    {
      this->Bounds[2 * a] = std::min(this->Bounds[2 * a], X(c)[a]);
      this->Bounds[2 * a + 1] = std::max(this->Bounds[2 * a + 1], X(c)[a]);
    }
  }
  const double diagonal = std::hypot(this->Bounds[1] - this->Bounds[0],
    std::hypot(this->Bounds[3] - this->Bounds[2], this->Bounds[5] - this->Bounds[4]));
  // Features below this size carry no direction we can trust; their neighbours cover them.
  const double degenerate = 1e-10 * (diagonal > 0 ? diagonal : 1.0);

  // --- Faces (non-degenerate triangles) and every edge occurrence.
  const int64_t numTriangles = static_cast<int64_t>(in.Triangles.size() / 3);
  // Triangles in the order of their first corner on the curve (a counting sort).
  std::vector<int64_t> triangleOrder(numTriangles);
  {
    std::vector<int64_t> start(nv + 1, 0);
    auto key = [&](int64_t t)
    {
      return std::min(canonical[in.Triangles[3 * t]],
        std::min(canonical[in.Triangles[3 * t + 1]], canonical[in.Triangles[3 * t + 2]]));
    };
    for (int64_t t = 0; t < numTriangles; ++t)
    {
      ++start[key(t) + 1];
    }
    for (int64_t v = 0; v < nv; ++v)
    {
      start[v + 1] += start[v];
    }
    for (int64_t t = 0; t < numTriangles; ++t)
    {
      triangleOrder[start[key(t)]++] = t;
    }
  }
  // The triangle at position i of that order: its merged corners, and whether it is a
  // face (then with its unit normal).
  auto corners = [&](int64_t i, int64_t c[3])
  {
    const int64_t* ids = &in.Triangles[3 * triangleOrder[i]];
    c[0] = canonical[ids[0]], c[1] = canonical[ids[1]], c[2] = canonical[ids[2]];
  };
  auto faceNormal = [&](const int64_t c[3], Vec& normal)
  {
    if (c[0] == c[1] || c[1] == c[2] || c[2] == c[0])
    {
      return false;
    }
    const Vec e1 = Sub(X(c[1]), X(c[0])), e2 = Sub(X(c[2]), X(c[0]));
    const Vec e3 = Sub(X(c[2]), X(c[1]));
    const Vec n = Cross(e1, e2);
    const double area2 = Norm(n);
    const double longest = std::max(Norm(e1), std::max(Norm(e2), Norm(e3)));
    if (!(area2 > degenerate * longest))
    {
      return false;
    }
    normal = Scale(n, 1.0 / area2);
    return true;
  };
  // Two passes over fixed chunks of that order, so that faces are numbered as a serial
  // loop would number them whatever the schedule: count faces and edge records, then
  // write them. Edge records go straight into buckets by their smaller point (a
  // counting sort); sorting each small bucket by (B, Face) then orders them all by
  // (A, B, Face), whatever order the threads filled it in.
  constexpr int64_t Chunk = 4096;
  const int64_t numChunks = (numTriangles + Chunk - 1) / Chunk;
  std::vector<int64_t> chunkFaces(numChunks + 1, 0);
  std::vector<std::atomic<int64_t>> edgeCount(nv + 1); // value-initialized: zeros
  std::vector<uint8_t> isFace(numTriangles);
  Run(parallelFor,
    numChunks,
    1,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t chunk = begin; chunk < end; ++chunk)
      {
        int64_t count = 0;
        for (int64_t i = chunk * Chunk; i < std::min(numTriangles, (chunk + 1) * Chunk); ++i)
        {
          int64_t c[3];
          corners(i, c);
          Vec normal;
          isFace[i] = faceNormal(c, normal);
          count += isFace[i];
          for (int k = 0; k < 3; ++k)
          {
            const int64_t a = c[k], b = c[(k + 1) % 3];
            if (a != b)
            {
              edgeCount[std::min(a, b) + 1].fetch_add(1, std::memory_order_relaxed);
            }
          }
        }
        chunkFaces[chunk + 1] = count;
      }
    });
  const int64_t numSegments = static_cast<int64_t>(in.Segments.size() / 2);
  for (int64_t s = 0; s < numSegments; ++s)
  {
    const int64_t a = canonical[in.Segments[2 * s]], b = canonical[in.Segments[2 * s + 1]];
    edgeCount[std::min(a, b) + 1] += a != b;
  }
  std::vector<int64_t> edgeStart(nv + 1, 0);
  for (int64_t v = 0; v < nv; ++v)
  {
    edgeStart[v + 1] = edgeStart[v] + edgeCount[v + 1].load(std::memory_order_relaxed);
  }
  for (int64_t chunk = 0; chunk < numChunks; ++chunk)
  {
    chunkFaces[chunk + 1] += chunkFaces[chunk];
  }
  LargeVector<FaceRecord> faces(chunkFaces[numChunks]);
  this->Statistics.DegenerateFaces = numTriangles - chunkFaces[numChunks];
  LargeVector<EdgeRecord> edges(edgeStart[nv]);
  std::vector<std::atomic<int64_t>>& edgeFill = edgeCount; // reused: the next free record
  for (int64_t v = 0; v < nv; ++v)
  {
    edgeFill[v].store(edgeStart[v], std::memory_order_relaxed);
  }
  // The smallest input cell using each point (ClosestCellId of its vertex site).
  std::vector<std::atomic<int64_t>> vertexCell(nv);
  for (auto& cell : vertexCell)
  {
    cell.store(INT64_MAX, std::memory_order_relaxed);
  }
  auto useVertex = [&](int64_t v, int64_t cell)
  {
    int64_t old = vertexCell[v].load(std::memory_order_relaxed);
    while (cell < old && !vertexCell[v].compare_exchange_weak(old, cell, std::memory_order_relaxed))
    {
    }
  };
  auto addEdge = [&](int64_t a, int64_t b, int64_t face, int64_t cell)
  {
    if (a != b)
    {
      const int64_t at = edgeFill[std::min(a, b)].fetch_add(1, std::memory_order_relaxed);
      edges[at] = { std::min(a, b), std::max(a, b), face, cell };
    }
  };
  Run(parallelFor,
    numChunks,
    1,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t chunk = begin; chunk < end; ++chunk)
      {
        int64_t face = chunkFaces[chunk];
        for (int64_t i = chunk * Chunk; i < std::min(numTriangles, (chunk + 1) * Chunk); ++i)
        {
          const int64_t cell = in.TriangleCells[triangleOrder[i]];
          int64_t c[3];
          corners(i, c);
          for (int k = 0; k < 3; ++k)
          {
            useVertex(c[k], cell);
          }
          int64_t id = -1;
          if (isFace[i])
          {
            id = face++;
            FaceRecord& f = faces[id];
            faceNormal(c, f.Normal);
            std::copy(c, c + 3, f.P);
            f.Cell = cell;
          }
          for (int k = 0; k < 3; ++k)
          {
            addEdge(c[k], c[(k + 1) % 3], id, cell);
          }
        }
      }
    });
  for (int64_t s = 0; s < numSegments; ++s)
  {
    const int64_t a = canonical[in.Segments[2 * s]], b = canonical[in.Segments[2 * s + 1]];
    const int64_t cell = in.SegmentCells[s];
    useVertex(a, cell);
    useVertex(b, cell);
    addEdge(a, b, -1, cell);
  }
  for (size_t v = 0; v < in.Vertices.size(); ++v)
  {
    useVertex(canonical[in.Vertices[v]], in.VertexCells[v]);
  }
  SortBuckets(
    edges,
    edgeStart,
    [](const EdgeRecord& x, const EdgeRecord& y)
    { return x.B != y.B ? x.B < y.B : x.Face < y.Face; },
    parallelFor);

  // Orientation: make the sign's pseudonormals point outward for closed meshes.
  double volume = 0;
  for (const FaceRecord& f : faces)
  {
    const Vec a = Sub(X(f.P[0]), X(0)), b = Sub(X(f.P[1]), X(0)), c = Sub(X(f.P[2]), X(0));
    volume += Dot(a, Cross(b, c));
  }
  const double orientation = volume < 0 ? -1.0 : 1.0;

  // Vertex pseudonormals (angle weighted).
  const int64_t numFaces = static_cast<int64_t>(faces.size());
  // The corner angles in parallel, then summed in face order (the same sums either way).
  std::vector<double> cornerAngle(3 * numFaces);
  Run(parallelFor,
    numFaces,
    4096,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t fi = begin; fi < end; ++fi)
      {
        const FaceRecord& f = faces[fi];
        for (int k = 0; k < 3; ++k)
        {
          const Vec u = Sub(X(f.P[(k + 1) % 3]), X(f.P[k]));
          const Vec w = Sub(X(f.P[(k + 2) % 3]), X(f.P[k]));
          cornerAngle[3 * fi + k] = std::atan2(Norm(Cross(u, w)), Dot(u, w));
        }
      }
    });
  std::vector<Vec> vertexNormal(nv, Vec{ 0, 0, 0 });
  for (int64_t fi = 0; fi < numFaces; ++fi)
  {
    const FaceRecord& f = faces[fi];
    for (int k = 0; k < 3; ++k)
    {
      vertexNormal[f.P[k]] =
        Add(vertexNormal[f.P[k]], Scale(f.Normal, cornerAngle[3 * fi + k] * orientation));
    }
  }

  // --- Edges: one per group of equal records, unless degenerate. A group lies in one
  // bucket (the records of one smaller point), so the buckets are counted, then written,
  // in parallel; edges are numbered in bucket order, as a serial loop would.
  struct EdgeGroup
  {
    int64_t First, Last; // records [First, Last)
    int64_t Cell;        // smallest input cell
    int Faces;           // incident non-degenerate faces
    Vec Tangent;         // unit, from edgeEnds[0] to edgeEnds[1]
  };
  // Calls visit(first, last, b) for every group of bucket a (records [first, last), edge
  // from a to b) that is not degenerate; returns how many were.
  auto forEachGroup = [&](int64_t a, const auto& visit) -> int64_t
  {
    int64_t degenerateGroups = 0;
    for (int64_t e0 = edgeStart[a]; e0 < edgeStart[a + 1];)
    {
      int64_t e1 = e0 + 1;
      while (e1 < edgeStart[a + 1] && edges[e1].B == edges[e0].B)
      {
        ++e1;
      }
      if (Norm(Sub(X(edges[e0].B), X(a))) <= degenerate)
      {
        ++degenerateGroups;
      }
      else
      {
        visit(e0, e1, edges[e0].B);
      }
      e0 = e1;
    }
    return degenerateGroups;
  };
  std::vector<int64_t> groupStart(nv + 1, 0);
  std::atomic<int64_t> degenerateEdges{ 0 };
  Run(parallelFor,
    nv,
    4096,
    [&](int64_t begin, int64_t end)
    {
      int64_t local = 0;
      for (int64_t a = begin; a < end; ++a)
      {
        int64_t count = 0;
        local += forEachGroup(a, [&](int64_t, int64_t, int64_t) { ++count; });
        groupStart[a + 1] = count;
      }
      degenerateEdges += local;
    });
  this->Statistics.DegenerateEdges = degenerateEdges.load();
  for (int64_t v = 0; v < nv; ++v)
  {
    groupStart[v + 1] += groupStart[v];
  }
  const int64_t numEdges = groupStart[nv];
  LargeVector<EdgeGroup> edgeGroups(numEdges);
  LargeVector<std::array<int64_t, 2>> edgeEnds(numEdges);
  std::vector<std::atomic<int64_t>> vertexEdgeCount(nv + 1); // value-initialized: zeros
  Run(parallelFor,
    nv,
    4096,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t a = begin; a < end; ++a)
      {
        int64_t e = groupStart[a];
        forEachGroup(a,
          [&](int64_t first, int64_t last, int64_t b)
          {
            EdgeGroup& group = edgeGroups[e];
            group.First = first;
            group.Last = last;
            group.Cell = INT64_MAX;
            group.Faces = 0;
            for (int64_t r = first; r < last; ++r)
            {
              group.Cell = std::min(group.Cell, edges[r].Cell);
              group.Faces += edges[r].Face >= 0;
            }
            const Vec t = Sub(X(b), X(a));
            group.Tangent = Scale(t, 1.0 / Norm(t));
            edgeEnds[e] = { a, b };
            vertexEdgeCount[a + 1].fetch_add(1, std::memory_order_relaxed);
            vertexEdgeCount[b + 1].fetch_add(1, std::memory_order_relaxed);
            ++e;
          });
      }
    });
  // The faces of an edge (records with a face come last in a group: sorted by Face).
  auto edgeFace = [&](int64_t e, int which) -> int64_t
  { return edges[edgeGroups[e].Last - edgeGroups[e].Faces + which].Face; };

  // The edges of every vertex, contiguous per vertex, in edge order: (edge, direction
  // away from it). Filled in parallel, then each vertex's few sorted.
  std::vector<int64_t> vertexEdgeOffsets(nv + 1, 0);
  for (int64_t v = 0; v < nv; ++v)
  {
    vertexEdgeOffsets[v + 1] =
      vertexEdgeOffsets[v] + vertexEdgeCount[v + 1].load(std::memory_order_relaxed);
  }
  std::vector<std::atomic<int64_t>>& vertexEdgeFill = vertexEdgeCount; // the next free entry
  for (int64_t v = 0; v < nv; ++v)
  {
    vertexEdgeFill[v].store(vertexEdgeOffsets[v], std::memory_order_relaxed);
  }
  LargeVector<VertexEdge> vertexEdges(vertexEdgeOffsets[nv]);
  Run(parallelFor,
    numEdges,
    4096,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t e = begin; e < end; ++e)
      {
        for (int side = 0; side < 2; ++side)
        {
          const int64_t at =
            vertexEdgeFill[edgeEnds[e][side]].fetch_add(1, std::memory_order_relaxed);
          vertexEdges[at] = { e, side == 0 ? 1.0 : -1.0 };
        }
      }
    });
  SortBuckets(
    vertexEdges,
    vertexEdgeOffsets,
    [](const VertexEdge& x, const VertexEdge& y) { return x.Edge < y.Edge; },
    parallelFor);

  // The unit direction of an edge away from the vertex it is seen from.
  auto away = [&](const VertexEdge& eu) { return Scale(edgeGroups[eu.Edge].Tangent, eu.Sign); };
  auto incidentEdges = [&](int64_t v)
  {
    return VertexEdgeSpan{ vertexEdges.data() + vertexEdgeOffsets[v],
      static_cast<size_t>(vertexEdgeOffsets[v + 1] - vertexEdgeOffsets[v]) };
  };
  std::vector<std::vector<int64_t>> vertexFaces(culling == Culling::Manifold ? nv : 0);
  if (culling == Culling::Manifold)
  {
    for (size_t f = 0; f < faces.size(); ++f)
    {
      for (int k = 0; k < 3; ++k)
      {
        vertexFaces[faces[f].P[k]].push_back(static_cast<int64_t>(f));
      }
    }
  }

  // --- What bounds each vertex's domain (Manifold needs the neighbourhood's shape).
  enum VertexDomain : uint8_t
  {
    Unbounded,
    Polar,  // (x - p) . u <= 0 for every edge direction u: otherwise the edge is closer
    Pyramid // Theorem 1's square pyramid (hyperbolic vertex)
  };
  std::vector<uint8_t> vertexDomain(nv, Unbounded);
  std::vector<std::array<Vec, 4>> pyramidSides(culling == Culling::Manifold ? nv : 0);
  auto classify = [&](int64_t v) -> uint8_t
  {
    const VertexEdgeSpan incident = incidentEdges(v);
    if (culling != Culling::Manifold)
    {
      return culling == Culling::Auto && !incident.empty() ? Polar : Unbounded;
    }
    // Manifold culling: only where the faces around v form one closed fan.
    const auto& fan = vertexFaces[v];
    bool closed = !incident.empty() && fan.size() == incident.size();
    for (const auto& eu : incident)
    {
      closed = closed && edgeGroups[eu.Edge].Faces == 2;
    }
    if (closed)
    {
      // Walk the fan once around: it must visit every face (a single cycle).
      size_t steps = 0;
      int64_t edge = incident[0].Edge, face = edgeFace(edge, 0);
      const int64_t startFace = face;
      do
      {
        ++steps;
        int64_t next = -1;
        for (const auto& eu : incident)
        {
          if (eu.Edge != edge && (edgeFace(eu.Edge, 0) == face || edgeFace(eu.Edge, 1) == face))
          {
            next = eu.Edge;
          }
        }
        if (next < 0)
        {
          closed = false;
          break;
        }
        edge = next;
        face = edgeFace(edge, 0) == face ? edgeFace(edge, 1) : edgeFace(edge, 0);
      } while (face != startFace && steps <= fan.size());
      closed = closed && steps == fan.size();
    }
    if (!closed)
    {
      return Unbounded;
    }
    // Convex or concave vertex (every incident edge bends the same way): the polytope
    // spanned by the face normals, i.e. the planes orthogonal to the edges.
    int convex = 0, concave = 0;
    for (const auto& eu : incident)
    {
      const FaceRecord& f0 = faces[edgeFace(eu.Edge, 0)];
      const FaceRecord& f1 = faces[edgeFace(eu.Edge, 1)];
      const int64_t a = edgeEnds[eu.Edge][0], b = edgeEnds[eu.Edge][1];
      int64_t c1 = f1.P[0];
      for (int k = 0; k < 3; ++k)
      {
        if (f1.P[k] != a && f1.P[k] != b)
        {
          c1 = f1.P[k];
        }
      }
      const double bend = Dot(Scale(f0.Normal, orientation), Sub(X(c1), X(a)));
      convex += bend <= 0;
      concave += bend >= 0;
    }
    if (convex == static_cast<int>(incident.size()) || concave == static_cast<int>(incident.size()))
    {
      return Polar;
    }
    // Hyperbolic vertex (Theorem 1): cone about the mean normal n_a whose half-angle is
    // the largest angle between n_a and a face normal, circumscribed by a square pyramid.
    Vec na{ 0, 0, 0 };
    for (int64_t f : fan)
    {
      na = Add(na, faces[f].Normal);
    }
    const double nal = Norm(na);
    double cosTheta = 1;
    if (nal > 0)
    {
      na = Scale(na, 1.0 / nal);
      for (int64_t f : fan)
      {
        cosTheta = std::min(cosTheta, Dot(na, faces[f].Normal));
      }
    }
    if (!(nal > 0 && cosTheta > 1e-6)) // theta >= pi/2: no pyramid
    {
      return Unbounded;
    }
    const double sinTheta = std::sqrt(std::max(0.0, 1 - cosTheta * cosTheta));
    Vec b1 = std::fabs(na[0]) < 0.9 ? Vec{ 1, 0, 0 } : Vec{ 0, 1, 0 };
    b1 = Sub(b1.data(), Scale(na, Dot(b1, na)).data());
    b1 = Scale(b1, 1.0 / Norm(b1));
    const Vec b2 = Cross(na, b1);
    // The cone's tangent planes along +-b1, +-b2: a square pyramid containing the cone.
    std::array<Vec, 4>& sides = pyramidSides[v];
    const Vec directions[4] = { b1, Scale(b1, -1), b2, Scale(b2, -1) };
    for (int i = 0; i < 4; ++i)
    {
      sides[i] = Sub(Scale(na, sinTheta).data(), Scale(directions[i], cosTheta).data());
    }
    // Theorem 1 is stated for saddles; check that the exact domain (the cone of
    // directions y with y.u <= 0 for every edge u) really lies in the pyramid.
    bool pyramid = true;
    double rank = 0;
    for (size_t i = 0; i < incident.size(); ++i)
    {
      for (size_t j = i + 1; j < incident.size(); ++j)
      {
        const Vec r = Cross(away(incident[i]), away(incident[j]));
        for (const auto& eu : incident)
        {
          rank = std::max(rank, std::fabs(Dot(r, away(eu))));
        }
        for (double sign : { 1.0, -1.0 })
        {
          const Vec ray = Scale(r, sign);
          bool inDomain = Norm(ray) > 1e-12;
          for (const auto& eu : incident)
          {
            inDomain = inDomain && Dot(ray, away(eu)) <= 1e-12;
          }
          for (const Vec& w : sides)
          {
            pyramid = pyramid && (!inDomain || Dot(ray, w) >= -1e-12);
          }
        }
      }
    }
    return pyramid && rank > 1e-9 ? Pyramid : Unbounded;
  };
  Run(parallelFor,
    nv,
    1024,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t v = begin; v < end; ++v)
      {
        vertexDomain[v] = classify(v);
      }
    });

  // --- Plane counts, then every site and its planes written in place, in parallel.
  auto edgePlanes = [&](int64_t e)
  {
    const bool wedge =
      culling == Culling::Auto || (culling == Culling::Manifold && edgeGroups[e].Faces == 2);
    return 2 + (wedge ? edgeGroups[e].Faces : 0);
  };
  auto vertexPlanes = [&](int64_t v) -> int
  {
    return vertexDomain[v] == Polar
      ? static_cast<int>(vertexEdgeOffsets[v + 1] - vertexEdgeOffsets[v])
      : (vertexDomain[v] == Pyramid ? 4 : 0);
  };
  const int64_t numSites = numFaces + numEdges + nv;
  std::vector<uint32_t> planeBegin(numSites + 1, 0);
  for (int64_t i = 0; i < numSites; ++i)
  {
    const int64_t count = i < numFaces ? 3
      : i < numFaces + numEdges        ? edgePlanes(i - numFaces)
                                       : vertexPlanes(i - numFaces - numEdges);
    const uint64_t next = uint64_t(planeBegin[i]) + count;
    if (next > UINT32_MAX)
    {
      error = "the mesh needs more than 2^32 domain planes";
      return false;
    }
    planeBegin[i + 1] = static_cast<uint32_t>(next);
  }
  this->Sites.resize(numSites);
  this->Planes.resize(planeBegin[numSites]);
  // The plane through `through` with normal n, relative to the site's anchor. The offset
  // is computed from the rounded normal, so the stored plane still passes through it.
  auto setPlane = [&](uint32_t at, const Vec& n, const double* through, const double* anchor)
  {
    HalfSpace& h = this->Planes[at];
    for (int a = 0; a < 3; ++a)
    {
      h.N[a] = static_cast<float>(n[a]);
    }
    h.D =
      static_cast<float>(-(h.N[0] * (through[0] - anchor[0]) + h.N[1] * (through[1] - anchor[1]) +
                           h.N[2] * (through[2] - anchor[2])) +
        slack);
  };
  auto initSite = [&](int64_t index, uint8_t type, int64_t cell, const double* anchor) -> Site&
  {
    Site& s = this->Sites[index];
    s = Site{};
    s.Type = type;
    s.CellId = cell;
    s.PlaneBegin = planeBegin[index];
    s.PlaneCount = static_cast<uint16_t>(planeBegin[index + 1] - planeBegin[index]);
    for (int a = 0; a < 3; ++a)
    {
      s.Anchor[a] = anchor[a];
      s.BoundsMin[a] = FloatBelow(anchor[a]);
      s.BoundsMax[a] = FloatAbove(anchor[a]);
    }
    return s;
  };
  auto grow = [](Site& s, const double* x)
  {
    for (int a = 0; a < 3; ++a)
    {
      s.BoundsMin[a] = std::min(s.BoundsMin[a], FloatBelow(x[a]));
      s.BoundsMax[a] = std::max(s.BoundsMax[a], FloatAbove(x[a]));
    }
  };

  // Face sites: the triangle prism (three planes through the edges, orthogonal to the
  // triangle), required for the plane-distance formula to be exact.
  Run(parallelFor,
    numFaces,
    1024,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t fi = begin; fi < end; ++fi)
      {
        const FaceRecord& f = faces[fi];
        Site& s = initSite(fi, FaceSite, f.Cell, X(f.P[0]));
        for (int k = 0; k < 3; ++k)
        {
          const double* a = X(f.P[k]);
          const Vec e = Sub(X(f.P[(k + 1) % 3]), a);
          Vec m = Cross(f.Normal, e);
          m = Scale(m, 1.0 / Norm(m));
          if (Dot(m, Sub(X(f.P[(k + 2) % 3]), a)) < 0)
          {
            m = Scale(m, -1.0);
          }
          setPlane(s.PlaneBegin + k, m, a, s.Anchor);
          grow(s, X(f.P[k]));
        }
        for (int a = 0; a < 3; ++a)
        {
          s.Axis[a] = f.Normal[a];
          s.Normal[a] = static_cast<float>(f.Normal[a] * orientation);
        }
        s.Required = 3;
      }
    });

  // Edge sites: the slab between the end planes (required), then one plane per incident
  // face: a point on the face side of that plane is closer to the face.
  Run(parallelFor,
    numEdges,
    1024,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t e = begin; e < end; ++e)
      {
        const int64_t a = edgeEnds[e][0], b = edgeEnds[e][1];
        const Vec& t = edgeGroups[e].Tangent;
        Site& s = initSite(numFaces + e, EdgeSite, edgeGroups[e].Cell, X(a));
        grow(s, X(b));
        uint32_t at = s.PlaneBegin;
        setPlane(at++, t, X(a), s.Anchor);
        setPlane(at++, Scale(t, -1.0), X(b), s.Anchor);
        s.Required = 2;
        const bool wedge = s.PlaneCount > 2;
        Vec pseudo{ 0, 0, 0 };
        for (int i = 0; i < edgeGroups[e].Faces; ++i)
        {
          const FaceRecord& f = faces[edgeFace(e, i)];
          pseudo = Add(pseudo, Scale(f.Normal, orientation));
          if (wedge)
          {
            int64_t c = f.P[0];
            for (int k = 0; k < 3; ++k)
            {
              if (f.P[k] != a && f.P[k] != b)
              {
                c = f.P[k];
              }
            }
            const Vec ac = Sub(X(c), X(a));
            Vec m = Sub(ac.data(), Scale(t, Dot(ac, t)).data());
            m = Scale(m, -1.0 / Norm(m));
            setPlane(at++, m, X(a), s.Anchor);
          }
        }
        for (int k = 0; k < 3; ++k)
        {
          s.Axis[k] = t[k];
          s.Normal[k] = static_cast<float>(pseudo[k]);
        }
      }
    });

  // Vertex sites.
  Run(parallelFor,
    nv,
    1024,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t v = begin; v < end; ++v)
      {
        Site& s = initSite(
          numFaces + numEdges + v, VertexSite, vertexCell[v].load(std::memory_order_relaxed), X(v));
        s.Required = 0;
        for (int a = 0; a < 3; ++a)
        {
          s.Normal[a] = static_cast<float>(vertexNormal[v][a]);
        }
        uint32_t at = s.PlaneBegin;
        if (vertexDomain[v] == Polar)
        {
          for (const auto& eu : incidentEdges(v))
          {
            setPlane(at++, Scale(away(eu), -1.0), X(v), s.Anchor);
          }
        }
        else if (vertexDomain[v] == Pyramid)
        {
          for (const Vec& w : pyramidSides[v])
          {
            setPlane(at++, w, X(v), s.Anchor);
          }
        }
      }
    });

  // Statistics.
  this->Statistics.Faces = numFaces;
  this->Statistics.Edges = numEdges;
  this->Statistics.Vertices = nv;
  for (int64_t e = 0; e < numEdges; ++e)
  {
    this->Statistics.EdgeWedges += edgePlanes(e) > 2;
  }
  for (int64_t v = 0; v < nv; ++v)
  {
    this->Statistics.PolarVertices += vertexDomain[v] == Polar;
    this->Statistics.PyramidVertices += vertexDomain[v] == Pyramid;
    this->Statistics.UnboundedVertices += vertexDomain[v] == Unbounded;
  }
  return true;
}

} // namespace vtkdf
