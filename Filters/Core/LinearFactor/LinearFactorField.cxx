#include "LinearFactor/LinearFactorField.h"

#include "Common/BackendPolicy.h"

#include "GL/HeadlessGL.h"
#include "LinearFactor/LinearFactorGPU.h"
#include "LinearFactor/LinearFactorScan.h"
#include "LinearFactor/LocalSites.h"
#include "LinearFactor/MeshSites.h"
#include "LinearFactor/NearestTriangleQueries.h"
#include "LinearFactor/RangeCulling.h"
#include "LinearFactor/SurfaceCoordinates.h"
#include "Winding/WindingSigns.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace vtkdf
{

namespace
{
/// Inside or outside at every sample by the winding number (on the GPU when `gl` is
/// given), the distances' signs set from it when `sign` says so, and w itself when asked
/// for.
bool WindingSign(const MeshInput& mesh,
  SignMode sign,
  const LocalSites& local,
  HeadlessGL* gl,
  bool crossingsOnCPU,
  const LinearFactorArrays& arrays,
  const Execution& execution,
  LinearFactorReport& report,
  std::string& error)
{
  const int64_t n = local.Request.Extent.Count();
  std::vector<uint8_t> inside(n);
  WindingSignOptions options;
  options.Value = arrays.WindingNumber;
  // Unsigned still, in world units: blocks near the surface split without trying.
  options.Distance = arrays.Distance;
  options.DistanceScale = 1 / local.Frame.Scale;
  options.CrossingsOnCPU = crossingsOnCPU;
  WindingSignStatistics stats;
  if (!ComputeWindingSigns(mesh.Points,
        mesh.Triangles,
        local.Request.Grid,
        local.Request.Extent,
        inside.data(),
        options,
        gl,
        execution.For,
        stats,
        error))
  {
    error = gl ? gl->Failure(error) : error;
    return false;
  }
  report.WindingBlockSamples = stats.BlockSamples;
  report.WindingLineSamples = stats.LineSamples;
  report.WindingOnGPU = stats.GPU;
  report.WindingExactSamples = stats.Exact;
  report.WindingCPUSamples = stats.CPUSamples;
  float* d = arrays.Distance;
  if (d && sign == SignMode::WindingNumber)
  {
    execution.For(n,
      65536,
      [d, &inside](int64_t begin, int64_t end)
      {
        for (int64_t v = begin; v < end; ++v)
        {
          d[v] = inside[v] ? -std::fabs(d[v]) : std::fabs(d[v]);
        }
      });
  }
  return true;
}

/// Where the field's arrays go, as Finalize and the queries take them.
LocalFieldArrays ArraysInFrame(const LinearFactorArrays& arrays,
  const LinearFactorRequest& request,
  const GridFrame& frame)
{
  LocalFieldArrays field;
  field.Frame = frame;
  field.Distance = arrays.Distance;
  field.Signed = request.Sign == SignMode::PseudoNormal;
  field.ClosestCellId = arrays.ClosestCellId;
  field.ClosestFeature = arrays.ClosestFeature;
  field.ClosestPoint = arrays.ClosestPoint;
  return field;
}

/// The winding sign or value, when the request asks for either.
bool WindingSignIfAsked(const MeshInput& mesh,
  const LinearFactorRequest& request,
  const LocalSites& local,
  HeadlessGL* gl,
  const LinearFactorArrays& arrays,
  const Execution& execution,
  LinearFactorReport& report,
  std::string& error)
{
  if ((request.Sign == SignMode::WindingNumber && arrays.Distance) || arrays.WindingNumber)
  {
    HeadlessGL* signGL = gl ? gl : request.SignContext;
    if (!WindingSign(mesh, request.Sign, local, signGL, !gl, arrays, execution, report, error))
    {
      return false;
    }
    execution.EndStage("sign");
  }
  return true;
}

/// Whether the request asks for the closest points' places on their cells or the gradient.
bool WantsSurfaceCoordinates(const LinearFactorArrays& arrays)
{
  return arrays.ClosestSubTriangle || arrays.ClosestBarycentric || arrays.Gradient;
}

/// The arrays the field writes: the caller's, with the closest cells (and the signed
/// distances, for a signed gradient) in `cells` and `distances` where the caller did not
/// ask for them but the surface coordinates need them.
LinearFactorArrays FieldArrays(const LinearFactorArrays& arrays,
  const LinearFactorRequest& request,
  LargeVector<int64_t>& cells,
  LargeVector<float>& distances)
{
  LinearFactorArrays field = arrays;
  if (!WantsSurfaceCoordinates(arrays))
  {
    return field;
  }
  const int64_t n = request.Extent.Count();
  if (!field.ClosestCellId)
  {
    cells.resize(n);
    field.ClosestCellId = cells.data();
  }
  if (!field.Distance && arrays.Gradient && request.Sign != SignMode::Unsigned)
  {
    distances.resize(n);
    field.Distance = distances.data();
  }
  return field;
}

/// The surface coordinates and the gradient, when the request asks for them, from the
/// field's closest cells and signed distances.
bool SurfaceCoordinatesIfAsked(const MeshInput& mesh,
  const LocalSites& local,
  const LinearFactorArrays& field,
  const Execution& execution,
  std::string& error)
{
  if (!WantsSurfaceCoordinates(field))
  {
    return true;
  }
  SurfaceCoordinateArrays out;
  out.ClosestSubTriangle = field.ClosestSubTriangle;
  out.ClosestBarycentric = field.ClosestBarycentric;
  out.Gradient = field.Gradient;
  if (!ComputeSurfaceCoordinates(mesh,
        local.Request.Grid,
        local.Request.Extent,
        field.ClosestCellId,
        field.Distance,
        out,
        execution.For,
        error))
  {
    error = "Invalid input mesh: " + error + ".";
    return false;
  }
  execution.EndStage("surface");
  return true;
}
} // namespace

LinearFactorWorkspace::LinearFactorWorkspace()
  : NearestSites(new NearestSiteBuffer)
{
}

LinearFactorWorkspace::~LinearFactorWorkspace() = default;

int64_t LinearFactorWorkspace::Bytes() const
{
  return this->NearestSites->Bytes();
}

void LinearFactorWorkspace::Release()
{
  this->NearestSites->Release();
}

NearestSiteBuffer& LinearFactorWorkspace::Nearest(int64_t samples)
{
  if (this->NearestSites->Bytes() > 2 * samples * int64_t(sizeof(uint64_t)))
  {
    this->NearestSites->Release();
  }
  return *this->NearestSites;
}

bool ComputeLinearFactorField(MeshInput mesh,
  const LinearFactorRequest& request,
  HeadlessGL* gl,
  const LinearFactorArrays& requested,
  const Execution& execution,
  LinearFactorReport& report,
  std::string& error)
{
  report = LinearFactorReport();
  LargeVector<int64_t> cells;
  LargeVector<float> distances;
  const LinearFactorArrays arrays = FieldArrays(requested, request, cells, distances);
  const double accuracy = 1e-3 * request.Grid.MinSpacing();
  if (request.MaximumDistance > 0 && request.MaximumDistance < accuracy)
  {
    error = "MaximumDistance (" + FormatNumber(request.MaximumDistance) +
      ") is below the field's accuracy, 1e-3 of the smallest spacing (" + FormatNumber(accuracy) +
      "): use 0 for no cap, or a larger one.";
    return false;
  }
  bool queries = request.Route == FieldRoute::SampleQueries;
  if (queries && gl)
  {
    error = "The sample-query route runs on the CPU only: use the site scan on the GPU.";
    return false;
  }
  // The route of an Auto request, by the policy's rule (Common/BackendPolicy.h).
  WorkDescription work;
  work.Backend = gl ? BackendChoice::GPU : BackendChoice::CPU;
  work.Route = static_cast<RouteChoice>(request.Route);
  work.QueriesFaster = [&]
  { return PreferSampleQueries(mesh, request.Grid, request.MaximumDistance); };
  queries = ChoosePlan(work, DeviceDescription()).SampleQueries;
  LocalSites local;
  if (queries)
  {
    report.Route = FieldRoute::SampleQueries;
    if (!MoveToGridFrame(mesh, request, execution.For, local, error))
    {
      return false;
    }
    if (mesh.Empty())
    {
      report.NoUsableCell = true;
      return true;
    }
    ScanStatistics stats;
    if (!QueryNearestTriangles(mesh,
          local.Request,
          ArraysInFrame(arrays, request, local.Frame),
          execution.Part(0.0, 0.9),
          stats,
          error))
    {
      error = "Invalid input mesh: " + error + ".";
      return false;
    }
    report.Evaluations = stats.Evaluations;
    if (stats.Aborted)
    {
      report.Aborted = true;
      return true;
    }
    execution.EndStage("queries");
    return WindingSignIfAsked(mesh, request, local, gl, arrays, execution, report, error) &&
      SurfaceCoordinatesIfAsked(mesh, local, arrays, execution, error);
  }
  const bool keepMesh = arrays.WindingNumber || WantsSurfaceCoordinates(arrays);
  if (!BuildLocalSites(mesh, request, keepMesh, execution.For, local, error))
  {
    return false;
  }
  if (local.Sites.Empty())
  {
    report.NoUsableCell = true;
    return true;
  }
  execution.EndStage("sites");
  if (!execution.Report(0.0))
  {
    report.Aborted = true;
    return true;
  }

  RangeCulling range;
  range.Build(local.Sites,
    local.Request.Grid,
    local.Request.Extent,
    local.Request.MaximumDistance,
    execution.For);
  execution.EndStage("culling");
  if (!execution.Report(0.1))
  {
    report.Aborted = true;
    return true;
  }

  const int64_t samples = local.Request.Extent.Count();
  NearestSiteBuffer own;
  NearestSiteBuffer& nearest = request.Workspace ? request.Workspace->Nearest(samples) : own;
  nearest.Reset(samples, execution.For);
  const ProgressCallback scanProgress = execution.Part(0.1, 0.9).Progress;
  ScanStatistics stats;
  if (gl)
  {
    if (!ScanSitesGPU(*gl,
          local.Sites,
          range,
          local.Request,
          nearest,
          execution.For,
          scanProgress,
          stats,
          error))
    {
      error = gl->Failure(error);
      return false;
    }
  }
  else
  {
    stats = ScanSitesCPU(local.Sites, range, local.Request, nearest, execution.For, scanProgress);
  }
  if (stats.Aborted)
  {
    report.Aborted = true;
    return true;
  }
  execution.EndStage("scan");
  report.Evaluations = stats.Evaluations;

  Finalize(local.Sites,
    local.Request,
    nearest,
    ArraysInFrame(arrays, request, local.Frame),
    execution.For);
  execution.EndStage("finalize");
  return WindingSignIfAsked(mesh, request, local, gl, arrays, execution, report, error) &&
    SurfaceCoordinatesIfAsked(mesh, local, arrays, execution, error);
}

bool ComputeLinearFactorFieldOnGPU(HeadlessGL& gl,
  MeshInput mesh,
  const LinearFactorRequest& request,
  const Execution& execution,
  const std::function<bool(const GPUField&, std::string&)>& use,
  LinearFactorReport& report,
  std::string& error)
{
  report = LinearFactorReport();
  LocalSites local;
  if (!BuildLocalSites(mesh, request, false, execution.For, local, error))
  {
    return false;
  }
  if (local.Sites.Empty())
  {
    report.NoUsableCell = true;
    return true;
  }
  RangeCulling range;
  range.Build(local.Sites, local.Request.Grid, local.Request.Extent, HUGE_VAL, execution.For);

  HeadlessGL::Scope scope(gl);
  if (!scope.Ok(error))
  {
    return false;
  }
  const GLFunctions& functions = gl.GL();
  GPUField field;
  field.Grid = local.Request.Grid;
  field.Extent = local.Request.Extent;
  field.Frame = local.Frame;
  const int64_t samples = local.Request.Extent.Count();
  GLuint buffers[3] = { 0, 0, 0 };
  functions.GenBuffers(3, buffers);
  const int64_t bytes[3] = { samples * 4, samples * 12, samples * 4 };
  for (int b = 0; b < 3; ++b)
  {
    functions.BindBuffer(GL_SHADER_STORAGE_BUFFER, buffers[b]);
    functions.BufferData(GL_SHADER_STORAGE_BUFFER, bytes[b], nullptr, GL_DYNAMIC_COPY);
  }
  field.Distance = buffers[0];
  field.ClosestPoint = buffers[1];
  field.SiteIds = buffers[2];
  NearestSiteBuffer unused;
  ScanStatistics stats;
  bool ok = ScanSitesGPU(gl,
    local.Sites,
    range,
    local.Request,
    unused,
    execution.For,
    execution.Progress,
    stats,
    error,
    field.SiteIds);
  if (!ok)
  {
    error = gl.Failure(error);
  }
  report.Evaluations = stats.Evaluations;
  report.Aborted = stats.Aborted;
  if (ok && !stats.Aborted)
  {
    ok = FinalizeGPU(gl,
      local.Sites,
      local.Request,
      local.Frame,
      field.SiteIds,
      request.Sign == SignMode::PseudoNormal,
      field.Distance,
      field.ClosestPoint,
      error);
    if (!ok)
    {
      error = gl.Failure(error);
    }
    else
    {
      field.SiteCells.resize(local.Sites.Count());
      field.SiteTypes.resize(local.Sites.Count());
      for (int64_t s = 0; s < local.Sites.Count(); ++s)
      {
        field.SiteCells[s] = local.Sites.CellOf(s);
        field.SiteTypes[s] = local.Sites.TypeOf(s);
      }
      ok = use(field, error);
    }
  }
  functions.DeleteBuffers(3, buffers);
  return ok;
}

} // namespace vtkdf
