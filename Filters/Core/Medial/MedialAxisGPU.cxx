#include "Medial/MedialAxisGPU.h"

#include "GL/GridUniforms.h"

#include "GL/GLFunctions.h"
#include "MedialAxis_comp.h"

#include <algorithm>
#include <cmath>

namespace vtkdf
{

namespace
{
/// The medial pass over a field already in GL buffers (1 and 3 floats per voxel);
/// fills `cosine`.
bool MedialPass(HeadlessGL& context,
  const MedialInput& input,
  GLuint distanceBuffer,
  GLuint closestBuffer,
  double* cosine,
  std::string& error)
{
  const GLFunctions& gl = context.GL();
  const IndexBox& whole = input.Grid.Whole;
  const int nx = whole.Size(0), ny = whole.Size(1), nz = whole.Size(2);
  const int64_t slice = int64_t(nx) * ny, voxels = slice * nz;
  GLint alignment = 1;
  const int64_t slab = SlabSlices(gl, slice, 12, nz, alignment);
  if (slab == 0 || voxels > INT32_MAX)
  {
    error = "a slice of " + std::to_string(nx) + " x " + std::to_string(ny) +
      " closest points does not fit GL_MAX_SHADER_STORAGE_BLOCK_SIZE";
    return false;
  }
  std::string log;
  const GLuint program = context.BuildProgram({ { GL_COMPUTE_SHADER, MedialAxis_comp } }, log);
  if (!program)
  {
    error = log;
    return false;
  }
  GLuint cosines = 0;
  gl.GenBuffers(1, &cosines);
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, cosines);
  gl.BufferData(GL_SHADER_STORAGE_BUFFER, voxels * 8, nullptr, GL_DYNAMIC_READ);
  gl.UseProgram(program);
  auto uniform = [&](const char* name) { return gl.GetUniformLocation(program, name); };
  SetGridUniforms(gl, program, input.Grid, whole);
  gl.Uniform1d(uniform("Threshold"), std::cos(input.SeparationAngle * M_PI / 180.0));
  gl.Uniform1i(uniform("Region"), static_cast<int>(input.Region));
  const auto& h = input.Grid.Spacing;
  gl.Uniform1d(uniform("HalfDiagonal"), 0.5 * std::sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]));
  gl.Uniform1d(uniform("CapTolerance"), MedialCapTolerance);
  gl.Uniform1d(uniform("FanMargin"), MedialFanMargin);
  gl.MemoryBarrier(GL_ALL_BARRIER_BITS);
  const int64_t perDispatch = int64_t(65535) * 64;
  for (int64_t z0 = 0; z0 < nz; z0 += slab)
  {
    const int64_t z1 = std::min<int64_t>(nz, z0 + slab); // exclusive
    // Voxels [from, to) are read (one slice of neighbours on each side).
    const int64_t from = std::max<int64_t>(0, z0 - 1) * slice,
                  to = std::min<int64_t>(nz, z1 + 1) * slice;
    gl.Uniform1i(uniform("DistanceBase"),
      static_cast<int>(BindVoxelRange(gl, 0, distanceBuffer, from, to, 4, 4, alignment)));
    gl.Uniform1i(uniform("ClosestBase"),
      static_cast<int>(BindVoxelRange(gl, 1, closestBuffer, from, to, 12, 4, alignment)));
    gl.Uniform1i(uniform("CosineBase"),
      static_cast<int>(BindVoxelRange(gl, 2, cosines, z0 * slice, z1 * slice, 8, 8, alignment)));
    gl.Uniform1i(uniform("Last"), static_cast<int>(z1 * slice));
    for (int64_t first = z0 * slice; first < z1 * slice; first += perDispatch)
    {
      gl.Uniform1i(uniform("First"), static_cast<int>(first));
      gl.DispatchCompute(
        static_cast<GLuint>((std::min(perDispatch, z1 * slice - first) + 63) / 64), 1, 1);
    }
  }
  gl.MemoryBarrier(GL_ALL_BARRIER_BITS);
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, cosines);
  gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, voxels * 8, cosine);
  gl.DeleteBuffers(1, &cosines);
  gl.DeleteProgram(program);
  return NoGLError(gl, "in the medial axis pass", error);
}

int64_t Mark(const double* cosine, uint8_t* medial, int64_t voxels)
{
  int64_t count = 0;
  for (int64_t v = 0; v < voxels; ++v)
  {
    medial[v] = cosine[v] <= 1 ? 1 : 0;
    count += medial[v];
  }
  return count;
}

/// Two GL buffers deleted with the scope.
struct Buffers
{
  const GLFunctions& GL;
  GLuint Id[3] = { 0, 0, 0 };
  explicit Buffers(const GLFunctions& gl)
    : GL(gl)
  {
    gl.GenBuffers(3, this->Id);
  }
  ~Buffers() { this->GL.DeleteBuffers(3, this->Id); }
};
} // namespace

bool MedialAxisGPU(HeadlessGL& context,
  const MedialInput& input,
  uint8_t* medial,
  double* cosine,
  int64_t& count,
  std::string& error)
{
  HeadlessGL::Scope scope(context);
  if (!scope.Ok(error))
  {
    return false;
  }
  const GLFunctions& gl = context.GL();
  const int64_t voxels = input.Grid.Whole.Count();
  Buffers field(gl);
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, field.Id[0]);
  gl.BufferData(GL_SHADER_STORAGE_BUFFER, voxels * 4, input.Distance, GL_STATIC_DRAW);
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, field.Id[1]);
  gl.BufferData(GL_SHADER_STORAGE_BUFFER, voxels * 12, input.ClosestPoint, GL_STATIC_DRAW);
  if (!MedialPass(context, input, field.Id[0], field.Id[1], cosine, error))
  {
    return false;
  }
  count = Mark(cosine, medial, voxels);
  return true;
}

bool MedialAxisOnGPUField(HeadlessGL& context,
  const GPUField& field,
  const MedialInput& parameters,
  float* distance,
  uint8_t* medial,
  double* cosine,
  int64_t& count,
  std::string& error)
{
  HeadlessGL::Scope scope(context);
  if (!scope.Ok(error) ||
    !MedialPass(context, parameters, field.Distance, field.ClosestPoint, cosine, error))
  {
    return false;
  }
  const GLFunctions& gl = context.GL();
  const int64_t voxels = field.Extent.Count();
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, field.Distance);
  gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, voxels * 4, distance);
  count = Mark(cosine, medial, voxels);
  return true;
}

} // namespace vtkdf
