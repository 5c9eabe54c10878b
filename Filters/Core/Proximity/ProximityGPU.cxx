#include "Proximity/ProximityGPU.h"

#include "GL/GLFunctions.h"
#include "GL/HeadlessGL.h"
#include "ProximityNearest_comp.h"

#include <algorithm>
#include <climits>
#include <limits>

namespace vtkdf
{
namespace
{
/// One model's buffers on the device.
struct ModelBuffers
{
  // Coordinates, every frame: points, node boxes. Topology, once: triangles, node links,
  // the hierarchy's order. Answers for the model's points (the other model's nearest).
  GLuint Points = 0, Bounds = 0, Triangles = 0, Links = 0, Order = 0;
  GLuint PointAnswers = 0, PointTriangles = 0;
  uint64_t Topology = 0; // the generation the topology buffers hold, 0 for none
  int64_t PointCount = 0;
};
} // namespace

struct ProximityDevice::State
{
  HeadlessGL& Context;
  GLuint Program = 0;
  ModelBuffers Models[2];
  GLuint Items = 0, Answers = 0, AnswerTriangles = 0;
  int64_t AnswerCapacity = 0;
  int64_t BytesSent = 0, BytesRead = 0;

  explicit State(HeadlessGL& context)
    : Context(context)
  {
  }

  std::vector<GLuint*> Buffers()
  {
    std::vector<GLuint*> all = { &this->Items, &this->Answers, &this->AnswerTriangles };
    for (ModelBuffers& m : this->Models)
    {
      for (GLuint* b : { &m.Points,
             &m.Bounds,
             &m.Triangles,
             &m.Links,
             &m.Order,
             &m.PointAnswers,
             &m.PointTriangles })
      {
        all.push_back(b);
      }
    }
    return all;
  }
};

ProximityDevice::ProximityDevice(HeadlessGL& context)
  : S(new State(context))
{
}

ProximityDevice::~ProximityDevice()
{
  HeadlessGL::Scope scope(this->S->Context);
  if (!scope.Ok())
  {
    return;
  }
  const GLFunctions& gl = this->S->Context.GL();
  for (GLuint* buffer : this->S->Buffers())
  {
    if (*buffer)
    {
      gl.DeleteBuffers(1, buffer);
    }
  }
  if (this->S->Program)
  {
    gl.DeleteProgram(this->S->Program);
  }
}

HeadlessGL& ProximityDevice::Context() const
{
  return this->S->Context;
}

namespace
{
/// Fills `buffer` (made when 0) with `bytes` of `data` (at least 16 bytes: an empty
/// buffer cannot be bound).
void Upload(const GLFunctions& gl, GLuint& buffer, const void* data, int64_t bytes, GLenum usage)
{
  if (!buffer)
  {
    gl.GenBuffers(1, &buffer);
  }
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, buffer);
  gl.BufferData(GL_SHADER_STORAGE_BUFFER, std::max<int64_t>(bytes, 16), nullptr, usage);
  if (data && bytes > 0)
  {
    gl.BufferSubData(GL_SHADER_STORAGE_BUFFER, 0, bytes, data);
  }
}

bool FitsBlock(const GLFunctions& gl, int64_t bytes, const char* what, std::string& error)
{
  const GLint64 maxBlock = MaxStorageBlock(gl);
  if (bytes > maxBlock)
  {
    error = std::string("the proximity search's ") + what + " (" + std::to_string(bytes) +
      " bytes in one buffer) does not fit GL_MAX_SHADER_STORAGE_BLOCK_SIZE (" +
      std::to_string(maxBlock) + "): use the CPU backend";
    return false;
  }
  return true;
}

/// Samples a dispatch: the group count limit, and the answers within one storage block.
int64_t DispatchSamples(const GLFunctions& gl)
{
  return std::max<int64_t>(1, std::min<int64_t>(int64_t(65535) * 64, MaxStorageBlock(gl) / 32));
}

/// `error` as a failure of the GPU backend, naming the renderer; false.
bool Failed(const ProximityDevice::State& s, std::string& error)
{
  error = s.Context.Failure(error);
  return false;
}

/// The program, built on first use.
bool Program(ProximityDevice::State& s, std::string& error)
{
  if (!s.Program)
  {
    std::string log;
    s.Program = s.Context.BuildProgram({ { GL_COMPUTE_SHADER, ProximityNearest_comp } }, log);
    if (!s.Program)
    {
      error = log;
      return false;
    }
  }
  return true;
}

/// Binds the other model's search buffers and the self model's points, triangles and
/// hints, and sets the common uniforms.
void BindModels(ProximityDevice::State& s, int self, int other, int mode)
{
  const GLFunctions& gl = s.Context.GL();
  const ModelBuffers& o = s.Models[other];
  const ModelBuffers& m = s.Models[self];
  const GLuint bindings[8] = {
    o.Points, o.Triangles, o.Bounds, o.Links, o.Order, m.Points, m.Triangles, m.PointTriangles
  };
  for (GLuint b = 0; b < 8; ++b)
  {
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, b, bindings[b]);
  }
  gl.UseProgram(s.Program);
  gl.Uniform1i(gl.GetUniformLocation(s.Program, "Mode"), mode);
  gl.Uniform1d(
    gl.GetUniformLocation(s.Program, "BoxShrink"), 1 - 8 * std::numeric_limits<double>::epsilon());
}

