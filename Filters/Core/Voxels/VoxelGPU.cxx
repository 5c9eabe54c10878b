#include "Voxels/VoxelGPU.h"

#include "GL/GridUniforms.h"

#include "ChamferLayer_comp.h"
#include "ChamferSeed_comp.h"
#include "GL/GLFunctions.h"
#include "VoxelizeCombine_comp.h"
#include "VoxelizeCommon.h"
#include "VoxelizeFill_comp.h"
#include "VoxelizeRaster_frag.h"
#include "VoxelizeRaster_geom.h"
#include "VoxelizeRaster_vert.h"
#include "Voxels/VoxelizerRules.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

namespace vtkdf
{
using namespace voxelizer;
namespace
{
/// Shaders/VoxelizeCommon.glsl's `Tri` (std430: 224 bytes, 32-byte aligned).
struct alignas(32) GpuTriangle
{
  int64_t X[4];
  int64_t Y[4];
  double Z[4];
  double P[3][4];
  int32_t Flags[4];
  int32_t Pad[4];
};
static_assert(sizeof(GpuTriangle) == 224, "std430 layout of Tri");

/// Shaders/VoxelizeCommon.glsl's `BoundaryTri` (std430: 256 bytes).
struct alignas(32) GpuBoundaryTriangle
{
  double X[4], Y[4], Z[4], Slack[4];
  double P[3][4];
  int32_t Rect[4];
  int32_t Depth[4];
};
static_assert(sizeof(GpuBoundaryTriangle) == 256, "std430 layout of BoundaryTri");

GpuBoundaryTriangle Pack(const BoundaryTriangle& t)
{
  GpuBoundaryTriangle g{};
  for (int k = 0; k < 3; ++k)
  {
    g.X[k] = t.X[k];
    g.Y[k] = t.Y[k];
    g.Z[k] = t.Z[k];
    g.Slack[k] = t.Slack[k];
    for (int d = 0; d < 3; ++d)
    {
      g.P[k][d] = t.P[k][d];
    }
  }
  g.X[3] = t.Orientation;
  g.Y[3] = t.GradP;
  g.Z[3] = t.GradQ;
  g.Slack[3] = t.Spread;
  g.Rect[0] = t.P0;
  g.Rect[1] = t.P1;
  g.Rect[2] = t.Q0;
  g.Rect[3] = t.Q1;
  g.Depth[0] = t.K0;
  g.Depth[1] = t.K1;
  return g;
}

/// A lane texture: RGBA32UI 2D array, Nx x Ny lanes of Texels x 128 bits.
class Lanes
{
public:
  explicit Lanes(const GLFunctions& gl)
    : GL(gl)
  {
  }
  ~Lanes()
  {
    if (this->Id)
    {
      this->GL.DeleteTextures(1, &this->Id);
    }
  }
  Lanes(const Lanes&) = delete;
  Lanes& operator=(const Lanes&) = delete;

  void Create(int nx, int ny, int bits)
  {
    this->Nx = nx;
    this->Ny = ny;
    this->Texels = std::max(1, (bits + 127) / 128);
    this->GL.GenTextures(1, &this->Id);
    this->GL.BindTexture(GL_TEXTURE_2D_ARRAY, this->Id);
    this->GL.TexStorage3D(GL_TEXTURE_2D_ARRAY, 1, GL_RGBA32UI, nx, ny, this->Texels);
    this->GL.ClearTexImage(this->Id, 0, GL_RGBA_INTEGER, GL_UNSIGNED_INT, nullptr);
  }
  void Bind(GLuint unit, GLenum access) const
  {
    this->GL.BindImageTexture(unit, this->Id, 0, GL_TRUE, 0, access, GL_RGBA32UI);
  }
  size_t Words32() const { return size_t(this->Nx) * this->Ny * this->Texels * 4; }

