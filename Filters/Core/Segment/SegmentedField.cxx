#include "Segment/SegmentedField.h"

#include "GL/HeadlessGL.h"
#include "LinearFactor/LinearFactorField.h"
#include "Segment/SegmentFieldGPU.h"
#include "Segment/SegmentRegions.h"
#include "Segment/SelfIntersections.h"
#include "Segment/SurfacePatches.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vtkdf
{

namespace
{
/// The surface the field is of: the mesh's triangles (cut along their crossings), its
/// patches, and the triangles that have one (those with an area).
struct Surface
{
  LargeVector<double> WorldPoints; // when cut: the cut's points
  LargeVector<double> LocalPoints; // the points in the grid's local frame
  const LargeVector<double>* World = nullptr;
  const LargeVector<int64_t>* Triangles = nullptr;
  SelfIntersectionCut Cut;
  SurfacePatches Patches;
  std::vector<int64_t> Kept; // per field triangle, its triangle of Patches
};

/// Cuts the crossings (in world coordinates: the cut's new points are rounded there, so
/// the field and the patches see the same points) and builds the patches in the local
/// frame.
void BuildSurface(const MeshInput& mesh,
  const SegmentedFieldRequest& request,
  const GridFrame& frame,
  Surface& surface,
  SegmentedFieldReport& report,
  const Execution& execution)
{
  surface.World = &mesh.Points;
  surface.Triangles = &mesh.Triangles;
  if (request.CutSelfIntersections)
  {
    CutSelfIntersections(mesh.Points, mesh.Triangles, surface.Cut);
    if (surface.Cut.FailedGroups > 0)
    {
      report.Warnings.push_back(std::to_string(surface.Cut.FailedGroups) + " of " +
        std::to_string(surface.Cut.CrossingGroups) + " groups of crossing triangles (" +
        std::to_string(surface.Cut.FailedTriangles) +
        " triangles) could not be cut along their crossings (" + surface.Cut.FailedMessage +
        "); there the field is that of the uncut mesh.");
    }
    if (surface.Cut.Cut())
    {
      report.CrossedTriangles = surface.Cut.CutTriangles;
      surface.World = &surface.Cut.Points;
      surface.Triangles = &surface.Cut.Triangles;
    }
  }
  execution.EndStage("crossings");
  surface.LocalPoints = *surface.World;
  for (size_t i = 0; i < surface.LocalPoints.size(); ++i)
  {
    surface.LocalPoints[i] = frame.ToLocal(static_cast<int>(i % 3), surface.LocalPoints[i]);
  }
  surface.Patches.Build(surface.LocalPoints, *surface.Triangles);
  report.PatchCount = surface.Patches.PatchCount;
  report.CutEdges = surface.Patches.CutEdges;
  for (size_t t = 0; t < surface.Patches.Patch.size(); ++t)
  {
    if (surface.Patches.Patch[t] >= 0)
    {
      surface.Kept.push_back(static_cast<int64_t>(t));
    }
  }
  if (surface.Patches.CutEdges > 0)
  {
    report.Warnings.push_back("Some patches are not orientable: they were cut along " +
      std::to_string(surface.Patches.CutEdges) + " edges.");
  }
}

/// The triangles with a patch as a mesh of their own (world coordinates).
MeshInput FieldMesh(const Surface& surface)
{
  MeshInput field;
  field.Points = *surface.World;
  for (size_t k = 0; k < surface.Kept.size(); ++k)
  {
    const int64_t* ids = &(*surface.Triangles)[3 * surface.Kept[k]];
    field.Triangles.insert(field.Triangles.end(), ids, ids + 3);
    field.TriangleCells.push_back(static_cast<int64_t>(k));
  }
  UsedPointBounds(field, field.Bounds);
  return field;
}

/// The triangle of the patches that field cell `cell` is (-1: none).
int64_t KeptTriangle(const Surface& surface, int64_t cell)
{
  return cell >= 0 && cell < static_cast<int64_t>(surface.Kept.size()) ? surface.Kept[cell] : -1;
}

/// What the regions read, per sample: the field in the local frame, and each sample's
/// side label (GPU) or closest triangle, feature and point (CPU).
struct LocalField
{
  std::vector<float> Distance;
  std::vector<int32_t> Labels;
  std::vector<int64_t> Triangle;
  std::vector<uint8_t> Feature;
  std::vector<double> Closest;
};

/// The field on the GPU, the side labels computed where it lies; the distances in the
/// local frame from the world ones, as FieldOnCPU has them.
bool FieldOnGPU(HeadlessGL& gl,
  const Surface& surface,
  const SegmentedFieldRequest& request,
  const SegmentedFieldArrays& arrays,
  const Execution& execution,
  LocalField& local,
  SegmentedFieldReport& report,
  std::string& error)
{
  const IndexBox& extent = request.Extent;
  const int64_t n = extent.Count();
  std::vector<float> scratch(arrays.ClosestPoint ? 0 : 3 * static_cast<size_t>(n));
  local.Labels.resize(n);
  GridFrame frame;
  auto labels = [&](const GPUField& field, std::string& labelError)
  {
    std::vector<int32_t> siteTriangle(2 * field.SiteCells.size());
    for (size_t i = 0; i < field.SiteCells.size(); ++i)
    {
      siteTriangle[2 * i] = static_cast<int32_t>(KeptTriangle(surface, field.SiteCells[i]));
      siteTriangle[2 * i + 1] = field.SiteTypes[i];
    }
    frame = field.Frame;
    return SideLabelsOnGPUField(gl,
      field,
      surface.Patches,
      siteTriangle,
      arrays.Distance,
      arrays.ClosestPoint ? arrays.ClosestPoint : scratch.data(),
      local.Labels.data(),
      labelError);
  };
  LinearFactorRequest field;
  field.Grid = request.Grid;
  field.Extent = extent;
  LinearFactorReport fieldReport;
  if (!ComputeLinearFactorFieldOnGPU(
        gl, FieldMesh(surface), field, execution.Part(0.05, 0.55), labels, fieldReport, error))
  {
    error = "The GPU field and side labels failed: " + error;
    return false;
  }
  if (fieldReport.NoUsableCell)
  {
    error = "Invalid input mesh: no usable cell.";
    return false;
  }
  report.Aborted = fieldReport.Aborted;
  if (report.Aborted)
  {
    return true;
  }
  // The regions read the distances in the local frame, as FieldOnCPU gives them.
  const float* d = arrays.Distance;
  execution.For(n,
    4096,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t v = begin; v < end; ++v)
      {
        local.Distance[v] = static_cast<float>(d[v] / frame.Scale);
      }
    });
  return true;
}

