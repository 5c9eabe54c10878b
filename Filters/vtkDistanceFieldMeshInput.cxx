#include "vtkDistanceFieldMeshInput.h"

#include "vtkArrayDispatch.h"
#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkDataArrayRange.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkTypeInt32Array.h"
#include "vtkTypeInt64Array.h"

#include "vtkDistanceFieldExecution.h"

#include "Polygons/PolygonTriangulation.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <sstream>

namespace vtkdf
{

namespace
{
/// The bounds of the points marked in `used`, or the first such point that is not
/// finite (-1 when all are): one pass over the typed point array.
struct UsedBoundsWorker
{
  const std::vector<uint8_t>* Used;
  double* Bounds;
  vtkIdType FirstBad = -1;

  template<typename ArrayT>
  void operator()(ArrayT* points)
  {
    const auto tuples = vtk::DataArrayTupleRange<3>(points);
    const std::vector<uint8_t>& used = *this->Used;
    vtkIdType id = 0;
    for (const auto x : tuples)
    {
      if (used[id])
      {
        const double p[3] = {
          static_cast<double>(x[0]), static_cast<double>(x[1]), static_cast<double>(x[2])
        };
        if (!(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2])))
        {
          this->FirstBad = id;
          return;
        }
        for (int a = 0; a < 3; ++a)
        {
          this->Bounds[2 * a] = std::min(this->Bounds[2 * a], p[a]);
          this->Bounds[2 * a + 1] = std::max(this->Bounds[2 * a + 1], p[a]);
        }
      }
      ++id;
    }
  }
};

/// Calls `body(offsets, ids, numIds)` with a cell array's raw arrays, in whichever
/// storage (64- or 32-bit) it has.
template<typename Body>
void WithRawArrays(vtkCellArray* cells, const Body& body)
{
  if (cells->IsStorage64Bit())
  {
    body(cells->GetOffsetsArray64()->GetPointer(0),
      cells->GetConnectivityArray64()->GetPointer(0),
      cells->GetConnectivityArray64()->GetNumberOfValues());
  }
  else
  {
    body(cells->GetOffsetsArray32()->GetPointer(0),
      cells->GetConnectivityArray32()->GetPointer(0),
      cells->GetConnectivityArray32()->GetNumberOfValues());
  }
}

/// Calls `body(ids, count)` with the point ids of a cell array's cells: the connectivity
/// up to the last cell's end.
template<typename Body>
void ForConnectivity(vtkCellArray* cells, const Body& body)
{
  const vtkIdType numCells = cells->GetNumberOfCells();
  WithRawArrays(cells,
    [&](const auto* offsets, const auto* ids, vtkIdType numIds)
    {
      const vtkIdType end = numCells > 0 ? static_cast<vtkIdType>(offsets[numCells]) : 0;
      body(ids, std::min(end, numIds));
    });
}

/// Marks the points that the cells use in `used`, in parallel; false when an id is out
/// of range (the caller then finds the first such cell in order).
bool MarkUsedPoints(vtkPolyData* input, vtkIdType numPoints, std::vector<uint8_t>& used)
{
  std::atomic<bool> inRange{ true };
  for (vtkCellArray* cells :
    { input->GetVerts(), input->GetLines(), input->GetPolys(), input->GetStrips() })
  {
    ForConnectivity(cells,
      [&](const auto* ids, vtkIdType count)
      {
        SMPFor(count,
          1 << 14,
          [&](int64_t begin, int64_t end)
          {
            bool ok = true;
            for (int64_t i = begin; i < end; ++i)
            {
              const vtkIdType id = ids[i];
              const bool valid = id >= 0 && id < numPoints;
              ok = ok && valid;
              if (valid)
              {
                // Threads may mark the same point: the same value, stored atomically.
                __atomic_store_n(&used[id], uint8_t(1), __ATOMIC_RELAXED);
              }
            }
            if (!ok)
            {
              inRange = false;
            }
          });
      });
  }
  return inRange;
}

