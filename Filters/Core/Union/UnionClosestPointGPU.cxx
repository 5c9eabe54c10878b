#include "Union/UnionClosestPointGPU.h"

#include "UnionBound_comp.h"

#include <algorithm>
#include <climits>
#include <cmath>

namespace vtkdf
{

namespace
{
enum Binding
{
  CornersBuffer,
  FaceRecordsBuffer,
  FacePlanesBuffer,
  PieceRecordsBuffer,
  PieceBoxesBuffer,
  QueriesBuffer,
  BlockBoundsBuffer,
  BlockStopsBuffer,
  BufferCount
};

/// The GL objects of one run, freed while the context is current.
struct Objects
{
  explicit Objects(const GLFunctions& gl)
    : GL(gl)
  {
    gl.GenBuffers(BufferCount, this->Id);
  }
  ~Objects()
  {
    this->GL.DeleteBuffers(BufferCount, this->Id);
    this->GL.DeleteProgram(this->Program);
  }
  Objects(const Objects&) = delete;
  Objects& operator=(const Objects&) = delete;
  const GLFunctions& GL;
  GLuint Id[BufferCount] = {};
  GLuint Program = 0;
};

/// The pieces as the pass reads them: faces one after another, each with its piece, its
/// corners and its plane; per piece its faces and box.
struct FlatPieces
{
  std::vector<double> Corners, Planes, Boxes;
  std::vector<int32_t> FaceRecords, PieceRecords;
  int64_t FaceCount = 0;

  explicit FlatPieces(const UnionClosestPoint& u)
  {
    for (size_t i = 0; i < u.Pieces.size(); ++i)
    {
      const ConvexPiece& piece = u.Pieces[i];
      this->PieceRecords.push_back(static_cast<int32_t>(this->FaceCount));
      this->PieceRecords.push_back(static_cast<int32_t>(piece.Faces.size()));
      this->Boxes.insert(this->Boxes.end(), piece.Lo, piece.Lo + 3);
      this->Boxes.insert(this->Boxes.end(), piece.Hi, piece.Hi + 3);
      for (size_t f = 0; f < piece.Faces.size(); ++f)
      {
        const std::vector<double>& corners = piece.Faces[f];
        this->FaceRecords.insert(this->FaceRecords.end(),
          { static_cast<int32_t>(i),
            static_cast<int32_t>(this->Corners.size() / 3),
            static_cast<int32_t>(corners.size() / 3),
            0 });
        this->Corners.insert(this->Corners.end(), corners.begin(), corners.end());
        this->Planes.insert(this->Planes.end(), &piece.Planes[4 * f], &piece.Planes[4 * f] + 4);
        ++this->FaceCount;
      }
    }
  }
};

/// Uploads `bytes` of `data` (or room for them, when null) to buffer `binding`.
void Upload(const GLFunctions& gl,
  const Objects& objects,
  int binding,
  size_t bytes,
  const void* data)
{
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, objects.Id[binding]);
  // An empty buffer cannot be bound: at least one element.
  gl.BufferData(GL_SHADER_STORAGE_BUFFER,
    static_cast<GLsizeiptr>(std::max<size_t>(bytes, 16)),
    nullptr,
    data ? GL_STATIC_DRAW : GL_DYNAMIC_READ);
  if (data && bytes > 0)
  {
    gl.BufferSubData(GL_SHADER_STORAGE_BUFFER, 0, static_cast<GLsizeiptr>(bytes), data);
  }
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, objects.Id[binding]);
}

/// The loop iterations an invocation may run on `context`: see UnionGPUSettings.
int IterationBudget(const HeadlessGL& context, const UnionGPUSettings& settings)
{
  if (settings.IterationBudget > 0)
  {
    return settings.IterationBudget;
  }
  // The pass counts iterations; its loop entries are no more than those, so half the
  // context's budget covers both (INT32_MAX, no limit, stays as it is).
  const int budget = context.InvocationLoopBudget();
  return budget == INT32_MAX ? budget : budget / 2;
}