/// The field on the CPU, in world units as the output has it; the regions read it back
/// in the local frame (from those float arrays, as the output's own field).
bool FieldOnCPU(const Surface& surface,
  const SegmentedFieldRequest& request,
  const SegmentedFieldArrays& arrays,
  const GridFrame& frame,
  const Execution& execution,
  LocalField& local,
  SegmentedFieldReport& report,
  std::string& error)
{
  const int64_t n = request.Extent.Count();
  std::vector<float> scratch(arrays.ClosestPoint ? 0 : 3 * static_cast<size_t>(n));
  std::vector<int64_t> cells(n);
  local.Feature.resize(n);
  LinearFactorArrays field;
  field.Distance = arrays.Distance;
  field.ClosestCellId = cells.data();
  field.ClosestFeature = local.Feature.data();
  field.ClosestPoint = arrays.ClosestPoint ? arrays.ClosestPoint : scratch.data();
  LinearFactorRequest fieldRequest;
  fieldRequest.Grid = request.Grid;
  fieldRequest.Extent = request.Extent;
  LinearFactorReport fieldReport;
  Execution quiet = execution.Part(0.05, 0.55);
  quiet.Stages = nullptr; // the field is one stage here
  if (!ComputeLinearFactorField(
        FieldMesh(surface), fieldRequest, nullptr, field, quiet, fieldReport, error) ||
    fieldReport.NoUsableCell)
  {
    error = "The distance field of the input could not be computed: " +
      (fieldReport.NoUsableCell ? std::string("no usable cell") : error);
    return false;
  }
  report.Aborted = fieldReport.Aborted;
  if (report.Aborted)
  {
    return true;
  }
  local.Triangle.resize(n);
  local.Closest.resize(3 * static_cast<size_t>(n));
  const float* d = field.Distance;
  const float* x = field.ClosestPoint;
  execution.For(n,
    4096,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t v = begin; v < end; ++v)
      {
        local.Distance[v] = static_cast<float>(d[v] / frame.Scale);
        local.Triangle[v] = KeptTriangle(surface, cells[v]);
        for (int a = 0; a < 3; ++a)
        {
          local.Closest[3 * v + a] = frame.ToLocal(a, x[3 * v + a]);
        }
      }
    });
  return true;
}

/// SegmentedDistance, RegionIndex and PatchId from the regions and the world distances.
void WriteArrays(const SegmentResult& result,
  const SegmentedFieldArrays& arrays,
  double delta,
  double offset,
  const Execution& execution)
{
  const float* distance = arrays.Distance;
  float* f = arrays.SegmentedDistance;
  int32_t* r = arrays.RegionIndex;
  int32_t* pid = arrays.PatchId;
  execution.For(static_cast<int64_t>(result.Region.size()),
    4096,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t v = begin; v < end; ++v)
      {
        r[v] = result.Region[v];
        pid[v] = result.Patch[v];
        f[v] =
          static_cast<float>(std::min(double(distance[v]), delta) + offset * std::max(0, r[v]));
      }
    });
}
} // namespace