/// Runs invocations [0, count) in dispatches of at most `chunk`, each written from the
/// start of the answer buffers and read into `answers` at its place.
void Dispatch(ProximityDevice::State& s,
  GLuint values,
  GLuint triangles,
  int64_t count,
  int64_t chunk,
  bool fromStart,
  NearestAnswers& answers)
{
  const GLFunctions& gl = s.Context.GL();
  answers.Values.resize(static_cast<size_t>(4 * count));
  answers.Triangles.resize(static_cast<size_t>(count));
  const GLint first = gl.GetUniformLocation(s.Program, "First");
  const GLint last = gl.GetUniformLocation(s.Program, "Last");
  for (int64_t begin = 0; begin < count; begin += chunk)
  {
    const int64_t n = std::min(chunk, count - begin);
    gl.Uniform1i(first, static_cast<int>(begin));
    gl.Uniform1i(last, static_cast<int>(begin + n));
    gl.DispatchCompute(static_cast<GLuint>((n + 63) / 64), 1, 1);
    gl.MemoryBarrier(GL_ALL_BARRIER_BITS);
    // Points write at their index; samples at their place in the chunk.
    const int64_t at = fromStart ? 0 : begin;
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, values);
    gl.GetBufferSubData(
      GL_SHADER_STORAGE_BUFFER, at * 32, n * 32, answers.Values.data() + 4 * begin);
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, triangles);
    gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, at * 4, n * 4, answers.Triangles.data() + begin);
    s.BytesRead += n * 36;
  }
}
} // namespace

int64_t DeviceBatchSamples(ProximityDevice& device)
{
  HeadlessGL::Scope scope(device.Get().Context);
  return scope.Ok()
    ? std::min<int64_t>(int64_t(1) << 22, DispatchSamples(device.Get().Context.GL()))
    : int64_t(1) << 22;
}

void DeviceResetTraffic(ProximityDevice& device)
{
  device.Get().BytesSent = device.Get().BytesRead = 0;
}

void DeviceTraffic(ProximityDevice& device, int64_t& sent, int64_t& read)
{
  sent = device.Get().BytesSent;
  read = device.Get().BytesRead;
}

