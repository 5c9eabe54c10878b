#include "LinearFactor/LinearFactorGPU.h"

#include "GL/GridUniforms.h"

#include "LinearFactorFinalize_comp.h"
#include "LinearFactorRows_comp.h"

#include "GL/GLFunctions.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>

namespace vtkdf
{
namespace
{

/// Deletes the GL objects of one run, whatever way it ends.
struct RowScanObjects
{
  const GLFunctions& gl;
  GLuint Programs[2] = { 0, 0 }, Buffers[4] = { 0, 0, 0, 0 };
  ~RowScanObjects()
  {
    gl.DeleteBuffers(4, Buffers);
    gl.DeleteProgram(Programs[0]);
    gl.DeleteProgram(Programs[1]);
  }
};

/// One run of ScanSitesGPU: batches of the CPU's rows (CollectScanRows) evaluated on the
/// GPU into the samples' nearest sites, kept in GL buffers of the extent (the least
/// squared distance's bits and the least site, or both packed in 64 bits).
class RowScan
{
public:
  RowScan(HeadlessGL& context, const LocalFieldRequest& request, unsigned residentIds)
    : Context(context)
    , GL(context.GL())
    , Extent(request.Extent)
    , ResidentIds(residentIds)
    , Objects{ context.GL() }
  {
  }

  /// The programs and the extent's buffers; false and `error` when the GPU cannot.
  bool Setup(std::string& error);
  /// Offers every row of `batch` to its samples.
  void Scan(const ScanRows& batch);
  /// The nearest sites into `nearest` (unless they stay in the resident ids).
  void ReadBack(NearestSiteBuffer& nearest, const ParallelFor& parallelFor);

private:
  void Dispatch(GLuint program, const std::vector<ScanRow>& rows, int64_t slab);
  void CutRows(const ScanRows& batch);

