// vtkDistanceFieldExecution: how the module's filters run the cores: vtkSMPTools behind
// the cores' parallel loop, the GL context a Backend resolves to, and the failure rule
// of every filter (an empty output and a non-zero error code). Private to the module
// (not wrapped).
#ifndef vtkDistanceFieldExecution_h
#define vtkDistanceFieldExecution_h

#include "vtkType.h"

#include "Common/BackendPolicy.h"

#include <cstdint>
#include <functional>
#include <string>

class vtkAlgorithm;
class vtkInformation;
class vtkInformationVector;

namespace vtkdf
{
class HeadlessGL;

/// Whether a filter's BackendType (re-declared by each wrapped class, where VTK's wrapping
/// finds it) has the values of BackendChoice (Common/BackendPolicy.h), the one definition.
template<typename Filter>
constexpr bool SameBackendValues()
{
  return Filter::BACKEND_AUTO == static_cast<int>(BackendChoice::Auto) &&
    Filter::BACKEND_GPU == static_cast<int>(BackendChoice::GPU) &&
    Filter::BACKEND_CPU == static_cast<int>(BackendChoice::CPU);
}

/// The device as ChoosePlan (Common/BackendPolicy.h, where the rules are) sees it:
/// HeadlessGL::HasHardwareDevice, looked for once per process and only when a plan asks;
/// and the tests' hook, the environment variable VTKDF_AUTO_GPU_SIGN (1: Auto's GPU
/// stages on any context, a software rasterizer included, at any size, which is how the
/// tests run that path without a GPU; 0: never). A user needs neither.
DeviceDescription DescribeDevice();

/// The context for a plan's field: the process's (any, even a software rasterizer) when
/// plan.FieldOnGPU, else null (the CPU). False, with `error`, when the plan puts the
/// field on the GPU and there is none.
bool FieldContext(const ExecutionPlan& plan, HeadlessGL*& gl, std::string& error);

/// The context for a plan's winding sign beside a field on the CPU: the process's when
/// plan.SignOnGPU and it is no software rasterizer (any, under the tests' hook); else null
/// (the CPU, with the same signs).
HeadlessGL* SignContext(const ExecutionPlan& plan);

/// vtkSMPTools::For behind the cores' ParallelFor hook. An exception thrown by `body`
/// (std::bad_alloc) stops the remaining chunks and is rethrown here, on the calling
/// thread, whatever the SMP backend (a std::thread backend would otherwise terminate).
void SMPFor(int64_t n, int64_t grain, const std::function<void(int64_t, int64_t)>& body);

/// A filter's ProcessRequest: `process` (its superclass's) run with every exception
/// caught and reported (std::bad_alloc as out of memory). A failed request leaves every
/// output empty and, when the filter set none, the error code UserError; a new run (the
/// information request) starts from NoError. `setErrorCode` is the filter's own
/// (protected) SetErrorCode.
vtkTypeBool ProcessRequestOrEmpty(vtkAlgorithm* filter,
  bool newRun,
  const std::function<vtkTypeBool()>& process,
  const std::function<void(unsigned long)>& setErrorCode);

/// Asks an input for all of its data: the whole extent of an image, piece 0 of 1 of
/// anything, no ghost levels. A distributed pipeline (ParaView's MPI engine) otherwise
/// passes each rank's piece upstream, and an image source that can produce sub-extents
/// then makes only that piece, although every voxel here may depend on every other.
void RequestWholeInput(vtkInformation* input);

/// RequestWholeInput for the first connection of each of ports 0 to `ports` - 1.
void RequestWholeInputs(vtkInformationVector** inputVector, int ports);

} // namespace vtkdf

#endif
