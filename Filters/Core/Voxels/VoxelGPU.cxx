#include "Voxels/VoxelGPU.h"

#include "GL/GridUniforms.h"

#include "ChamferLayer_comp.h"
#include "ChamferSeed_comp.h"
#include "GL/GLFunctions.h"
#include "VoxelizeCombine_comp.h"
#include "VoxelizeCommon.h"
#include "VoxelizeFill_comp.h"
#include "VoxelizeLanes_comp.h"
#include "Voxels/VoxelizerRules.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstring>
#include <vector>

namespace vtkdf
{
using namespace voxelizer;
namespace
{
/// Texels of 128 bits along a lane of `bits` bits.
int LaneTexels(int bits)
{
  return std::max(1, (bits + 127) / 128);
}

/// The solid's half-voxel bins along a lane of `n` voxels (guard bins first).
int SolidBins(int n)
{
  return 2 * n + 1 + SolidGuard;
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
    this->Texels = LaneTexels(bits);
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

/// Buffers and programs of one run.
struct Objects
{
  explicit Objects(const GLFunctions& gl)
    : GL(gl)
  {
    gl.GenBuffers(9, this->Buffers);
  }
  ~Objects()
  {
    this->GL.DeleteBuffers(9, this->Buffers);
    for (GLuint p : this->Programs)
    {
      this->GL.DeleteProgram(p);
    }
  }
  const GLFunctions& GL;
  // points, distances, counts, triangles' point ids, first and second lane words, far
  // count, points in voxel units, the large triangles of a view
  GLuint Buffers[9] = { 0, 0, 0, 0, 0, 0, 0, 0, 0 };
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

/// `count` records into `buffer` (one record's worth at least: an empty buffer cannot be
/// bound), bound at shader storage binding `binding`.
template<typename Record>
void UploadRecords(const GLFunctions& gl,
  GLuint buffer,
  GLuint binding,
  size_t count,
  const Record* records)
{
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, buffer);
  const size_t bytes = std::max<size_t>(1, count) * sizeof(Record);
  gl.BufferData(GL_SHADER_STORAGE_BUFFER, bytes, count ? records : nullptr, GL_STATIC_DRAW);
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

/// Shaders/VoxelizeLanes.comp.glsl's tiles of lanes a side.
constexpr int LaneTileSide = 16;

/// The triangles of `mesh` whose lane rectangle in the view along axis `a` may span more
/// than one tile (their boxes along the other two axes, grown by the boundary rule's
/// reach and more than a lane of rounding: a superset of those the shader finds), and the
/// most tiles one of them may span: the second pass of VoxelizeLanes walks those.
struct LargeTriangles
{
  std::vector<int32_t> Ids;
  GLuint Tiles = 0; // at most GL's least work group count: the invocations a triangle gets

  LargeTriangles(const MeshInput& mesh, const SampleGrid& grid, int a)
  {
    const int axes[2] = { (a + 1) % 3, (a + 2) % 3 };
    const double reach[2] = { BoundaryReach(grid, axes[0]), BoundaryReach(grid, axes[1]) };
    const auto& x = mesh.Points;
    int64_t most = 0;
    for (size_t t = 0; t + 2 < mesh.Triangles.size(); t += 3)
    {
      int64_t tiles = 1;
      for (int k = 0; k < 2; ++k)
      {
        const int c = axes[k];
        const double u = x[3 * mesh.Triangles[t] + c], v = x[3 * mesh.Triangles[t + 1] + c],
                     w = x[3 * mesh.Triangles[t + 2] + c];
        const double lanes = std::min<double>(grid.Whole.Size(c),
          (std::max({ u, v, w }) - std::min({ u, v, w })) / grid.Spacing[c] + 2 * reach[k] + 3);
        tiles *= static_cast<int64_t>(lanes) / LaneTileSide + 1;
      }
      if (tiles > 1)
      {
        this->Ids.push_back(static_cast<int32_t>(t / 3));
        most = std::max(most, tiles);
      }
    }
    this->Tiles = static_cast<GLuint>(std::min<int64_t>(most, 65535));
  }
};

/// Runs Shaders/VoxelizeLanes.comp.glsl (`program`) in `mode` over `count` triangles or
/// points, in dispatches of at most GL's least work group count; with `large`, then its
/// second pass over the large triangles, `large->Tiles` invocations each.
void RunLanesProgram(const GLFunctions& gl,
  GLuint program,
  int mode,
  int64_t count,
  const LargeTriangles* large = nullptr)
{
  gl.Uniform1i(Uniform(gl, program, "Mode"), mode);
  for (int pass = 0; pass < (large && !large->Ids.empty() ? 2 : 1); ++pass)
  {
    const int64_t n = pass == 0 ? count : static_cast<int64_t>(large->Ids.size());
    gl.Uniform1i(Uniform(gl, program, "TilePass"), pass);
    gl.Uniform1i(Uniform(gl, program, "Count"), static_cast<GLint>(n));
    const int64_t perDispatch = int64_t(65535) * 64;
    for (int64_t base = 0; base < n; base += perDispatch)
    {
      gl.Uniform1i(Uniform(gl, program, "Base"), static_cast<GLint>(base));
      gl.DispatchCompute(static_cast<GLuint>((std::min(perDispatch, n - base) + 63) / 64),
        pass == 0 ? 1 : large->Tiles,
        1);
    }
  }
}

/// Runs Shaders/VoxelizeLanes.comp.glsl (`program`, its view's uniforms set) over
/// `count` triangles (then `large` again, tile by tile) in `mode` into the lane textures
/// `first` (and `second`, of the same size), through the buffers `laneBuffers`: in passes of as
/// many texel layers as one storage block holds, each clearing the buffers, running every triangle
/// and copying the buffers into the textures' layers (as a pixel unpack buffer: on the GPU).
bool SetLaneBits(const GLFunctions& gl,
  GLuint program,
  int mode,
  int64_t count,
  const LargeTriangles& large,
  const Lanes& first,
  const Lanes* second,
  const GLuint laneBuffers[2],
  std::string& error)
{
  const int64_t layerBytes = int64_t(first.Nx) * first.Ny * 16;
  const int64_t maxBytes = std::min<int64_t>(MaxStorageBlock(gl), INT_MAX);
  const int layers = static_cast<int>(std::min<int64_t>(first.Texels, maxBytes / layerBytes));
  if (layers < 1)
  {
    error = "a layer of " + std::to_string(first.Nx) + " x " + std::to_string(first.Ny) +
      " lanes (" + std::to_string(layerBytes / 1048576) +
      " MiB) exceeds GL_MAX_SHADER_STORAGE_BLOCK_SIZE (" +
      std::to_string(MaxStorageBlock(gl) / 1048576) + " MiB)";
    return false;
  }
  const Lanes* targets[2] = { &first, second };
  for (int t = 0; t < 2; ++t)
  {
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, laneBuffers[t]);
    gl.BufferData(
      GL_SHADER_STORAGE_BUFFER, targets[t] ? layers * layerBytes : 4, nullptr, GL_DYNAMIC_COPY);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 2 + t, laneBuffers[t]);
  }
  gl.Uniform1i(Uniform(gl, program, "Layers"), layers);
  for (int layer0 = 0; layer0 < first.Texels; layer0 += layers)
  {
    const int passLayers = std::min(layers, first.Texels - layer0);
    const uint32_t zero = 0;
    for (int t = 0; t < 2; ++t)
    {
      if (targets[t])
      {
        gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, laneBuffers[t]);
        gl.ClearBufferData(
          GL_SHADER_STORAGE_BUFFER, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
      }
    }
    gl.Uniform1i(Uniform(gl, program, "FirstLayer"), layer0);
    RunLanesProgram(gl, program, mode, count, &large);
    gl.MemoryBarrier(GL_PIXEL_BUFFER_BARRIER_BIT);
    for (int t = 0; t < 2; ++t)
    {
      if (targets[t])
      {
        gl.BindBuffer(GL_PIXEL_UNPACK_BUFFER, laneBuffers[t]);
        gl.TextureSubImage3D(targets[t]->Id,
          0,
          0,
          0,
          layer0,
          first.Nx,
          first.Ny,
          passLayers,
          GL_RGBA_INTEGER,
          GL_UNSIGNED_INT,
          nullptr);
      }
    }
    gl.BindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
  }
  gl.MemoryBarrier(GL_ALL_BARRIER_BITS);
  return true;
}

/// VoxelizeToLanes' views: each looks along axis A (b = A + 1, c = A + 2), rasterizes the
/// boundary triangles it owns and the solid's front and back crossings onto its lanes,
/// and fills the solid's [front, back] intervals.
class ViewRaster
{
public:
  ViewRaster(const GLFunctions& gl, const MeshInput& mesh, const SampleGrid& grid)
    : GL(gl)
    , Mesh(mesh)
    , Grid(grid)
    , Orientation(MeshOrientation(mesh))
    , Boundary{ Lanes(gl), Lanes(gl), Lanes(gl) }
    , Front{ Lanes(gl), Lanes(gl), Lanes(gl) }
    , Back{ Lanes(gl), Lanes(gl), Lanes(gl) }
    , Solid{ Lanes(gl), Lanes(gl), Lanes(gl) }
  {
    for (int a = 0; a < 3; ++a)
    {
      this->N[a] = grid.Whole.Size(a);
    }
  }

