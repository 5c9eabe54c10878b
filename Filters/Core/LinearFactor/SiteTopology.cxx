#include "LinearFactor/SiteBuilder.h"

#include "Common/FloatBounds.h"
#include "Common/Vector3.h"

#include <numeric>

namespace vtkdf
{
namespace sites
{
bool SiteBuilder::MergePoints(std::string& error)
{
  const double* P = this->P;
  const int64_t numPoints = this->NumPoints;
  std::vector<char> used(numPoints, 0);
  auto markUsed = [&](const LargeVector<int64_t>& ids) -> bool
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
  // Which points equal the one before them on the curve (in parallel: two random reads
  // each), then their canonical numbers in order.
  const int64_t numUsed = static_cast<int64_t>(order.size());
  std::vector<uint8_t> repeats(numUsed, 0);
  Run(this->For,
    numUsed,
    8192,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t k = std::max<int64_t>(begin, 1); k < end; ++k)
      {
        repeats[k] = std::equal(P + 3 * order[k], P + 3 * order[k] + 3, P + 3 * order[k - 1]);
      }
    });
  this->Canonical.assign(numPoints, -1);
  std::vector<int64_t> merged; // canonical index -> input point id
  for (int64_t k = 0; k < numUsed; ++k)
  {
    const int64_t id = order[k];
    if (repeats[k])
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
  if (nv >= int64_t(UINT32_MAX))
  {
    error = "the mesh has " + std::to_string(nv) + " distinct points, more than 2^32 - 2";
    return false;
  }
  this->NumVertices = nv;
  // The merged points, contiguous in curve order: every later pass reads them there.
  // Copied and bounded in fixed chunks in parallel (a minimum does not depend on the
  // order).
  this->Out.SitePoints.resize(3 * nv);
  const int64_t chunk = 65536, chunks = (nv + chunk - 1) / chunk;
  std::vector<std::array<double, 6>> chunkBounds(chunks);
  Run(this->For,
    chunks,
    1,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t k = begin; k < end; ++k)
      {
        std::array<double, 6>& b = chunkBounds[k];
        b = { HUGE_VAL, -HUGE_VAL, HUGE_VAL, -HUGE_VAL, HUGE_VAL, -HUGE_VAL };
        for (int64_t c = k * chunk; c < std::min(nv, (k + 1) * chunk); ++c)
        {
          const double* x = P + 3 * merged[c];
          std::copy(x, x + 3, &this->Out.SitePoints[3 * c]);
          for (int a = 0; a < 3; ++a)
          {
            b[2 * a] = std::min(b[2 * a], x[a]);
            b[2 * a + 1] = std::max(b[2 * a + 1], x[a]);
          }
        }
      }
    });
  this->Points = this->Out.SitePoints.data();
  double* bounds = this->Out.Bounds;
  for (int a = 0; a < 3; ++a)
  {
    bounds[2 * a] = this->X(0)[a];
    bounds[2 * a + 1] = this->X(0)[a];
    for (const std::array<double, 6>& b : chunkBounds)
    {
      bounds[2 * a] = std::min(bounds[2 * a], b[2 * a]);
      bounds[2 * a + 1] = std::max(bounds[2 * a + 1], b[2 * a + 1]);
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
  const LargeVector<int64_t>& triangles = this->In.Triangles;
  const int64_t numTriangles = static_cast<int64_t>(triangles.size() / 3);
  this->TriangleOrder.resize(numTriangles);
  // The keys in parallel (three random reads each), then counted and placed in order.
  LargeVector<uint32_t> keys(numTriangles);
  Run(this->For,
    numTriangles,
    8192,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t t = begin; t < end; ++t)
      {
        keys[t] = static_cast<uint32_t>(std::min(this->Canonical[triangles[3 * t]],
          std::min(this->Canonical[triangles[3 * t + 1]], this->Canonical[triangles[3 * t + 2]])));
      }
    });
  std::vector<int64_t> start(this->NumVertices + 1, 0);
  for (int64_t t = 0; t < numTriangles; ++t)
  {
    ++start[keys[t] + 1];
  }
  for (int64_t v = 0; v < this->NumVertices; ++v)
  {
    start[v + 1] += start[v];
  }
  for (int64_t t = 0; t < numTriangles; ++t)
  {
    this->TriangleOrder[start[keys[t]]++] = t;
  }
}

