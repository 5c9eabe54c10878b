#include "LinearFactor/MeshSites.h"

#include "Common/FloatBounds.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <numeric>

namespace vtkdf
{
namespace
{

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

/// An edge of the mesh: a group of equal edge records.
struct EdgeGroup
{
  int64_t First, Last; // records [First, Last)
  int64_t Cell;        // smallest input cell
  int Faces;           // incident non-degenerate faces
  Vec Tangent;         // unit, from its first end to its second
};

/// What bounds a vertex's domain (Manifold needs the neighbourhood's shape).
enum VertexDomain : uint8_t
{
  Unbounded,
  Polar,  // (x - p) . u <= 0 for every edge direction u: otherwise the edge is closer
  Pyramid // Theorem 1's square pyramid (hyperbolic vertex)
};

/// MeshSites::Build's passes, in the order Build runs them, over what they share. Each
/// pass that runs in parallel numbers what it makes as a serial loop would, so the sites
/// and planes are the same whatever the schedule.
class SiteBuilder
{
public:
  SiteBuilder(const MeshInput& input,
    Culling culling,
    double slack,
    const ParallelFor& parallelFor,
    MeshSites& sites)
    : In(input)
    , Mode(culling)
    , Slack(slack)
    , For(parallelFor)
    , Out(sites)
    , P(input.Points.data())
    , NumPoints(static_cast<int64_t>(input.Points.size() / 3))
  {
  }

  /// Points that cells use, merged when their coordinates are identical, so that polygon
  /// soups and duplicated points still get their topology (and tight domains), in the
  /// order of a Morton curve. False and `error` on a bad id or coordinate; `Empty()`
  /// afterwards when no cell uses a point.
  bool MergePoints(std::string& error);
  bool Empty() const { return this->NumVertices == 0; }
  /// Faces (non-degenerate triangles) and every edge occurrence, bucketed by its
  /// smaller point; the smallest input cell of every vertex.
  void CollectFacesAndEdges();
  /// The orientation that makes the pseudonormals point outward for closed meshes, and
  /// the vertices' angle-weighted pseudonormals.
  void VertexNormals();
  /// One edge per group of equal records (unless degenerate), and the edges of every
  /// vertex.
  void GroupEdges();
  /// What bounds every vertex's domain.
  void ClassifyVertices();
  /// The sites and their planes, in place: faces, edges, then vertices. False and
  /// `error` when the planes overflow their 32-bit indices.
  bool WriteSites(std::string& error);
  /// How many sites got which kind of domain.
  void CountDomains();

private:
  const double* X(int64_t c) const { return this->Points + 3 * c; }
  void SortAlongCurve(std::vector<int64_t>& order) const;
  void OrderTriangles();
  void CountFacesAndEdges(std::vector<int64_t>& chunkFaces);
  void WriteFacesAndEdges(const std::vector<int64_t>& chunkFaces);
  void Corners(int64_t i, int64_t c[3]) const;
  bool FaceNormal(const int64_t c[3], Vec& normal) const;
  void UseVertex(int64_t v, int64_t cell);
  void AddEdge(int64_t a, int64_t b, int64_t face, int64_t cell);
  template<typename Visit>
  int64_t ForEachGroup(int64_t a, const Visit& visit) const;
  int64_t EdgeFace(int64_t e, int which) const;
  Vec Away(const VertexEdge& eu) const;
  VertexEdgeSpan IncidentEdges(int64_t v) const;
  uint8_t Classify(int64_t v);
  bool ClosedFan(int64_t v, const VertexEdgeSpan& incident) const;
  bool PyramidAround(int64_t v, const VertexEdgeSpan& incident);
  int EdgePlanes(int64_t e) const;
  int VertexPlanes(int64_t v) const;
  void SetPlane(uint32_t at, const Vec& n, const double* through, const double* anchor);
  Site& InitSite(int64_t index, uint8_t type, int64_t cell, const double* anchor);
  void WriteFaceSites();
  void WriteEdgeSites();
  void WriteVertexSites();