  HeadlessGL& Context;
  const GLFunctions& GL;
  const IndexBox& Extent;
  const unsigned ResidentIds;
  RowScanObjects Objects;
  bool OnePass = false;
  int64_t SlabSamples = 0, Slabs = 1;
  GLint Alignment = 1;
  std::vector<std::vector<ScanRow>> SlabRows;
};

bool RowScan::Setup(std::string& error)
{
  const GLFunctions& gl = this->GL;
  const int64_t samples = this->Extent.Count();
  if (samples >= (int64_t(1) << 31))
  {
    error = "the extent has " + std::to_string(samples) +
      " samples, more than the GPU scan indexes (2^31 - 1)";
    return false;
  }
  // One 64-bit atomic minimum where the GL has it (not for resident ids, which are the
  // two-pass scan's site buffer); VTKDF_GPU_TWO_PASS forces the two passes anywhere.
  this->OnePass = !this->ResidentIds && gl.HasExtension("GL_NV_shader_atomic_int64") &&
    gl.HasExtension("GL_ARB_gpu_shader_int64") && !std::getenv("VTKDF_GPU_TWO_PASS");
  const int64_t bytes = this->OnePass ? 8 : 4;
  const int64_t slice = int64_t(this->Extent.Size(0)) * this->Extent.Size(1);
  const int64_t slabSlices = SlabSlices(gl, slice, bytes, this->Extent.Size(2), this->Alignment);
  if (slabSlices == 0)
  {
    error = "a slice of nearest sites does not fit GL_MAX_SHADER_STORAGE_BLOCK_SIZE";
    return false;
  }
  this->SlabSamples = slabSlices * slice;
  this->Slabs = (samples + this->SlabSamples - 1) / this->SlabSamples;
  const std::string body = LinearFactorRows_comp;
  const std::string head = "#version 450 core\n";
  const std::string passes[2] = { this->OnePass
      ? head + "#extension GL_ARB_gpu_shader_int64 : require\n" +
        "#extension GL_NV_shader_atomic_int64 : require\n#define ONE_PASS\n" + body
      : head + "#define DISTANCE_PASS\n" + body,
    head + body };
  for (int p = 0; p < (this->OnePass ? 1 : 2); ++p)
  {
    std::string log;
    this->Objects.Programs[p] =
      this->Context.BuildProgram({ { GL_COMPUTE_SHADER, passes[p].c_str() } }, log);
    if (!this->Objects.Programs[p])
    {
      error = log;
      return false;
    }
  }
  GLuint* buffers = this->Objects.Buffers;
  gl.GenBuffers(4, buffers);
  const uint32_t empty = 0xffffffffu;
  for (int b = 2; b < 4; ++b)
  {
    if (b == 3 && this->OnePass)
    {
      break;
    }
    const GLuint buffer = b == 3 && this->ResidentIds ? this->ResidentIds : buffers[b];
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, buffer);
    if (buffer == buffers[b])
    {
      gl.BufferData(
        GL_SHADER_STORAGE_BUFFER, std::max<int64_t>(1, samples) * bytes, nullptr, GL_DYNAMIC_COPY);
    }
    gl.ClearBufferData(GL_SHADER_STORAGE_BUFFER, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &empty);
  }
  return NoGLError(gl, "setting up the GPU scan", error);
}

/// The rows by the slab of samples they lie in, when the extent takes more than one. Only
/// a row along z crosses slices, so slabs: it is cut there, its pieces keeping their
/// samples' indices i, so their bits.
void RowScan::CutRows(const ScanRows& batch)
{
  for (std::vector<ScanRow>& rows : this->SlabRows)
  {
    rows.clear();
  }
  this->SlabRows.resize(static_cast<size_t>(this->Slabs));
  const int64_t n = this->SlabSamples;
  for (const ScanRow& row : batch.Rows)
  {
    const int64_t stride = row.Stride;
    ScanRow piece = row;
    for (int i = row.I0; i <= row.I1; ++i)
    {
      const int64_t at = row.At + int64_t(i - row.I0) * stride;
      if (i == row.I1 || (at + stride) / n != at / n)
      {
        piece.I1 = i;
        this->SlabRows[at / n].push_back(piece);
        piece.I0 = i + 1;
        piece.At = static_cast<int32_t>(at + stride);
      }
    }
  }
}

void RowScan::Scan(const ScanRows& batch)
{
  const GLFunctions& gl = this->GL;
  GLuint* buffers = this->Objects.Buffers;
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, buffers[0]);
  gl.BufferData(GL_SHADER_STORAGE_BUFFER,
    std::max<size_t>(1, batch.Frames.size()) * sizeof(ScanFrame),
    batch.Frames.data(),
    GL_STREAM_DRAW);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffers[0]);
  if (this->Slabs > 1)
  {
    this->CutRows(batch);
  }
  for (int64_t slab = 0; slab < this->Slabs; ++slab)
  {
    const std::vector<ScanRow>& rows = this->Slabs > 1 ? this->SlabRows[slab] : batch.Rows;
    if (rows.empty())
    {
      continue;
    }
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, buffers[1]);
    gl.BufferData(
      GL_SHADER_STORAGE_BUFFER, rows.size() * sizeof(ScanRow), rows.data(), GL_STREAM_DRAW);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, buffers[1]);
    for (int p = 0; p < (this->OnePass ? 1 : 2); ++p)
    {
      this->Dispatch(this->Objects.Programs[p], rows, slab);
      gl.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
  }
}

