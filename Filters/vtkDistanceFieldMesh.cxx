#include "vtkDistanceFieldMesh.h"

#include "vtkAlgorithm.h"
#include "vtkArrayDispatch.h"
#include "vtkCallbackCommand.h"
#include "vtkCellArray.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkDataArrayRange.h"
#include "vtkDataObject.h"
#include "vtkErrorCode.h"
#include "vtkIdList.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolygon.h"
#include "vtkSMPTools.h"

#include "Voxels/VoxelGPU.h"
#include "Voxels/Voxelizer.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <mutex>
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

/// The first cell (in the filters' numbering: verts, lines, polys, strips) using `point`.
vtkIdType FirstCellUsing(vtkPolyData* input, vtkIdType point)
{
  vtkIdType cellId = 0;
  for (vtkCellArray* cells :
    { input->GetVerts(), input->GetLines(), input->GetPolys(), input->GetStrips() })
  {
    vtkIdType count;
    const vtkIdType* ids;
    for (cells->InitTraversal(); cells->GetNextCell(count, ids); ++cellId)
    {
      if (std::find(ids, ids + count, point) != ids + count)
      {
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
  bool any = false;
  vtkIdType cellId = 0;
  for (vtkCellArray* cells :
    { input->GetVerts(), input->GetLines(), input->GetPolys(), input->GetStrips() })
  {
    vtkIdType count;
    const vtkIdType* ids;
    for (cells->InitTraversal(); cells->GetNextCell(count, ids); ++cellId)
    {
      for (vtkIdType i = 0; i < count; ++i)
      {
        if (ids[i] < 0 || ids[i] >= numPoints)
        {
          error = "cell " + std::to_string(cellId) + " refers to point " + std::to_string(ids[i]) +
            ", but the mesh has " + std::to_string(numPoints) + " points";
          return false;
        }
        used[ids[i]] = 1;
        any = true;
      }
    }
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
    error = "point " + std::to_string(worker.FirstBad) + " (used by cell " +
      std::to_string(FirstCellUsing(input, worker.FirstBad)) + ") has " +
      (std::isnan(x[0] + x[1] + x[2]) ? "a NaN" : "an infinite") + " coordinate";
    return false;
  }
  return true;
}

bool MeshConversion::Run(vtkPolyData* input, const SampleGrid& grid, std::string& error)
{
  double bounds[6];
  if (!UsedPointBounds(input, bounds, error))
  {
    return false;
  }
  if (!CheckGrid(grid, bounds, error))
  {
    return false;
  }
  this->Frame = GridFrame::For(grid);
  this->Grid = this->Frame.Local(grid);
  for (int a = 0; a < 3; ++a)
  {
    this->LocalBounds[2 * a] = this->Frame.ToLocal(a, bounds[2 * a]);
    this->LocalBounds[2 * a + 1] = this->Frame.ToLocal(a, bounds[2 * a + 1]);
  }
  vtkPoints* points = input->GetPoints();
  const vtkIdType numPoints = points ? points->GetNumberOfPoints() : 0;
  this->Mesh.Points.resize(3 * numPoints);
  SMPFor(numPoints,
    4096,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t i = begin; i < end; ++i)
      {
        double* x = &this->Mesh.Points[3 * i];
        points->GetPoint(i, x);
        for (int a = 0; a < 3; ++a)
        {
          x[a] = this->Frame.ToLocal(a, x[a]);
        }
      }
    });
  vtkIdType cellId = 0;
  vtkIdType count;
  const vtkIdType* ids;
  vtkCellArray* verts = input->GetVerts();
  for (verts->InitTraversal(); verts->GetNextCell(count, ids); ++cellId)
  {
    this->EmptyVertices += count == 0;
    for (vtkIdType i = 0; i < count; ++i)
    {
      this->Mesh.Vertices.push_back(ids[i]);
      this->Mesh.VertexCells.push_back(cellId);
    }
  }
  vtkCellArray* lines = input->GetLines();
  for (lines->InitTraversal(); lines->GetNextCell(count, ids); ++cellId)
  {
    this->ShortLines += count < 2;
    for (vtkIdType i = 0; i + 1 < count; ++i)
    {
      this->Mesh.Segments.insert(this->Mesh.Segments.end(), { ids[i], ids[i + 1] });
      this->Mesh.SegmentCells.push_back(cellId);
    }
  }
  vtkNew<vtkPolygon> polygon;
  vtkNew<vtkIdList> triangles;
  vtkCellArray* polys = input->GetPolys();
  for (polys->InitTraversal(); polys->GetNextCell(count, ids); ++cellId)
  {
    if (count < 3)
    {
      ++this->ShortPolygons;
      continue;
    }
    if (count == 3)
    {
      this->AddTriangle(ids[0], ids[1], ids[2], cellId);
      continue;
    }
    // Concave polygons need an ear-cut; a fan covers what the ear-cut rejects.
    polygon->GetPointIds()->SetNumberOfIds(count);
    polygon->GetPoints()->SetNumberOfPoints(count);
    for (vtkIdType i = 0; i < count; ++i)
    {
      polygon->GetPointIds()->SetId(i, i);
      polygon->GetPoints()->SetPoint(i, &this->Mesh.Points[3 * ids[i]]);
    }
    if (polygon->Triangulate(triangles) && triangles->GetNumberOfIds() == 3 * (count - 2))
    {
      for (vtkIdType t = 0; t < triangles->GetNumberOfIds(); t += 3)
      {
        this->AddTriangle(ids[triangles->GetId(t)],
          ids[triangles->GetId(t + 1)],
          ids[triangles->GetId(t + 2)],
          cellId);
      }
    }
    else
    {
      for (vtkIdType i = 1; i + 1 < count; ++i)
      {
        this->AddTriangle(ids[0], ids[i], ids[i + 1], cellId);
      }
    }
  }
  vtkCellArray* strips = input->GetStrips();
  for (strips->InitTraversal(); strips->GetNextCell(count, ids); ++cellId)
  {
    this->ShortStrips += count < 3;
    for (vtkIdType i = 0; i + 2 < count; ++i)
    {
      if (i % 2 == 0)
      {
        this->AddTriangle(ids[i], ids[i + 1], ids[i + 2], cellId);
      }
      else
      {
        this->AddTriangle(ids[i + 1], ids[i], ids[i + 2], cellId);
      }
    }
  }
  return true;
}

void MeshConversion::AddTriangle(vtkIdType a, vtkIdType b, vtkIdType c, vtkIdType cell)
{
  this->Mesh.Triangles.insert(this->Mesh.Triangles.end(), { a, b, c });
  this->Mesh.TriangleCells.push_back(cell);
}

std::string MeshConversion::IgnoredCells() const
{
  if (!this->ShortPolygons && !this->ShortLines && !this->ShortStrips && !this->EmptyVertices)
  {
    return std::string();
  }
  std::ostringstream text;
  text << "Ignored cells it cannot use: " << this->ShortPolygons
       << " polygons with fewer than 3 points, " << this->ShortLines
       << " lines with fewer than 2 points, " << this->ShortStrips
       << " triangle strips with fewer than 3 points, " << this->EmptyVertices
       << " vertex cells without points. The other cells are used.";
  return text.str();
}

bool BuildSites(vtkPolyData* input,
  Culling culling,
  const SampleGrid& grid,
  MeshConversion& conversion,
  MeshSites& sites,
  std::string& warning,
  std::string& error)
{
  if (!conversion.Run(input, grid, error))
  {
    error = "Invalid input: " + error + ".";
    return false;
  }
  warning = conversion.IgnoredCells();
  // The planes are used between the mesh and the samples: the diagonal of the box that
  // holds both bounds that distance (all in the local frame).
  const SampleGrid& local = conversion.Grid;
  double diagonal2 = 0;
  for (int a = 0; a < 3; ++a)
  {
    const double g0 = local.Coordinate(a, local.Whole.Lo[a]);
    const double g1 = local.Coordinate(a, local.Whole.Hi[a]);
    const double lo = std::min(std::min(g0, g1), conversion.LocalBounds[2 * a]);
    const double hi = std::max(std::max(g0, g1), conversion.LocalBounds[2 * a + 1]);
    diagonal2 += (hi - lo) * (hi - lo);
  }
  const double slack = MeshSites::PlaneSlack(1e-4 * local.MinSpacing(), std::sqrt(diagonal2));
  if (!sites.Build(conversion.Mesh, culling, slack, error, SMPFor))
  {
    error = "Invalid input mesh: " + error + ".";
    return false;
  }
  if (sites.Sites.size() >= 0xffffffffu)
  {
    error = "The mesh has " + std::to_string(sites.Sites.size()) + " sites, more than 2^32 - 1.";
    return false;
  }
  return true;
}

vtkDataArray* SampleArray(vtkImageData* image, const char* name, int components, std::string& error)
{
  vtkAbstractArray* abstract = image->GetPointData()->GetAbstractArray(name);
  if (!abstract)
  {
    error = std::string("The input image has no point-data array named ") + name + ".";
    return nullptr;
  }
  vtkDataArray* array = vtkDataArray::SafeDownCast(abstract);
  if (!array)
  {
    error = std::string("The ") + name + " array is a " + abstract->GetClassName() +
      ", not a numeric array.";
    return nullptr;
  }
  if (array->GetNumberOfComponents() != components)
  {
    error = std::string("The ") + name + " array has " +
      std::to_string(array->GetNumberOfComponents()) + " components; it needs " +
      std::to_string(components) + ".";
    return nullptr;
  }
  if (array->GetNumberOfTuples() != image->GetNumberOfPoints())
  {
    error = std::string("The ") + name + " array has " +
      std::to_string(array->GetNumberOfTuples()) + " values for " +
      std::to_string(image->GetNumberOfPoints()) + " samples.";
    return nullptr;
  }
  return array;
}

std::string TrianglesOnly(const MeshConversion& conversion)
{
  std::string warning = conversion.IgnoredCells();
  const size_t flat = conversion.Mesh.Segments.size() / 2 + conversion.Mesh.Vertices.size();
  if (flat > 0)
  {
    warning += (warning.empty() ? "" : " ") +
      std::string("Vertex and line cells have no area to voxelize: ") + std::to_string(flat) +
      " points and segments ignored.";
  }
  return warning;
}

std::string FarTriangles(const VoxelizeStatistics& statistics)
{
  return statistics.FarTriangles > 0 ? std::to_string(statistics.FarTriangles) +
      " triangles with a vertex more than 2^22 cells from the grid were ignored."
                                     : std::string();
}

bool VoxelizeMesh(vtkPolyData* input,
  const SampleGrid& grid,
  HeadlessGL* gpu,
  BitVolume* boundary,
  BitVolume* solid,
  std::string& error,
  std::string& warning)
{
  MeshConversion conversion;
  if (!conversion.Run(input, grid, error))
  {
    return false;
  }
  warning = TrianglesOnly(conversion);
  VoxelizeStatistics statistics;
  const bool ok = gpu
    ? VoxelizeGPU(*gpu, conversion.Mesh, conversion.Grid, boundary, solid, statistics, error)
    : VoxelizeCPU(conversion.Mesh, conversion.Grid, boundary, solid, SMPFor, statistics, error);
  const std::string far = FarTriangles(statistics);
  warning += (warning.empty() || far.empty() ? "" : " ") + far;
  return ok;
}

void BitsToMask(const BitVolume& bits, const SampleGrid& grid, const IndexBox& extent, uint8_t* out)
{
  // Tiles of 64 lanes (x) by 64 voxels (z), transposed so that each row of bits runs
  // along x, the order of the output.
  const int nx = extent.Size(0), ny = extent.Size(1), nz = extent.Size(2);
  const int zBlocks = (nz + 63) / 64;
  SMPFor(int64_t(ny) * zBlocks,
    1,
    [&](int64_t begin, int64_t end)
    {
      uint64_t tile[64];
      for (int64_t id = begin; id < end; ++id)
      {
        const int j = static_cast<int>(id % ny), z0 = 64 * static_cast<int>(id / ny);
        const int y = extent.Lo[1] + j - grid.Whole.Lo[1];
        const int zLane = extent.Lo[2] + z0 - grid.Whole.Lo[2];
        for (int x0 = 0; x0 < nx; x0 += 64)
        {
          for (int r = 0; r < 64; ++r)
          {
            tile[r] =
              x0 + r < nx ? bits.Bits64(extent.Lo[0] + x0 + r - grid.Whole.Lo[0], y, zLane) : 0;
          }
          TransposeBits64(tile);
          for (int c = 0; c < 64 && z0 + c < nz; ++c)
          {
            uint8_t* row = out + (int64_t(z0 + c) * ny + j) * nx + x0;
            const int count = std::min(64, nx - x0);
            for (int b = 0; b < count; ++b)
            {
              row[b] = static_cast<uint8_t>((tile[c] >> b) & 1u);
            }
          }
        }
      }
    });
}

void AllocateTuples(vtkDataArray* array, vtkIdType tuples)
{
  array->SetNumberOfTuples(tuples);
  if (array->GetNumberOfTuples() != tuples)
  {
    throw std::bad_alloc();
  }
}

int RunOrEmpty(vtkDataObject* output,
  const std::function<int()>& compute,
  const std::function<void(unsigned long)>& setErrorCode)
{
  setErrorCode(vtkErrorCode::NoError);
  const int ok = compute();
  if (!ok)
  {
    output->Initialize();
    setErrorCode(vtkErrorCode::UserError);
  }
  return ok;
}

void SMPFor(int64_t n, int64_t grain, const std::function<void(int64_t, int64_t)>& body)
{
  std::atomic<bool> failed{ false };
  std::exception_ptr first;
  std::mutex lock;
  vtkSMPTools::For(0,
    static_cast<vtkIdType>(n),
    static_cast<vtkIdType>(grain),
    [&](vtkIdType begin, vtkIdType end)
    {
      if (failed.load(std::memory_order_relaxed))
      {
        return;
      }
      try
      {
        body(begin, end);
      }
      catch (...)
      {
        std::lock_guard<std::mutex> guard(lock);
        if (!failed.exchange(true))
        {
          first = std::current_exception();
        }
      }
    });
  if (first)
  {
    std::rethrow_exception(first);
  }
}

InnerErrors::InnerErrors(vtkAlgorithm* inner)
{
  this->Command = vtkSmartPointer<vtkCallbackCommand>::New();
  this->Command->SetClientData(&this->Text);
  this->Command->SetCallback(
    [](vtkObject*, unsigned long, void* clientData, void* callData)
    {
      auto* text = static_cast<std::string*>(clientData);
      if (callData && text->empty())
      {
        // "ERROR: In FILE, line N\nCLASS (ADDRESS): MESSAGE\n": keep MESSAGE.
        std::string message = static_cast<const char*>(callData);
        const size_t start = message.find("): ");
        message = start == std::string::npos ? message : message.substr(start + 3);
        while (!message.empty() && (message.back() == '\n' || message.back() == ' '))
        {
          message.pop_back();
        }
        *text = message;
      }
    });
  inner->AddObserver(vtkCommand::ErrorEvent, this->Command);
}

std::string InnerErrors::Message(const char* fallback) const
{
  return this->Text.empty() ? std::string(fallback) : this->Text;
}

bool ChooseContext(int backend, HeadlessGL*& gl, std::string& error)
{
  gl = nullptr;
  if (backend == 2)
  {
    return true;
  }
  std::string why;
  HeadlessGL* context = HeadlessGL::Get(why);
  if (backend == 1 && !context)
  {
    error = "Backend is GPU but " + why;
    return false;
  }
  gl = backend == 1 || (context && !context->IsSoftware()) ? context : nullptr;
  return true;
}

} // namespace vtkdf