  const MeshInput& In;
  const Culling Mode;
  const double Slack;
  const ParallelFor& For;
  MeshSites& Out;
  const double* P;
  const int64_t NumPoints;
  // The merged points.
  std::vector<int64_t> Canonical; // input id -> merged index
  int64_t NumVertices = 0;
  const double* Points = nullptr; // Out.SitePoints
  double Degenerate = 0;          // features below this size carry no direction
  // Faces and edge records.
  std::vector<int64_t> TriangleOrder;
  std::vector<uint8_t> IsFace;
  LargeVector<FaceRecord> Faces;
  std::vector<int64_t> EdgeStart;
  // Per point: first the records of its bucket, then the next free record.
  std::vector<std::atomic<int64_t>> EdgeFill;
  LargeVector<EdgeRecord> Edges;
  std::vector<std::atomic<int64_t>> VertexCell;
  double Orientation = 1;
  std::vector<Vec> VertexNormal;
  // Edges and the edges of every vertex.
  std::vector<int64_t> GroupStart;
  LargeVector<EdgeGroup> EdgeGroups;
  LargeVector<std::array<int64_t, 2>> EdgeEnds;
  std::vector<int64_t> VertexEdgeOffsets;
  LargeVector<VertexEdge> VertexEdges;
  std::vector<std::vector<int64_t>> VertexFaces;
  // Domains.
  std::vector<uint8_t> Domain;
  std::vector<std::array<Vec, 4>> PyramidSides;
  std::vector<uint32_t> PlaneBegin;
  int64_t NumFaces = 0, NumEdges = 0;
};

bool SiteBuilder::MergePoints(std::string& error)
{
  const double* P = this->P;
  const int64_t numPoints = this->NumPoints;
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
  if (!markUsed(this->In.Triangles) || !markUsed(this->In.Segments) || !markUsed(this->In.Vertices))
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
  this->SortAlongCurve(order);
  this->Canonical.assign(numPoints, -1);
  std::vector<int64_t> merged; // canonical index -> input point id
  for (size_t k = 0; k < order.size(); ++k)
  {
    const int64_t id = order[k];
    if (k > 0 && std::equal(P + 3 * id, P + 3 * id + 3, P + 3 * order[k - 1]))
    {
      this->Canonical[id] = this->Canonical[order[k - 1]];
      ++this->Out.Statistics.MergedPoints;
    }
    else
    {
      this->Canonical[id] = static_cast<int64_t>(merged.size());
      merged.push_back(id);
    }
  }
  const int64_t nv = static_cast<int64_t>(merged.size());
  this->NumVertices = nv;
  // The merged points, contiguous in curve order: every later pass reads them there.
  this->Out.SitePoints.resize(3 * nv);
  for (int64_t c = 0; c < nv; ++c)
  {
    std::copy(P + 3 * merged[c], P + 3 * merged[c] + 3, &this->Out.SitePoints[3 * c]);
  }
  this->Points = this->Out.SitePoints.data();
  double* bounds = this->Out.Bounds;
  for (int a = 0; a < 3; ++a)
  {
    bounds[2 * a] = this->X(0)[a];
    bounds[2 * a + 1] = this->X(0)[a];
  }
  for (int64_t c = 0; c < nv; ++c)
  {
    for (int a = 0; a < 3; ++a)
    {
      bounds[2 * a] = std::min(bounds[2 * a], this->X(c)[a]);
      bounds[2 * a + 1] = std::max(bounds[2 * a + 1], this->X(c)[a]);
    }
  }
  const double diagonal =
    std::hypot(bounds[1] - bounds[0], std::hypot(bounds[3] - bounds[2], bounds[5] - bounds[4]));
  this->Degenerate = 1e-10 * (diagonal > 0 ? diagonal : 1.0);
  return true;
}

/// Sorts the points along a Morton curve (identical points stay adjacent, so they merge
/// afterwards): sites, planes and every later pass then walk memory in space order, which
/// matters for large polygon soups whose input order is arbitrary.
void SiteBuilder::SortAlongCurve(std::vector<int64_t>& order) const
{
  const double* P = this->P;
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
  Run(this->For,
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
    this->For);
  for (size_t i = 0; i < keys.size(); ++i)
  {
    order[i] = keys[i].Id;
  }
}

/// Triangles in the order of their first corner on the curve (a counting sort).
void SiteBuilder::OrderTriangles()
{
  const std::vector<int64_t>& triangles = this->In.Triangles;
  const int64_t numTriangles = static_cast<int64_t>(triangles.size() / 3);
  this->TriangleOrder.resize(numTriangles);
  std::vector<int64_t> start(this->NumVertices + 1, 0);
  auto key = [&](int64_t t)
  {
    return std::min(this->Canonical[triangles[3 * t]],
      std::min(this->Canonical[triangles[3 * t + 1]], this->Canonical[triangles[3 * t + 2]]));
  };
  for (int64_t t = 0; t < numTriangles; ++t)
  {
    ++start[key(t) + 1];
  }
  for (int64_t v = 0; v < this->NumVertices; ++v)
  {
    start[v + 1] += start[v];
  }
  for (int64_t t = 0; t < numTriangles; ++t)
  {
    this->TriangleOrder[start[key(t)]++] = t;
  }
}

/// The merged corners of the triangle at position i of TriangleOrder.
void SiteBuilder::Corners(int64_t i, int64_t c[3]) const
{
  const int64_t* ids = &this->In.Triangles[3 * this->TriangleOrder[i]];
  c[0] = this->Canonical[ids[0]], c[1] = this->Canonical[ids[1]], c[2] = this->Canonical[ids[2]];
}

/// Whether corners c make a face, and then its unit normal.
bool SiteBuilder::FaceNormal(const int64_t c[3], Vec& normal) const
{
  if (c[0] == c[1] || c[1] == c[2] || c[2] == c[0])
  {
    return false;
  }
  const Vec e1 = Sub(this->X(c[1]), this->X(c[0])), e2 = Sub(this->X(c[2]), this->X(c[0]));
  const Vec e3 = Sub(this->X(c[2]), this->X(c[1]));
  const Vec n = Cross(e1, e2);
  const double area2 = Norm(n);
  const double longest = std::max(Norm(e1), std::max(Norm(e2), Norm(e3)));
  if (!(area2 > this->Degenerate * longest))
  {
    return false;
  }
  normal = Scale(n, 1.0 / area2);
  return true;
}

void SiteBuilder::UseVertex(int64_t v, int64_t cell)
{
  std::atomic<int64_t>& smallest = this->VertexCell[v];
  int64_t old = smallest.load(std::memory_order_relaxed);
  while (cell < old && !smallest.compare_exchange_weak(old, cell, std::memory_order_relaxed))
  {
  }
}

/// Appends an edge record to the bucket of its smaller point.
void SiteBuilder::AddEdge(int64_t a, int64_t b, int64_t face, int64_t cell)
{
  if (a != b)
  {
    const int64_t at = this->EdgeFill[std::min(a, b)].fetch_add(1, std::memory_order_relaxed);
    this->Edges[at] = { std::min(a, b), std::max(a, b), face, cell };
  }
}

// Two passes over fixed chunks of TriangleOrder, so that faces are numbered as a serial
// loop would number them whatever the schedule: count faces and edge records, then write
// them. Edge records go straight into buckets by their smaller point (a counting sort);
// sorting each small bucket by (B, Face) then orders them all by (A, B, Face), whatever
// order the threads filled it in.
constexpr int64_t Chunk = 4096;

void SiteBuilder::CollectFacesAndEdges()
{
  const int64_t nv = this->NumVertices;
  this->OrderTriangles();
  const int64_t numTriangles = static_cast<int64_t>(this->TriangleOrder.size());
  std::vector<int64_t> chunkFaces((numTriangles + Chunk - 1) / Chunk + 1, 0);
  this->CountFacesAndEdges(chunkFaces);
  const int64_t numChunks = static_cast<int64_t>(chunkFaces.size()) - 1;
  this->EdgeStart.assign(nv + 1, 0);
  for (int64_t v = 0; v < nv; ++v)
  {
    this->EdgeStart[v + 1] =
      this->EdgeStart[v] + this->EdgeFill[v + 1].load(std::memory_order_relaxed);
  }
  for (int64_t chunk = 0; chunk < numChunks; ++chunk)
  {
    chunkFaces[chunk + 1] += chunkFaces[chunk];
  }
  this->Faces.resize(chunkFaces[numChunks]);
  this->Out.Statistics.DegenerateFaces = numTriangles - chunkFaces[numChunks];
  this->Edges.resize(this->EdgeStart[nv]);
  for (int64_t v = 0; v < nv; ++v)
  {
    this->EdgeFill[v].store(this->EdgeStart[v], std::memory_order_relaxed);
  }
  // The smallest input cell using each point (ClosestCellId of its vertex site).
  this->VertexCell = std::vector<std::atomic<int64_t>>(nv);
  for (auto& cell : this->VertexCell)
  {
    cell.store(INT64_MAX, std::memory_order_relaxed);
  }
  this->WriteFacesAndEdges(chunkFaces);
  SortBuckets(
    this->Edges,
    this->EdgeStart,
    [](const EdgeRecord& x, const EdgeRecord& y)
    { return x.B != y.B ? x.B < y.B : x.Face < y.Face; },
    this->For);
}

/// The faces of every chunk of TriangleOrder (chunkFaces[chunk + 1]) and the edge
/// records of every bucket (EdgeFill[a + 1]).
void SiteBuilder::CountFacesAndEdges(std::vector<int64_t>& chunkFaces)
{
  const int64_t numTriangles = static_cast<int64_t>(this->TriangleOrder.size());
  const int64_t numChunks = static_cast<int64_t>(chunkFaces.size()) - 1;
  this->EdgeFill = std::vector<std::atomic<int64_t>>(this->NumVertices + 1); // zeros
  this->IsFace.resize(numTriangles);
  Run(this->For,
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
          this->Corners(i, c);
          Vec normal;
          this->IsFace[i] = this->FaceNormal(c, normal);
          count += this->IsFace[i];
          for (int k = 0; k < 3; ++k)
          {
            const int64_t a = c[k], b = c[(k + 1) % 3];
            if (a != b)
            {
              this->EdgeFill[std::min(a, b) + 1].fetch_add(1, std::memory_order_relaxed);
            }
          }
        }
        chunkFaces[chunk + 1] = count;
      }
    });
  const std::vector<int64_t>& segments = this->In.Segments;
  for (size_t s = 0; s < segments.size() / 2; ++s)
  {
    const int64_t a = this->Canonical[segments[2 * s]], b = this->Canonical[segments[2 * s + 1]];
    this->EdgeFill[std::min(a, b) + 1] += a != b;
  }
}