/// The merged corners of the triangle at position i of TriangleOrder.
void SiteBuilder::Corners(int64_t i, int64_t c[3]) const
{
  const int64_t* ids = &this->In.Triangles[3 * this->TriangleOrder[i]];
  c[0] = this->Canonical[ids[0]], c[1] = this->Canonical[ids[1]], c[2] = this->Canonical[ids[2]];
}

/// Whether merged corners c make a face (ProperFace).
bool SiteBuilder::IsFaceTriangle(const int64_t c[3]) const
{
  double n[3], area2;
  return c[0] != c[1] && c[1] != c[2] && c[2] != c[0] &&
    ProperFace(this->X(c[0]), this->X(c[1]), this->X(c[2]), this->Degenerate, n, area2);
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
void SiteBuilder::AddEdge(int64_t a, int64_t b, uint32_t source)
{
  if (a != b)
  {
    const int64_t at = this->EdgeFill[std::min(a, b)].fetch_add(1, std::memory_order_relaxed);
    this->Edges[at] = { static_cast<uint32_t>(std::max(a, b)), source };
  }
}

// Two passes over fixed chunks of TriangleOrder, so that faces are numbered as a serial
// loop would number them whatever the schedule: count faces and edge records, then write
// them. Edge records go straight into buckets by their smaller point (a counting sort);
// sorting each small bucket by (B, Source) then orders them all by (A, B, Source), whatever
// order the threads filled it in (the records of faces first in their group, by face).
constexpr int64_t Chunk = 4096;

bool SiteBuilder::CollectFacesAndEdges(std::string& error, MeshInput* release)
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
  const int64_t numFaces = chunkFaces[numChunks];
  const int64_t numLoose = numTriangles - numFaces + int64_t(this->In.Segments.size() / 2);
  if (numFaces + numLoose >= int64_t(UINT32_MAX))
  {
    error = "the mesh has " + std::to_string(numFaces + numLoose) +
      " triangles and segments, more than 2^32 - 2";
    return false;
  }
  this->NumFaces = numFaces;
  this->LooseCells.resize(numLoose);
  this->Out.FaceCorners.resize(numFaces);
  this->Out.FaceCells.resize(numFaces);
  this->Out.Statistics.DegenerateFaces = numTriangles - numFaces;
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
    { return x.B != y.B ? x.B < y.B : x.Source < y.Source; },
    this->For);
  // What only this pass reads.
  std::vector<int64_t>().swap(this->Canonical);
  std::vector<int64_t>().swap(this->TriangleOrder);
  std::vector<uint8_t>().swap(this->IsFace);
  std::vector<std::atomic<int64_t>>().swap(this->EdgeFill);
  if (release)
  {
    const std::array<double, 6> bounds = release->Bounds;
    *release = MeshInput();
    release->Bounds = bounds;
  }
  return true;
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
          this->IsFace[i] = this->IsFaceTriangle(c);
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
  const LargeVector<int64_t>& segments = this->In.Segments;
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
          uint32_t source;
          if (this->IsFace[i])
          {
            source = static_cast<uint32_t>(face++);
            for (int k = 0; k < 3; ++k)
            {
              this->Out.FaceCorners[source][k] = static_cast<uint32_t>(c[k]);
            }
            this->Out.FaceCells[source] = cell;
          }
          else
          {
            // The degenerate triangles before this one: i less the faces before it.
            const int64_t loose = i - face;
            this->LooseCells[loose] = cell;
            source = static_cast<uint32_t>(this->NumFaces + loose);
          }
          for (int k = 0; k < 3; ++k)
          {
            this->AddEdge(c[k], c[(k + 1) % 3], source);
          }
        }
      }
    });
  const LargeVector<int64_t>& segments = this->In.Segments;
  for (size_t s = 0; s < segments.size() / 2; ++s)
  {
    const int64_t a = this->Canonical[segments[2 * s]], b = this->Canonical[segments[2 * s + 1]];
    const int64_t cell = this->In.SegmentCells[s];
    this->UseVertex(a, cell);
    this->UseVertex(b, cell);
    const int64_t loose = numTriangles - this->NumFaces + static_cast<int64_t>(s);
    this->LooseCells[loose] = cell;
    this->AddEdge(a, b, static_cast<uint32_t>(this->NumFaces + loose));
  }
  for (size_t v = 0; v < this->In.Vertices.size(); ++v)
  {
    this->UseVertex(this->Canonical[this->In.Vertices[v]], this->In.VertexCells[v]);
  }
}
} // namespace sites
} // namespace vtkdf