  /// View `a`: the boundary lanes (when wanted), the solid's front and back lanes and
  /// their intervals (when wanted). False and `error` when a layer of lanes exceeds a
  /// storage block.
  bool Rasterize(int a,
    GLuint lanes,
    GLuint fill,
    const GLuint laneBuffers[2],
    GLuint largeBuffer,
    bool wantBoundary,
    bool wantSolid,
    std::string& error)
  {
    const GLFunctions& gl = this->GL;
    const int* n = this->N;
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    gl.UseProgram(lanes);
    gl.Uniform1i(Uniform(gl, lanes, "Nb"), n[b]);
    gl.Uniform1i(Uniform(gl, lanes, "Nc"), n[c]);
    gl.Uniform1i(Uniform(gl, lanes, "Na"), n[a]);
    gl.Uniform3i(Uniform(gl, lanes, "Axes"), a, b, c);
    SetGridUniforms(gl, lanes, this->Grid, this->Grid.Whole);
    gl.Uniform1d(Uniform(gl, lanes, "Limit2"), BoundaryLimit2(this->Grid));
    gl.Uniform1d(Uniform(gl, lanes, "Reach"), BoundaryReach(this->Grid, a));
    const BoundaryReaches reaches(this->Grid);
    gl.Uniform3d(Uniform(gl, lanes, "Reaches"), reaches.R[0], reaches.R[1], reaches.R[2]);
    gl.Uniform1d(Uniform(gl, lanes, "Orientation"), this->Orientation);
    const auto numTriangles = static_cast<int64_t>(this->Mesh.Triangles.size() / 3);
    const LargeTriangles large(this->Mesh, this->Grid, a);
    UploadRecords(gl, largeBuffer, 6, large.Ids.size(), large.Ids.data());
    if (wantBoundary)
    {
      this->Boundary[a].Create(n[b], n[c], n[a]);
      if (!SetLaneBits(
            gl, lanes, 0, numTriangles, large, this->Boundary[a], nullptr, laneBuffers, error))
      {
        return false;
      }
    }
    if (wantSolid)
    {
      Lanes& front = this->Front[a];
      Lanes& back = this->Back[a];
      front.Create(n[b], n[c], SolidBins(n[a]));
      back.Create(n[b], n[c], SolidBins(n[a]));
      if (!SetLaneBits(gl, lanes, 1, numTriangles, large, front, &back, laneBuffers, error))
      {
        return false;
      }
      // The [front, back] intervals of this view.
      this->Solid[a].Create(n[b], n[c], SolidBins(n[a]));
      gl.UseProgram(fill);
      front.Bind(0, GL_READ_ONLY);
      back.Bind(1, GL_READ_ONLY);
      this->Solid[a].Bind(2, GL_READ_WRITE);
      gl.Uniform2i(Uniform(gl, fill, "Lanes"), n[b], n[c]);
      gl.Uniform1i(Uniform(gl, fill, "Texels"), this->Solid[a].Texels);
      gl.DispatchCompute((n[b] + 7) / 8, (n[c] + 7) / 8, 1);
      gl.MemoryBarrier(GL_ALL_BARRIER_BITS);
    }
    return true;
  }

