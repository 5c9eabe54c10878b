#include "LinearFactor/LinearFactorGPU.h"

#include "GL/GridUniforms.h"

#include "LinearFactor/SliceDomain.h"
#include "LinearFactorDomain_frag.h"
#include "LinearFactorDomain_geom.h"
#include "LinearFactorDomain_vert.h"
#include "LinearFactorFinalize_comp.h"
#include "LinearFactorKeep_comp.h"
#include "LinearFactorSites.h"

#include "GL/GLFunctions.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>

namespace vtkdf
{
namespace
{
constexpr int GpuMaxPlanes = 28; // Shaders/LinearFactorDomain.geom.glsl

struct GpuSite
{
  float Anchor[4];
  float Axis[4];
  int32_t Lo[4];
  int32_t Hi[4];
};

/// Deletes the GL objects of one run, whatever way it ends.
struct GLObjects
{
  const GLFunctions& gl;
  GLuint Program = 0, Buffers[5] = { 0, 0, 0, 0, 0 }, VAO = 0, FBO = 0, Textures[3] = { 0, 0, 0 };
  ~GLObjects()
  {
    gl.DeleteTextures(3, Textures);
    gl.DeleteFramebuffers(1, &FBO);
    gl.DeleteVertexArrays(1, &VAO);
    gl.DeleteBuffers(5, Buffers);
    gl.DeleteProgram(Program);
  }
};

/// One run of ScanSitesGPU: the sites' domains drawn as polygons on every slice of a batch
/// of slices (layered rendering), the depth test keeping the nearest site.
class DomainScan
{
public:
  DomainScan(HeadlessGL& context,
    const MeshSites& sites,
    const RangeCulling& culling,
    const LocalFieldRequest& request,
    unsigned residentIds)
    : Context(context)
    , GL(context.GL())
    , Sites(sites)
    , Culling(culling)
    , Grid(request.Grid)
    , Extent(request.Extent)
    , ResidentIds(residentIds)
    , Nx(request.Extent.Size(0))
    , Ny(request.Extent.Size(1))
    , Nz(request.Extent.Size(2))
    , Objects{ context.GL() }
  {
  }
  ~DomainScan()
  {
    this->GL.DeleteProgram(this->Keep);
    if (this->Query)
    {
      this->GL.DeleteQueries(1, &this->Query);
    }
  }

  /// The shaders, the sites and their planes in GL buffers, the layered framebuffer and
  /// the uniforms; false and `error` when the GPU cannot.
  bool Setup(std::string& error);
  /// The layers the framebuffer holds: the most slices a batch may have.
  int Layers() const { return this->LayerCount; }
  /// Whether the GPU counts the fragments drawn (the distance evaluations).
  bool Counts() const { return this->Query != 0; }
  /// Scans slices k0..k1 (extent indices) and reads their nearest sites back into
  /// `nearest`, or keeps them in the resident ids; adds the fragments drawn to
  /// `evaluations` when the GPU counts them. False and `error` on a GL error.
  bool ScanBatch(int k0,
    int k1,
    NearestSiteBuffer& nearest,
    int64_t& evaluations,
    std::string& error);

private:
  bool BuildPrograms(std::string& error);
  void UploadSites();
  bool AllocateLayers(std::string& error);
  void SetUniforms();
  void KeepIds(int k0, int count);
  void ReadBack(int k0, int count, NearestSiteBuffer& nearest);

