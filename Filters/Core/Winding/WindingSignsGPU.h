// WindingSignsGPU: WindingSigns on the GPU, a compute shader over the flattened hierarchy
// (Shaders/WindingNumber.comp.glsl) that decides every sample alone by WindingNumber's
// rule: the order-1 approximation where its error bound decides, the exact sum
// elsewhere. So it gives WindingSigns' signs, but for samples whose exact |w| lies within
// rounding (about 1e-12) of 1/2. A sample whose loops would run past the context's limit
// (HeadlessGL::InvocationLoopBudget: a software renderer's) is decided on the CPU by
// WindingNumber::Inside, whose bits the shader's are (WindingSignStatistics::CPUSamples).
#ifndef vtkdf_WindingSignsGPU_h
#define vtkdf_WindingSignsGPU_h

#include "GL/HeadlessGL.h"
#include "Winding/WindingSigns.h"

#include <string>

namespace vtkdf
{

/// As WindingSigns (options.Value honoured; Distance and Blocks not used: every sample is
/// decided alone); false and `error` when the GPU cannot run it. `parallelFor` (optional)
/// runs the samples the CPU finishes.
bool WindingSignsGPU(HeadlessGL& context,
  const WindingNumber& winding,
  const SampleGrid& grid,
  const IndexBox& extent,
  uint8_t* inside,
  const WindingSignOptions& options,
  const ParallelFor& parallelFor,
  WindingSignStatistics& stats,
  std::string& error);

} // namespace vtkdf

#endif