bool ComputeSegmentedField(MeshInput mesh,
  const SegmentedFieldRequest& pieceRequest,
  HeadlessGL* gl,
  const SegmentedFieldArrays& arrays,
  const Execution& execution,
  SegmentedFieldReport& report,
  std::string& error)
{
  report = SegmentedFieldReport();
  SegmentedFieldRequest request = pieceRequest;
  const SampleGrid& grid = request.Grid;
  if (request.Extent.Empty())
  {
    request.Extent = grid.Whole;
  }
  const bool piece = static_cast<bool>(request.Combine);
  if (piece ? !request.Extent.Contains(request.Pieces.Piece.Grown(1, grid.Whole))
            : !(request.Extent == grid.Whole))
  {
    error = piece ? "A piece's extent must hold the piece and one sample around it."
                  : "A part of the grid needs the other parts' region evidence (Combine).";
    return false;
  }
  const double largest = std::max({ grid.Spacing[0], grid.Spacing[1], grid.Spacing[2] });
  const double delta = request.Delta > 0 ? request.Delta : 2 * largest;
  const double offset = request.RegionOffset > 0 ? request.RegionOffset : 4 * largest;
  if (delta < largest || !(delta < offset))
  {
    error = "Delta must be at least the largest grid spacing (" + FormatNumber(largest) +
      ") and below RegionOffset; they are " + FormatNumber(delta) + " and " + FormatNumber(offset) +
      ".";
    return false;
  }
  report.Delta = delta;
  report.RegionOffset = offset;
  if (!CheckGrid(grid, mesh.Bounds.data(), error))
  {
    error = "Invalid input: " + error + ".";
    return false;
  }
  if (!mesh.Segments.empty() || !mesh.Vertices.empty())
  {
    report.Warnings.push_back(
      "The segmented distance is that of the surface: " + std::to_string(mesh.SegmentCells.size()) +
      " line segments and " + std::to_string(mesh.Vertices.size()) + " vertices are ignored.");
  }
  const GridFrame frame = GridFrame::For(grid);
  Surface surface;
  BuildSurface(mesh, request, frame, surface, report, execution);
  if (surface.Kept.empty())
  {
    error = "The input has no triangle with an area: there is no surface to segment.";
    return false;
  }
  execution.EndStage("patches");

  // The exact unsigned field with each sample's closest feature, and its side label.
  const int64_t n = request.Extent.Count();
  LocalField local;
  local.Distance.resize(n);
  const bool ok = gl ? FieldOnGPU(*gl, surface, request, arrays, execution, local, report, error)
                     : FieldOnCPU(surface, request, arrays, frame, execution, local, report, error);
  if (!ok || report.Aborted)
  {
    return ok;
  }
  execution.EndStage("field");
  if (!execution.Report(0.6))
  {
    report.Aborted = true;
    return true;
  }

  // Regions, in the grid's local frame.
  SegmentInput input;
  input.Patches = &surface.Patches;
  input.Grid = frame.Local(grid);
  input.Grid.Whole = request.Extent;
  if (piece)
  {
    input.Ownership = &request.Pieces;
    input.WholeGrid = grid.Whole;
    input.Combine = request.Combine;
  }
  input.Distance = local.Distance.data();
  if (gl)
  {
    input.Labels = local.Labels.data();
  }
  else
  {
    input.ClosestTriangle = local.Triangle.data();
    input.ClosestFeature = local.Feature.data();
    input.ClosestPoint = local.Closest.data();
  }
  SegmentResult result;
  if (!SegmentRegions(input, result, error, execution.For))
  {
    error = "The regions could not be merged across the pieces: " + error + ".";
    return false;
  }
  report.RegionCount = result.RegionCount;
  report.RefusedMerges = result.Refused;
  execution.EndStage("regions");
  // SegmentedDistance is float: its largest value must exist, and distances near it keep
  // what float's resolution there leaves them.
  const double top = offset * std::max(0, result.RegionCount - 1) + delta;
  if (!(top <= std::numeric_limits<float>::max()))
  {
    error = "RegionOffset (" + FormatNumber(offset) + ") times the " +
      std::to_string(result.RegionCount - 1) +
      " regions after the first exceeds the float range of SegmentedDistance.";
    return false;
  }
  const double resolution = top * std::numeric_limits<float>::epsilon();
  if (resolution > 1e-3 * grid.MinSpacing())
  {
    report.Warnings.push_back("SegmentedDistance is float: in region " +
      std::to_string(result.RegionCount - 1) + " it resolves distances only to " +
      FormatNumber(resolution) + " (a smaller RegionOffset keeps more).");
  }
  WriteArrays(result, arrays, delta, offset, execution);
  report.Sides = std::move(result.Sides);
  return true;
}

bool SelfIntersectionCutAvailable()
{
#ifdef DF_HAVE_CGAL
  return true;
#else
  return false;
#endif
}

} // namespace vtkdf