  /// The views rotated into z-lanes and combined (OR for the boundary, AND for the solid).
  void Combine(GLuint combine, Lanes* boundaryZ, Lanes* solidZ)
  {
    const GLFunctions& gl = this->GL;
    const int* n = this->N;
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
        this->Boundary[a].Bind(a, GL_READ_ONLY);
      }
      if (solidZ)
      {
        this->Solid[a].Bind(3 + a, GL_READ_ONLY);
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
    SetGridUniforms(gl, combine, this->Grid, this->Grid.Whole);
    gl.Uniform1i(Uniform(gl, combine, "WantBoundary"), boundaryZ != nullptr);
    gl.Uniform1i(Uniform(gl, combine, "WantSolid"), solidZ != nullptr);
    gl.DispatchCompute((n[0] + 7) / 8, (n[1] + 7) / 8, (n[2] + 127) / 128);
    gl.MemoryBarrier(GL_ALL_BARRIER_BITS);
  }

  const GLFunctions& GL;
  const MeshInput& Mesh;
  const SampleGrid& Grid;
  const double Orientation;
  int N[3];
  Lanes Boundary[3], Front[3], Back[3], Solid[3];
};

/// Whether the GPU can voxelize the mesh on the grid; else false and `error`.
bool CheckVoxelizer(HeadlessGL& context,
  const MeshInput& mesh,
  const SampleGrid& grid,
  std::string& error)
{
  const GLFunctions& gl = context.GL();
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
  // The shaders read the mesh as it is: its points and its triangles' 32-bit point ids
  // each in one storage block.
  const auto points = static_cast<GLint64>(mesh.Points.size() / 3);
  const auto triangles = static_cast<GLint64>(mesh.Triangles.size() / 3);
  const GLint64 maxBlock = MaxStorageBlock(gl);
  if (points > UINT32_MAX || triangles > INT_MAX / 3 || points * 24 > maxBlock ||
    triangles * 12 > maxBlock)
  {
    error = "the GPU voxelizer takes at most 2^32 points and 2^31 / 3 triangles, "
            "their coordinates and ids each within GL_MAX_SHADER_STORAGE_BLOCK_SIZE (" +
      std::to_string(maxBlock / 1048576) + " MiB); the mesh has " + std::to_string(points) +
      " points and " + std::to_string(triangles) + " triangles";
    return false;
  }
  const IndexBox& whole = grid.Whole;
  const int n[3] = { whole.Size(0), whole.Size(1), whole.Size(2) };
  for (int a = 0; a < 3; ++a)
  {
    if (!CheckLimits(gl, n[(a + 1) % 3], n[(a + 2) % 3], LaneTexels(SolidBins(n[a])), error))
    {
      return false;
    }
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
  if (!CheckVoxelizer(context, mesh, grid, error))
  {
    return false;
  }
  statistics.Triangles = static_cast<int64_t>(mesh.Triangles.size() / 3);
  ViewRaster views(gl, mesh, grid);
  statistics.FlippedOrientation = views.Orientation < 0;
  const GLuint lanes = Build(context,
    objects,
    { { GL_COMPUTE_SHADER, std::string(VoxelizeCommon) + VoxelizeLanes_comp } },
    error);
  const GLuint fill =
    solidZ ? Build(context, objects, { { GL_COMPUTE_SHADER, VoxelizeFill_comp } }, error) : 1;
  const GLuint combine =
    Build(context, objects, { { GL_COMPUTE_SHADER, VoxelizeCombine_comp } }, error);
  if (!lanes || !fill || !combine)
  {
    return false;
  }
  // The mesh as it is (the shaders set up each triangle), and the far triangles' count.
  std::vector<uint32_t> ids(mesh.Triangles.begin(), mesh.Triangles.end());
  UploadRecords(gl, objects.Buffers[0], 0, mesh.Points.size(), mesh.Points.data());
  UploadRecords(gl, objects.Buffers[3], 1, ids.size(), ids.data());
  const uint32_t zero = 0;
  UploadRecords(gl, objects.Buffers[6], 4, 1, &zero);
  // The points in voxel units, once for every view and rule.
  const auto numPoints = static_cast<int64_t>(mesh.Points.size() / 3);
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, objects.Buffers[7]);
  gl.BufferData(GL_SHADER_STORAGE_BUFFER,
    std::max<size_t>(1, mesh.Points.size()) * 8,
    nullptr,
    GL_DYNAMIC_COPY);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, objects.Buffers[7]);
  gl.UseProgram(lanes);
  SetGridUniforms(gl, lanes, grid, grid.Whole);
  RunLanesProgram(gl, lanes, 2, numPoints);
  gl.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  for (int a = 0; a < 3; ++a)
  {
    if (!views.Rasterize(
          a, lanes, fill, objects.Buffers + 4, objects.Buffers[8], boundaryZ, solidZ, error))
    {
      return false;
    }
  }
  uint32_t far = 0;
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, objects.Buffers[6]);
  gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof(far), &far);
  statistics.FarTriangles = far / 3; // once per view
  views.Combine(combine, boundaryZ, solidZ);
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