/// The faces (numbered from chunkFaces, the chunks' first faces), the edge records of
/// triangles, segments and the vertices' smallest cells.
void SiteBuilder::WriteFacesAndEdges(const std::vector<int64_t>& chunkFaces)
{
  const int64_t numTriangles = static_cast<int64_t>(this->TriangleOrder.size());
  const int64_t numChunks = static_cast<int64_t>(chunkFaces.size()) - 1;
  Run(this->For,
    numChunks,
    1,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t chunk = begin; chunk < end; ++chunk)
      {
        int64_t face = chunkFaces[chunk];
        for (int64_t i = chunk * Chunk; i < std::min(numTriangles, (chunk + 1) * Chunk); ++i)
        {
          const int64_t cell = this->In.TriangleCells[this->TriangleOrder[i]];
          int64_t c[3];
          this->Corners(i, c);
          for (int k = 0; k < 3; ++k)
          {
            this->UseVertex(c[k], cell);
          }
          int64_t id = -1;
          if (this->IsFace[i])
          {
            id = face++;
            FaceRecord& f = this->Faces[id];
            this->FaceNormal(c, f.Normal);
            std::copy(c, c + 3, f.P);
            f.Cell = cell;
          }
          for (int k = 0; k < 3; ++k)
          {
            this->AddEdge(c[k], c[(k + 1) % 3], id, cell);
          }
        }
      }
    });
  const std::vector<int64_t>& segments = this->In.Segments;
  for (size_t s = 0; s < segments.size() / 2; ++s)
  {
    const int64_t a = this->Canonical[segments[2 * s]], b = this->Canonical[segments[2 * s + 1]];
    const int64_t cell = this->In.SegmentCells[s];
    this->UseVertex(a, cell);
    this->UseVertex(b, cell);
    this->AddEdge(a, b, -1, cell);
  }
  for (size_t v = 0; v < this->In.Vertices.size(); ++v)
  {
    this->UseVertex(this->Canonical[this->In.Vertices[v]], this->In.VertexCells[v]);
  }
}

