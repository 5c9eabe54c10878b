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

} // namespace vtkdf