namespace
{
/// ChamferGPU's passes over the distance array, which is bound a slab of whole texels
/// (128 slices) at a time: a texel's invocation writes only its own 128 slices.
class ChamferPasses
{
public:
  ChamferPasses(HeadlessGL& context, Objects& objects, const SampleGrid& grid)
    : Context(context)
    , GL(context.GL())
    , GLObjects(objects)
    , Grid(grid)
    , Nx(grid.Whole.Size(0))
    , Ny(grid.Whole.Size(1))
    , Nz(grid.Whole.Size(2))
    , Texels((grid.Whole.Size(2) + 127) / 128)
  {
  }

  /// Whether the lanes and a slab of the distance array fit the GPU's limits.
  bool CheckLimits(std::string& error)
  {
    const GLFunctions& gl = this->GL;
    if (!vtkdf::CheckLimits(gl, this->Nx, this->Ny, this->Texels, error))
    {
      return false;
    }
    const int64_t slice = int64_t(this->Nx) * this->Ny;
    const int64_t slabSlices = SlabSlices(gl, slice, 4, this->Nz, this->Alignment);
    this->TexelsPerSlab = slabSlices >= this->Nz
      ? this->Texels
      : static_cast<int>(std::min<int64_t>(slabSlices / 128, this->Texels));
    if (this->TexelsPerSlab < 1)
    {
      error = "128 slices of the distance array (" + std::to_string(slice * 512 / 1048576) +
        " MiB) exceed GL_MAX_SHADER_STORAGE_BLOCK_SIZE (" +
        std::to_string(MaxStorageBlock(gl) / 1048576) + " MiB)";
      return false;
    }
    return true;
  }