void SiteBuilder::VertexNormals()
{
  const LargeVector<FaceRecord>& faces = this->Faces;
  double volume = 0;
  for (const FaceRecord& f : faces)
  {
    const Vec a = Sub(this->X(f.P[0]), this->X(0)), b = Sub(this->X(f.P[1]), this->X(0)),
              c = Sub(this->X(f.P[2]), this->X(0));
    volume += Dot(a, Cross(b, c));
  }
  this->Orientation = volume < 0 ? -1.0 : 1.0;
  this->NumFaces = static_cast<int64_t>(faces.size());
  // The corner angles in parallel, then summed in face order (the same sums either way).
  std::vector<double> cornerAngle(3 * this->NumFaces);
  Run(this->For,
    this->NumFaces,
    4096,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t fi = begin; fi < end; ++fi)
      {
        const FaceRecord& f = faces[fi];
        for (int k = 0; k < 3; ++k)
        {
          const Vec u = Sub(this->X(f.P[(k + 1) % 3]), this->X(f.P[k]));
          const Vec w = Sub(this->X(f.P[(k + 2) % 3]), this->X(f.P[k]));
          cornerAngle[3 * fi + k] = std::atan2(Norm(Cross(u, w)), Dot(u, w));
        }
      }
    });
  this->VertexNormal.assign(this->NumVertices, Vec{ 0, 0, 0 });
  for (int64_t fi = 0; fi < this->NumFaces; ++fi)
  {
    const FaceRecord& f = faces[fi];
    for (int k = 0; k < 3; ++k)
    {
      this->VertexNormal[f.P[k]] = Add(
        this->VertexNormal[f.P[k]], Scale(f.Normal, cornerAngle[3 * fi + k] * this->Orientation));
    }
  }
}

/// Calls visit(first, last, b) for every group of bucket a (records [first, last), edge
/// from a to b) that is not degenerate; returns how many were.
template<typename Visit>
int64_t SiteBuilder::ForEachGroup(int64_t a, const Visit& visit) const
{
  int64_t degenerateGroups = 0;
  for (int64_t e0 = this->EdgeStart[a]; e0 < this->EdgeStart[a + 1];)
  {
    int64_t e1 = e0 + 1;
    while (e1 < this->EdgeStart[a + 1] && this->Edges[e1].B == this->Edges[e0].B)
    {
      ++e1;
    }
    if (Norm(Sub(this->X(this->Edges[e0].B), this->X(a))) <= this->Degenerate)
    {
      ++degenerateGroups;
    }
    else
    {
      visit(e0, e1, this->Edges[e0].B);
    }
    e0 = e1;
  }
  return degenerateGroups;
}