  /// Into 64-bit lanes (`bits` already sized nx x ny x nz).
  void Download(BitVolume& bits) const
  {
    std::vector<uint32_t> data(this->Words32());
    this->GL.GetTextureImage(this->Id,
      0,
      GL_RGBA_INTEGER,
      GL_UNSIGNED_INT,
      static_cast<GLsizei>(data.size() * 4),
      data.data());
    const int words = bits.WordsPerLane();
    for (int y = 0; y < this->Ny; ++y)
    {
      for (int x = 0; x < this->Nx; ++x)
      {
        uint64_t* lane = bits.Lane(x, y);
        for (int w = 0; w < words; ++w)
        {
          const size_t texel = (size_t(w / 2) * this->Ny + y) * this->Nx + x;
          const uint32_t* c = &data[4 * texel + 2 * (w % 2)];
          lane[w] = uint64_t(c[0]) | (uint64_t(c[1]) << 32);
        }
        lane[words - 1] &= bits.LastWordMask();
      }
    }
  }

  /// From 64-bit lanes.
  void Upload(const BitVolume& bits)
  {
    std::vector<uint32_t> data(this->Words32(), 0);
    const int words = bits.WordsPerLane();
    for (int y = 0; y < this->Ny; ++y)
    {
      for (int x = 0; x < this->Nx; ++x)
      {
        const uint64_t* lane = bits.Lane(x, y);
        for (int w = 0; w < words; ++w)
        {
          const size_t texel = (size_t(w / 2) * this->Ny + y) * this->Nx + x;
          data[4 * texel + 2 * (w % 2)] = static_cast<uint32_t>(lane[w]);
          data[4 * texel + 2 * (w % 2) + 1] = static_cast<uint32_t>(lane[w] >> 32);
        }
      }
    }
    this->GL.TextureSubImage3D(this->Id,
      0,
      0,
      0,
      0,
      this->Nx,
      this->Ny,
      this->Texels,
      GL_RGBA_INTEGER,
      GL_UNSIGNED_INT,
      data.data());
  }

  const GLFunctions& GL;
  GLuint Id = 0;
  int Nx = 0, Ny = 0, Texels = 0;
};

/// Buffers, vertex array, framebuffer and programs of one run.
struct Objects
{
  explicit Objects(const GLFunctions& gl)
    : GL(gl)
  {
  }
  ~Objects()
  {
    this->GL.DeleteBuffers(4, this->Buffers);
    this->GL.DeleteVertexArrays(1, &this->VAO);
    this->GL.DeleteFramebuffers(1, &this->FBO);
    for (GLuint p : this->Programs)
    {
      this->GL.DeleteProgram(p);
    }
  }
  const GLFunctions& GL;
  GLuint Buffers[4] = { 0, 0, 0, 0 }; // triangles, distances, counts, boundary triangles
  GLuint VAO = 0, FBO = 0;
  std::vector<GLuint> Programs;
};

GLuint Build(HeadlessGL& context,
  Objects& objects,
  const std::vector<std::pair<unsigned, std::string>>& stages,
  std::string& error)
{
  std::vector<std::pair<unsigned, const char*>> sources;
  for (const auto& s : stages)
  {
    sources.emplace_back(s.first, s.second.c_str());
  }
  std::string log;
  const GLuint program = context.BuildProgram(sources, log);
  if (!program)
  {
    error = log;
  }
  else
  {
    objects.Programs.push_back(program);
  }
  return program;
}

/// `records` into `buffer` (one record's worth at least: an empty buffer cannot be
/// bound), bound at shader storage binding `binding`.
template<typename Record>
void UploadRecords(const GLFunctions& gl,
  GLuint buffer,
  GLuint binding,
  const std::vector<Record>& records)
{
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, buffer);
  gl.BufferData(GL_SHADER_STORAGE_BUFFER,
    std::max<size_t>(1, records.size()) * sizeof(Record),
    records.data(),
    GL_STATIC_DRAW);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, buffer);
}

GLint Uniform(const GLFunctions& gl, GLuint program, const char* name)
{
  return gl.GetUniformLocation(program, name);
}