  /// The seed and layer programs, the distance array (every voxel unreached) and the
  /// counts of a batch of layers.
  bool Setup(int32_t unreached, std::string& error)
  {
    const GLFunctions& gl = this->GL;
    Objects& objects = this->GLObjects;
    this->Seed = Build(this->Context, objects, { { GL_COMPUTE_SHADER, ChamferSeed_comp } }, error);
    this->Layer =
      Build(this->Context, objects, { { GL_COMPUTE_SHADER, ChamferLayer_comp } }, error);
    if (!this->Seed || !this->Layer)
    {
      return false;
    }
    this->Distances = objects.Buffers[1];
    this->Counts = objects.Buffers[2];
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, this->Distances);
    gl.BufferData(GL_SHADER_STORAGE_BUFFER, this->Voxels() * 4, nullptr, GL_DYNAMIC_COPY);
    gl.ClearBufferData(GL_SHADER_STORAGE_BUFFER, GL_R32I, GL_RED_INTEGER, GL_INT, &unreached);
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, this->Counts);
    gl.BufferData(GL_SHADER_STORAGE_BUFFER, Batch * 4, nullptr, GL_DYNAMIC_READ);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, this->Counts);
    this->SeedSlab[0] = Uniform(gl, this->Seed, "TexelBase");
    this->SeedSlab[1] = Uniform(gl, this->Seed, "DistanceBase");
    this->LayerSlab[0] = Uniform(gl, this->Layer, "TexelBase");
    this->LayerSlab[1] = Uniform(gl, this->Layer, "DistanceBase");
    return true;
  }

  /// Layer 0: the zero set's voxels get 0; returns how many there are.
  uint32_t SeedZeroSet(const Lanes& boundaryZ)
  {
    const GLFunctions& gl = this->GL;
    const uint32_t zeros[Batch] = {};
    gl.BufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof(zeros), zeros);
    gl.UseProgram(this->Seed);
    boundaryZ.Bind(0, GL_READ_ONLY);
    SetGridUniforms(gl, this->Seed, this->Grid, this->Grid.Whole);
    gl.Uniform1i(Uniform(gl, this->Seed, "Texels"), this->Texels);
    gl.Uniform1i(Uniform(gl, this->Seed, "Value"), 0);
    gl.Uniform1i(Uniform(gl, this->Seed, "Negate"), 0);
    this->DispatchSlabs(this->SeedSlab);
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, this->Counts);
    uint32_t zeroSet = 0;
    gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof(zeroSet), &zeroSet);
    return zeroSet;
  }

  /// The layers from the zero set, in batches between which the counts are read back
  /// and progress is told; an abort leaves result.Aborted set.
  void Propagate(const Lanes& boundaryZ,
    ChamferMetric metric,
    int maximumLayers,
    const ProgressCallback& progress,
    ChamferResult& result);

  /// The solid's voxels negated.
  void Negate(const Lanes& solidZ)
  {
    const GLFunctions& gl = this->GL;
    gl.UseProgram(this->Seed);
    solidZ.Bind(0, GL_READ_ONLY);
    gl.Uniform1i(Uniform(gl, this->Seed, "Negate"), 1);
    this->DispatchSlabs(this->SeedSlab);
  }

  void ReadDistances(int32_t* distance)
  {
    this->GL.BindBuffer(GL_SHADER_STORAGE_BUFFER, this->Distances);
    this->GL.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, this->Voxels() * 4, distance);
  }