/// U for every query (HUGE_VAL where the pass found no face point certainly on the
/// boundary) and whether a block of its faces ran out of iterations, a dispatch of
/// queries at a time; progress from 0 to 0.5.
bool ComputeBounds(HeadlessGL& context,
  const UnionClosestPoint& u,
  const std::vector<double>& queries,
  const UnionGPUSettings& settings,
  std::vector<UnionGPUAnswer>& answers,
  std::string& error)
{
  const GLFunctions& gl = context.GL();
  const FlatPieces flat(u);
  const int64_t count = static_cast<int64_t>(queries.size() / 3);
  const int64_t blockFaces = std::max(1, settings.BlockFaces);
  const int64_t blocks = std::max<int64_t>(1, (flat.FaceCount + blockFaces - 1) / blockFaces);
  const GLint64 maxBlock = MaxStorageBlock(gl);
  // Queries a dispatch: the face tests asked for, the group count limit, the storage
  // block limit of the per-block answers.
  const int64_t perDispatch = std::max<int64_t>(1,
    std::min<int64_t>({ settings.DispatchTests / std::max<int64_t>(1, flat.FaceCount),
      int64_t(65535) * 64 / blocks,
      maxBlock / (blocks * int64_t(sizeof(double))),
      count }));
  if (flat.Corners.size() * sizeof(double) > static_cast<size_t>(maxBlock) ||
    blocks > int64_t(65535) * 64 || flat.Corners.size() > INT32_MAX)
  {
    error = "the union's " + std::to_string(flat.FaceCount) + " faces (" +
      std::to_string(flat.Corners.size() / 3) +
      " corners) do not fit the GPU's shader storage limits";
    return false;
  }
  std::string log;
  Objects objects(gl);
  objects.Program = context.BuildProgram({ { GL_COMPUTE_SHADER, UnionBound_comp } }, log);
  if (!objects.Program)
  {
    error = "the union bound shader did not build: " + log;
    return false;
  }
  Upload(gl, objects, CornersBuffer, flat.Corners.size() * sizeof(double), flat.Corners.data());
  Upload(gl, objects, FaceRecordsBuffer, flat.FaceRecords.size() * 4, flat.FaceRecords.data());
  Upload(gl, objects, FacePlanesBuffer, flat.Planes.size() * sizeof(double), flat.Planes.data());
  Upload(gl, objects, PieceRecordsBuffer, flat.PieceRecords.size() * 4, flat.PieceRecords.data());
  Upload(gl, objects, PieceBoxesBuffer, flat.Boxes.size() * sizeof(double), flat.Boxes.data());
  Upload(gl, objects, QueriesBuffer, perDispatch * 3 * sizeof(double), nullptr);
  Upload(gl, objects, BlockBoundsBuffer, perDispatch * blocks * sizeof(double), nullptr);
  Upload(gl, objects, BlockStopsBuffer, perDispatch * blocks * sizeof(uint32_t), nullptr);
  const GLuint program = objects.Program;
  gl.UseProgram(program);
  auto uniform = [&](const char* name) { return gl.GetUniformLocation(program, name); };
  gl.Uniform1i(uniform("Blocks"), static_cast<GLint>(blocks));
  gl.Uniform1i(uniform("BlockFaces"), static_cast<GLint>(blockFaces));
  gl.Uniform1i(uniform("FaceCount"), static_cast<GLint>(flat.FaceCount));
  gl.Uniform1i(uniform("PieceCount"), static_cast<GLint>(u.Pieces.size()));
  gl.Uniform1d(uniform("Tolerance"), u.Tolerance);
  gl.Uniform1i(uniform("IterationBudget"), IterationBudget(context, settings));
  std::vector<double> blockBounds(perDispatch * blocks);
  std::vector<uint32_t> blockStops(perDispatch * blocks);
  for (int64_t first = 0; first < count; first += perDispatch)
  {
    const int64_t n = std::min(perDispatch, count - first);
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, objects.Id[QueriesBuffer]);
    gl.BufferSubData(GL_SHADER_STORAGE_BUFFER, 0, n * 3 * sizeof(double), &queries[3 * first]);
    gl.Uniform1i(uniform("QueryCount"), static_cast<GLint>(n));
    gl.DispatchCompute(static_cast<GLuint>((n * blocks + 63) / 64), 1, 1);
    gl.MemoryBarrier(GL_ALL_BARRIER_BITS);
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, objects.Id[BlockBoundsBuffer]);
    gl.GetBufferSubData(
      GL_SHADER_STORAGE_BUFFER, 0, n * blocks * sizeof(double), blockBounds.data());
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, objects.Id[BlockStopsBuffer]);
    gl.GetBufferSubData(
      GL_SHADER_STORAGE_BUFFER, 0, n * blocks * sizeof(uint32_t), blockStops.data());
    for (int64_t q = 0; q < n; ++q)
    {
      double best = HUGE_VAL;
      for (int64_t b = 0; b < blocks; ++b)
      {
        const double d2 = blockBounds[q * blocks + b];
        best = d2 >= 0 ? std::min(best, d2) : best;
        answers[first + q].Stopped = answers[first + q].Stopped || blockStops[q * blocks + b];
      }
      answers[first + q].Estimate = std::sqrt(best);
    }
    if (settings.Progress && !settings.Progress(0.5 * double(first + n) / double(count)))
    {
      error = "aborted";
      return false;
    }
  }
  gl.UseProgram(0);
  return NoGLError(gl, "in the union bound pass", error);
}