bool CheckLimits(const GLFunctions& gl, int nx, int ny, int texels, std::string& error)
{
  GLint maxSize = 0, maxLayers = 0;
  gl.GetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
  gl.GetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxLayers);
  if (nx > maxSize || ny > maxSize || texels > maxLayers)
  {
    error = "a lane grid of " + std::to_string(nx) + " x " + std::to_string(ny) + " x " +
      std::to_string(texels) + " texels exceeds GL_MAX_TEXTURE_SIZE " + std::to_string(maxSize) +
      " or GL_MAX_ARRAY_TEXTURE_LAYERS " + std::to_string(maxLayers);
    return false;
  }
  return true;
}

/// Voxelizes into z-lane textures (boundaryZ / solidZ created when wanted).
bool VoxelizeToLanes(HeadlessGL& context,
  Objects& objects,
  const MeshInput& mesh,
  const SampleGrid& grid,
  Lanes* boundaryZ,
  Lanes* solidZ,
  VoxelizeStatistics& statistics,
  std::string& error)
{
  const GLFunctions& gl = context.GL();
  statistics = VoxelizeStatistics();
  if (!ValidateMesh(mesh, grid, error))
  {
    return false;
  }
  if (!gl.HasExtension("GL_ARB_gpu_shader_int64"))
  {
    error =
      "the GPU voxelizer needs GL_ARB_gpu_shader_int64, which " + context.Renderer() + " lacks";
    return false;
  }
  statistics.Triangles = static_cast<int64_t>(mesh.Triangles.size() / 3);
  const double orientation = MeshOrientation(mesh);
  statistics.FlippedOrientation = orientation < 0;
  const IndexBox& whole = grid.Whole;
  const int n[3] = { whole.Size(0), whole.Size(1), whole.Size(2) };
  for (int a = 0; a < 3; ++a)
  {
    if (!CheckLimits(gl, n[(a + 1) % 3], n[(a + 2) % 3], (2 * n[a] + 3 + 127) / 128, error))
    {
      return false;
    }
  }

  const std::string common = VoxelizeCommon;
  const GLuint raster = Build(context,
    objects,
    { { GL_VERTEX_SHADER, common + VoxelizeRaster_vert },
      { GL_GEOMETRY_SHADER, common + VoxelizeRaster_geom },
      { GL_FRAGMENT_SHADER, common + VoxelizeRaster_frag } },
    error);
  const GLuint fill =
    solidZ ? Build(context, objects, { { GL_COMPUTE_SHADER, VoxelizeFill_comp } }, error) : 1;
  const GLuint combine =
    Build(context, objects, { { GL_COMPUTE_SHADER, VoxelizeCombine_comp } }, error);
  if (!raster || !fill || !combine)
  {
    return false;
  }
  if (!objects.VAO)
  {
    gl.GenVertexArrays(1, &objects.VAO);
    gl.GenBuffers(4, objects.Buffers);
    gl.GenFramebuffers(1, &objects.FBO);
  }
  gl.BindVertexArray(objects.VAO);
  gl.BindFramebuffer(GL_FRAMEBUFFER, objects.FBO);
  gl.Disable(GL_DEPTH_TEST);
  gl.Disable(GL_BLEND);
  gl.Enable(GL_COLOR_LOGIC_OP);
  gl.LogicOp(GL_OR);

  const double limit2 = BoundaryLimit2(grid);
  Lanes boundary[3] = { Lanes(gl), Lanes(gl), Lanes(gl) };
  Lanes front[3] = { Lanes(gl), Lanes(gl), Lanes(gl) };
  Lanes back[3] = { Lanes(gl), Lanes(gl), Lanes(gl) };
  Lanes solid[3] = { Lanes(gl), Lanes(gl), Lanes(gl) };
  const int64_t numTriangles = static_cast<int64_t>(mesh.Triangles.size() / 3);
  std::vector<GpuTriangle> records;
  std::vector<GpuBoundaryTriangle> boundaryRecords[3];
  if (boundaryZ)
  {
    // Each triangle in its boundary view (VoxelizerRules.h, BoundaryTriangle).
    for (int64_t t = 0; t < numTriangles; ++t)
    {
      BoundaryTriangle setup;
      if (SetupBoundaryTriangle(mesh, t, grid, setup))
      {
        boundaryRecords[setup.View].push_back(Pack(setup));
      }
    }
  }
  records.reserve(solidZ ? numTriangles : 0);
  int64_t far = 0;
  for (int a = 0; a < 3; ++a)
  {
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    records.clear();
    for (int64_t t = 0; solidZ && t < numTriangles; ++t)
    {
      ProjectedTriangle p;
      bool isFar = false;
      if (!ProjectTriangle(mesh, t, grid, a, orientation, p, isFar))
      {
        far += isFar;
        continue;
      }
      GpuTriangle g{};
      for (int k = 0; k < 3; ++k)
      {
        g.X[k] = p.X[k];
        g.Y[k] = p.Y[k];
        g.Z[k] = p.Z[k];
        for (int d = 0; d < 3; ++d)
        {
          g.P[k][d] = p.P[k][d];
        }
        g.Flags[k + 1] = p.Owns[k];
      }
      g.X[3] = p.Area;
      g.Flags[0] = p.Entering;
      records.push_back(g);
    }
    UploadRecords(gl, objects.Buffers[0], 0, records);
    const std::vector<GpuBoundaryTriangle>& boundaryView = boundaryRecords[a];
    UploadRecords(gl, objects.Buffers[3], 1, boundaryView);

    gl.UseProgram(raster);
    gl.Uniform1i(Uniform(gl, raster, "Nb"), n[b]);
    gl.Uniform1i(Uniform(gl, raster, "Nc"), n[c]);
    gl.Uniform1i(Uniform(gl, raster, "Na"), n[a]);
    gl.Uniform3i(Uniform(gl, raster, "Axes"), a, b, c);
    SetGridUniforms(gl, raster, grid, whole);
    gl.Uniform1d(Uniform(gl, raster, "Limit2"), limit2);
    gl.Uniform1d(Uniform(gl, raster, "Reach"), BoundaryReach(grid, a));
    gl.Viewport(0, 0, n[b], n[c]);
    const GLenum buffers[2] = { GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1 };
    if (boundaryZ)
    {
      boundary[a].Create(n[b], n[c], n[a]);
      gl.FramebufferTexture(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, boundary[a].Id, 0);
      gl.FramebufferTexture(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, 0, 0);
      gl.DrawBuffers(1, buffers);
      if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      {
        error = "the boundary lane framebuffer is incomplete";
        return false;
      }
      gl.Uniform1i(Uniform(gl, raster, "Mode"), 0);
      gl.DrawArrays(GL_POINTS, 0, static_cast<GLsizei>(boundaryView.size()));
    }
    if (solidZ)
    {
      front[a].Create(n[b], n[c], 2 * n[a] + 1 + SolidGuard);
      back[a].Create(n[b], n[c], 2 * n[a] + 1 + SolidGuard);
      gl.FramebufferTexture(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, front[a].Id, 0);
      gl.FramebufferTexture(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, back[a].Id, 0);
      gl.DrawBuffers(2, buffers);
      if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      {
        error = "the solid lane framebuffer is incomplete";
        return false;
      }
      gl.Uniform1i(Uniform(gl, raster, "Mode"), 1);
      gl.DrawArrays(GL_POINTS, 0, static_cast<GLsizei>(records.size()));
      gl.MemoryBarrier(GL_ALL_BARRIER_BITS);
      // The [front, back] intervals of this view.
      solid[a].Create(n[b], n[c], 2 * n[a] + 1 + SolidGuard);
      gl.UseProgram(fill);
      front[a].Bind(0, GL_READ_ONLY);
      back[a].Bind(1, GL_READ_ONLY);
      solid[a].Bind(2, GL_READ_WRITE);
      gl.Uniform2i(Uniform(gl, fill, "Lanes"), n[b], n[c]);
      gl.Uniform1i(Uniform(gl, fill, "Texels"), solid[a].Texels);
      gl.DispatchCompute((n[b] + 7) / 8, (n[c] + 7) / 8, 1);
      gl.MemoryBarrier(GL_ALL_BARRIER_BITS);
    }
  }
  gl.Disable(GL_COLOR_LOGIC_OP);
  statistics.FarTriangles = far / 3;

  // The views rotated into z-lanes and combined.
  if (boundaryZ)
  {
    boundaryZ->Create(n[0], n[1], n[2]);
  }
  if (solidZ)
  {
    solidZ->Create(n[0], n[1], n[2]);
  }
  gl.UseProgram(combine);
  for (int a = 0; a < 3; ++a)
  {
    if (boundaryZ)
    {
      boundary[a].Bind(a, GL_READ_ONLY);
    }
    if (solidZ)
    {
      solid[a].Bind(3 + a, GL_READ_ONLY);
    }
  }
  if (boundaryZ)
  {
    boundaryZ->Bind(6, GL_WRITE_ONLY);
  }
  if (solidZ)
  {
    solidZ->Bind(7, GL_WRITE_ONLY);
  }
  SetGridUniforms(gl, combine, grid, whole);
  gl.Uniform1i(Uniform(gl, combine, "WantBoundary"), boundaryZ != nullptr);
  gl.Uniform1i(Uniform(gl, combine, "WantSolid"), solidZ != nullptr);
  gl.DispatchCompute((n[0] + 7) / 8, (n[1] + 7) / 8, (n[2] + 127) / 128);
  gl.MemoryBarrier(GL_ALL_BARRIER_BITS);
  return NoGLError(gl, "while voxelizing", error);
}
} // namespace