  HeadlessGL& Context;
  const GLFunctions& GL;
  const MeshSites& Sites;
  const RangeCulling& Culling;
  const SampleGrid& Grid;
  const IndexBox& Extent;
  const unsigned ResidentIds;
  const int Nx, Ny, Nz;
  GLObjects Objects;
  GLuint Keep = 0;  // the compute program that keeps ids on the GPU
  GLuint Query = 0; // fragment counts, when the GPU has them
  double Base[3] = { 0, 0, 0 };
  std::vector<GpuSite> GpuSites;
  int LayerCount = 1;
  GLint LayerBaseAt = -1, LayerCountAt = -1;
  std::vector<int32_t> Points;
  std::vector<float> Distances;
  std::vector<int32_t> Ids;
};

bool DomainScan::Setup(std::string& error)
{
  const GLFunctions& gl = this->GL;
  GLint maxSize = 0;
  gl.GetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
  if (this->Nx > maxSize || this->Ny > maxSize)
  {
    error = "the slice (" + std::to_string(this->Nx) + " x " + std::to_string(this->Ny) +
      ") exceeds GL_MAX_TEXTURE_SIZE " + std::to_string(maxSize);
    return false;
  }
  if (!this->BuildPrograms(error))
  {
    return false;
  }
  this->UploadSites();
  if (!this->AllocateLayers(error))
  {
    return false;
  }
  this->SetUniforms();
  if (gl.HasExtension("GL_ARB_pipeline_statistics_query"))
  {
    gl.GenQueries(1, &this->Query);
  }
  this->Distances.resize(this->ResidentIds ? 0 : size_t(this->Nx) * this->Ny * this->LayerCount);
  this->Ids.resize(this->Distances.size());
  return true;
}

bool DomainScan::BuildPrograms(std::string& error)
{
  std::string log;
  const std::string geometry = std::string(LinearFactorSites) + LinearFactorDomain_geom;
  const std::string fragment = std::string(LinearFactorSites) + LinearFactorDomain_frag;
  this->Objects.Program =
    this->Context.BuildProgram({ { GL_VERTEX_SHADER, LinearFactorDomain_vert },
                                 { GL_GEOMETRY_SHADER, geometry.c_str() },
                                 { GL_FRAGMENT_SHADER, fragment.c_str() } },
      log);
  if (!this->Objects.Program)
  {
    error = log;
    return false;
  }
  if (this->ResidentIds)
  {
    this->Keep = this->Context.BuildProgram({ { GL_COMPUTE_SHADER, LinearFactorKeep_comp } }, log);
    if (!this->Keep)
    {
      error = log;
      return false;
    }
  }
  return true;
}

/// Sites and their planes, relative to the whole grid's first sample (so that a sample's
/// bits do not depend on the extent), planes in sample-index units relative to the site's
/// anchor; the sites' bounds (rounded outward to float) and the blocks' bounds, for the
/// slice test.
void DomainScan::UploadSites()
{
  const GLFunctions& gl = this->GL;
  const SampleGrid& grid = this->Grid;
  const IndexBox& ext = this->Extent;
  const int64_t numSites = this->Sites.Count();
  this->GpuSites.resize(numSites);
  std::vector<float> planes;
  std::vector<float> siteBounds(8 * std::max<int64_t>(1, numSites), 0.f);
  for (int a = 0; a < 3; ++a)
  {
    this->Base[a] = grid.Coordinate(a, grid.Whole.Lo[a]);
  }
  const double* base = this->Base;
  IndexPlane indexPlanes[GpuMaxPlanes];
  Site site;
  this->Culling.ForEachSite(0,
    numSites,
    [&](int64_t s, const IndexBox& reach)
    {
      this->Sites.Describe(s, site);
      GpuSite& g = this->GpuSites[s];
      const IndexBox r = this->Culling.Region(reach, site);
      int count = SiteIndexPlanes(this->Sites, s, site, grid, indexPlanes, GpuMaxPlanes);
      double anchorIndex[3];
      for (int a = 0; a < 3; ++a)
      {
        g.Anchor[a] = static_cast<float>(site.Anchor[a] - base[a]);
        g.Axis[a] = static_cast<float>(site.Axis[a]);
        g.Lo[a] = r.Lo[a] - ext.Lo[a];
        g.Hi[a] = r.Hi[a] - ext.Lo[a];
        anchorIndex[a] = (site.Anchor[a] - grid.Origin[a]) / grid.Spacing[a];
        siteBounds[8 * s + a] =
          std::nextafter(static_cast<float>(site.BoundsMin[a] - base[a]), -HUGE_VALF);
        siteBounds[8 * s + 4 + a] =
          std::nextafter(static_cast<float>(site.BoundsMax[a] - base[a]), HUGE_VALF);
      }
      g.Anchor[3] = site.Type;
      g.Axis[3] = site.Required;
      g.Lo[3] = static_cast<int32_t>(planes.size() / 4);
      g.Hi[3] = count;
      for (int p = 0; p < count; ++p)
      {
        const IndexPlane& q = indexPlanes[p];
        planes.push_back(static_cast<float>(q.A));
        planes.push_back(static_cast<float>(q.B));
        planes.push_back(static_cast<float>(q.C));
        planes.push_back(static_cast<float>(
          q.A * anchorIndex[0] + q.B * anchorIndex[1] + q.C * anchorIndex[2] + q.D));
      }
    });
  if (planes.empty())
  {
    planes.assign(4, 0.f);
  }
  std::vector<float> blockBounds = this->Culling.BlockBound;
  if (blockBounds.empty())
  {
    blockBounds.assign(1, HUGE_VALF);
  }
  GLuint* buffers = this->Objects.Buffers;
  gl.GenBuffers(5, buffers);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, buffers[3]);
  gl.BufferData(
    GL_SHADER_STORAGE_BUFFER, siteBounds.size() * sizeof(float), siteBounds.data(), GL_STATIC_DRAW);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, buffers[4]);
  gl.BufferData(GL_SHADER_STORAGE_BUFFER,
    blockBounds.size() * sizeof(float),
    blockBounds.data(),
    GL_STATIC_DRAW);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffers[0]);
  gl.BufferData(GL_SHADER_STORAGE_BUFFER,
    std::max<size_t>(1, numSites) * sizeof(GpuSite),
    this->GpuSites.data(),
    GL_STATIC_DRAW);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, buffers[1]);
  gl.BufferData(
    GL_SHADER_STORAGE_BUFFER, planes.size() * sizeof(float), planes.data(), GL_STATIC_DRAW);
  gl.GenVertexArrays(1, &this->Objects.VAO);
  gl.BindVertexArray(this->Objects.VAO);
}

