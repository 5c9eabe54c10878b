#include "Union/UnionClosestPointGPU.h"

#include "UnionView_frag.h"
#include "UnionView_geom.h"
#include "UnionView_vert.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vtkdf
{

namespace
{
/// The GL objects of one run, freed while the context is current.
struct Objects
{
  explicit Objects(const GLFunctions& gl)
    : GL(gl)
  {
  }
  ~Objects()
  {
    // The state the views change, back to the defaults the other GPU passes expect,
    // however the run ended (an error, an abort).
    this->GL.BindFramebuffer(GL_FRAMEBUFFER, 0);
    this->GL.BindVertexArray(0);
    this->GL.UseProgram(0);
    this->GL.Disable(GL_DEPTH_TEST);
    this->GL.Disable(GL_STENCIL_TEST);
    this->GL.Disable(GL_CULL_FACE);
    this->GL.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    this->GL.DepthMask(GL_TRUE);
    this->GL.DeleteBuffers(1, &this->Buffer);
    this->GL.DeleteBuffers(2, this->Storage);
    this->GL.DeleteVertexArrays(1, &this->VAO);
    this->GL.DeleteFramebuffers(1, &this->FBO);
    this->GL.DeleteTextures(1, &this->DepthStencil);
    if (!this->Queries.empty())
    {
      this->GL.DeleteQueries(static_cast<GLsizei>(this->Queries.size()), this->Queries.data());
    }
    this->GL.DeleteProgram(this->Program);
  }
  const GLFunctions& GL;
  GLuint Buffer = 0, VAO = 0, FBO = 0, DepthStencil = 0, Program = 0;
  GLuint Storage[2] = { 0, 0 }; // per query of a batch: O and Far; which pieces hold O
  std::vector<GLuint> Queries;
};

/// The six views: forward and up per cube face; right = forward x up, so that the frame
/// (right, up, -forward) is right-handed and the rasterizer's winding is not mirrored.
void ViewFrames(double frames[6][9])
{
  const double forward[6][3] = {
    { 1, 0, 0 }, { -1, 0, 0 }, { 0, 1, 0 }, { 0, -1, 0 }, { 0, 0, 1 }, { 0, 0, -1 }
  };
  const double up[6][3] = {
    { 0, 1, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, { 0, 0, 1 }, { 0, 1, 0 }, { 0, 1, 0 }
  };
  for (int v = 0; v < 6; ++v)
  {
    const double* f = forward[v];
    const double* u = up[v];
    const double r[3] = {
      f[1] * u[2] - f[2] * u[1], f[2] * u[0] - f[0] * u[2], f[0] * u[1] - f[1] * u[0]
    };
    for (int a = 0; a < 3; ++a)
    {
      frames[v][a] = r[a];
      frames[v][3 + a] = u[a];
      frames[v][6 + a] = f[a];
    }
  }
}
/// One run of QueryUnionGPU: the pieces drawn six views at a time around each query, in
/// batches, then every answer certified (or estimated) on the CPU.
class UnionViews
{
public:
  UnionViews(HeadlessGL& context,
    const UnionClosestPoint& u,
    const std::vector<double>& queries,
    const UnionGPUSettings& settings)
    : Context(context)
    , GL(context.GL())
    , Union(u)
    , Queries(queries)
    , Settings(settings)
    , N(settings.Resolution)
    , Count(queries.size() / 3)
    , Pieces(u.Pieces.size())
    , Views(context.GL())
  {
    ViewFrames(this->Frame);
  }

  /// The program, the pieces' triangles, the views' uniforms and state.
  bool Setup(std::string& error);
  /// Per query: Far and the pieces that hold it; the queries inside and outside.
  void ClassifyQueries();
  /// The layered depth-stencil texture of a batch of queries.
  bool AllocateViews(std::string& error);
  /// Renders every batch (inside, then outside) and fills each query's image-space
  /// answer; false and `error` on a GL error or an abort.
  bool RenderAll(std::vector<UnionGPUAnswer>& answers,
    std::vector<float>* images,
    std::string& error);
  /// Certifies (or estimates) every answer, in blocks between which progress is told.
  bool FinishAll(std::vector<UnionGPUAnswer>& answers, std::string& error) const;
  const double (&ViewFrame() const)[6][9] { return this->Frame; }

private:
  void UploadPieces();
  void SetViewUniforms();
  int DrawFromOutside(GLsizei instances);
  int DrawFromInside(GLsizei instances, const std::vector<bool>& anyHolds);
  bool RenderBatch(const std::vector<size_t>& group,
    size_t begin,
    size_t size,
    bool fromInside,
    std::vector<UnionGPUAnswer>& answers,
    std::vector<float>* images,
    std::string& error);
  void ReadAnswer(size_t q,
    const float* view,
    bool fromInside,
    int passes,
    UnionGPUAnswer& result,
    std::vector<float>* images) const;
  void Finish(size_t q, UnionGPUAnswer& result) const;

  HeadlessGL& Context;
  const GLFunctions& GL;
  const UnionClosestPoint& Union;
  const std::vector<double>& Queries;
  const UnionGPUSettings& Settings;
  const int N;
  const size_t Count, Pieces;
  Objects Views; // the GL objects of the run
  double Frame[6][9];
  double Centre[3] = { 0, 0, 0 };
  std::vector<GLint> First;
  std::vector<GLsizei> VertexCount;
  GLint BiasLocation = -1, ZeroLocation = -1, PieceLocation = -1;
  std::vector<double> Far;
  std::vector<uint32_t> Contains;
  std::vector<size_t> Inside, Outside;
  size_t Batch = 1;
  std::vector<float> Depth;
};

bool UnionViews::Setup(std::string& error)
{
  const GLFunctions& gl = this->GL;
  GLint maxSize = 0;
  gl.GetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
  if (this->N > maxSize)
  {
    error = "the view resolution " + std::to_string(this->N) +
      " is above the GPU's texture limit " + std::to_string(maxSize);
    return false;
  }
  std::string log;
  this->Views.Program = this->Context.BuildProgram({ { GL_VERTEX_SHADER, UnionView_vert },
                                                     { GL_GEOMETRY_SHADER, UnionView_geom },
                                                     { GL_FRAGMENT_SHADER, UnionView_frag } },
    log);
  if (!this->Views.Program)
  {
    error = "the union view shaders did not build: " + log;
    return false;
  }
  this->UploadPieces();
  // The views: one layered depth-stencil texture array, six layers a query.
  gl.GenTextures(1, &this->Views.DepthStencil);
  this->Views.Queries.resize(this->Pieces);
  gl.GenQueries(static_cast<GLsizei>(this->Views.Queries.size()), this->Views.Queries.data());
  gl.GenBuffers(2, this->Views.Storage);
  this->SetViewUniforms();
  return true;
}

/// The pieces' triangles (each face a fan, counter-clockwise seen from outside), relative
/// to the scene's centre, in float.
void UnionViews::UploadPieces()
{
  const GLFunctions& gl = this->GL;
  double lo[3] = { HUGE_VAL, HUGE_VAL, HUGE_VAL }, hi[3] = { -HUGE_VAL, -HUGE_VAL, -HUGE_VAL };
  for (const ConvexPiece& piece : this->Union.Pieces)
  {
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = std::min(lo[a], piece.Lo[a]);
      hi[a] = std::max(hi[a], piece.Hi[a]);
    }
  }
  for (int a = 0; a < 3; ++a)
  {
    this->Centre[a] = 0.5 * (lo[a] + hi[a]);
  }
  std::vector<float> vertices;
  this->First.resize(this->Pieces);
  this->VertexCount.resize(this->Pieces);
  for (size_t i = 0; i < this->Pieces; ++i)
  {
    this->First[i] = static_cast<GLint>(vertices.size() / 3);
    for (const std::vector<double>& face : this->Union.Pieces[i].Faces)
    {
      for (size_t k = 3; k + 3 < face.size(); k += 3)
      {
        for (const size_t c : { size_t(0), k, k + 3 })
        {
          for (int a = 0; a < 3; ++a)
          {
            vertices.push_back(static_cast<float>(face[c + a] - this->Centre[a]));
          }
        }
      }
    }
    this->VertexCount[i] = static_cast<GLsizei>(vertices.size() / 3) - this->First[i];
  }
  gl.GenVertexArrays(1, &this->Views.VAO);
  gl.GenBuffers(1, &this->Views.Buffer);
  gl.BindVertexArray(this->Views.VAO);
  gl.BindBuffer(GL_ARRAY_BUFFER, this->Views.Buffer);
  gl.BufferData(GL_ARRAY_BUFFER,
    static_cast<GLsizeiptr>(vertices.size() * sizeof(float)),
    vertices.data(),
    GL_STATIC_DRAW);
  gl.EnableVertexAttribArray(0);
  gl.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
}

void UnionViews::SetViewUniforms()
{
  const GLFunctions& gl = this->GL;
  const GLuint program = this->Views.Program;
  gl.UseProgram(program);
  float views[6][9];
  for (int v = 0; v < 6; ++v)
  {
    for (int k = 0; k < 9; ++k)
    {
      // Rows: right, up, back.
      views[v][k] = static_cast<float>(k < 6 ? this->Frame[v][k] : -this->Frame[v][k]);
    }
  }
  gl.UniformMatrix3fv(gl.GetUniformLocation(program, "Views"), 6, GL_TRUE, &views[0][0]);
  this->BiasLocation = gl.GetUniformLocation(program, "Bias");
  this->ZeroLocation = gl.GetUniformLocation(program, "ZeroPass");
  this->PieceLocation = gl.GetUniformLocation(program, "Piece");
  gl.Uniform1i(gl.GetUniformLocation(program, "PieceCount"), static_cast<GLint>(this->Pieces));
  gl.Uniform1f(gl.GetUniformLocation(program, "Pixels"), static_cast<float>(this->N));
  gl.Viewport(0, 0, this->N, this->N);
  gl.Enable(GL_DEPTH_TEST);
  gl.Enable(GL_STENCIL_TEST);
  gl.Enable(GL_CULL_FACE);
  gl.Disable(GL_BLEND);
  gl.ColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
}

/// Far is the farthest corner (a convex piece's farthest point is a corner); the pieces
/// that hold O are found exactly on the CPU.
void UnionViews::ClassifyQueries()
{
  const size_t m = this->Pieces;
  this->Far.assign(this->Count, 0);
  this->Contains.assign(this->Count * m, 0);
  for (size_t q = 0; q < this->Count; ++q)
  {
    const double* o = &this->Queries[3 * q];
    bool any = false;
    for (size_t i = 0; i < m; ++i)
    {
      const ConvexPiece& piece = this->Union.Pieces[i];
      double f2 = 0;
      for (int a = 0; a < 3; ++a)
      {
        const double g = std::max(std::fabs(o[a] - piece.Lo[a]), std::fabs(piece.Hi[a] - o[a]));
        f2 += g * g;
      }
      this->Far[q] = std::max(this->Far[q], std::sqrt(f2));
      this->Contains[q * m + i] = this->Union.PieceContains(i, o) ? 1 : 0;
      any = any || this->Contains[q * m + i];
    }
    this->Far[q] = this->Far[q] * 1.001 + 1e-30;
    (any ? this->Inside : this->Outside).push_back(q);
  }
}

/// As many queries a batch as the memory and the layer limit allow.
bool UnionViews::AllocateViews(std::string& error)
{
  const GLFunctions& gl = this->GL;
  const int n = this->N;
  GLint maxLayers = 0;
  gl.GetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxLayers);
  const int64_t perQuery = int64_t(6) * n * n * 8;
  this->Batch = static_cast<size_t>(std::max<int64_t>(1,
    std::min<int64_t>(
      { this->Settings.BatchBytes / perQuery, maxLayers / 6, int64_t(this->Count) })));
  gl.BindTexture(GL_TEXTURE_2D_ARRAY, this->Views.DepthStencil);
  gl.TexStorage3D(
    GL_TEXTURE_2D_ARRAY, 1, GL_DEPTH32F_STENCIL8, n, n, static_cast<GLsizei>(6 * this->Batch));
  gl.GenFramebuffers(1, &this->Views.FBO);
  gl.BindFramebuffer(GL_FRAMEBUFFER, this->Views.FBO);
  gl.FramebufferTexture(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, this->Views.DepthStencil, 0);
  gl.DrawBuffer(GL_NONE);
  gl.ReadBuffer(GL_NONE);
  if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
  {
    error = "the layered depth-stencil framebuffer of the union views is incomplete";
    return false;
  }
  this->Depth.resize(static_cast<size_t>(n) * n * 6 * this->Batch);
  return true;
}

bool UnionViews::RenderAll(std::vector<UnionGPUAnswer>& answers,
  std::vector<float>* images,
  std::string& error)
{
  size_t rendered = 0;
  for (const bool fromInside : { true, false })
  {
    const std::vector<size_t>& group = fromInside ? this->Inside : this->Outside;
    for (size_t begin = 0; begin < group.size(); begin += this->Batch)
    {
      const size_t size = std::min(this->Batch, group.size() - begin);
      if (!this->RenderBatch(group, begin, size, fromInside, answers, images, error))
      {
        return false;
      }
      rendered += size;
      if (this->Settings.Progress &&
        !this->Settings.Progress(0.5 * rendered / std::max<size_t>(1, this->Count)))
      {
        error = "aborted";
        return false;
      }
    }
  }
  return true;
}

/// The nearest surface: front faces, less test.
int UnionViews::DrawFromOutside(GLsizei instances)
{
  const GLFunctions& gl = this->GL;
  gl.CullFace(GL_BACK);
  gl.DepthFunc(GL_LESS);
  gl.StencilFunc(GL_ALWAYS, 0, 0xff);
  gl.StencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
  for (size_t i = 0; i < this->Pieces; ++i)
  {
    gl.DrawArraysInstanced(GL_TRIANGLES, this->First[i], this->VertexCount[i], instances);
  }
  return 1;
}

/// The boundary of the union from inside: the zero hops, then the rounds of windows;
/// returns the rounds drawn.
int UnionViews::DrawFromInside(GLsizei instances, const std::vector<bool>& anyHolds)
{
  const GLFunctions& gl = this->GL;
  const size_t m = this->Pieces;
  // Zero hops: each piece's back faces, once, for the queries whose O it holds.
  gl.CullFace(GL_FRONT);
  gl.DepthFunc(GL_GREATER);
  gl.StencilFunc(GL_ALWAYS, 0, 0xff);
  gl.StencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
  gl.Uniform1i(this->ZeroLocation, 1);
  for (size_t i = 0; i < m; ++i)
  {
    if (anyHolds[i])
    {
      gl.Uniform1i(this->PieceLocation, static_cast<GLint>(i));
      gl.DrawArraysInstanced(GL_TRIANGLES, this->First[i], this->VertexCount[i], instances);
    }
  }
  gl.Uniform1i(this->ZeroLocation, 0);
  // Then every piece, round after round, until a round changes nothing. (A piece that
  // holds a query's O shows that query no front face: it opens no window.)
  int passes = 0;
  for (size_t round = 0; round < m + 1; ++round)
  {
    for (size_t i = 0; i < m; ++i)
    {
      // Front faces that pierce or touch the boundary open the window (stencil 1).
      gl.DepthMask(GL_FALSE);
      gl.CullFace(GL_BACK);
      gl.DepthFunc(GL_LEQUAL);
      gl.Uniform1f(this->BiasLocation, static_cast<float>(this->Settings.TouchBias));
      gl.StencilFunc(GL_ALWAYS, 1, 0xff);
      gl.StencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
      gl.DrawArraysInstanced(GL_TRIANGLES, this->First[i], this->VertexCount[i], instances);
      // Back faces in the window, greater test; every back-face fragment closes it.
      gl.DepthMask(GL_TRUE);
      gl.CullFace(GL_FRONT);
      gl.DepthFunc(GL_GREATER);
      gl.Uniform1f(this->BiasLocation, 0.0f);
      gl.StencilFunc(GL_EQUAL, 1, 0xff);
      gl.StencilOp(GL_KEEP, GL_ZERO, GL_ZERO);
      gl.BeginQuery(GL_ANY_SAMPLES_PASSED, this->Views.Queries[i]);
      gl.DrawArraysInstanced(GL_TRIANGLES, this->First[i], this->VertexCount[i], instances);
      gl.EndQuery(GL_ANY_SAMPLES_PASSED);
    }
    ++passes;
    bool changed = false;
    for (size_t i = 0; i < m; ++i)
    {
      GLuint64 passed = 0;
      gl.GetQueryObjectui64v(this->Views.Queries[i], GL_QUERY_RESULT, &passed);
      changed = changed || passed != 0;
    }
    if (!changed)
    {
      break;
    }
  }
  return passes;
}

bool UnionViews::RenderBatch(const std::vector<size_t>& group,
  size_t begin,
  size_t size,
  bool fromInside,
  std::vector<UnionGPUAnswer>& answers,
  std::vector<float>* images,
  std::string& error)
{
  const GLFunctions& gl = this->GL;
  const size_t m = this->Pieces;
  const int n = this->N;
  const GLsizei instances = static_cast<GLsizei>(size);
  std::vector<float> block(4 * size);
  std::vector<uint32_t> held(size * m);
  std::vector<bool> anyHolds(m, false);
  for (size_t k = 0; k < size; ++k)
  {
    const size_t q = group[begin + k];
    for (int a = 0; a < 3; ++a)
    {
      block[4 * k + a] = static_cast<float>(this->Queries[3 * q + a] - this->Centre[a]);
    }
    block[4 * k + 3] = static_cast<float>(this->Far[q]);
    for (size_t i = 0; i < m; ++i)
    {
      held[k * m + i] = this->Contains[q * m + i];
      anyHolds[i] = anyHolds[i] || this->Contains[q * m + i];
    }
  }
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, this->Views.Storage[0]);
  gl.BufferData(GL_SHADER_STORAGE_BUFFER,
    static_cast<GLsizeiptr>(block.size() * sizeof(float)),
    block.data(),
    GL_DYNAMIC_DRAW);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, this->Views.Storage[1]);
  gl.BufferData(GL_SHADER_STORAGE_BUFFER,
    static_cast<GLsizeiptr>(held.size() * sizeof(uint32_t)),
    held.data(),
    GL_DYNAMIC_DRAW);
  gl.Uniform1f(this->BiasLocation, 0.0f);
  gl.Uniform1i(this->ZeroLocation, 0);
  gl.DepthMask(GL_TRUE);
  gl.ClearBufferfi(GL_DEPTH_STENCIL, 0, fromInside ? 0.0f : 1.0f, 0);
  const int passes =
    fromInside ? this->DrawFromInside(instances, anyHolds) : this->DrawFromOutside(instances);
  const size_t values = static_cast<size_t>(n) * n * 6 * size;
  gl.GetTextureSubImage(this->Views.DepthStencil,
    0,
    0,
    0,
    0,
    n,
    n,
    static_cast<GLsizei>(6 * size),
    GL_DEPTH_COMPONENT,
    GL_FLOAT,
    static_cast<GLsizei>(values * sizeof(float)),
    this->Depth.data());
  if (!NoGLError(gl, "in the union views", error))
  {
    return false;
  }
  for (size_t k = 0; k < size; ++k)
  {
    const size_t q = group[begin + k];
    this->ReadAnswer(
      q, &this->Depth[k * static_cast<size_t>(n) * n * 6], fromInside, passes, answers[q], images);
  }
  return true;
}

