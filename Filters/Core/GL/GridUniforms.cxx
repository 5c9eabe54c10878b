#include "GL/GridUniforms.h"

#include "SampleGridUniforms.h" // Shaders/SampleGridUniforms.glsl, embedded

namespace vtkdf
{

void SetGridUniforms(const GLFunctions& gl,
  GLuint program,
  const SampleGrid& grid,
  const IndexBox& extent)
{
  gl.Uniform3i(
    gl.GetUniformLocation(program, "Dims"), extent.Size(0), extent.Size(1), extent.Size(2));
  gl.Uniform3i(gl.GetUniformLocation(program, "Lo"), extent.Lo[0], extent.Lo[1], extent.Lo[2]);
  gl.Uniform3d(
    gl.GetUniformLocation(program, "Origin"), grid.Origin[0], grid.Origin[1], grid.Origin[2]);
  gl.Uniform3d(
    gl.GetUniformLocation(program, "Spacing"), grid.Spacing[0], grid.Spacing[1], grid.Spacing[2]);
}

std::string WithSampleGrid(const char* source)
{
  std::string text = source;
  const std::string marker = "//DF::SampleGrid";
  const size_t at = text.find(marker);
  if (at != std::string::npos)
  {
    text.replace(at, marker.size(), SampleGridUniforms);
  }
  return text;
}

} // namespace vtkdf
