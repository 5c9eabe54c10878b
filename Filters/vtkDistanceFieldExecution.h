// vtkDistanceFieldExecution: how the module's filters run the cores: vtkSMPTools behind
// the cores' parallel loop, the GL context a Backend resolves to, and the failure rule
// of every filter (an empty output and a non-zero error code). Private to the module
// (not wrapped).
#ifndef vtkDistanceFieldExecution_h
#define vtkDistanceFieldExecution_h

#include "vtkType.h"

#include <cstdint>
#include <functional>
#include <string>

class vtkAlgorithm;
class vtkInformation;

namespace vtkdf
{
class HeadlessGL;

/// The values of every filter's Backend property (each base class re-declares them as
/// its BackendType, where VTK's wrapping finds them).
enum BackendValue
{
  BackendAuto = 0, // where the filters were measured fastest: today the CPU for all
  BackendGPU = 1,  // the GPU, even a software rasterizer; an error when there is none
  BackendCPU = 2   // the CPU
};

/// The GPU context for a Backend: `gl` is the context (GPU: any, even a software
/// rasterizer) or null for the CPU (CPU, Auto). False, with `error`, when Backend is GPU
/// and there is no context.
bool ChooseContext(int backend, HeadlessGL*& gl, std::string& error);

/// The context on which Backend Auto runs the winding-number sign of `samples` samples
/// while the field runs on the CPU: a hardware GPU's from 2^22 samples on, else null.
/// On an NVIDIA H100 beside 16 CPU threads, the GPU's winding pass took half the time of
/// the CPU's at 256^3 (the whole field 1.36-1.75 times faster), but its context and
/// programs cost about 0.4 s once per process, which smaller grids do not repay
/// (docs/benchmarks.md). The device is looked for once per process, without making a
/// context where none is hardware; a software rasterizer (llvmpipe, OSMesa) is not
/// taken. The environment variable VTKDF_AUTO_GPU_SIGN=1 takes any context at any size
/// (how the tests run this path), VTKDF_AUTO_GPU_SIGN=0 none. `cpuIsFaster`, asked only
/// where a context would be taken, may say the CPU has the faster route (the crossings
/// along the grid lines, Winding/WindingCrossings.h): then none either.
HeadlessGL* AutoSignContext(int64_t samples,
  const std::function<bool()>& cpuIsFaster = std::function<bool()>());

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

} // namespace vtkdf

#endif