/// One pass over `rows`, whose samples lie in `slab`.
void RowScan::Dispatch(GLuint program, const std::vector<ScanRow>& rows, int64_t slab)
{
  const GLFunctions& gl = this->GL;
  const int64_t from = slab * this->SlabSamples;
  const int64_t to = std::min(this->Extent.Count(), from + this->SlabSamples);
  const int64_t bytes = this->OnePass ? 8 : 4;
  gl.UseProgram(program);
  int64_t base =
    BindVoxelRange(gl, 2, this->Objects.Buffers[2], from, to, bytes, bytes, this->Alignment);
  if (!this->OnePass)
  {
    BindVoxelRange(gl,
      3,
      this->ResidentIds ? this->ResidentIds : this->Objects.Buffers[3],
      from,
      to,
      4,
      4,
      this->Alignment);
  }
  gl.Uniform1i(gl.GetUniformLocation(program, "SampleBase"), static_cast<GLint>(base));
  const GLint first = gl.GetUniformLocation(program, "First");
  gl.Uniform1i(gl.GetUniformLocation(program, "Count"), static_cast<GLint>(rows.size()));
  const int64_t perDispatch = int64_t(65535) * 64;
  for (int64_t r = 0; r < int64_t(rows.size()); r += perDispatch)
  {
    gl.Uniform1i(first, static_cast<GLint>(r));
    const int64_t n = std::min<int64_t>(perDispatch, int64_t(rows.size()) - r);
    gl.DispatchCompute(static_cast<GLuint>((n + 63) / 64), 1, 1);
  }
}

void RowScan::ReadBack(NearestSiteBuffer& nearest, const ParallelFor& parallelFor)
{
  if (this->ResidentIds)
  {
    return;
  }
  const GLFunctions& gl = this->GL;
  const int64_t samples = this->Extent.Count();
  gl.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  if (this->OnePass)
  {
    std::vector<uint64_t> packed(static_cast<size_t>(samples));
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, this->Objects.Buffers[2]);
    gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, samples * 8, packed.data());
    parallelFor(samples,
      1 << 16,
      [&](int64_t begin, int64_t end)
      {
        for (int64_t at = begin; at < end; ++at)
        {
          nearest.Set(at, packed[at]);
        }
      });
    return;
  }
  std::vector<uint32_t> distance2(static_cast<size_t>(samples)), site(distance2.size());
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, this->Objects.Buffers[2]);
  gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, samples * 4, distance2.data());
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, this->Objects.Buffers[3]);
  gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, samples * 4, site.data());
  parallelFor(samples,
    1 << 16,
    [&](int64_t begin, int64_t end)
    {
      for (int64_t at = begin; at < end; ++at)
      {
        nearest.Set(at, (uint64_t(distance2[at]) << 32) | site[at]);
      }
    });
}
} // namespace

bool ScanSitesGPU(HeadlessGL& context,
  const MeshSites& sites,
  const RangeCulling& culling,
  const LocalFieldRequest& request,
  NearestSiteBuffer& nearest,
  const ParallelFor& parallelFor,
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
  RowScan scan(context, request, residentIds);
  if (!scan.Setup(error))
  {
    return false;
  }
  // Batches of sites, as the CPU scan reports progress: the CPU collects a batch's rows
  // while the GPU may still evaluate the last one's.
  const int64_t numSites = static_cast<int64_t>(culling.Order.size());
  const int64_t batches = std::max<int64_t>(1, std::min<int64_t>(20, numSites / 1024));
  ScanRows rows;
  for (int64_t batch = 0; batch < batches; ++batch)
  {
    CollectScanRows(sites,
      culling,
      request,
      numSites * batch / batches,
      numSites * (batch + 1) / batches,
      parallelFor,
      rows);
    stats.Evaluations += rows.Evaluations;
    scan.Scan(rows);
    if (progress)
    {
      context.GL().Finish();
      if (!progress(double(batch + 1) / batches))
      {
        stats.Aborted = true;
        break;
      }
    }
  }
  if (!stats.Aborted)
  {
    scan.ReadBack(nearest, parallelFor);
  }
  return NoGLError(context.GL(), "in the GPU scan", error);
}

bool FinalizeGPU(HeadlessGL& context,
  const MeshSites& sites,
  const LocalFieldRequest& request,
  const GridFrame& frame,
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
  gl.Uniform3d(uniform("FrameOrigin"), frame.Origin[0], frame.Origin[1], frame.Origin[2]);
  gl.Uniform1d(uniform("FrameScale"), frame.Scale);
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
