#include "LinearFactor/SurfaceCoordinates.h"

#include "Common/Barycentric.h"
#include "Common/PointTriangleDistance.h"
#include "Common/Vector3.h"
#include "LinearFactor/QueryTree.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>
#include <vector>

namespace vtkdf
{
namespace
{
/// The mesh's primitives grouped by cell: each cell's triangles, segments or points in
/// the mesh's order (primitive p: triangle p, segment p - T, point p - T - S).
struct CellPrimitives
{
  int64_t Triangles = 0, Segments = 0;
  std::vector<int64_t> Offsets; // cell c's primitives: Primitives[Offsets[c], Offsets[c + 1])
  std::vector<int64_t> Primitives;

  void Build(const MeshInput& mesh)
  {
    this->Triangles = static_cast<int64_t>(mesh.Triangles.size() / 3);
    this->Segments = static_cast<int64_t>(mesh.Segments.size() / 2);
    const LargeVector<int64_t>* runs[3] = {
      &mesh.TriangleCells, &mesh.SegmentCells, &mesh.VertexCells
    };
    int64_t cells = 0;
    for (const LargeVector<int64_t>* run : runs)
    {
      for (const int64_t cell : *run)
      {
        cells = std::max(cells, cell + 1);
      }
    }
    // A counting sort: the primitives of a cell keep the mesh's order.
    this->Offsets.assign(cells + 1, 0);
    for (const LargeVector<int64_t>* run : runs)
    {
      for (const int64_t cell : *run)
      {
        ++this->Offsets[cell + 1];
      }
    }
    for (int64_t c = 0; c < cells; ++c)
    {
      this->Offsets[c + 1] += this->Offsets[c];
    }
    this->Primitives.resize(this->Offsets[cells]);
    std::vector<int64_t> next(this->Offsets.begin(), this->Offsets.end() - 1);
    int64_t p = 0;
    for (const LargeVector<int64_t>* run : runs)
    {
      for (const int64_t cell : *run)
      {
        this->Primitives[next[cell]++] = p++;
      }
    }
  }