/// A query's smallest distance in its six views: a boundary point, U.
void UnionViews::ReadAnswer(size_t q,
  const float* view,
  bool fromInside,
  int passes,
  UnionGPUAnswer& result,
  std::vector<float>* images) const
{
  const int n = this->N;
  const double far = this->Far[q];
  const size_t pixels = static_cast<size_t>(n) * n * 6;
  double best = HUGE_VAL;
  size_t at = 0;
  for (size_t p = 0; p < pixels; ++p)
  {
    const bool seen = fromInside || view[p] < 1.0f;
    if (seen && view[p] * far < best)
    {
      best = view[p] * far;
      at = p;
    }
  }
  result.Passes = passes;
  result.Estimate = best;
  const int v = static_cast<int>(at / (static_cast<size_t>(n) * n));
  const int row = static_cast<int>(at / n % n), column = static_cast<int>(at % n);
  const double x = 2.0 * (column + 0.5) / n - 1, y = 2.0 * (row + 0.5) / n - 1;
  double direction[3], length2 = 0;
  for (int a = 0; a < 3; ++a)
  {
    direction[a] = x * this->Frame[v][a] + y * this->Frame[v][3 + a] + this->Frame[v][6 + a];
    length2 += direction[a] * direction[a];
  }
  UnionAnswer& a = result.Answer;
  a.Inside = fromInside;
  a.Distance = fromInside ? -best : best;
  for (int c = 0; c < 3; ++c)
  {
    a.Closest[c] = this->Queries[3 * q + c] + best * direction[c] / std::sqrt(length2);
  }
  if (images && q + 1 == this->Count)
  {
    images->resize(pixels);
    for (size_t p = 0; p < pixels; ++p)
    {
      (*images)[p] = !fromInside && view[p] >= 1.0f ? std::numeric_limits<float>::quiet_NaN()
                                                    : static_cast<float>(view[p] * far);
    }
  }
}