bool DeviceLoadModel(ProximityDevice& device,
  int slot,
  const TriangleModel& model,
  const TriangleBoxTree& tree,
  uint64_t topology,
  std::string& error)
{
  ProximityDevice::State& s = device.Get();
  HeadlessGL::Scope scope(s.Context);
  if (!scope.Ok(error))
  {
    return Failed(s, error);
  }
  const GLFunctions& gl = s.Context.GL();
  ModelBuffers& m = s.Models[slot];
  const int64_t points = static_cast<int64_t>(model.Points.size());
  const int64_t triangles = static_cast<int64_t>(model.Triangles.size());
  const int64_t nodes = static_cast<int64_t>(tree.Nodes().size());
  if (points > INT32_MAX / 3 || triangles > INT32_MAX / 3)
  {
    error = "the proximity search on the GPU indexes points and triangles with 32-bit integers";
    return Failed(s, error);
  }
  if (!FitsBlock(gl, 3 * 8 * points, "points", error) ||
    !FitsBlock(gl, 6 * 8 * nodes, "hierarchy", error) ||
    !FitsBlock(gl, 32 * points, "answers for the points", error))
  {
    return Failed(s, error);
  }
  if (m.Topology != topology)
  {
    std::vector<int32_t> corners(static_cast<size_t>(3 * triangles));
    for (size_t t = 0; t < model.Triangles.size(); ++t)
    {
      for (int c = 0; c < 3; ++c)
      {
        corners[3 * t + c] = static_cast<int32_t>(model.Triangles[t][c]);
      }
    }
    std::vector<int32_t> links(static_cast<size_t>(4 * nodes));
    for (size_t n = 0; n < tree.Nodes().size(); ++n)
    {
      const auto& node = tree.Nodes()[n];
      links[4 * n] = static_cast<int32_t>(node.Left);
      links[4 * n + 1] = static_cast<int32_t>(node.Right);
      links[4 * n + 2] = static_cast<int32_t>(node.Begin);
      links[4 * n + 3] = static_cast<int32_t>(node.End);
    }
    std::vector<int32_t> order(tree.Order().begin(), tree.Order().end());
    Upload(gl, m.Triangles, corners.data(), 4 * 3 * triangles, GL_STATIC_DRAW);
    Upload(gl, m.Links, links.data(), 4 * 4 * nodes, GL_STATIC_DRAW);
    Upload(gl, m.Order, order.data(), 4 * triangles, GL_STATIC_DRAW);
    Upload(gl, m.PointAnswers, nullptr, 32 * points, GL_DYNAMIC_READ);
    Upload(gl, m.PointTriangles, nullptr, 4 * points, GL_DYNAMIC_READ);
    s.BytesSent += 4 * (3 * triangles + 4 * nodes + triangles);
    m.Topology = topology;
    m.PointCount = points;
  }
  std::vector<double> bounds(static_cast<size_t>(6 * nodes));
  for (size_t n = 0; n < tree.Nodes().size(); ++n)
  {
    const Box& box = tree.Nodes()[n].Bounds;
    for (int k = 0; k < 3; ++k)
    {
      bounds[6 * n + k] = box.Min[k];
      bounds[6 * n + 3 + k] = box.Max[k];
    }
  }
  Upload(gl, m.Points, model.Points.data(), 3 * 8 * points, GL_DYNAMIC_DRAW);
  Upload(gl, m.Bounds, bounds.data(), 6 * 8 * nodes, GL_DYNAMIC_DRAW);
  s.BytesSent += 8 * (3 * points + 6 * nodes);
  return NoGLError(gl, "uploading a model for the proximity search", error) || Failed(s, error);
}

bool DeviceNearestToPoints(ProximityDevice& device,
  int self,
  int other,
  NearestAnswers& answers,
  std::string& error)
{
  ProximityDevice::State& s = device.Get();
  HeadlessGL::Scope scope(s.Context);
  if (!scope.Ok(error) || !Program(s, error))
  {
    return Failed(s, error);
  }
  const GLFunctions& gl = s.Context.GL();
  ModelBuffers& m = s.Models[self];
  BindModels(s, self, other, 0);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 8, m.PointAnswers);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 9, m.PointTriangles);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 10, m.PointTriangles); // unread in Mode 0
  // The points' answers stay whole on the device (the samples' hints): one buffer, each
  // dispatch writing at the points' indices through First.
  Dispatch(s, m.PointAnswers, m.PointTriangles, m.PointCount, int64_t(65535) * 64, false, answers);
  return NoGLError(gl, "in the proximity search of points", error) || Failed(s, error);
}

bool DeviceNearestToSamples(ProximityDevice& device,
  int self,
  int other,
  const SampleBatch& batch,
  NearestAnswers& answers,
  std::string& error)
{
  ProximityDevice::State& s = device.Get();
  HeadlessGL::Scope scope(s.Context);
  if (!scope.Ok(error) || !Program(s, error))
  {
    return Failed(s, error);
  }
  const GLFunctions& gl = s.Context.GL();
  const int64_t items = static_cast<int64_t>(batch.Items.size() / 4);
  if (batch.Samples > INT32_MAX || !FitsBlock(gl, 16 * items, "triangle list", error))
  {
    error = error.empty() ? "a batch of face samples exceeds 32-bit indices" : error;
    return Failed(s, error);
  }
  const int64_t chunk = std::max<int64_t>(1, std::min(DispatchSamples(gl), batch.Samples));
  if (chunk > s.AnswerCapacity)
  {
    Upload(gl, s.Answers, nullptr, 32 * chunk, GL_DYNAMIC_READ);
    Upload(gl, s.AnswerTriangles, nullptr, 4 * chunk, GL_DYNAMIC_READ);
    s.AnswerCapacity = chunk;
  }
  Upload(gl, s.Items, batch.Items.data(), 4 * 4 * items, GL_DYNAMIC_DRAW);
  s.BytesSent += 16 * items;
  BindModels(s, self, other, 1);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 8, s.Answers);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 9, s.AnswerTriangles);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 10, s.Items);
  gl.Uniform1i(gl.GetUniformLocation(s.Program, "ItemCount"), static_cast<int>(items));
  Dispatch(s, s.Answers, s.AnswerTriangles, batch.Samples, chunk, true, answers);
  return NoGLError(gl, "in the proximity search of face samples", error) || Failed(s, error);
}
} // namespace vtkdf
