// MedialAxisGPU: the medial axis pass as a compute shader (Shaders/MedialAxis.comp.glsl),
// the same double-precision arithmetic as MedialAxisCPU, so the same voxels.
#ifndef vtkdf_MedialAxisGPU_h
#define vtkdf_MedialAxisGPU_h

#include "GL/HeadlessGL.h"
#include "LinearFactor/LinearFactorField.h"
#include "Medial/MedialAxis.h"

#include <string>

namespace vtkdf
{

/// As MedialAxisCPU; false and `error` when the GPU cannot run it.
bool MedialAxisGPU(HeadlessGL& context,
  const MedialInput& input,
  uint8_t* medial,
  double* cosine,
  int64_t& count,
  std::string& error);

/// The medial pass over a field on the GPU (ComputeLinearFactorFieldOnGPU, signed, in its
/// local frame), read where it lies; its distances (local units) come back into
/// `distance`.
bool MedialAxisOnGPUField(HeadlessGL& context,
  const GPUField& field,
  const MedialInput& parameters,
  float* distance,
  uint8_t* medial,
  double* cosine,
  int64_t& count,
  std::string& error);

} // namespace vtkdf

#endif