/// Certification (exact), or the image-space answer.
void UnionViews::Finish(size_t q, UnionGPUAnswer& result) const
{
  const UnionClosestPoint& u = this->Union;
  const double* o = &this->Queries[3 * q];
  const double best = result.Estimate;
  if (this->Settings.Certify || best == HUGE_VAL)
  {
    // The exact search of the faces nearer than U (slightly above, for the float depth);
    // the full search when U was not above the answer.
    const double seed = best == HUGE_VAL ? HUGE_VAL : best * (1 + 1e-5) + 10 * u.Tolerance;
    result.Answer = u.Query(o, seed);
    if (result.Answer.Piece < 0)
    {
      const int64_t visited = result.Answer.FacesVisited;
      result.Answer = u.Query(o);
      result.Answer.FacesVisited += visited;
    }
    result.Certified = true;
    result.ErrorBound = 0;
    return;
  }
  // Image space only: U's point, in the piece whose face holds it (the face plane nearest
  // the point), and what a pixel's angle can hide: the true closest point's direction is
  // within half a pixel's diagonal of a pixel centre, and a boundary point at distance U
  // that far off the ray is U tan(alpha) away (a face across the ray gives far less, a
  // crease in the union about that much; a gap of free space narrower than a pixel,
  // anything).
  UnionAnswer& a = result.Answer;
  double nearest = HUGE_VAL;
  for (size_t i = 0; i < this->Pieces; ++i)
  {
    const ConvexPiece& piece = u.Pieces[i];
    double worst = -HUGE_VAL;
    for (size_t f = 0; f < piece.Faces.size(); ++f)
    {
      const double* plane = &piece.Planes[4 * f];
      worst = std::max(worst,
        plane[0] * a.Closest[0] + plane[1] * a.Closest[1] + plane[2] * a.Closest[2] - plane[3]);
    }
    if (std::fabs(worst) < nearest)
    {
      nearest = std::fabs(worst);
      a.Piece = static_cast<int64_t>(i);
    }
  }
  result.ErrorBound = best * std::sqrt(2.0) / this->N + this->Far[q] * 1e-6;
  result.Certified = false;
}

