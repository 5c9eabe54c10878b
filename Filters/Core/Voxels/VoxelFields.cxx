#include "Voxels/VoxelFields.h"

#include "GL/HeadlessGL.h"
#include "Voxels/VoxelGPU.h"
#include "Voxels/Voxelizer.h"

namespace vtkdf
{

namespace
{
/// Checks the grid with the mesh and moves the mesh into the grid's local frame; the
/// grid there is `local`. The warning names what a voxelizer ignores (vertices and line
/// segments have no area).
bool ToLocalFrame(MeshInput& mesh,
  const SampleGrid& grid,
  const ParallelFor& parallelFor,
  SampleGrid& local,
  VoxelReport& report,
  std::string& error)
{
  if (!CheckGrid(grid, mesh.Bounds.data(), error))
  {
    error = "Invalid input: " + error + ".";
    return false;
  }
  const GridFrame frame = GridFrame::For(grid);
  local = frame.Local(grid);
  MoveToLocalFrame(mesh, frame, parallelFor);
  const size_t flat = mesh.Segments.size() / 2 + mesh.Vertices.size();
  if (flat > 0)
  {
    report.Warning = "Vertex and line cells have no area to voxelize: " + std::to_string(flat) +
      " points and segments ignored.";
  }
  return true;
}

/// Adds the far triangles to the report's warning.
void ReportFarTriangles(const VoxelizeStatistics& statistics, VoxelReport& report)
{
  report.FarTriangles = statistics.FarTriangles;
  if (statistics.FarTriangles > 0)
  {
    report.Warning += (report.Warning.empty() ? "" : " ") +
      std::to_string(statistics.FarTriangles) +
      " triangles with a vertex more than 2^22 cells from the grid were ignored.";
  }
}

const char* const EmptyZeroSet =
  "The zero set is empty: no Boundary voxel is set, so no distance can be propagated.";

/// The bits of `from` (over the box `box`) on the voxels of `part`, a box within it.
BitVolume ExtractBits(const BitVolume& from,
  const IndexBox& box,
  const IndexBox& part,
  const ParallelFor& parallelFor)
{
  BitVolume to(part.Size(0), part.Size(1), part.Size(2));
  const int dx = part.Lo[0] - box.Lo[0], dy = part.Lo[1] - box.Lo[1], dz = part.Lo[2] - box.Lo[2];
  auto lanes = [&](int64_t begin, int64_t end)
  {
    for (int64_t lane = begin; lane < end; ++lane)
    {
      const int x = static_cast<int>(lane % part.Size(0));
      const int y = static_cast<int>(lane / part.Size(0));
      // A word at a time: the part's lane is the source lane from voxel dz on.
      uint64_t* words = to.Lane(x, y);
      for (int w = 0; w < to.WordsPerLane(); ++w)
      {
        words[w] = from.Bits64(x + dx, y + dy, dz + 64 * w);
      }
      words[to.WordsPerLane() - 1] &= to.LastWordMask();
    }
  };
  const int64_t count = int64_t(part.Size(0)) * part.Size(1);
  parallelFor ? parallelFor(count, 256, lanes) : lanes(0, count);
  return to;
}

/// Whether every voxel of `piece` holds a distance of at most `layers` in `values`
/// (laid out over `box`).
bool AllReached(const int32_t* values, const IndexBox& box, const IndexBox& piece, int layers)
{
  const int64_t nx = box.Size(0), ny = box.Size(1);
  for (int k = piece.Lo[2]; k <= piece.Hi[2]; ++k)
  {
    for (int j = piece.Lo[1]; j <= piece.Hi[1]; ++j)
    {
      const int32_t* row =
        values + ((k - box.Lo[2]) * ny + (j - box.Lo[1])) * nx + (piece.Lo[0] - box.Lo[0]);
      for (int i = 0; i < piece.Size(0); ++i)
      {
        if (row[i] > layers || row[i] < -layers)
        {
          return false;
        }
      }
    }
  }
  return true;
}

/// The chamfer field on the voxels of `needed` (a box of the masks' grid) from the masks
/// there, with request.MaximumLayers layers, into `output(needed)`.
bool PropagateBox(const BitVolume& boundary,
  const BitVolume* solid,
  const IndexBox& needed,
  const ChamferRequest& request,
  HeadlessGL* gl,
  const ChamferOutput& output,
  const Execution& execution,
  ChamferReport& report,
  std::string& error)
{
  const BitVolume partBoundary = ExtractBits(boundary, request.Grid.Whole, needed, execution.For);
  BitVolume partSolid;
  if (solid)
  {
    partSolid = ExtractBits(*solid, request.Grid.Whole, needed, execution.For);
  }
  int32_t* values = output(needed);
  ChamferRequest part = request;
  part.Grid.Whole = needed;
  if (partBoundary.Any())
  {
    const VoxelReport voxels = report.Voxels;
    const bool ok = ComputeChamferField(
      partBoundary, solid ? &partSolid : nullptr, part, gl, values, execution, report, error);
    report.Voxels = voxels;
    return ok;
  }
  // No zero-set voxel within MaximumLayers of the piece: none is reached.
  report.Result = ChamferResult();
  const int32_t unreached = request.Unreached();
  const int nx = needed.Size(0), ny = needed.Size(1), nz = needed.Size(2);
  for (int z = 0; z < nz; ++z)
  {
    for (int y = 0; y < ny; ++y)
    {
      for (int x = 0; x < nx; ++x)
      {
        const bool inside = request.Signed && solid && partSolid.Get(x, y, z);
        *values++ = inside ? -unreached : unreached;
      }
    }
  }
  return true;
}
} // namespace

bool VoxelizeMesh(MeshInput mesh,
  const SampleGrid& grid,
  HeadlessGL* gl,
  BitVolume* boundary,
  BitVolume* solid,
  const Execution& execution,
  VoxelReport& report,
  std::string& error)
{
  report = VoxelReport();
  SampleGrid local;
  if (!ToLocalFrame(mesh, grid, execution.For, local, report, error))
  {
    return false;
  }
  VoxelizeStatistics statistics;
  if (gl)
  {
    if (!VoxelizeGPU(*gl, mesh, local, boundary, solid, statistics, error))
    {
      error = "The GPU voxelizer (" + gl->Renderer() + ") failed: " + error + ".";
      return false;
    }
  }
  else if (!VoxelizeCPU(mesh, local, boundary, solid, execution.For, statistics, error))
  {
    error = "Invalid input: " + error + ".";
    return false;
  }
  ReportFarTriangles(statistics, report);
  return true;
}

bool ComputeChamferField(MeshInput mesh,
  const ChamferRequest& request,
  HeadlessGL* gl,
  int32_t* distance,
  BitVolume& boundary,
  BitVolume& solid,
  bool keepMasks,
  const Execution& execution,
  ChamferReport& report,
  std::string& error)
{
  report = ChamferReport();
  if (!gl)
  {
    // Voxelized on the CPU, then propagated from the masks.
    if (!VoxelizeMesh(std::move(mesh),
          request.Grid,
          nullptr,
          &boundary,
          request.Signed ? &solid : nullptr,
          execution,
          report.Voxels,
          error))
    {
      return false;
    }
    const VoxelReport voxels = report.Voxels;
    if (!boundary.Any())
    {
      error = EmptyZeroSet;
      return false;
    }
    execution.EndStage("voxelize");
    const bool ok = ComputeChamferField(boundary,
      request.Signed ? &solid : nullptr,
      request,
      nullptr,
      distance,
      execution,
      report,
      error);
    report.Voxels = voxels;
    return ok;
  }
  // On the GPU the voxelization stays there for the propagation.
  SampleGrid local;
  if (!ToLocalFrame(mesh, request.Grid, execution.For, local, report.Voxels, error))
  {
    return false;
  }
  execution.EndStage("voxelize");
  ChamferInput input;
  input.Mesh = &mesh;
  input.Grid = local;
  VoxelizeStatistics statistics;
  if (!ChamferGPU(*gl,
        input,
        request.Metric,
        request.MaximumLayers,
        request.Unreached(),
        request.Signed,
        distance,
        keepMasks ? &boundary : nullptr,
        keepMasks && request.Signed ? &solid : nullptr,
        report.Result,
        statistics,
        error,
        execution.Part(0.1, 0.95).Progress))
  {
    error = gl->Failure(error) + ".";
    return false;
  }
  if (report.Result.Aborted)
  {
    return true;
  }
  ReportFarTriangles(statistics, report.Voxels);
  if (report.Result.ZeroSet == 0)
  {
    error = EmptyZeroSet;
    return false;
  }
  execution.EndStage("propagate");
  return true;
}

bool ComputeChamferField(const BitVolume& boundary,
  const BitVolume* solid,
  const ChamferRequest& request,
  HeadlessGL* gl,
  int32_t* distance,
  const Execution& execution,
  ChamferReport& report,
  std::string& error)
{
  report = ChamferReport();
  if (!boundary.Any())
  {
    error = EmptyZeroSet;
    return false;
  }
  const ProgressCallback progress = execution.Part(0.1, 0.95).Progress;
  const BitVolume* inside = request.Signed ? solid : nullptr;
  if (gl)
  {
    ChamferInput input;
    input.Grid = request.Grid;
    input.Boundary = &boundary;
    input.Solid = solid;
    VoxelizeStatistics statistics;
    if (!ChamferGPU(*gl,
          input,
          request.Metric,
          request.MaximumLayers,
          request.Unreached(),
          inside != nullptr,
          distance,
          nullptr,
          nullptr,
          report.Result,
          statistics,
          error,
          progress))
    {
      error = gl->Failure(error) + ".";
      return false;
    }
  }
  else
  {
    report.Result = ChamferPropagate(boundary,
      request.Metric,
      request.MaximumLayers,
      request.Unreached(),
      inside,
      distance,
      execution.For,
      progress);
  }
  if (!report.Result.Aborted)
  {
    execution.EndStage("propagate");
  }
  return true;
}

bool ComputeChamferPiece(const BitVolume& boundary,
  const BitVolume* solid,
  const IndexBox& piece,
  const ChamferRequest& request,
  HeadlessGL* gl,
  const ChamferOutput& output,
  IndexBox& computed,
  const Execution& execution,
  ChamferReport& report,
  std::string& error)
{
  if (!boundary.Any())
  {
    error = EmptyZeroSet;
    return false;
  }
  const IndexBox& whole = request.Grid.Whole;
  if (request.MaximumLayers > 0)
  {
    computed = piece.Grown(request.MaximumLayers, whole);
    return PropagateBox(boundary, solid, computed, request, gl, output, execution, report, error);
  }
  for (int margin = 16;; margin *= 2)
  {
    ChamferRequest bounded = request;
    computed = piece.Grown(margin, whole);
    if (computed.Count() > whole.Count() / 4)
    {
      computed = whole;
    }
    bounded.MaximumLayers = computed == whole ? 0 : margin;
    // The box's values live where `output` put them: remember where, to check them.
    int32_t* values = nullptr;
    const ChamferOutput remember = [&output, &values](const IndexBox& box)
    { return values = output(box); };
    if (!PropagateBox(boundary, solid, computed, bounded, gl, remember, execution, report, error))
    {
      return false;
    }
    if (report.Result.Aborted || bounded.MaximumLayers == 0 ||
      AllReached(values, computed, piece, margin))
    {
      return true;
    }
  }
}

} // namespace vtkdf