/// The layered framebuffer: as many layers as the array textures and a memory budget
/// allow.
bool DomainScan::AllocateLayers(std::string& error)
{
  const GLFunctions& gl = this->GL;
  GLint maxLayers = 0;
  gl.GetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxLayers);
  const int64_t bytesPerLayer = int64_t(this->Nx) * this->Ny * 12;
  const int64_t budget = int64_t(1) << 30;
  this->LayerCount = static_cast<int>(std::max<int64_t>(1,
    std::min<int64_t>(
      { int64_t(this->Nz), int64_t(maxLayers), budget / std::max<int64_t>(1, bytesPerLayer) })));
  GLuint* textures = this->Objects.Textures;
  gl.GenTextures(3, textures);
  const GLenum formats[3] = { GL_R32F, GL_R32I, GL_DEPTH_COMPONENT32F };
  for (int t = 0; t < 3; ++t)
  {
    gl.BindTexture(GL_TEXTURE_2D_ARRAY, textures[t]);
    gl.TexStorage3D(GL_TEXTURE_2D_ARRAY, 1, formats[t], this->Nx, this->Ny, this->LayerCount);
  }
  gl.GenFramebuffers(1, &this->Objects.FBO);
  gl.BindFramebuffer(GL_FRAMEBUFFER, this->Objects.FBO);
  gl.FramebufferTexture(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, textures[0], 0);
  gl.FramebufferTexture(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, textures[1], 0);
  gl.FramebufferTexture(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, textures[2], 0);
  const GLenum drawBuffers[2] = { GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1 };
  gl.DrawBuffers(2, drawBuffers);
  if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
  {
    error = "layered framebuffer incomplete";
    return false;
  }
  return true;
}

void DomainScan::SetUniforms()
{
  const GLFunctions& gl = this->GL;
  const GLuint program = this->Objects.Program;
  const SampleGrid& grid = this->Grid;
  gl.UseProgram(program);
  gl.Uniform2i(gl.GetUniformLocation(program, "viewportSize"), this->Nx, this->Ny);
  gl.Uniform3f(gl.GetUniformLocation(program, "spacing"),
    static_cast<float>(grid.Spacing[0]),
    static_cast<float>(grid.Spacing[1]),
    static_cast<float>(grid.Spacing[2]));
  gl.Uniform1f(gl.GetUniformLocation(program, "margin"), 0.02f);
  const std::array<int, 3> blockCounts = this->Culling.BlockBound.empty()
    ? std::array<int, 3>{ { 1, 1, 1 } }
    : this->Culling.BlockCounts;
  gl.Uniform3i(
    gl.GetUniformLocation(program, "blockCounts"), blockCounts[0], blockCounts[1], blockCounts[2]);
  gl.Uniform1i(gl.GetUniformLocation(program, "blockSize"), RangeCulling::BlockSize);
  gl.Uniform1f(gl.GetUniformLocation(program, "minSpacing"), static_cast<float>(grid.MinSpacing()));
  gl.Uniform3i(gl.GetUniformLocation(program, "extentLo"),
    this->Extent.Lo[0] - grid.Whole.Lo[0],
    this->Extent.Lo[1] - grid.Whole.Lo[1],
    this->Extent.Lo[2] - grid.Whole.Lo[2]);
  // The depth of a fragment is its distance over the largest one a site can have in the
  // whole grid (not the extent: equal distances must give equal depths in any extent).
  double diagonal = 0;
  for (int a = 0; a < 3; ++a)
  {
    diagonal += std::pow(grid.Whole.Size(a) * grid.Spacing[a], 2);
  }
  double reach = 2 * std::sqrt(diagonal) + 1e-30;
  for (int64_t s = 0; s < this->Sites.Count(); ++s)
  {
    const double* anchor = this->Sites.AnchorOf(s);
    for (int a = 0; a < 3; ++a)
    {
      reach = std::max(reach, 2 * std::fabs(anchor[a] - this->Base[a]) + std::sqrt(diagonal));
    }
  }
  gl.Uniform1f(gl.GetUniformLocation(program, "depthScale"), static_cast<float>(1.0 / reach));
  this->LayerBaseAt = gl.GetUniformLocation(program, "layerBase");
  this->LayerCountAt = gl.GetUniformLocation(program, "layerCount");
  gl.Viewport(0, 0, this->Nx, this->Ny);
  gl.Enable(GL_DEPTH_TEST);
  gl.DepthFunc(GL_LESS);
  gl.Disable(GL_CULL_FACE);
}