// A group lies in one bucket (the records of one smaller point), so the buckets are
// counted, then written, in parallel; edges are numbered in bucket order, as a serial
// loop would.
void SiteBuilder::GroupEdges()
{
  const int64_t nv = this->NumVertices;
  this->GroupStart.assign(nv + 1, 0);
  std::atomic<int64_t> degenerateEdges{ 0 };
  Run(this->For,
    nv,
    4096,
    [&](int64_t begin, int64_t end)
    {
      int64_t local = 0;
      for (int64_t a = begin; a < end; ++a)
      {
        int64_t count = 0;
        local += this->ForEachGroup(a, [&](int64_t, int64_t, int64_t) { ++count; });
        this->GroupStart[a + 1] = count;
      }
      degenerateEdges += local;
    });
  this->Out.Statistics.DegenerateEdges = degenerateEdges.load();
  for (int64_t v = 0; v < nv; ++v)
  {
    this->GroupStart[v + 1] += this->GroupStart[v];
  }
  this->NumEdges = this->GroupStart[nv];
  this->EdgeGroups.resize(this->NumEdges);
  this->EdgeEnds.resize(this->NumEdges);
  std::vector<std::atomic<int64_t>> vertexEdgeCount(nv + 1); // value-initialized: zeros
  Run(this->For,
    nv,
    4096,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t a = begin; a < end; ++a)
      {
        int64_t e = this->GroupStart[a];
        this->ForEachGroup(a,
          [&](int64_t first, int64_t last, int64_t b)
          {
            EdgeGroup& group = this->EdgeGroups[e];
            group.First = first;
            group.Last = last;
            group.Cell = INT64_MAX;
            group.Faces = 0;
            for (int64_t r = first; r < last; ++r)
            {
              group.Cell = std::min(group.Cell, this->Edges[r].Cell);
              group.Faces += this->Edges[r].Face >= 0;
            }
            const Vec t = Sub(this->X(b), this->X(a));
            group.Tangent = Scale(t, 1.0 / Norm(t));
            this->EdgeEnds[e] = { a, b };
            vertexEdgeCount[a + 1].fetch_add(1, std::memory_order_relaxed);
            vertexEdgeCount[b + 1].fetch_add(1, std::memory_order_relaxed);
            ++e;
          });
      }
    });

  // The edges of every vertex, contiguous per vertex, in edge order: (edge, direction
  // away from it). Filled in parallel, then each vertex's few sorted.
  this->VertexEdgeOffsets.assign(nv + 1, 0);
  for (int64_t v = 0; v < nv; ++v)
  {
    this->VertexEdgeOffsets[v + 1] =
      this->VertexEdgeOffsets[v] + vertexEdgeCount[v + 1].load(std::memory_order_relaxed);
  }
  std::vector<std::atomic<int64_t>>& vertexEdgeFill = vertexEdgeCount; // the next free entry
  for (int64_t v = 0; v < nv; ++v)
  {
    vertexEdgeFill[v].store(this->VertexEdgeOffsets[v], std::memory_order_relaxed);
  }
  this->VertexEdges.resize(this->VertexEdgeOffsets[nv]);
  Run(this->For,
    this->NumEdges,
    4096,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t e = begin; e < end; ++e)
      {
        for (int side = 0; side < 2; ++side)
        {
          const int64_t at =
            vertexEdgeFill[this->EdgeEnds[e][side]].fetch_add(1, std::memory_order_relaxed);
          this->VertexEdges[at] = { e, side == 0 ? 1.0 : -1.0 };
        }
      }
    });
  SortBuckets(
    this->VertexEdges,
    this->VertexEdgeOffsets,
    [](const VertexEdge& x, const VertexEdge& y) { return x.Edge < y.Edge; },
    this->For);
}

/// The faces of an edge (records with a face come last in a group: sorted by Face).
int64_t SiteBuilder::EdgeFace(int64_t e, int which) const
{
  return this->Edges[this->EdgeGroups[e].Last - this->EdgeGroups[e].Faces + which].Face;
}

/// The unit direction of an edge away from the vertex it is seen from.
Vec SiteBuilder::Away(const VertexEdge& eu) const
{
  return Scale(this->EdgeGroups[eu.Edge].Tangent, eu.Sign);
}

VertexEdgeSpan SiteBuilder::IncidentEdges(int64_t v) const
{
  return VertexEdgeSpan{ this->VertexEdges.data() + this->VertexEdgeOffsets[v],
    static_cast<size_t>(this->VertexEdgeOffsets[v + 1] - this->VertexEdgeOffsets[v]) };
}