  int64_t Cells() const { return static_cast<int64_t>(this->Offsets.size()) - 1; }
  /// 0 triangle, 1 segment, 2 point.
  int Kind(int64_t p) const
  {
    return p < this->Triangles ? 0 : (p < this->Triangles + this->Segments ? 1 : 2);
  }
};

/// The closest point to x on primitive p of `mesh`, its squared distance and coordinates
/// on the primitive (a segment's third is 0, a point's (1, 0, 0)).
double ClosestOnPrimitive(const MeshInput& mesh,
  const CellPrimitives& index,
  int64_t p,
  const double x[3],
  double closest[3],
  double bary[3])
{
  const double* P = mesh.Points.data();
  const int kind = index.Kind(p);
  if (kind == 0)
  {
    const int64_t* t = &mesh.Triangles[3 * p];
    const double *a = P + 3 * t[0], *b = P + 3 * t[1], *c = P + 3 * t[2];
    int feature = InFace;
    const double d2 = SquaredDistanceToTriangle(x, a, b, c, closest, &feature);
    FeatureBarycentric(a, b, c, feature, closest, bary);
    return d2;
  }
  if (kind == 1)
  {
    const int64_t* s = &mesh.Segments[2 * (p - index.Triangles)];
    const double *a = P + 3 * s[0], *b = P + 3 * s[1];
    const double d2 = SquaredDistanceToSegment(x, a, b, closest);
    bary[1] = SegmentParameter(a, b, closest);
    bary[0] = 1 - bary[1];
    bary[2] = 0;
    return d2;
  }
  const double* a = P + 3 * mesh.Vertices[p - index.Triangles - index.Segments];
  std::copy(a, a + 3, closest);
  bary[0] = 1, bary[1] = bary[2] = 0;
  double d2 = 0;
  for (int k = 0; k < 3; ++k)
  {
    d2 += (x[k] - a[k]) * (x[k] - a[k]);
  }
  return d2;
}

/// The unit pseudonormal of the feature of the mesh at x, a point of the surface: the
/// gradient PointDistance gives there (0 where the feature has no face).
void SurfaceNormal(const nearest::QueryTree& tree, const double x[3], float gradient[3])
{
  int64_t index = -1;
  double best2 = 0, closest[3];
  int feature = InFace;
  tree.Nearest(x, HUGE_VAL, index, best2, closest, feature);
  double normal[3] = { 0, 0, 0 };
  if (index >= 0 && feature == InFace)
  {
    tree.FaceNormalOf(index, normal);
  }
  else if (index >= 0)
  {
    const nearest::Primitive& t = tree.Get(index);
    const int first = feature >= OnEdgeAB ? feature - OnEdgeAB : feature;
    const double* a = t.X + 3 * first;
    const double* b = feature >= OnEdgeAB ? t.X + 3 * ((first + 1) % 3) : nullptr;
    int64_t cell = tree.Cell(index);
    tree.FeatureCellAndNormal(a, b, cell, normal);
  }
  const double length = std::sqrt(Dot(normal, normal));
  for (int k = 0; k < 3; ++k)
  {
    gradient[k] = length > 0 ? static_cast<float>(normal[k] / length) : 0.0f;
  }
}
} // namespace

bool ComputeSurfaceCoordinates(const MeshInput& mesh,
  const SampleGrid& grid,
  const IndexBox& extent,
  const int64_t* cells,
  const float* distance,
  const SurfaceCoordinateArrays& arrays,
  const ParallelFor& parallelFor,
  std::string& error)
{
  CellPrimitives index;
  index.Build(mesh);
  const int64_t nx = extent.Size(0), ny = extent.Size(1);
  std::atomic<int64_t> unknownCells{ 0 };
  std::mutex surfaceMutex;
  std::vector<int64_t> onSurface; // samples whose closest point is the sample itself
  auto pass = [&](int64_t rowBegin, int64_t rowEnd)
  {
    std::vector<int64_t> surface;
    for (int64_t row = rowBegin; row < rowEnd; ++row)
    {
      const double y = grid.Coordinate(1, extent.Lo[1] + static_cast<int>(row % ny));
      const double z = grid.Coordinate(2, extent.Lo[2] + static_cast<int>(row / ny));
      for (int64_t at = row * nx, i = extent.Lo[0]; at < (row + 1) * nx; ++at, ++i)
      {
        const double x[3] = { grid.Coordinate(0, static_cast<int>(i)), y, z };
        const int64_t cell = cells[at];
        double best2 = HUGE_VAL, closest[3] = { NAN, NAN, NAN }, bary[3] = { NAN, NAN, NAN };
        int64_t sub = -1;
        if (cell >= index.Cells())
        {
          ++unknownCells;
        }
        else if (cell >= 0)
        {
          // Strictly nearer only: ties go to the cell's first primitive.
          int64_t kindStart = index.Offsets[cell];
          for (int64_t q = index.Offsets[cell]; q < index.Offsets[cell + 1]; ++q)
          {
            const int64_t p = index.Primitives[q];
            if (q > kindStart && index.Kind(p) != index.Kind(index.Primitives[q - 1]))
            {
              kindStart = q;
            }
            double c[3], b[3];
            const double d2 = ClosestOnPrimitive(mesh, index, p, x, c, b);
            if (d2 < best2)
            {
              best2 = d2, sub = q - kindStart;
              std::copy(c, c + 3, closest);
              std::copy(b, b + 3, bary);
            }
          }
        }
        if (arrays.ClosestSubTriangle)
        {
          arrays.ClosestSubTriangle[at] = sub;
        }
        if (arrays.ClosestBarycentric)
        {
          for (int k = 0; k < 3; ++k)
          {
            arrays.ClosestBarycentric[3 * at + k] = static_cast<float>(bary[k]);
          }
        }
        if (!arrays.Gradient)
        {
          continue;
        }
        double d[3];
        for (int k = 0; k < 3; ++k)
        {
          d[k] = x[k] - closest[k];
        }
        const double length = std::sqrt(Dot(d, d));
        if (sub >= 0 && best2 > 0 && length > 0)
        {
          const double sign = distance && std::signbit(distance[at]) ? -1 : 1;
          for (int k = 0; k < 3; ++k)
          {
            arrays.Gradient[3 * at + k] = static_cast<float>(sign * d[k] / length);
          }
        }
        else if (sub >= 0)
        {
          surface.push_back(at);
        }
        else
        {
          std::fill(arrays.Gradient + 3 * at, arrays.Gradient + 3 * at + 3, NAN);
        }
      }
    }
    if (!surface.empty())
    {
      std::lock_guard<std::mutex> lock(surfaceMutex);
      onSurface.insert(onSurface.end(), surface.begin(), surface.end());
    }
  };
  const int64_t rows = ny * extent.Size(2);
  parallelFor ? parallelFor(rows, std::max<int64_t>(1, 4096 / nx), pass) : pass(0, rows);
  if (unknownCells > 0)
  {
    error = "the field's closest cells are not cells of the mesh";
    return false;
  }
  if (onSurface.empty())
  {
    return true;
  }
  // Samples on the surface (rare but for grids aligned with flat faces): the feature's
  // pseudonormal, from the nearest-primitive tree.
  nearest::QueryTree tree;
  if (!tree.Build(mesh, parallelFor, error))
  {
    return false;
  }
  auto normals = [&](int64_t begin, int64_t end)
  {
    for (int64_t s = begin; s < end; ++s)
    {
      const int64_t at = onSurface[s];
      const int64_t i = at % nx, j = (at / nx) % ny, k = at / (nx * ny);
      const double x[3] = { grid.Coordinate(0, extent.Lo[0] + static_cast<int>(i)),
        grid.Coordinate(1, extent.Lo[1] + static_cast<int>(j)),
        grid.Coordinate(2, extent.Lo[2] + static_cast<int>(k)) };
      SurfaceNormal(tree, x, arrays.Gradient + 3 * at);
    }
  };
  const int64_t count = static_cast<int64_t>(onSurface.size());
  parallelFor ? parallelFor(count, 256, normals) : normals(0, count);
  return true;
}

} // namespace vtkdf
