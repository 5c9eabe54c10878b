#include "Segment/SegmentFieldGPU.h"

#include "GL/GridUniforms.h"

#include "GL/GLFunctions.h"
#include "SideLabel_comp.h"

#include <algorithm>

namespace vtkdf
{

namespace
{
/// GL buffers deleted with the scope.
struct Buffers
{
  const GLFunctions& GL;
  GLuint Id[4] = { 0, 0, 0, 0 };
  explicit Buffers(const GLFunctions& gl)
    : GL(gl)
  {
    gl.GenBuffers(4, this->Id);
  }
  ~Buffers() { this->GL.DeleteBuffers(4, this->Id); }
};
} // namespace

bool SideLabelsOnGPUField(HeadlessGL& context,
  const GPUField& field,
  const SurfacePatches& patches,
  const std::vector<int32_t>& siteTriangle,
  float* distance,
  float* closest,
  int32_t* label,
  std::string& error)
{
  HeadlessGL::Scope scope(context);
  if (!scope.Ok(error))
  {
    return false;
  }
  const GLFunctions& gl = context.GL();
  const IndexBox& extent = field.Extent;
  const int nx = extent.Size(0), ny = extent.Size(1), nz = extent.Size(2);
  const int64_t slice = int64_t(nx) * ny, voxels = slice * nz;
  std::vector<int32_t> triangles, corners;
  if (voxels > INT32_MAX || !patches.Flatten(triangles, corners))
  {
    error = "the grid or the mesh is too large for the GPU's int indices";
    return false;
  }
  // The labels, then the mesh; the field's buffers are the GPUField's.
  enum
  {
    LabelBuffer,
    SiteBuffer,
    TriangleBuffer,
    PositionBuffer
  };
  Buffers buffers(gl);
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, buffers.Id[LabelBuffer]);
  gl.BufferData(GL_SHADER_STORAGE_BUFFER, voxels * 4, nullptr, GL_DYNAMIC_COPY);

  std::string log;
  const GLuint program = context.BuildProgram({ { GL_COMPUTE_SHADER, SideLabel_comp } }, log);
  if (!program)
  {
    error = log;
    return false;
  }
  auto upload = [&](int which, const void* data, int64_t size)
  {
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, buffers.Id[which]);
    gl.BufferData(GL_SHADER_STORAGE_BUFFER, std::max<int64_t>(size, 4), data, GL_STATIC_DRAW);
  };
  const LargeVector<double>& points = *patches.PointArray();
  upload(SiteBuffer, siteTriangle.data(), static_cast<int64_t>(siteTriangle.size()) * 4);
  upload(TriangleBuffer, triangles.data(), static_cast<int64_t>(triangles.size()) * 4);
  upload(PositionBuffer, points.data(), static_cast<int64_t>(points.size()) * 8);
  GLuint cornerBuffer = 0;
  gl.GenBuffers(1, &cornerBuffer);
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, cornerBuffer);
  gl.BufferData(GL_SHADER_STORAGE_BUFFER,
    static_cast<int64_t>(corners.size()) * 4,
    corners.data(),
    GL_STATIC_DRAW);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, buffers.Id[SiteBuffer]);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, buffers.Id[TriangleBuffer]);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, buffers.Id[PositionBuffer]);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 6, cornerBuffer);

  gl.UseProgram(program);
  auto uniform = [&](const char* name) { return gl.GetUniformLocation(program, name); };
  const SampleGrid& grid = field.Grid;
  SetGridUniforms(gl, program, grid, extent);
  gl.Uniform1i(uniform("KeyCount"), static_cast<int>(corners.size() - patches.CornerCount() - 1));
  const GridFrame& frame = field.Frame;
  gl.Uniform3d(uniform("FrameOrigin"), frame.Origin[0], frame.Origin[1], frame.Origin[2]);
  gl.Uniform1d(uniform("FrameInverse"), 1 / frame.Scale);
  gl.MemoryBarrier(GL_ALL_BARRIER_BITS);
  // The per-sample buffers a slab of z at a time (within the storage block limit).
  GLint alignment = 1;
  const int64_t slab = SlabSlices(gl, slice, 12, nz, alignment);
  if (slab == 0)
  {
    gl.DeleteBuffers(1, &cornerBuffer);
    gl.DeleteProgram(program);
    error = "a slice of " + std::to_string(nx) + " x " + std::to_string(ny) +
      " closest points does not fit GL_MAX_SHADER_STORAGE_BLOCK_SIZE";
    return false;
  }
  const int64_t perDispatch = int64_t(65535) * 64;
  for (int64_t z0 = 0; z0 < nz; z0 += slab)
  {
    const int64_t z1 = std::min<int64_t>(nz, z0 + slab), from = z0 * slice, to = z1 * slice;
    gl.Uniform1i(uniform("SiteBase"),
      static_cast<int>(BindVoxelRange(gl, 0, field.SiteIds, from, to, 4, 4, alignment)));
    gl.Uniform1i(uniform("ClosestBase"),
      static_cast<int>(BindVoxelRange(gl, 1, field.ClosestPoint, from, to, 12, 4, alignment)));
    gl.Uniform1i(uniform("LabelBase"),
      static_cast<int>(BindVoxelRange(gl, 2, buffers.Id[LabelBuffer], from, to, 4, 4, alignment)));
    gl.Uniform1i(uniform("Last"), static_cast<int>(to));
    for (int64_t first = from; first < to; first += perDispatch)
    {
      gl.Uniform1i(uniform("First"), static_cast<int>(first));
      gl.DispatchCompute(static_cast<GLuint>((std::min(perDispatch, to - first) + 63) / 64), 1, 1);
    }
  }
  gl.MemoryBarrier(GL_ALL_BARRIER_BITS);
  const struct
  {
    GLuint Buffer;
    void* Out;
    int64_t Bytes;
  } results[3] = { { field.Distance, distance, voxels * 4 },
    { field.ClosestPoint, closest, voxels * 12 },
    { buffers.Id[LabelBuffer], label, voxels * 4 } };
  for (const auto& r : results)
  {
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, r.Buffer);
    gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, r.Bytes, r.Out);
  }
  gl.DeleteBuffers(1, &cornerBuffer);
  gl.DeleteProgram(program);
  return NoGLError(gl, "in the side-label pass", error);
}

} // namespace vtkdf
