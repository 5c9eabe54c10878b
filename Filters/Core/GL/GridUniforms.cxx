#include "GL/GridUniforms.h"

#include "CorrectlyRounded.h"   // Shaders/CorrectlyRounded.glsl, embedded
#include "SampleGridUniforms.h" // Shaders/SampleGridUniforms.glsl, embedded
#include "TriangleDistance.h"   // Shaders/TriangleDistance.glsl, embedded

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

std::string WithSharedCode(const char* source)
{
  std::string text = source;
  const std::pair<const char*, const char*> shared[] = { { "//DF::SampleGrid", SampleGridUniforms },
    { "//DF::TriangleDistance", TriangleDistance },
    { "//DF::CorrectlyRounded", CorrectlyRounded } };
  for (const auto& [marker, code] : shared)
  {
    const size_t at = text.find(marker);
    if (at != std::string::npos)
    {
      text.replace(at, std::string(marker).size(), code);
    }
  }
  return text;
}

} // namespace vtkdf
