#include "Winding/WindingSignsGPU.h"

#include "GL/GridUniforms.h"

#include "GL/GLFunctions.h"
#include "WindingNumber_comp.h"

#include <algorithm>
#include <atomic>
#include <climits>
#include <cmath>

namespace vtkdf
{

namespace
{
/// GL buffers deleted with the scope.
struct Buffers
{
  const GLFunctions& GL;
  GLuint Id[5] = { 0, 0, 0, 0, 0 };
  explicit Buffers(const GLFunctions& gl)
    : GL(gl)
  {
    gl.GenBuffers(5, this->Id);
  }
  ~Buffers() { this->GL.DeleteBuffers(5, this->Id); }
};
/// The samples whose loops the context could not run to the end (a software renderer's
/// loop limit): WindingNumber::Inside, whose bits the shader's are.
void FinishOnCPU(const WindingNumber& winding,
  const SampleGrid& grid,
  const IndexBox& extent,
  const std::vector<int64_t>& samples,
  uint8_t* inside,
  const WindingSignOptions& options,
  const ParallelFor& parallelFor,
  WindingSignStatistics& stats)
{
  const int64_t nx = extent.Size(0), ny = extent.Size(1);
  std::atomic<int64_t> exactSums(0);
  auto decide = [&](int64_t begin, int64_t end)
  {
    int64_t exactHere = 0;
    for (int64_t n = begin; n < end; ++n)
    {
      const int64_t s = samples[n];
      const int ijk[3] = { static_cast<int>(extent.Lo[0] + s % nx),
        static_cast<int>(extent.Lo[1] + (s / nx) % ny),
        static_cast<int>(extent.Lo[2] + s / (nx * ny)) };
      const double q[3] = {
        grid.Coordinate(0, ijk[0]), grid.Coordinate(1, ijk[1]), grid.Coordinate(2, ijk[2])
      };
      double w = 0;
      bool exact = false;
      inside[s] = winding.Inside(q, options.Value ? &w : nullptr, &exact) ? 1 : 0;
      if (options.Value)
      {
        options.Value[s] = static_cast<float>(w);
      }
      exactHere += exact;
    }
    exactSums += exactHere;
  };
  const int64_t count = static_cast<int64_t>(samples.size());
  if (parallelFor)
  {
    parallelFor(count, 64, decide);
  }
  else
  {
    decide(0, count);
  }
  stats.Exact += exactSums.load();
  stats.CPUSamples = count;
}
} // namespace

bool WindingSignsGPU(HeadlessGL& context,
  const WindingNumber& winding,
  const SampleGrid& grid,
  const IndexBox& extent,
  uint8_t* inside,
  const WindingSignOptions& options,
  const ParallelFor& parallelFor,
  WindingSignStatistics& stats,
  std::string& error)
{
  HeadlessGL::Scope scope(context);
  if (!scope.Ok(error))
  {
    return false;
  }
  const GLFunctions& gl = context.GL();
  const int64_t samples = extent.Count();
  std::vector<double> nodes;
  std::vector<int32_t> links;
  winding.Flatten(nodes, links);
  const LargeVector<double>& corners = winding.TriangleCorners();
  const GLint64 maxBlock = MaxStorageBlock(gl);
  const int64_t sizes[3] = { static_cast<int64_t>(nodes.size() * sizeof(double)),
    static_cast<int64_t>(links.size() * sizeof(int32_t)),
    static_cast<int64_t>(corners.size() * sizeof(double)) };
  for (const int64_t size : sizes)
  {
    if (size > maxBlock)
    {
      error = "the winding-number hierarchy of " + std::to_string(winding.TriangleCount()) +
        " triangles (" + std::to_string(size) +
        " bytes in one buffer) does not fit GL_MAX_SHADER_STORAGE_BLOCK_SIZE (" +
        std::to_string(maxBlock) + ")";
      return false;
    }
  }
  if (samples > INT32_MAX || winding.TriangleCount() > INT32_MAX)
  {
    error = "the winding-number pass indexes samples and triangles with 32-bit integers";
    return false;
  }
  std::string log;
  const GLuint program = context.BuildProgram({ { GL_COMPUTE_SHADER, WindingNumber_comp } }, log);
  if (!program)
  {
    error = log;
    return false;
  }
  // Samples per dispatch: the group count limit, and the answers within one block.
  const int64_t chunk = std::min<int64_t>(
    { int64_t(65535) * 64, samples, static_cast<int64_t>(maxBlock / sizeof(float)) });
  Buffers buffers(gl);
  const void* data[3] = { nodes.data(), links.data(), corners.data() };
  for (int b = 0; b < 3; ++b)
  {
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, buffers.Id[b]);
    // An empty buffer cannot be bound: at least one element.
    gl.BufferData(
      GL_SHADER_STORAGE_BUFFER, std::max<int64_t>(sizes[b], 16), nullptr, GL_STATIC_DRAW);
    if (sizes[b] > 0)
    {
      gl.BufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizes[b], data[b]);
    }
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, b, buffers.Id[b]);
  }
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, buffers.Id[3]);
  gl.BufferData(GL_SHADER_STORAGE_BUFFER, chunk * 4, nullptr, GL_DYNAMIC_READ);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, buffers.Id[3]);
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, buffers.Id[4]);
  gl.BufferData(GL_SHADER_STORAGE_BUFFER, options.Value ? chunk * 4 : 16, nullptr, GL_DYNAMIC_READ);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, buffers.Id[4]);

  gl.UseProgram(program);
  auto uniform = [&](const char* name) { return gl.GetUniformLocation(program, name); };
  SetGridUniforms(gl, program, grid, extent);
  gl.Uniform1i(uniform("TriangleCount"), static_cast<int>(winding.TriangleCount()));
  gl.Uniform1d(uniform("CoarseAccuracy"), WindingNumber::CoarseAccuracy);
  gl.Uniform1d(uniform("Accuracy"), winding.GetAccuracy());
  gl.Uniform1d(uniform("ValueAccuracy"), WindingNumber::ValueAccuracy);
  gl.Uniform1d(uniform("RoundingSlack"), WindingNumber::RoundingSlack);
  gl.Uniform1d(uniform("TwoPi"), 2 * M_PI);
  gl.Uniform1d(uniform("FourPi"), 4 * M_PI);
  SetArcTangentUniforms(gl, program);
  gl.Uniform1i(uniform("WantValues"), options.Value ? 1 : 0);
  gl.Uniform1i(uniform("IterationBudget"),
    options.IterationBudget > 0 ? options.IterationBudget : context.InvocationLoopBudget());
  std::vector<uint32_t> answers(chunk);
  std::vector<int64_t> unfinished;
  stats = WindingSignStatistics();
  for (int64_t first = 0; first < samples; first += chunk)
  {
    const int64_t count = std::min(chunk, samples - first);
    gl.Uniform1i(uniform("First"), static_cast<int>(first));
    gl.Uniform1i(uniform("Last"), static_cast<int>(first + count));
    gl.DispatchCompute(static_cast<GLuint>((count + 63) / 64), 1, 1);
    gl.MemoryBarrier(GL_ALL_BARRIER_BITS);
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, buffers.Id[3]);
    gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, count * 4, answers.data());
    for (int64_t s = 0; s < count; ++s)
    {
      inside[first + s] = answers[s] & 1u;
      stats.Exact += (answers[s] >> 1) & 1u;
      if (answers[s] & 4u)
      {
        unfinished.push_back(first + s);
      }
    }
    if (options.Value)
    {
      gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, buffers.Id[4]);
      gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, count * 4, options.Value + first);
    }
  }
  stats.Evaluated = samples;
  gl.DeleteProgram(program);
  if (!NoGLError(gl, "in the winding-number pass", error))
  {
    return false;
  }
  FinishOnCPU(winding, grid, extent, unfinished, inside, options, parallelFor, stats);
  return true;
}

} // namespace vtkdf