/// The exact search of the faces nearer than U (slightly above it, for the GPU's
/// rounding); the full search when U was not above the answer.
void Certify(const UnionClosestPoint& u, const double o[3], UnionGPUAnswer& result)
{
  const double bound = result.Estimate;
  const double seed = bound == HUGE_VAL ? HUGE_VAL : bound * (1 + 1e-9) + 10 * u.Tolerance;
  result.Answer = u.Query(o, seed);
  if (result.Answer.Piece < 0 && seed != HUGE_VAL)
  {
    const int64_t visited = result.Answer.FacesVisited;
    result.Answer = u.Query(o);
    result.Answer.FacesVisited += visited;
    result.Reseeded = true;
  }
}

/// Over the queries in parallel (settings.For), in blocks of 64 between which progress is
/// told; progress from 0.5 to 1.
bool CertifyAll(const UnionClosestPoint& u,
  const std::vector<double>& queries,
  const UnionGPUSettings& settings,
  std::vector<UnionGPUAnswer>& answers,
  std::string& error)
{
  const int64_t count = static_cast<int64_t>(answers.size());
  auto certify = [&](int64_t begin, int64_t end)
  {
    for (int64_t q = begin; q < end; ++q)
    {
      Certify(u, &queries[3 * q], answers[q]);
    }
  };
  const int64_t block = 64;
  for (int64_t begin = 0; begin < count; begin += block)
  {
    const int64_t end = std::min<int64_t>(count, begin + block);
    if (settings.For)
    {
      settings.For(end - begin, 1, [&](int64_t b, int64_t e) { certify(begin + b, begin + e); });
    }
    else
    {
      certify(begin, end);
    }
    if (settings.Progress && !settings.Progress(0.5 + 0.5 * double(end) / double(count)))
    {
      error = "aborted";
      return false;
    }
  }
  return true;
}
} // namespace

bool QueryUnionGPU(HeadlessGL& context,
  const UnionClosestPoint& u,
  const std::vector<double>& queries,
  const UnionGPUSettings& settings,
  std::vector<UnionGPUAnswer>& answers,
  std::string& error)
{
  answers.assign(queries.size() / 3, UnionGPUAnswer());
  if (answers.empty())
  {
    return true;
  }
  {
    HeadlessGL::Scope scope(context);
    if (!scope.Ok(error) || !ComputeBounds(context, u, queries, settings, answers, error))
    {
      return false;
    }
  }
  return CertifyAll(u, queries, settings, answers, error);
}

} // namespace vtkdf