void SiteBuilder::ClassifyVertices()
{
  const int64_t nv = this->NumVertices;
  if (this->Mode == Culling::Manifold)
  {
    this->VertexFaces.resize(nv);
    for (size_t f = 0; f < this->Faces.size(); ++f)
    {
      for (int k = 0; k < 3; ++k)
      {
        this->VertexFaces[this->Faces[f].P[k]].push_back(static_cast<int64_t>(f));
      }
    }
    this->PyramidSides.resize(nv);
  }
  this->Domain.assign(nv, Unbounded);
  Run(this->For,
    nv,
    1024,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t v = begin; v < end; ++v)
      {
        this->Domain[v] = this->Classify(v);
      }
    });
}

uint8_t SiteBuilder::Classify(int64_t v)
{
  const VertexEdgeSpan incident = this->IncidentEdges(v);
  if (this->Mode != Culling::Manifold)
  {
    return this->Mode == Culling::Auto && !incident.empty() ? Polar : Unbounded;
  }
  // Manifold culling: only where the faces around v form one closed fan.
  if (!this->ClosedFan(v, incident))
  {
    return Unbounded;
  }
  // Convex or concave vertex (every incident edge bends the same way): the polytope
  // spanned by the face normals, i.e. the planes orthogonal to the edges.
  int convex = 0, concave = 0;
  for (const auto& eu : incident)
  {
    const FaceRecord& f0 = this->Faces[this->EdgeFace(eu.Edge, 0)];
    const FaceRecord& f1 = this->Faces[this->EdgeFace(eu.Edge, 1)];
    const int64_t a = this->EdgeEnds[eu.Edge][0], b = this->EdgeEnds[eu.Edge][1];
    int64_t c1 = f1.P[0];
    for (int k = 0; k < 3; ++k)
    {
      if (f1.P[k] != a && f1.P[k] != b)
      {
        c1 = f1.P[k];
      }
    }
    const double bend = Dot(Scale(f0.Normal, this->Orientation), Sub(this->X(c1), this->X(a)));
    convex += bend <= 0;
    concave += bend >= 0;
  }
  if (convex == static_cast<int>(incident.size()) || concave == static_cast<int>(incident.size()))
  {
    return Polar;
  }
  return this->PyramidAround(v, incident) ? Pyramid : Unbounded;
}

/// Whether the faces around v form one closed fan: every incident edge has two faces, as
/// many as the faces around v, and a walk around them visits each once.
bool SiteBuilder::ClosedFan(int64_t v, const VertexEdgeSpan& incident) const
{
  const auto& fan = this->VertexFaces[v];
  bool closed = !incident.empty() && fan.size() == incident.size();
  for (const auto& eu : incident)
  {
    closed = closed && this->EdgeGroups[eu.Edge].Faces == 2;
  }
  if (!closed)
  {
    return false;
  }
  size_t steps = 0;
  int64_t edge = incident[0].Edge, face = this->EdgeFace(edge, 0);
  const int64_t startFace = face;
  do
  {
    ++steps;
    int64_t next = -1;
    for (const auto& eu : incident)
    {
      if (eu.Edge != edge &&
        (this->EdgeFace(eu.Edge, 0) == face || this->EdgeFace(eu.Edge, 1) == face))
      {
        next = eu.Edge;
      }
    }
    if (next < 0)
    {
      return false;
    }
    edge = next;
    face = this->EdgeFace(edge, 0) == face ? this->EdgeFace(edge, 1) : this->EdgeFace(edge, 0);
  } while (face != startFace && steps <= fan.size());
  return steps == fan.size();
}

/// A hyperbolic vertex (Theorem 1): the cone about the mean normal n_a whose half-angle
/// is the largest angle between n_a and a face normal, circumscribed by a square pyramid
/// (PyramidSides[v]); false when there is none or it does not hold the exact domain.
bool SiteBuilder::PyramidAround(int64_t v, const VertexEdgeSpan& incident)
{
  const auto& fan = this->VertexFaces[v];
  Vec na{ 0, 0, 0 };
  for (int64_t f : fan)
  {
    na = Add(na, this->Faces[f].Normal);
  }
  const double nal = Norm(na);
  double cosTheta = 1;
  if (nal > 0)
  {
    na = Scale(na, 1.0 / nal);
    for (int64_t f : fan)
    {
      cosTheta = std::min(cosTheta, Dot(na, this->Faces[f].Normal));
    }
  }
  if (!(nal > 0 && cosTheta > 1e-6)) // theta >= pi/2: no pyramid
  {
    return false;
  }
  const double sinTheta = std::sqrt(std::max(0.0, 1 - cosTheta * cosTheta));
  Vec b1 = std::fabs(na[0]) < 0.9 ? Vec{ 1, 0, 0 } : Vec{ 0, 1, 0 };
  b1 = Sub(b1.data(), Scale(na, Dot(b1, na)).data());
  b1 = Scale(b1, 1.0 / Norm(b1));
  const Vec b2 = Cross(na, b1);
  // The cone's tangent planes along +-b1, +-b2: a square pyramid containing the cone.
  std::array<Vec, 4>& sides = this->PyramidSides[v];
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
      const Vec r = Cross(this->Away(incident[i]), this->Away(incident[j]));
      for (const auto& eu : incident)
      {
        rank = std::max(rank, std::fabs(Dot(r, this->Away(eu))));
      }
      for (double sign : { 1.0, -1.0 })
      {
        const Vec ray = Scale(r, sign);
        bool inDomain = Norm(ray) > 1e-12;
        for (const auto& eu : incident)
        {
          inDomain = inDomain && Dot(ray, this->Away(eu)) <= 1e-12;
        }
        for (const Vec& w : sides)
        {
          pyramid = pyramid && (!inDomain || Dot(ray, w) >= -1e-12);
        }
      }
    }
  }
  return pyramid && rank > 1e-9;
}

