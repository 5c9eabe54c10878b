#include "GL/GridUniforms.h"

#include "Common/ArcTangent.h"

#include "ArcTangent2.h"        // Shaders/ArcTangent2.glsl, embedded
#include "CorrectlyRounded.h"   // Shaders/CorrectlyRounded.glsl, embedded
#include "SampleGridUniforms.h" // Shaders/SampleGridUniforms.glsl, embedded
#include "TriangleDistance.h"   // Shaders/TriangleDistance.glsl, embedded

#include <cstdint>
#include <cstring>
#include <vector>

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

void SetArcTangentUniforms(const GLFunctions& gl, GLuint program)
{
  const ArcTangentTable& table = ArcTangentConstants();
  // The tables as the bits of their doubles, two 32-bit words each (low word first, as
  // packDouble2x32 takes them).
  auto setBits = [&](const char* name, const double* values, int count)
  {
    std::vector<GLuint> words(2 * count);
    for (int i = 0; i < count; ++i)
    {
      uint64_t bits;
      std::memcpy(&bits, values + i, sizeof bits);
      words[2 * i] = static_cast<GLuint>(bits & 0xffffffffu);
      words[2 * i + 1] = static_cast<GLuint>(bits >> 32);
    }
    gl.Uniform2uiv(gl.GetUniformLocation(program, name), count, words.data());
  };
  setBits("AtanAtPoint", table.AtPoint, ArcTangentTable::Points);
  setBits("AtanCoefficient", table.Coefficient, ArcTangentTable::Terms);
  gl.Uniform1d(gl.GetUniformLocation(program, "AtanPi"), table.Pi);
  gl.Uniform1d(gl.GetUniformLocation(program, "AtanHalfPi"), table.HalfPi);
}

std::string WithSharedCode(const char* source)
{
  std::string text = source;
  const std::pair<const char*, const char*> shared[] = { { "//DF::SampleGrid", SampleGridUniforms },
    { "//DF::TriangleDistance", TriangleDistance },
    { "//DF::CorrectlyRounded", CorrectlyRounded },
    { "//DF::ArcTangent2", ::ArcTangent2 } }; // ::, the source (vtkdf::ArcTangent2 is the C++)
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
