// MedialAxisGPU: the medial axis pass as a compute shader (Shaders/MedialAxis.comp.glsl),
// the same double-precision arithmetic as MedialAxisCPU, so the same voxels.
#ifndef vtkdf_MedialAxisGPU_h
#define vtkdf_MedialAxisGPU_h

#include "HeadlessGL.h"
#include "MedialAxis.h"

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

} // namespace vtkdf

#endif