int SiteBuilder::EdgePlanes(int64_t e) const
{
  const bool wedge = this->Mode == Culling::Auto ||
    (this->Mode == Culling::Manifold && this->EdgeGroups[e].Faces == 2);
  return 2 + (wedge ? this->EdgeGroups[e].Faces : 0);
}

int SiteBuilder::VertexPlanes(int64_t v) const
{
  return this->Domain[v] == Polar
    ? static_cast<int>(this->VertexEdgeOffsets[v + 1] - this->VertexEdgeOffsets[v])
    : (this->Domain[v] == Pyramid ? 4 : 0);
}

/// The plane through `through` with normal n, relative to the site's anchor. The offset
/// is computed from the rounded normal, so the stored plane still passes through it.
void SiteBuilder::SetPlane(uint32_t at, const Vec& n, const double* through, const double* anchor)
{
  HalfSpace& h = this->Out.Planes[at];
  for (int a = 0; a < 3; ++a)
  {
    h.N[a] = static_cast<float>(n[a]);
  }
  h.D = static_cast<float>(-(h.N[0] * (through[0] - anchor[0]) + h.N[1] * (through[1] - anchor[1]) +
                             h.N[2] * (through[2] - anchor[2])) +
    this->Slack);
}

Site& SiteBuilder::InitSite(int64_t index, uint8_t type, int64_t cell, const double* anchor)
{
  Site& s = this->Out.Sites[index];
  s = Site{};
  s.Type = type;
  s.CellId = cell;
  s.PlaneBegin = this->PlaneBegin[index];
  s.PlaneCount = static_cast<uint16_t>(this->PlaneBegin[index + 1] - this->PlaneBegin[index]);
  for (int a = 0; a < 3; ++a)
  {
    s.Anchor[a] = anchor[a];
    s.BoundsMin[a] = FloatBelow(anchor[a]);
    s.BoundsMax[a] = FloatAbove(anchor[a]);
  }
  return s;
}

/// Grows a site's box to hold x.
void Grow(Site& s, const double* x)
{
  for (int a = 0; a < 3; ++a)
  {
    s.BoundsMin[a] = std::min(s.BoundsMin[a], FloatBelow(x[a]));
    s.BoundsMax[a] = std::max(s.BoundsMax[a], FloatAbove(x[a]));
  }
}

bool SiteBuilder::WriteSites(std::string& error)
{
  // Plane counts first, then every site and its planes written in place, in parallel.
  const int64_t numSites = this->NumFaces + this->NumEdges + this->NumVertices;
  this->PlaneBegin.assign(numSites + 1, 0);
  for (int64_t i = 0; i < numSites; ++i)
  {
    const int64_t count = i < this->NumFaces ? 3
      : i < this->NumFaces + this->NumEdges
      ? this->EdgePlanes(i - this->NumFaces)
      : this->VertexPlanes(i - this->NumFaces - this->NumEdges);
    const uint64_t next = uint64_t(this->PlaneBegin[i]) + count;
    if (next > UINT32_MAX)
    {
      error = "the mesh needs more than 2^32 domain planes";
      return false;
    }
    this->PlaneBegin[i + 1] = static_cast<uint32_t>(next);
  }
  this->Out.Sites.resize(numSites);
  this->Out.Planes.resize(this->PlaneBegin[numSites]);
  this->WriteFaceSites();
  this->WriteEdgeSites();
  this->WriteVertexSites();
  return true;
}