private:
  static constexpr int Batch = 8;
  int64_t Voxels() const { return int64_t(this->Nx) * this->Ny * this->Nz; }

  /// Runs the current program over every lane texel, one slab of texels at a time, with
  /// the slab's part of the distance array bound; `slabUniforms` are the program's
  /// TexelBase and DistanceBase locations.
  void DispatchSlabs(const GLint slabUniforms[2])
  {
    const GLFunctions& gl = this->GL;
    const int64_t slice = int64_t(this->Nx) * this->Ny;
    const GLuint groupsX = (this->Nx + 7) / 8, groupsY = (this->Ny + 7) / 8;
    const GLint texelBase = slabUniforms[0], distanceBase = slabUniforms[1];
    for (int t0 = 0; t0 < this->Texels; t0 += this->TexelsPerSlab)
    {
      const int t1 = std::min(this->Texels, t0 + this->TexelsPerSlab);
      const int64_t from = 128 * int64_t(t0) * slice;
      const int64_t to = std::min<int64_t>(128 * int64_t(t1), this->Nz) * slice;
      gl.Uniform1i(texelBase, t0);
      gl.Uniform1i(distanceBase,
        static_cast<int>(BindVoxelRange(gl, 0, this->Distances, from, to, 4, 4, this->Alignment)));
      gl.DispatchCompute(groupsX, groupsY, t1 - t0);
    }
    gl.MemoryBarrier(GL_ALL_BARRIER_BITS);
  }

  HeadlessGL& Context;
  const GLFunctions& GL;
  Objects& GLObjects;
  const SampleGrid& Grid;
  const int Nx, Ny, Nz, Texels;
  int TexelsPerSlab = 1;
  GLint Alignment = 0;
  GLuint Seed = 0, Layer = 0, Distances = 0, Counts = 0;
  GLint SeedSlab[2] = { -1, -1 }, LayerSlab[2] = { -1, -1 };
};

