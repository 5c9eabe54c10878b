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
  // The arrays are bound a slab of z at a time (with one slice of neighbours on each
  // side), so that no range exceeds GL_MAX_SHADER_STORAGE_BLOCK_SIZE.
  GLint64 maxBlock = 0;
  GLint alignment = 1;
  gl.GetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &maxBlock);
  gl.GetIntegerv(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT, &alignment);
  const int nx = whole.Size(0), ny = whole.Size(1), nz = whole.Size(2);
  const int64_t slice = int64_t(nx) * ny;
  const int64_t usable = maxBlock - 2 * alignment;
  const int64_t slab = std::min<int64_t>(nz, usable / (slice * 12) - 2);
  if (slab < 1 || voxels > INT32_MAX || alignment % 8 != 0)
  {
    error = "a slice of " + std::to_string(nx) + " x " + std::to_string(ny) +
      " closest points does not fit GL_MAX_SHADER_STORAGE_BLOCK_SIZE (" +
      std::to_string(maxBlock / 1048576) + " MiB)";
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
  const int64_t elementBytes[3] = { 4, 12, 8 };
  for (int b = 0; b < 3; ++b)
  {
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, buffers[b]);
    gl.BufferData(GL_SHADER_STORAGE_BUFFER,
      voxels * elementBytes[b],
      b < 2 ? data[b] : nullptr,
      b < 2 ? GL_STATIC_DRAW : GL_DYNAMIC_READ);
  }
  gl.UseProgram(program);
  auto uniform = [&](const char* name) { return gl.GetUniformLocation(program, name); };
  gl.Uniform3i(uniform("Dims"), nx, ny, nz);
  gl.Uniform3i(uniform("Lo"), whole.Lo[0], whole.Lo[1], whole.Lo[2]);
  gl.Uniform3d(uniform("Origin"), input.Grid.Origin[0], input.Grid.Origin[1], input.Grid.Origin[2]);
  gl.Uniform3d(
    uniform("Spacing"), input.Grid.Spacing[0], input.Grid.Spacing[1], input.Grid.Spacing[2]);
  gl.Uniform1d(uniform("Threshold"), std::cos(input.SeparationAngle * M_PI / 180.0));
  gl.Uniform1i(uniform("Region"), static_cast<int>(input.Region));
  gl.Uniform1d(uniform("Depth"), MedialMinimumDepth);
  const char* bases[3] = { "DistanceBase", "ClosestBase", "CosineBase" };
  const int64_t perDispatch = int64_t(65535) * 64;
  for (int z0 = 0; z0 < nz; z0 += static_cast<int>(slab))
  {
    const int z1 = static_cast<int>(std::min<int64_t>(nz, z0 + slab)); // exclusive
    // Voxels [from, to) must be readable; the range starts on an aligned byte offset.
    const int64_t from = std::max(0, z0 - 1) * slice, to = std::min(nz, z1 + 1) * slice;
    for (int b = 0; b < 3; ++b)
    {
      const int64_t begin = from * elementBytes[b] / alignment * alignment;
      const int64_t end = to * elementBytes[b];
      gl.BindBufferRange(GL_SHADER_STORAGE_BUFFER, b, buffers[b], begin, end - begin);
      gl.Uniform1i(uniform(bases[b]), static_cast<int>(begin / (b == 2 ? 8 : 4)));
    }
    gl.Uniform1i(uniform("Last"), static_cast<int>(z1 * slice));
    for (int64_t first = z0 * slice; first < z1 * slice; first += perDispatch)
    {
      gl.Uniform1i(uniform("First"), static_cast<int>(first));
      const int64_t n = std::min(perDispatch, z1 * slice - first);
      gl.DispatchCompute(static_cast<GLuint>((n + 63) / 64), 1, 1);
    }
  }
  gl.MemoryBarrier(GL_ALL_BARRIER_BITS);
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, buffers[2]);
  gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, voxels * 8, cosine);
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
