// SiteBuilder: the passes of MeshSites::Build over what they share (the merged points,
// the faces and edge records, the edge groups, the vertices' domains). They live in three
// sources, in the order Build runs them: SiteTopology.cxx (points merged, faces and edges
// collected), SiteClassification.cxx (pseudonormals, edge groups, vertex domains) and
// MeshSites.cxx (the sites and their planes). Private to the linear-factorization family.
#ifndef vtkdf_SiteBuilder_h
#define vtkdf_SiteBuilder_h

#include "LinearFactor/MeshSites.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace vtkdf
{
namespace sites
{
using Vec = std::array<double, 3>;

inline Vec Sub(const double* a, const double* b)
{
  return { a[0] - b[0], a[1] - b[1], a[2] - b[2] };
}
inline double Dot(const Vec& a, const Vec& b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline Vec Cross(const Vec& a, const Vec& b)
{
  return { a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0] };
}
inline double Norm(const Vec& a)
{
  return std::sqrt(Dot(a, a));
}
inline Vec Scale(const Vec& a, double s)
{
  return { a[0] * s, a[1] * s, a[2] * s };
}
inline Vec Add(const Vec& a, const Vec& b)
{
  return { a[0] + b[0], a[1] + b[1], a[2] + b[2] };
}

/// An edge occurrence, in the bucket of its smaller point A: B the larger merged point;
/// Source the non-degenerate face it bounds (below the face count), or the face count
/// plus its entry in LooseCells (a degenerate triangle's, a segment's).
struct EdgeRecord
{
  uint32_t B, Source;
};

/// The edges of a vertex (indices, ascending).
struct EdgeSpan
{
  const uint32_t* First = nullptr;
  size_t Count = 0;
  const uint32_t* begin() const { return First; }
  const uint32_t* end() const { return First + Count; }
  size_t size() const { return Count; }
  bool empty() const { return Count == 0; }
  uint32_t operator[](size_t i) const { return First[i]; }
};

/// parallelFor when the caller gave one, else a plain loop.
inline void Run(const ParallelFor& parallelFor,
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

/// The bits of x (21 of them) moved to every third position: one axis of a Morton code.
inline uint64_t SpreadBits(uint64_t x)
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

/// What bounds a vertex's domain (Manifold needs the neighbourhood's shape).
enum VertexDomain : uint8_t
{
  Unbounded,
  Polar,  // (x - p) . u <= 0 for every edge direction u: otherwise the edge is closer
  Pyramid // Theorem 1's square pyramid (hyperbolic vertex)
};

/// MeshSites::Build's passes, in the order Build runs them, over what they share. Each
/// pass that runs in parallel numbers what it makes as a serial loop would, so the sites
/// are the same whatever the schedule. The passes write MeshSites' compact arrays as
/// they go and release what the later passes no longer read, so that the build's peak
/// stays near what the sites keep.
class SiteBuilder
{
public:
  SiteBuilder(const MeshInput& input,
    DomainShape shape,
    double slack,
    const ParallelFor& parallelFor,
    MeshSites& sites)
    : In(input)
    , Mode(shape)
    , For(parallelFor)
    , Out(sites)
    , P(input.Points.data())
    , NumPoints(static_cast<int64_t>(input.Points.size() / 3))
  {
    sites.Shape = shape;
    sites.Slack = slack;
  }

  /// Points that cells use, merged when their coordinates are identical, so that polygon
  /// soups and duplicated points still get their topology (and tight domains), in the
  /// order of a Morton curve. False and `error` on a bad id or coordinate; `Empty()`
  /// afterwards when no cell uses a point.
  bool MergePoints(std::string& error);
  bool Empty() const { return this->NumVertices == 0; }
  /// Faces (non-degenerate triangles) and every edge occurrence, bucketed by its
  /// smaller point; the smallest input cell of every vertex. False and `error` when the
  /// faces are 2^32 - 1 or more: they are numbered in 32 bits. The later passes do not
  /// read the input: `release` (optional) is the input, whose arrays are then freed.
  bool CollectFacesAndEdges(std::string& error, MeshInput* release);
  /// The orientation that makes the pseudonormals point outward for closed meshes, and
  /// the vertices' angle-weighted pseudonormals.
  void VertexNormals();
  /// One edge per group of equal records (unless degenerate), its faces, and the edges
  /// of every vertex. False and `error` when the sites (or their edges' faces, or their
  /// vertices' edges) are 2^32 or more: they are numbered in 32 bits.
  bool GroupEdges(std::string& error);
  /// What bounds every vertex's domain.
  void ClassifyVertices();
  /// The vertices' cells in their compact form; the builder's own arrays released.
  void Finish();
  /// How many sites got which kind of domain.
  void CountDomains();

private:
  const double* X(int64_t c) const { return this->Points + 3 * c; }
  void SortAlongCurve(std::vector<int64_t>& order) const;
  void OrderTriangles();
  void CountFacesAndEdges(std::vector<int64_t>& chunkFaces);
  void WriteFacesAndEdges(const std::vector<int64_t>& chunkFaces);
  void Corners(int64_t i, int64_t c[3]) const;
  bool IsFaceTriangle(const int64_t c[3]) const;
  void UseVertex(int64_t v, int64_t cell);
  void AddEdge(int64_t a, int64_t b, uint32_t source);
  bool IsFaceRecord(const EdgeRecord& r) const { return r.Source < this->NumFaces; }
  int64_t RecordCell(const EdgeRecord& r) const
  {
    return this->IsFaceRecord(r) ? this->Out.FaceCells[r.Source]
                                 : this->LooseCells[r.Source - this->NumFaces];
  }
  Vec Normal(int64_t f) const
  {
    Vec n;
    this->Out.FaceNormal(f, n.data());
    return n;
  }
  template<typename Visit>
  int64_t ForEachGroup(int64_t a, const Visit& visit) const;
  int EdgeFaceCount(int64_t e) const
  {
    return static_cast<int>(this->Out.EdgeFaceStart[e + 1] - this->Out.EdgeFaceStart[e]);
  }
  int64_t EdgeFace(int64_t e, int which) const
  {
    return this->Out.EdgeFaces[this->Out.EdgeFaceStart[e] + which];
  }
  Vec Away(int64_t v, int64_t e) const;
  EdgeSpan IncidentEdges(int64_t v) const;
  uint8_t Classify(int64_t v);
  bool ClosedFan(int64_t v, const EdgeSpan& incident) const;
  bool PyramidAround(int64_t v, const EdgeSpan& incident);

  const MeshInput& In;
  const DomainShape Mode;
  const ParallelFor& For;
  MeshSites& Out;
  const double* P;
  const int64_t NumPoints;
  // The merged points.
  std::vector<int64_t> Canonical; // input id -> merged index
  int64_t NumVertices = 0;
  const double* Points = nullptr; // Out.SitePoints
  double Degenerate = 0;          // features below this size carry no direction
  // Triangles and edge records.
  std::vector<int64_t> TriangleOrder;
  std::vector<uint8_t> IsFace;
  std::vector<int64_t> EdgeStart;
  // Per point: first the records of its bucket, then the next free record.
  std::vector<std::atomic<int64_t>> EdgeFill;
  LargeVector<EdgeRecord> Edges;
  std::vector<int64_t> LooseCells; // the input cells of the records without a face
  std::vector<std::atomic<int64_t>> VertexCell;
  // Classification (DomainShape::Manifold).
  std::vector<std::vector<int64_t>> VertexFaces;
  int64_t NumFaces = 0, NumEdges = 0;
};
} // namespace sites
} // namespace vtkdf

#endif