void ChamferPasses::Propagate(const Lanes& boundaryZ,
  ChamferMetric metric,
  int maximumLayers,
  const ProgressCallback& progress,
  ChamferResult& result)
{
  const GLFunctions& gl = this->GL;
  const int nx = this->Nx, ny = this->Ny, nz = this->Nz;
  Lanes first(gl), second(gl), accumulated(gl);
  first.Create(nx, ny, nz);
  second.Create(nx, ny, nz);
  accumulated.Create(nx, ny, nz);
  for (const Lanes* copy : { &first, &accumulated })
  {
    gl.CopyImageSubData(boundaryZ.Id,
      GL_TEXTURE_2D_ARRAY,
      0,
      0,
      0,
      0,
      copy->Id,
      GL_TEXTURE_2D_ARRAY,
      0,
      0,
      0,
      0,
      nx,
      ny,
      this->Texels);
  }
  Lanes* current = &first;
  Lanes* next = &second;
  gl.UseProgram(this->Layer);
  SetGridUniforms(gl, this->Layer, this->Grid, this->Grid.Whole);
  gl.Uniform1i(Uniform(gl, this->Layer, "Texels"), this->Texels);
  gl.Uniform1i(Uniform(gl, this->Layer, "Metric"), static_cast<int>(metric));
  const GLint layerLocation = Uniform(gl, this->Layer, "Layer");
  const GLint slotLocation = Uniform(gl, this->Layer, "CountSlot");
  const uint32_t zeros[Batch] = {};
  bool done = result.ZeroSet == 0;
  for (int start = 1; !done && (maximumLayers <= 0 || start <= maximumLayers); start += Batch)
  {
    const int end =
      maximumLayers > 0 ? std::min(start + Batch - 1, maximumLayers) : start + Batch - 1;
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, this->Counts);
    gl.BufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof(zeros), zeros);
    for (int l = start; l <= end; ++l)
    {
      current->Bind(0, GL_READ_ONLY);
      next->Bind(1, GL_WRITE_ONLY);
      accumulated.Bind(2, GL_READ_WRITE);
      gl.Uniform1i(layerLocation, l);
      gl.Uniform1i(slotLocation, l - start);
      this->DispatchSlabs(this->LayerSlab);
      std::swap(current, next);
    }
    uint32_t reached[Batch] = {};
    gl.BindBuffer(
      GL_SHADER_STORAGE_BUFFER, this->Counts); // BindBufferRange moved the generic binding
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
    const double fraction = maximumLayers > 0 ? double(end) / maximumLayers
                                              : double(result.Reached) / double(this->Voxels());
    if (progress && !done && !progress(std::min(1.0, fraction)))
    {
      result.Aborted = true;
      return;
    }
  }
}
} // namespace

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
  ChamferPasses passes(context, objects, input.Grid);
  if (!passes.CheckLimits(error))
  {
    return false;
  }
  // The zero set (and the solid) as z-lanes.
  const int nx = input.Grid.Whole.Size(0), ny = input.Grid.Whole.Size(1),
            nz = input.Grid.Whole.Size(2);
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
  if (!passes.Setup(unreached, error))
  {
    return false;
  }
  result.ZeroSet = result.Reached = passes.SeedZeroSet(boundaryZ);
  passes.Propagate(boundaryZ, metric, maximumLayers, progress, result);
  if (result.Aborted)
  {
    return true;
  }
  if (negateSolid && haveSolid)
  {
    passes.Negate(solidZ);
  }
  passes.ReadDistances(distance);
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