/// The first cell (in the filters' numbering: verts, lines, polys, strips) with a point
/// id for which `match(id)` holds, and that id in `found`; -1 when there is none.
template<typename Match>
vtkIdType FirstCellWith(vtkPolyData* input, const Match& match, vtkIdType& found)
{
  vtkIdType cellId = 0;
  for (vtkCellArray* cells :
    { input->GetVerts(), input->GetLines(), input->GetPolys(), input->GetStrips() })
  {
    vtkIdType count;
    const vtkIdType* ids;
    for (cells->InitTraversal(); cells->GetNextCell(count, ids); ++cellId)
    {
      const vtkIdType* at = std::find_if(ids, ids + count, match);
      if (at != ids + count)
      {
        found = *at;
        return cellId;
      }
    }
  }
  return -1;
}
} // namespace

bool UsedPointBounds(vtkPolyData* input, double bounds[6], std::string& error)
{
  const vtkIdType numPoints = input->GetPoints() ? input->GetNumberOfPoints() : 0;
  for (int a = 0; a < 3; ++a)
  {
    bounds[2 * a] = VTK_DOUBLE_MAX;
    bounds[2 * a + 1] = -VTK_DOUBLE_MAX;
  }
  // The ids first, checked before any point is read (a file may hold any number
  // there); then each used point once, from the typed array.
  std::vector<uint8_t> used(numPoints, 0);
  if (!MarkUsedPoints(input, numPoints, used))
  {
    // The first bad id in the filters' cell order, for the message.
    vtkIdType id = -1;
    const vtkIdType cellId = FirstCellWith(
      input, [&](vtkIdType i) { return i < 0 || i >= numPoints; }, id);
    if (cellId >= 0)
    {
      error = "cell " + std::to_string(cellId) + " refers to point " + std::to_string(id) +
        ", but the mesh has " + std::to_string(numPoints) + " points";
      return false;
    }
  }
  bool any = false;
  for (vtkCellArray* cells :
    { input->GetVerts(), input->GetLines(), input->GetPolys(), input->GetStrips() })
  {
    ForConnectivity(cells, [&](const auto*, vtkIdType count) { any = any || count > 0; });
  }
  if (!any)
  {
    error = "no cell of the mesh uses a point";
    return false;
  }
  UsedBoundsWorker worker{ &used, bounds };
  vtkDataArray* points = input->GetPoints()->GetData();
  if (!vtkArrayDispatch::DispatchByValueType<vtkArrayDispatch::Reals>::Execute(points, worker))
  {
    worker(points); // other value types, through the vtkDataArray API
  }
  if (worker.FirstBad >= 0)
  {
    double x[3];
    input->GetPoint(worker.FirstBad, x);
    vtkIdType unused;
    error = "point " + std::to_string(worker.FirstBad) + " (used by cell " +
      std::to_string(FirstCellWith(
        input, [&](vtkIdType i) { return i == worker.FirstBad; }, unused)) +
      ") has " + (std::isnan(x[0] + x[1] + x[2]) ? "a NaN" : "an infinite") + " coordinate";
    return false;
  }
  return true;
}

namespace
{
/// Appends the cells of `input` to `mesh`, in the filters' numbering.
class CellCopy
{
public:
  CellCopy(vtkPolyData* input, const GridFrame& frame, MeshInput& mesh, MeshCopyReport& report)
    : Input(input)
    , Frame(frame)
    , Mesh(mesh)
    , Ignored(report)
  {
  }

  /// False and `error` when a polygon has no triangulation.
  bool Run(std::string& error)
  {
    vtkIdType cellId = 0;
    this->Vertices(cellId);
    this->Lines(cellId);
    if (!this->Polygons(cellId, error))
    {
      return false;
    }
    this->Strips(cellId);
    return true;
  }

private:
  void Vertices(vtkIdType& cellId)
  {
    vtkIdType count;
    const vtkIdType* ids;
    vtkCellArray* verts = this->Input->GetVerts();
    for (verts->InitTraversal(); verts->GetNextCell(count, ids); ++cellId)
    {
      this->Ignored.EmptyVertices += count == 0;
      for (vtkIdType i = 0; i < count; ++i)
      {
        this->Mesh.Vertices.push_back(ids[i]);
        this->Mesh.VertexCells.push_back(cellId);
      }
    }
  }