bool DomainScan::ScanBatch(int k0,
  int k1,
  NearestSiteBuffer& nearest,
  int64_t& evaluations,
  std::string& error)
{
  const GLFunctions& gl = this->GL;
  gl.Uniform1i(this->LayerCountAt, k1 - k0 + 1);
  // One point per site and slice of its region in the batch: the geometry shader builds
  // the site's domain polygon there. (A point per run of slices, amplified by geometry
  // shader invocations, left most invocations idle on thin domains: 16 times slower on
  // llvmpipe, and about 5 us a site on an H100.)
  this->Points.clear();
  for (size_t s = 0; s < this->GpuSites.size(); ++s)
  {
    const GpuSite& g = this->GpuSites[s];
    if (g.Hi[0] < g.Lo[0] || g.Hi[1] < g.Lo[1] || g.Hi[2] < g.Lo[2])
    {
      continue; // an empty region
    }
    const int lo = std::max(g.Lo[2], k0), hi = std::min(g.Hi[2], k1);
    for (int k = lo; k <= hi; ++k)
    {
      this->Points.push_back(static_cast<int32_t>(s));
      this->Points.push_back(k);
    }
  }
  const float farDepth = 1.0f, noDistance = -1.0f;
  const GLint noSite = -1;
  gl.ClearBufferfv(GL_DEPTH, 0, &farDepth);
  gl.ClearBufferfv(GL_COLOR, 0, &noDistance);
  gl.ClearBufferiv(GL_COLOR, 1, &noSite);
  gl.Uniform1i(this->LayerBaseAt, k0);
  gl.BindBuffer(GL_ARRAY_BUFFER, this->Objects.Buffers[2]);
  gl.BufferData(GL_ARRAY_BUFFER,
    std::max<size_t>(1, this->Points.size()) * sizeof(int32_t),
    this->Points.data(),
    GL_STREAM_DRAW);
  gl.EnableVertexAttribArray(0);
  gl.VertexAttribIPointer(0, 2, GL_INT, 0, nullptr);
  if (this->Query)
  {
    gl.BeginQuery(GL_FRAGMENT_SHADER_INVOCATIONS_ARB, this->Query);
  }
  gl.DrawArrays(GL_POINTS, 0, static_cast<GLsizei>(this->Points.size() / 2));
  if (this->Query)
  {
    gl.EndQuery(GL_FRAGMENT_SHADER_INVOCATIONS_ARB);
    GLuint64 fragments = 0;
    gl.GetQueryObjectui64v(this->Query, GL_QUERY_RESULT, &fragments);
    evaluations += static_cast<int64_t>(fragments);
  }
  if (this->ResidentIds)
  {
    this->KeepIds(k0, k1 - k0 + 1);
  }
  else
  {
    this->ReadBack(k0, k1 - k0 + 1, nearest);
  }
  return NoGLError(gl, "in the domain scan", error);
}