bool VoxelizeGPU(HeadlessGL& context,
  const MeshInput& mesh,
  const SampleGrid& grid,
  BitVolume* boundary,
  BitVolume* solid,
  VoxelizeStatistics& statistics,
  std::string& error)
{
  HeadlessGL::Scope scope(context);
  if (!scope.Ok(error))
  {
    return false;
  }
  const GLFunctions& gl = context.GL();
  Objects objects(gl);
  Lanes boundaryZ(gl), solidZ(gl);
  if (!VoxelizeToLanes(context,
        objects,
        mesh,
        grid,
        boundary ? &boundaryZ : nullptr,
        solid ? &solidZ : nullptr,
        statistics,
        error))
  {
    return false;
  }
  const IndexBox& whole = grid.Whole;
  if (boundary)
  {
    boundary->Resize(whole.Size(0), whole.Size(1), whole.Size(2));
    boundaryZ.Download(*boundary);
  }
  if (solid)
  {
    solid->Resize(whole.Size(0), whole.Size(1), whole.Size(2));
    solidZ.Download(*solid);
  }
  return true;
}

bool ChamferGPU(HeadlessGL& context,
  const ChamferInput& input,
  ChamferMetric metric,
  int maximumLayers,
  int32_t unreached,
  bool negateSolid,
  int32_t* distance,
  BitVolume* boundaryOut,
  BitVolume* solidOut,
  ChamferResult& result,
  VoxelizeStatistics& statistics,
  std::string& error,
  const ProgressCallback& progress)
{
  result = ChamferResult();
  HeadlessGL::Scope scope(context);
  if (!scope.Ok(error))
  {
    return false;
  }
  const GLFunctions& gl = context.GL();
  Objects objects(gl);
  const IndexBox& whole = input.Grid.Whole;
  const int nx = whole.Size(0), ny = whole.Size(1), nz = whole.Size(2);
  const int texels = (nz + 127) / 128;
  if (!CheckLimits(gl, nx, ny, texels, error))
  {
    return false;
  }
  const int64_t voxels = int64_t(nx) * ny * nz, slice = int64_t(nx) * ny;
  // The distance array is bound a slab of whole texels (128 slices) at a time: a
  // texel's invocation writes only its own 128 slices.
  GLint alignment = 0;
  const int64_t slabSlices = SlabSlices(gl, slice, 4, nz, alignment);
  const int texelsPerSlab =
    slabSlices >= nz ? texels : static_cast<int>(std::min<int64_t>(slabSlices / 128, texels));
  if (texelsPerSlab < 1)
  {
    error = "128 slices of the distance array (" + std::to_string(slice * 512 / 1048576) +
      " MiB) exceed GL_MAX_SHADER_STORAGE_BLOCK_SIZE (" +
      std::to_string(MaxStorageBlock(gl) / 1048576) + " MiB)";
    return false;
  }

  // The zero set (and the solid) as z-lanes.
  Lanes boundaryZ(gl), solidZ(gl);
  const bool wantSolid = negateSolid || solidOut;
  bool haveSolid = false;
  if (input.Mesh)
  {
    if (!VoxelizeToLanes(context,
          objects,
          *input.Mesh,
          input.Grid,
          &boundaryZ,
          wantSolid ? &solidZ : nullptr,
          statistics,
          error))
    {
      return false;
    }
    haveSolid = wantSolid;
  }
  else
  {
    boundaryZ.Create(nx, ny, nz);
    boundaryZ.Upload(*input.Boundary);
    if (input.Solid && wantSolid)
    {
      solidZ.Create(nx, ny, nz);
      solidZ.Upload(*input.Solid);
      haveSolid = true;
    }
  }

  const GLuint seed = Build(context, objects, { { GL_COMPUTE_SHADER, ChamferSeed_comp } }, error);
  const GLuint layer = Build(context, objects, { { GL_COMPUTE_SHADER, ChamferLayer_comp } }, error);
  if (!seed || !layer)
  {
    return false;
  }
  if (!objects.VAO)
  {
    gl.GenVertexArrays(1, &objects.VAO);
    gl.GenBuffers(4, objects.Buffers);
    gl.GenFramebuffers(1, &objects.FBO);
  }
  const GLuint distances = objects.Buffers[1], counts = objects.Buffers[2];
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, distances);
  gl.BufferData(GL_SHADER_STORAGE_BUFFER, voxels * 4, nullptr, GL_DYNAMIC_COPY);
  gl.ClearBufferData(GL_SHADER_STORAGE_BUFFER, GL_R32I, GL_RED_INTEGER, GL_INT, &unreached);
  constexpr int Batch = 8;
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, counts);
  gl.BufferData(GL_SHADER_STORAGE_BUFFER, Batch * 4, nullptr, GL_DYNAMIC_READ);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, counts);

  // Runs the current program over every lane texel, one slab of texels at a time, with
  // the slab's part of the distance array bound; `slabUniforms` are the program's
  // TexelBase and DistanceBase locations.
  const GLuint groupsX = (nx + 7) / 8, groupsY = (ny + 7) / 8;
  const GLint seedSlab[2] = { Uniform(gl, seed, "TexelBase"), Uniform(gl, seed, "DistanceBase") };
  const GLint layerSlab[2] = { Uniform(gl, layer, "TexelBase"),
    Uniform(gl, layer, "DistanceBase") };
  auto dispatchSlabs = [&](const GLint slabUniforms[2])
  {
    const GLint texelBase = slabUniforms[0], distanceBase = slabUniforms[1];
    for (int t0 = 0; t0 < texels; t0 += texelsPerSlab)
    {
      const int t1 = std::min(texels, t0 + texelsPerSlab);
      const int64_t from = 128 * int64_t(t0) * slice;
      const int64_t to = std::min<int64_t>(128 * int64_t(t1), nz) * slice;
      gl.Uniform1i(texelBase, t0);
      gl.Uniform1i(distanceBase,
        static_cast<int>(BindVoxelRange(gl, 0, distances, from, to, 4, 4, alignment)));
      gl.DispatchCompute(groupsX, groupsY, t1 - t0);
    }
    gl.MemoryBarrier(GL_ALL_BARRIER_BITS);
  };

  // Layer 0.
  const uint32_t zeros[Batch] = {};
  gl.BufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof(zeros), zeros);
  gl.UseProgram(seed);
  boundaryZ.Bind(0, GL_READ_ONLY);
  SetGridUniforms(gl, seed, input.Grid, whole);
  gl.Uniform1i(Uniform(gl, seed, "Texels"), texels);
  gl.Uniform1i(Uniform(gl, seed, "Value"), 0);
  gl.Uniform1i(Uniform(gl, seed, "Negate"), 0);
  dispatchSlabs(seedSlab);
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, counts);
  uint32_t zeroSet = 0;
  gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof(zeroSet), &zeroSet);
  result.ZeroSet = result.Reached = zeroSet;

  // Layers, in batches between which the counts are read back.
  Lanes first(gl), second(gl), accumulated(gl);
  first.Create(nx, ny, nz);
  second.Create(nx, ny, nz);
  accumulated.Create(nx, ny, nz);
  gl.CopyImageSubData(boundaryZ.Id,
    GL_TEXTURE_2D_ARRAY,
    0,
    0,
    0,
    0,
    first.Id,
    GL_TEXTURE_2D_ARRAY,
    0,
    0,
    0,
    0,
    nx,
    ny,
    texels);
  gl.CopyImageSubData(boundaryZ.Id,
    GL_TEXTURE_2D_ARRAY,
    0,
    0,
    0,
    0,
    accumulated.Id,
    GL_TEXTURE_2D_ARRAY,
    0,
    0,
    0,
    0,
    nx,
    ny,
    texels);
  Lanes* current = &first;
  Lanes* next = &second;
  gl.UseProgram(layer);
  SetGridUniforms(gl, layer, input.Grid, whole);
  gl.Uniform1i(Uniform(gl, layer, "Texels"), texels);
  gl.Uniform1i(Uniform(gl, layer, "Metric"), static_cast<int>(metric));
  const GLint layerLocation = Uniform(gl, layer, "Layer");
  const GLint slotLocation = Uniform(gl, layer, "CountSlot");
  bool done = zeroSet == 0;
  for (int start = 1; !done && (maximumLayers <= 0 || start <= maximumLayers); start += Batch)
  {
    const int end =
      maximumLayers > 0 ? std::min(start + Batch - 1, maximumLayers) : start + Batch - 1;
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, counts);
    gl.BufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof(zeros), zeros);
    for (int l = start; l <= end; ++l)
    {
      current->Bind(0, GL_READ_ONLY);
      next->Bind(1, GL_WRITE_ONLY);
      accumulated.Bind(2, GL_READ_WRITE);
      gl.Uniform1i(layerLocation, l);
      gl.Uniform1i(slotLocation, l - start);
      dispatchSlabs(layerSlab);
      std::swap(current, next);
    }
    uint32_t reached[Batch] = {};
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, counts); // BindBufferRange moved the generic binding
    gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof(reached), reached);
    for (int l = start; l <= end; ++l)
    {
      if (reached[l - start] == 0)
      {
        done = true; // the front died: later layers are empty too
        break;
      }
      result.Layers = l;
      result.Reached += reached[l - start];
    }
    // Progress per batch (the readback above waited for it): the share of the voxels
    // reached, or of the layers when MaximumLayers bounds them.
    const double fraction =
      maximumLayers > 0 ? double(end) / maximumLayers : double(result.Reached) / double(voxels);
    if (progress && !done && !progress(std::min(1.0, fraction)))
    {
      result.Aborted = true;
      return true;
    }
  }

  if (negateSolid && haveSolid)
  {
    gl.UseProgram(seed);
    solidZ.Bind(0, GL_READ_ONLY);
    gl.Uniform1i(Uniform(gl, seed, "Negate"), 1);
    dispatchSlabs(seedSlab);
  }
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, distances);
  gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, voxels * 4, distance);
  if (boundaryOut)
  {
    boundaryOut->Resize(nx, ny, nz);
    boundaryZ.Download(*boundaryOut);
  }
  if (solidOut && haveSolid)
  {
    solidOut->Resize(nx, ny, nz);
    solidZ.Download(*solidOut);
  }
  return NoGLError(gl, "in the chamfer passes", error);
}

} // namespace vtkdf