  void Lines(vtkIdType& cellId)
  {
    vtkIdType count;
    const vtkIdType* ids;
    vtkCellArray* lines = this->Input->GetLines();
    for (lines->InitTraversal(); lines->GetNextCell(count, ids); ++cellId)
    {
      this->Ignored.ShortLines += count < 2;
      for (vtkIdType i = 0; i + 1 < count; ++i)
      {
        this->Mesh.Segments.insert(this->Mesh.Segments.end(), { ids[i], ids[i + 1] });
        this->Mesh.SegmentCells.push_back(cellId);
      }
    }
  }

  bool Polygons(vtkIdType& cellId, std::string& error)
  {
    if (this->CopyTriangles(cellId))
    {
      return true;
    }
    vtkIdType count;
    const vtkIdType* ids;
    vtkCellArray* polys = this->Input->GetPolys();
    for (polys->InitTraversal(); polys->GetNextCell(count, ids); ++cellId)
    {
      if (count < 3)
      {
        ++this->Ignored.ShortPolygons;
      }
      else if (count == 3)
      {
        this->Triangle(ids[0], ids[1], ids[2], cellId);
      }
      else if (!this->Polygon(count, ids, cellId, error))
      {
        return false;
      }
    }
    return true;
  }

  /// When every polygon is a triangle (offsets 0, 3, 6, ...), the usual case: their ids
  /// copied in parallel, and `cellId` moved past them. False (nothing done) otherwise.
  bool CopyTriangles(vtkIdType& cellId)
  {
    vtkCellArray* polys = this->Input->GetPolys();
    const vtkIdType n = polys->GetNumberOfCells();
    bool copied = false;
    auto copy = [&](const auto* offsets, const auto* ids, vtkIdType numIds)
    {
      if (n == 0 || numIds < 3 * n)
      {
        return;
      }
      std::atomic<bool> triangles{ true };
      SMPFor(n + 1,
        1 << 14,
        [&](int64_t begin, int64_t end)
        {
          bool all = true;
          for (int64_t i = begin; i < end; ++i)
          {
            all = all && offsets[i] == 3 * i;
          }
          if (!all)
          {
            triangles = false;
          }
        });
      if (!triangles)
      {
        return;
      }
      vtkdf::LargeVector<int64_t>& out = this->Mesh.Triangles;
      vtkdf::LargeVector<int64_t>& outCells = this->Mesh.TriangleCells;
      const size_t base = out.size(), baseCells = outCells.size();
      out.resize(base + 3 * n);
      outCells.resize(baseCells + n);
      const vtkIdType first = cellId;
      SMPFor(n,
        1 << 14,
        [&](int64_t begin, int64_t end)
        {
          for (int64_t i = begin; i < end; ++i)
          {
            for (int k = 0; k < 3; ++k)
            {
              out[base + 3 * i + k] = ids[3 * i + k];
            }
            outCells[baseCells + i] = first + i;
          }
        });
      cellId += n;
      copied = true;
    };
    WithRawArrays(polys, copy);
    return copied;
  }