/// Keeps a batch's ids on the GPU (no readback).
void DomainScan::KeepIds(int k0, int count)
{
  const GLFunctions& gl = this->GL;
  GLint alignment = 1;
  gl.GetIntegerv(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT, &alignment);
  const int64_t slice = int64_t(this->Nx) * this->Ny;
  const int64_t base =
    BindVoxelRange(gl, 4, this->ResidentIds, k0 * slice, (k0 + count) * slice, 4, 4, alignment);
  gl.MemoryBarrier(GL_ALL_BARRIER_BITS);
  gl.UseProgram(this->Keep);
  gl.BindImageTexture(0, this->Objects.Textures[1], 0, GL_TRUE, 0, GL_READ_ONLY, GL_R32I);
  gl.Uniform2i(gl.GetUniformLocation(this->Keep, "Size"), this->Nx, this->Ny);
  gl.Uniform1i(gl.GetUniformLocation(this->Keep, "Layers"), count);
  gl.Uniform1i(gl.GetUniformLocation(this->Keep, "Offset"), static_cast<int>(k0 * slice - base));
  gl.DispatchCompute((this->Nx + 7) / 8, (this->Ny + 7) / 8, count);
  gl.MemoryBarrier(GL_ALL_BARRIER_BITS);
  gl.UseProgram(this->Objects.Program);
}

/// Reads a batch's layers back into `nearest`.
void DomainScan::ReadBack(int k0, int count, NearestSiteBuffer& nearest)
{
  const GLFunctions& gl = this->GL;
  const int nx = this->Nx, ny = this->Ny;
  gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
  gl.GetTextureSubImage(this->Objects.Textures[0],
    0,
    0,
    0,
    0,
    nx,
    ny,
    count,
    GL_RED,
    GL_FLOAT,
    static_cast<GLsizei>(size_t(nx) * ny * count * sizeof(float)),
    this->Distances.data());
  gl.GetTextureSubImage(this->Objects.Textures[1],
    0,
    0,
    0,
    0,
    nx,
    ny,
    count,
    GL_RED_INTEGER,
    GL_INT,
    static_cast<GLsizei>(size_t(nx) * ny * count * sizeof(int32_t)),
    this->Ids.data());
  const int64_t offset = int64_t(k0) * nx * ny;
  const int64_t n = int64_t(count) * nx * ny;
  for (int64_t at = 0; at < n; ++at)
  {
    const int32_t id = this->Ids[at];
    const float d = this->Distances[at];
    nearest.Set(offset + at,
      id < 0 ? NearestSiteBuffer::Empty
             : NearestSiteBuffer::Pack(d * d, static_cast<uint32_t>(id)));
  }
}
} // namespace

bool ScanSitesGPU(HeadlessGL& context,
  const MeshSites& sites,
  const RangeCulling& culling,
  const LocalFieldRequest& request,
  NearestSiteBuffer& nearest,
  const ProgressCallback& progress,
  ScanStatistics& stats,
  std::string& error,
  unsigned residentIds)
{
  HeadlessGL::Scope scope(context);
  if (!scope.Ok(error))
  {
    return false;
  }
  stats = ScanStatistics();
  stats.Samples = request.Extent.Count();
  stats.Evaluations = -1;
  DomainScan scan(context, sites, culling, request, residentIds);
  if (!scan.Setup(error))
  {
    return false;
  }
  if (scan.Counts())
  {
    stats.Evaluations = 0;
  }
  // Batches of slices. With a progress callback, each batch is finished on the GPU
  // before it is reported (the fraction is then true, and an abort stops the scan within
  // one batch), and batches are sized by time: the first holds 1/MinimumBatches of the
  // slices, the next ones as many as the measured rate scans in BatchSeconds, at most
  // twice the last. Every batch costs a draw, a clear and a synchronisation (about 60 ms
  // on llvmpipe), so a fast GPU takes few large batches and a slow one still reports
  // often.
  const int nz = request.Extent.Size(2), layers = scan.Layers();
  int batchLayers = progress ? static_cast<int>(std::min<int64_t>(
                                 layers, (int64_t(nz) + MinimumBatches - 1) / MinimumBatches))
                             : layers;
  int64_t evaluations = 0;
  for (int k0 = 0, next = 0; k0 < nz; k0 = next)
  {
    const auto batchStart = std::chrono::steady_clock::now();
    const int k1 = std::min(nz, k0 + batchLayers) - 1;
    next = k1 + 1;
    if (!scan.ScanBatch(k0, k1, nearest, evaluations, error))
    {
      return false;
    }
    if (progress)
    {
      context.GL().Finish();
      if (!progress(double(k1 + 1) / nz))
      {
        stats.Aborted = true;
        break;
      }
      const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - batchStart).count();
      // At most twice the last batch, so that even a fast GPU reports a few times.
      const double rate = (k1 - k0 + 1) / std::max(seconds, 1e-6); // slices per second
      const double bound = std::min(double(layers), 2.0 * (k1 - k0 + 1));
      batchLayers = static_cast<int>(std::max(1.0, std::min(bound, rate * BatchSeconds)));
    }
  }
  if (scan.Counts())
  {
    stats.Evaluations = evaluations;
  }
  context.GL().BindFramebuffer(GL_FRAMEBUFFER, 0);
  return true;
}

