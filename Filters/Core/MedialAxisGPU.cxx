#include "MedialAxisGPU.h"

#include "GLFunctions.h"
#include "MedialAxis_comp.h"

#include <algorithm>
#include <cmath>

namespace vtkdf
{

bool MedialAxisGPU(HeadlessGL& context,
  const MedialInput& input,
  uint8_t* medial,
  double* cosine,
  int64_t& count,
  std::string& error)
{
  HeadlessGL::Scope scope(context);
  if (!scope.Ok())
  {
    error = "could not make the " + context.Platform() + " context current";
    return false;
  }
  const GLFunctions& gl = context.GL();
  const IndexBox& whole = input.Grid.Whole;
  const int64_t voxels = whole.Count();
  GLint64 maxBlock = 0;
  gl.GetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &maxBlock);
  if (voxels * 12 > maxBlock || voxels > INT32_MAX)
  {
    error = "the closest points (" + std::to_string(voxels * 12 / 1048576) +
      " MiB) exceed GL_MAX_SHADER_STORAGE_BLOCK_SIZE (" + std::to_string(maxBlock / 1048576) +
      " MiB)";
    return false;
  }
  std::string log;
  const GLuint program = context.BuildProgram({ { GL_COMPUTE_SHADER, MedialAxis_comp } }, log);
  if (!program)
  {
    error = log;
    return false;
  }
  GLuint buffers[3];
  gl.GenBuffers(3, buffers);
  const void* data[2] = { input.Distance, input.ClosestPoint };
  const int64_t bytes[3] = { voxels * 4, voxels * 12, voxels * 8 };
  for (int b = 0; b < 3; ++b)
  {
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, buffers[b]);
    gl.BufferData(GL_SHADER_STORAGE_BUFFER,
      bytes[b],
      b < 2 ? data[b] : nullptr,
      b < 2 ? GL_STATIC_DRAW : GL_DYNAMIC_READ);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, b, buffers[b]);
  }
  gl.UseProgram(program);
  auto uniform = [&](const char* name) { return gl.GetUniformLocation(program, name); };
  gl.Uniform3i(uniform("Dims"), whole.Size(0), whole.Size(1), whole.Size(2));
  gl.Uniform3i(uniform("Lo"), whole.Lo[0], whole.Lo[1], whole.Lo[2]);
  gl.Uniform3d(uniform("Origin"), input.Grid.Origin[0], input.Grid.Origin[1], input.Grid.Origin[2]);
  gl.Uniform3d(
    uniform("Spacing"), input.Grid.Spacing[0], input.Grid.Spacing[1], input.Grid.Spacing[2]);
  gl.Uniform1d(uniform("Threshold"), std::cos(input.SeparationAngle * M_PI / 180.0));
  gl.Uniform1i(uniform("Region"), static_cast<int>(input.Region));
  gl.Uniform1d(uniform("Depth"), MedialMinimumDepth);
  const int64_t perDispatch = int64_t(65535) * 64;
  for (int64_t first = 0; first < voxels; first += perDispatch)
  {
    gl.Uniform1i(uniform("First"), static_cast<int>(first));
    const int64_t n = std::min(perDispatch, voxels - first);
    gl.DispatchCompute(static_cast<GLuint>((n + 63) / 64), 1, 1);
  }
  gl.MemoryBarrier(GL_ALL_BARRIER_BITS);
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, buffers[2]);
  gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, bytes[2], cosine);
  const GLenum status = gl.GetError();
  gl.DeleteBuffers(3, buffers);
  gl.DeleteProgram(program);
  if (status != GL_NO_ERROR)
  {
    error = "OpenGL error " + std::to_string(status) + " in the medial axis pass";
    return false;
  }
  count = 0;
  for (int64_t v = 0; v < voxels; ++v)
  {
    medial[v] = cosine[v] <= 1 ? 1 : 0;
    count += medial[v];
  }
  return true;
}

} // namespace vtkdf