  /// Ear clipping in the polygon's best-fit plane (concave polygons included); never a
  /// fan, which covers area outside a concave polygon.
  bool Polygon(vtkIdType count, const vtkIdType* ids, vtkIdType cellId, std::string& error)
  {
    this->Corners.resize(3 * count);
    for (vtkIdType i = 0; i < count; ++i)
    {
      const double* world = &this->Mesh.Points[3 * ids[i]];
      for (int a = 0; a < 3; ++a)
      {
        this->Corners[3 * i + a] = this->Frame.ToLocal(a, world[a]);
      }
    }
    if (!this->Cut.Triangulate(this->Corners.data(), count))
    {
      error = "polygon cell " + std::to_string(cellId) + " (" + std::to_string(count) +
        " corners) has no triangulation along its edges: " + this->Cut.Problem() +
        ". Split it into simple polygons or triangles";
      return false;
    }
    if (this->Cut.Planarity() > PolygonPlanarityTolerance)
    {
      ++this->Ignored.NonPlanarPolygons;
      if (this->Cut.Planarity() > this->Ignored.FarthestPlanarity)
      {
        this->Ignored.FarthestPlanarity = this->Cut.Planarity();
        this->Ignored.FarthestNonPlanarCell = cellId;
      }
    }
    const std::vector<int64_t>& corners = this->Cut.Triangles();
    for (size_t t = 0; t < corners.size(); t += 3)
    {
      this->Triangle(ids[corners[t]], ids[corners[t + 1]], ids[corners[t + 2]], cellId);
    }
    return true;
  }

  void Strips(vtkIdType& cellId)
  {
    vtkIdType count;
    const vtkIdType* ids;
    vtkCellArray* strips = this->Input->GetStrips();
    for (strips->InitTraversal(); strips->GetNextCell(count, ids); ++cellId)
    {
      this->Ignored.ShortStrips += count < 3;
      for (vtkIdType i = 0; i + 2 < count; ++i)
      {
        if (i % 2 == 0)
        {
          this->Triangle(ids[i], ids[i + 1], ids[i + 2], cellId);
        }
        else
        {
          this->Triangle(ids[i + 1], ids[i], ids[i + 2], cellId);
        }
      }
    }
  }

  void Triangle(vtkIdType a, vtkIdType b, vtkIdType c, vtkIdType cell)
  {
    this->Mesh.Triangles.insert(this->Mesh.Triangles.end(), { a, b, c });
    this->Mesh.TriangleCells.push_back(cell);
  }

  vtkPolyData* Input;
  const GridFrame& Frame;
  MeshInput& Mesh;
  MeshCopyReport& Ignored;
  PolygonTriangulation Cut;
  std::vector<double> Corners;
};
} // namespace

bool CopyMesh(vtkPolyData* input,
  const double bounds[6],
  const GridFrame& frame,
  MeshInput& mesh,
  MeshCopyReport& report,
  std::string& error)
{
  mesh = MeshInput();
  report = MeshCopyReport();
  std::copy(bounds, bounds + 6, mesh.Bounds.begin());
  vtkPoints* points = input->GetPoints();
  const vtkIdType numPoints = points ? points->GetNumberOfPoints() : 0;
  mesh.Points.resize(3 * numPoints);
  SMPFor(numPoints,
    4096,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t i = begin; i < end; ++i)
      {
        points->GetPoint(i, &mesh.Points[3 * i]);
      }
    });
  return CellCopy(input, frame, mesh, report).Run(error);
}

std::string MeshCopyReport::Warnings() const
{
  std::ostringstream text;
  if (this->NonPlanarPolygons)
  {
    text << this->NonPlanarPolygons
         << (this->NonPlanarPolygons == 1 ? " polygon is" : " polygons are") << " not planar (cell "
         << this->FarthestNonPlanarCell << " lies up to " << this->FarthestPlanarity
         << " of its size from its best-fit plane): each is taken as the triangles of its "
            "projection on that plane, through its own corners.";
  }
  if (!this->ShortPolygons && !this->ShortLines && !this->ShortStrips && !this->EmptyVertices)
  {
    return text.str();
  }
  text << (this->NonPlanarPolygons ? " " : "");
  text << "Ignored cells it cannot use: " << this->ShortPolygons
       << " polygons with fewer than 3 points, " << this->ShortLines
       << " lines with fewer than 2 points, " << this->ShortStrips
       << " triangle strips with fewer than 3 points, " << this->EmptyVertices
       << " vertex cells without points. The other cells are used.";
  return text.str();
}

} // namespace vtkdf