bool FinalizeGPU(HeadlessGL& context,
  const MeshSites& sites,
  const LocalFieldRequest& request,
  unsigned residentIds,
  bool signedField,
  unsigned distanceBuffer,
  unsigned closestBuffer,
  std::string& error)
{
  HeadlessGL::Scope scope(context);
  const GLFunctions& gl = context.GL();
  if (!scope.Ok(error))
  {
    return false;
  }
  const IndexBox& ext = request.Extent;
  const int nx = ext.Size(0), ny = ext.Size(1), nz = ext.Size(2);
  const int64_t slice = int64_t(nx) * ny, voxels = slice * nz;
  GLint alignment = 1;
  const int64_t slab = SlabSlices(gl, slice, 12, nz, alignment);
  if (slab == 0 || voxels > INT32_MAX)
  {
    error = "a slice of closest points does not fit GL_MAX_SHADER_STORAGE_BLOCK_SIZE";
    return false;
  }
  std::string log;
  const GLuint program =
    context.BuildProgram({ { GL_COMPUTE_SHADER, LinearFactorFinalize_comp } }, log);
  if (!program)
  {
    error = log;
    return false;
  }
  // Sites in double: anchor (w: type), axis, pseudonormal.
  std::vector<double> data(12 * std::max<int64_t>(1, sites.Count()), 0.0);
  Site site;
  for (int64_t s = 0; s < sites.Count(); ++s)
  {
    sites.Describe(s, site);
    for (int a = 0; a < 3; ++a)
    {
      data[12 * s + a] = site.Anchor[a];
      data[12 * s + 4 + a] = site.Axis[a];
      data[12 * s + 8 + a] = site.Normal[a];
    }
    data[12 * s + 3] = site.Type;
  }
  GLuint siteBuffer = 0;
  gl.GenBuffers(1, &siteBuffer);
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, siteBuffer);
  gl.BufferData(
    GL_SHADER_STORAGE_BUFFER, data.size() * sizeof(double), data.data(), GL_STATIC_DRAW);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, siteBuffer);
  gl.UseProgram(program);
  auto uniform = [&](const char* name) { return gl.GetUniformLocation(program, name); };
  const SampleGrid& grid = request.Grid;
  SetGridUniforms(gl, program, grid, ext);
  gl.Uniform1i(uniform("Signed"), signedField);
  gl.MemoryBarrier(GL_ALL_BARRIER_BITS);
  const int64_t perDispatch = int64_t(65535) * 64;
  for (int64_t z0 = 0; z0 < nz; z0 += slab)
  {
    const int64_t from = z0 * slice, to = std::min<int64_t>(nz, z0 + slab) * slice;
    gl.Uniform1i(uniform("IdBase"),
      static_cast<int>(BindVoxelRange(gl, 1, residentIds, from, to, 4, 4, alignment)));
    gl.Uniform1i(uniform("DistanceBase"),
      static_cast<int>(BindVoxelRange(gl, 2, distanceBuffer, from, to, 4, 4, alignment)));
    gl.Uniform1i(uniform("ClosestBase"),
      static_cast<int>(BindVoxelRange(gl, 3, closestBuffer, from, to, 12, 4, alignment)));
    gl.Uniform1i(uniform("Last"), static_cast<int>(to));
    for (int64_t first = from; first < to; first += perDispatch)
    {
      gl.Uniform1i(uniform("First"), static_cast<int>(first));
      gl.DispatchCompute(static_cast<GLuint>((std::min(perDispatch, to - first) + 63) / 64), 1, 1);
    }
  }
  gl.MemoryBarrier(GL_ALL_BARRIER_BITS);
  gl.DeleteBuffers(1, &siteBuffer);
  gl.DeleteProgram(program);
  return NoGLError(gl, "in the GPU finalize", error);
}

} // namespace vtkdf