/// Over the queries in parallel (Settings.For), in blocks of 64 between which progress is
/// told.
bool UnionViews::FinishAll(std::vector<UnionGPUAnswer>& answers, std::string& error) const
{
  const int64_t count = static_cast<int64_t>(this->Count);
  auto finish = [&](int64_t begin, int64_t end)
  {
    for (int64_t q = begin; q < end; ++q)
    {
      this->Finish(static_cast<size_t>(q), answers[q]);
    }
  };
  const int64_t block = 64;
  for (int64_t begin = 0; begin < count; begin += block)
  {
    const int64_t end = std::min<int64_t>(count, begin + block);
    if (this->Settings.For)
    {
      this->Settings.For(
        end - begin, 1, [&](int64_t b, int64_t e) { finish(begin + b, begin + e); });
    }
    else
    {
      finish(begin, end);
    }
    if (this->Settings.Progress && !this->Settings.Progress(0.5 + 0.5 * end / count))
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
  std::string& error,
  std::vector<float>* images,
  std::vector<double>* frames)
{
  const int n = settings.Resolution;
  if (n < 8 || n > 8192)
  {
    error = "the view resolution must be 8 to 8192 pixels a side";
    return false;
  }
  HeadlessGL::Scope scope(context);
  if (!scope.Ok(error))
  {
    return false;
  }
  UnionViews views(context, u, queries, settings);
  answers.assign(queries.size() / 3, UnionGPUAnswer());
  if (!views.Setup(error))
  {
    return false;
  }
  views.ClassifyQueries();
  if (!views.AllocateViews(error) || !views.RenderAll(answers, images, error) ||
    !views.FinishAll(answers, error))
  {
    return false;
  }
  if (frames)
  {
    frames->assign(&views.ViewFrame()[0][0], &views.ViewFrame()[0][0] + 54);
  }
  return NoGLError(context.GL(), "after the union views", error);
}

} // namespace vtkdf