/// Face sites: the triangle prism (three planes through the edges, orthogonal to the
/// triangle), required for the plane-distance formula to be exact.
void SiteBuilder::WriteFaceSites()
{
  Run(this->For,
    this->NumFaces,
    1024,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t fi = begin; fi < end; ++fi)
      {
        const FaceRecord& f = this->Faces[fi];
        Site& s = this->InitSite(fi, FaceSite, f.Cell, this->X(f.P[0]));
        for (int k = 0; k < 3; ++k)
        {
          const double* a = this->X(f.P[k]);
          const Vec e = Sub(this->X(f.P[(k + 1) % 3]), a);
          Vec m = Cross(f.Normal, e);
          m = Scale(m, 1.0 / Norm(m));
          if (Dot(m, Sub(this->X(f.P[(k + 2) % 3]), a)) < 0)
          {
            m = Scale(m, -1.0);
          }
          this->SetPlane(s.PlaneBegin + k, m, a, s.Anchor);
          Grow(s, this->X(f.P[k]));
        }
        for (int a = 0; a < 3; ++a)
        {
          s.Axis[a] = f.Normal[a];
          s.Normal[a] = static_cast<float>(f.Normal[a] * this->Orientation);
        }
        s.Required = 3;
      }
    });
}

/// Edge sites: the slab between the end planes (required), then one plane per incident
/// face: a point on the face side of that plane is closer to the face.
void SiteBuilder::WriteEdgeSites()
{
  Run(this->For,
    this->NumEdges,
    1024,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t e = begin; e < end; ++e)
      {
        const int64_t a = this->EdgeEnds[e][0], b = this->EdgeEnds[e][1];
        const Vec& t = this->EdgeGroups[e].Tangent;
        Site& s =
          this->InitSite(this->NumFaces + e, EdgeSite, this->EdgeGroups[e].Cell, this->X(a));
        Grow(s, this->X(b));
        uint32_t at = s.PlaneBegin;
        this->SetPlane(at++, t, this->X(a), s.Anchor);
        this->SetPlane(at++, Scale(t, -1.0), this->X(b), s.Anchor);
        s.Required = 2;
        const bool wedge = s.PlaneCount > 2;
        Vec pseudo{ 0, 0, 0 };
        for (int i = 0; i < this->EdgeGroups[e].Faces; ++i)
        {
          const FaceRecord& f = this->Faces[this->EdgeFace(e, i)];
          pseudo = Add(pseudo, Scale(f.Normal, this->Orientation));
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
            const Vec ac = Sub(this->X(c), this->X(a));
            Vec m = Sub(ac.data(), Scale(t, Dot(ac, t)).data());
            m = Scale(m, -1.0 / Norm(m));
            this->SetPlane(at++, m, this->X(a), s.Anchor);
          }
        }
        for (int k = 0; k < 3; ++k)
        {
          s.Axis[k] = t[k];
          s.Normal[k] = static_cast<float>(pseudo[k]);
        }
      }
    });
}

void SiteBuilder::WriteVertexSites()
{
  Run(this->For,
    this->NumVertices,
    1024,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t v = begin; v < end; ++v)
      {
        Site& s = this->InitSite(this->NumFaces + this->NumEdges + v,
          VertexSite,
          this->VertexCell[v].load(std::memory_order_relaxed),
          this->X(v));
        s.Required = 0;
        for (int a = 0; a < 3; ++a)
        {
          s.Normal[a] = static_cast<float>(this->VertexNormal[v][a]);
        }
        uint32_t at = s.PlaneBegin;
        if (this->Domain[v] == Polar)
        {
          for (const auto& eu : this->IncidentEdges(v))
          {
            this->SetPlane(at++, Scale(this->Away(eu), -1.0), this->X(v), s.Anchor);
          }
        }
        else if (this->Domain[v] == Pyramid)
        {
          for (const Vec& w : this->PyramidSides[v])
          {
            this->SetPlane(at++, w, this->X(v), s.Anchor);
          }
        }
      }
    });
}

void SiteBuilder::CountDomains()
{
  DomainStatistics& statistics = this->Out.Statistics;
  statistics.Faces = this->NumFaces;
  statistics.Edges = this->NumEdges;
  statistics.Vertices = this->NumVertices;
  for (int64_t e = 0; e < this->NumEdges; ++e)
  {
    statistics.EdgeWedges += this->EdgePlanes(e) > 2;
  }
  for (int64_t v = 0; v < this->NumVertices; ++v)
  {
    statistics.PolarVertices += this->Domain[v] == Polar;
    statistics.PyramidVertices += this->Domain[v] == Pyramid;
    statistics.UnboundedVertices += this->Domain[v] == Unbounded;
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
  SiteBuilder builder(in, culling, slack, parallelFor, *this);
  if (!builder.MergePoints(error))
  {
    return false;
  }
  if (builder.Empty())
  {
    return true;
  }
  builder.CollectFacesAndEdges();
  builder.VertexNormals();
  builder.GroupEdges();
  builder.ClassifyVertices();
  if (!builder.WriteSites(error))
  {
    return false;
  }
  builder.CountDomains();
  return true;
}

} // namespace vtkdf
