#include "Medial/MedialAxisField.h"

#include "GL/HeadlessGL.h"
#include "Medial/MedialAxisGPU.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace vtkdf
{

namespace
{
/// The separation angle (degrees) and the radius (world units) of every voxel, from the
/// cosines of the pass and the distances.
void AnglesAndRadii(const std::vector<double>& cosine,
  const float* distance,
  const MedialArrays& arrays,
  const ParallelFor& parallelFor)
{
  float* angle = arrays.SeparationAngle;
  float* radius = arrays.Radius;
  parallelFor(static_cast<int64_t>(cosine.size()),
    4096,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t v = begin; v < end; ++v)
      {
        angle[v] = cosine[v] <= 1
          ? static_cast<float>(std::acos(std::max(-1.0, cosine[v])) * 180.0 / M_PI)
          : 0.0f;
        radius[v] = std::fabs(distance[v]);
      }
    });
}
} // namespace

bool ComputeMedialAxis(const MedialInput& field,
  HeadlessGL* gl,
  MedialArrays& arrays,
  const Execution& execution,
  std::string& error)
{
  std::vector<double> cosine(field.Grid.Whole.Count());
  if (gl)
  {
    if (!MedialAxisGPU(*gl, field, arrays.Medial, cosine.data(), arrays.Count, error))
    {
      error = gl->Failure(error) + ".";
      return false;
    }
  }
  else
  {
    arrays.Count = MedialAxisCPU(field, arrays.Medial, cosine.data(), execution.For);
  }
  AnglesAndRadii(cosine, field.Distance, arrays, execution.For);
  execution.EndStage("medial");
  return true;
}

bool ComputeMedialAxis(MeshInput mesh,
  SignMode sign,
  const MedialInput& parameters,
  const IndexBox& extent,
  HeadlessGL* gl,
  MedialArrays& arrays,
  const Execution& execution,
  std::string& error,
  HeadlessGL* signContext)
{
  LinearFactorRequest request;
  request.Grid = parameters.Grid;
  request.Extent = extent;
  request.Sign = sign;
  request.SignContext = gl ? nullptr : signContext;
  LinearFactorReport report;
  const int64_t voxels = request.Extent.Count();
  if (gl && sign == SignMode::PseudoNormal)
  {
    // The field and the medial pass, all on the GPU (only distances and cosines return).
    std::vector<float> distance(voxels);
    std::vector<double> cosine(voxels);
    auto medialPass = [&](const GPUField& field, std::string& passError)
    {
      // The field's buffers are in world units: the CPU's pass over them.
      MedialInput local = parameters;
      local.Grid.Whole = field.Extent; // the voxels in the buffers
      if (!MedialAxisOnGPUField(*gl,
            field,
            local,
            distance.data(),
            arrays.Medial,
            cosine.data(),
            arrays.Count,
            passError))
      {
        passError = gl->Failure(passError) + ".";
        return false;
      }
      return true;
    };
    // No progress here: with it the scan would run in many small batches (to report
    // between them), each drawing every site again (7 times slower on llvmpipe).
    Execution quiet;
    quiet.For = execution.For;
    if (!ComputeLinearFactorFieldOnGPU(
          *gl, std::move(mesh), request, quiet, medialPass, report, error))
    {
      return false;
    }
    if (report.NoUsableCell)
    {
      error = "Invalid input mesh: no usable cell.";
      return false;
    }
    if (report.Aborted)
    {
      arrays.Aborted = true;
      return true;
    }
    execution.EndStage("field+medial");
    AnglesAndRadii(cosine, distance.data(), arrays, execution.For);
    execution.EndStage("outputs");
    return true;
  }
  // The signed field with closest points on this backend (the winding-number sign on the
  // GPU too when it runs there), then the pass.
  std::vector<float> distance(voxels), closest(3 * voxels);
  LinearFactorArrays field;
  field.Distance = distance.data();
  field.ClosestPoint = closest.data();
  Execution quiet = execution.Part(0, 0.9);
  quiet.Stages = nullptr; // the field is one stage here
  if (!ComputeLinearFactorField(std::move(mesh), request, gl, field, quiet, report, error) ||
    report.NoUsableCell)
  {
    error = "The distance field of the input mesh could not be computed: " +
      (report.NoUsableCell ? std::string("the input has no usable cell") : error);
    return false;
  }
  if (report.Aborted)
  {
    arrays.Aborted = true;
    return true;
  }
  execution.EndStage("field");
  MedialInput input = parameters;
  input.Grid.Whole = extent;
  input.Distance = distance.data();
  input.ClosestPoint = closest.data();
  return ComputeMedialAxis(input, gl, arrays, execution, error);
}

} // namespace vtkdf
