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
  const GLFunctions& gl = context.GL();
  GLint maxSize = 0;
  gl.GetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
  if (n > maxSize)
  {
    error = "the view resolution " + std::to_string(n) + " is above the GPU's texture limit " +
      std::to_string(maxSize);
    return false;
  }
  Objects objects(gl);
  std::string log;
  objects.Program = context.BuildProgram({ { GL_VERTEX_SHADER, UnionView_vert },
                                           { GL_GEOMETRY_SHADER, UnionView_geom },
                                           { GL_FRAGMENT_SHADER, UnionView_frag } },
    log);
  if (!objects.Program)
  {
    error = "the union view shaders did not build: " + log;
    return false;
  }

  // The pieces' triangles (each face a fan, counter-clockwise seen from outside),
  // relative to the scene's centre, in float.
  double lo[3] = { HUGE_VAL, HUGE_VAL, HUGE_VAL }, hi[3] = { -HUGE_VAL, -HUGE_VAL, -HUGE_VAL };
  for (const ConvexPiece& piece : u.Pieces)
  {
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = std::min(lo[a], piece.Lo[a]);
      hi[a] = std::max(hi[a], piece.Hi[a]);
    }
  }
  const double centre[3] = { 0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2]) };
  std::vector<float> vertices;
  std::vector<GLint> first(u.Pieces.size());
  std::vector<GLsizei> vertexCount(u.Pieces.size());
  for (size_t i = 0; i < u.Pieces.size(); ++i)
  {
    first[i] = static_cast<GLint>(vertices.size() / 3);
    for (const std::vector<double>& face : u.Pieces[i].Faces)
    {
      for (size_t k = 3; k + 3 < face.size(); k += 3)
      {
        for (const size_t c : { size_t(0), k, k + 3 })
        {
          for (int a = 0; a < 3; ++a)
          {
            vertices.push_back(static_cast<float>(face[c + a] - centre[a]));
          }
        }
      }
    }
    vertexCount[i] = static_cast<GLsizei>(vertices.size() / 3) - first[i];
  }
  gl.GenVertexArrays(1, &objects.VAO);
  gl.GenBuffers(1, &objects.Buffer);
  gl.BindVertexArray(objects.VAO);
  gl.BindBuffer(GL_ARRAY_BUFFER, objects.Buffer);
  gl.BufferData(GL_ARRAY_BUFFER,
    static_cast<GLsizeiptr>(vertices.size() * sizeof(float)),
    vertices.data(),
    GL_STATIC_DRAW);
  gl.EnableVertexAttribArray(0);
  gl.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);

  // The views: one layered depth-stencil texture array, six layers a query.
  gl.GenTextures(1, &objects.DepthStencil);
  objects.Queries.resize(u.Pieces.size());
  gl.GenQueries(static_cast<GLsizei>(objects.Queries.size()), objects.Queries.data());
  gl.GenBuffers(2, objects.Storage);

  gl.UseProgram(objects.Program);
  double frame[6][9];
  ViewFrames(frame);
  float views[6][9];
  for (int v = 0; v < 6; ++v)
  {
    for (int k = 0; k < 9; ++k)
    {
      views[v][k] = static_cast<float>(k < 6 ? frame[v][k] : -frame[v][k]); // rows: right, up, back
    }
  }
  gl.UniformMatrix3fv(gl.GetUniformLocation(objects.Program, "Views"), 6, GL_TRUE, &views[0][0]);
  const GLint biasLocation = gl.GetUniformLocation(objects.Program, "Bias");
  const GLint zeroLocation = gl.GetUniformLocation(objects.Program, "ZeroPass");
  const GLint pieceLocation = gl.GetUniformLocation(objects.Program, "Piece");
  gl.Uniform1i(
    gl.GetUniformLocation(objects.Program, "PieceCount"), static_cast<GLint>(u.Pieces.size()));
  gl.Viewport(0, 0, n, n);
  gl.Enable(GL_DEPTH_TEST);
  gl.Enable(GL_STENCIL_TEST);
  gl.Enable(GL_CULL_FACE);
  gl.Disable(GL_BLEND);
  gl.ColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);

  // Per query: Far (the farthest corner: a convex piece's farthest point is a corner) and
  // the pieces that hold O, found exactly on the CPU.
  const size_t count = queries.size() / 3;
  const size_t m = u.Pieces.size();
  answers.assign(count, UnionGPUAnswer());
  std::vector<double> far(count);
  std::vector<uint32_t> contains(count * m);
  std::vector<size_t> inside, outside;
  for (size_t q = 0; q < count; ++q)
  {
    const double* o = &queries[3 * q];
    bool any = false;
    for (size_t i = 0; i < m; ++i)
    {
      const ConvexPiece& piece = u.Pieces[i];
      double f2 = 0;
      for (int a = 0; a < 3; ++a)
      {
        const double g = std::max(std::fabs(o[a] - piece.Lo[a]), std::fabs(piece.Hi[a] - o[a]));
        f2 += g * g;
      }
      far[q] = std::max(far[q], std::sqrt(f2));
      contains[q * m + i] = u.PieceContains(i, o) ? 1 : 0;
      any = any || contains[q * m + i];
    }
    far[q] = far[q] * 1.001 + 1e-30;
    (any ? inside : outside).push_back(q);
  }

  // The batches: as many queries as the memory and the layer limit allow.
  GLint maxLayers = 0;
  gl.GetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &maxLayers);
  const int64_t perQuery = int64_t(6) * n * n * 8;
  const size_t batch = static_cast<size_t>(std::max<int64_t>(
    1, std::min<int64_t>({ settings.BatchBytes / perQuery, maxLayers / 6, int64_t(count) })));
  gl.BindTexture(GL_TEXTURE_2D_ARRAY, objects.DepthStencil);
  gl.TexStorage3D(
    GL_TEXTURE_2D_ARRAY, 1, GL_DEPTH32F_STENCIL8, n, n, static_cast<GLsizei>(6 * batch));
  gl.GenFramebuffers(1, &objects.FBO);
  gl.BindFramebuffer(GL_FRAMEBUFFER, objects.FBO);
  gl.FramebufferTexture(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, objects.DepthStencil, 0);
  gl.DrawBuffer(GL_NONE);
  gl.ReadBuffer(GL_NONE);
  if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
  {
    error = "the layered depth-stencil framebuffer of the union views is incomplete";
    return false;
  }

  std::vector<float> depth(static_cast<size_t>(n) * n * 6 * batch);
  size_t rendered = 0;
  for (const bool fromInside : { true, false })
  {
    const std::vector<size_t>& group = fromInside ? inside : outside;
    for (size_t begin = 0; begin < group.size(); begin += batch)
    {
      const size_t size = std::min(batch, group.size() - begin);
      const GLsizei instances = static_cast<GLsizei>(size);
      std::vector<float> block(4 * size);
      std::vector<uint32_t> held(size * m);
      std::vector<bool> anyHolds(m, false);
      for (size_t k = 0; k < size; ++k)
      {
        const size_t q = group[begin + k];
        for (int a = 0; a < 3; ++a)
        {
          block[4 * k + a] = static_cast<float>(queries[3 * q + a] - centre[a]);
        }
        block[4 * k + 3] = static_cast<float>(far[q]);
        for (size_t i = 0; i < m; ++i)
        {
          held[k * m + i] = contains[q * m + i];
          anyHolds[i] = anyHolds[i] || contains[q * m + i];
        }
      }
      gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, objects.Storage[0]);
      gl.BufferData(GL_SHADER_STORAGE_BUFFER,
        static_cast<GLsizeiptr>(block.size() * sizeof(float)),
        block.data(),
        GL_DYNAMIC_DRAW);
      gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, objects.Storage[1]);
      gl.BufferData(GL_SHADER_STORAGE_BUFFER,
        static_cast<GLsizeiptr>(held.size() * sizeof(uint32_t)),
        held.data(),
        GL_DYNAMIC_DRAW);
      gl.Uniform1f(biasLocation, 0.0f);
      gl.Uniform1i(zeroLocation, 0);
      gl.DepthMask(GL_TRUE);
      gl.ClearBufferfi(GL_DEPTH_STENCIL, 0, fromInside ? 0.0f : 1.0f, 0);
      int passes = 0;
      if (!fromInside)
      {
        // The nearest surface: front faces, less test.
        gl.CullFace(GL_BACK);
        gl.DepthFunc(GL_LESS);
        gl.StencilFunc(GL_ALWAYS, 0, 0xff);
        gl.StencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
        for (size_t i = 0; i < m; ++i)
        {
          gl.DrawArraysInstanced(GL_TRIANGLES, first[i], vertexCount[i], instances);
        }
        passes = 1;
      }
      else
      {
        // Zero hops: each piece's back faces, once, for the queries whose O it holds.
        gl.CullFace(GL_FRONT);
        gl.DepthFunc(GL_GREATER);
        gl.StencilFunc(GL_ALWAYS, 0, 0xff);
        gl.StencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
        gl.Uniform1i(zeroLocation, 1);
        for (size_t i = 0; i < m; ++i)
        {
          if (anyHolds[i])
          {
            gl.Uniform1i(pieceLocation, static_cast<GLint>(i));
            gl.DrawArraysInstanced(GL_TRIANGLES, first[i], vertexCount[i], instances);
          }
        }
        gl.Uniform1i(zeroLocation, 0);
        // Then every piece, round after round, until a round changes nothing. (A piece
        // that holds a query's O shows that query no front face: it opens no window.)
        for (size_t round = 0; round < m + 1; ++round)
        {
          for (size_t i = 0; i < m; ++i)
          {
            // Front faces that pierce or touch the boundary open the window (stencil 1).
            gl.DepthMask(GL_FALSE);
            gl.CullFace(GL_BACK);
            gl.DepthFunc(GL_LEQUAL);
            gl.Uniform1f(biasLocation, static_cast<float>(settings.TouchBias));
            gl.StencilFunc(GL_ALWAYS, 1, 0xff);
            gl.StencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
            gl.DrawArraysInstanced(GL_TRIANGLES, first[i], vertexCount[i], instances);
            // Back faces in the window, greater test; every back-face fragment closes it.
            gl.DepthMask(GL_TRUE);
            gl.CullFace(GL_FRONT);
            gl.DepthFunc(GL_GREATER);
            gl.Uniform1f(biasLocation, 0.0f);
            gl.StencilFunc(GL_EQUAL, 1, 0xff);
            gl.StencilOp(GL_KEEP, GL_ZERO, GL_ZERO);
            gl.BeginQuery(GL_ANY_SAMPLES_PASSED, objects.Queries[i]);
            gl.DrawArraysInstanced(GL_TRIANGLES, first[i], vertexCount[i], instances);
            gl.EndQuery(GL_ANY_SAMPLES_PASSED);
          }
          ++passes;
          bool changed = false;
          for (size_t i = 0; i < m; ++i)
          {
            GLuint64 passed = 0;
            gl.GetQueryObjectui64v(objects.Queries[i], GL_QUERY_RESULT, &passed);
            changed = changed || passed != 0;
          }
          if (!changed)
          {
            break;
          }
        }
      }
      const size_t values = static_cast<size_t>(n) * n * 6 * size;
      gl.GetTextureSubImage(objects.DepthStencil,
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
        depth.data());
      if (!NoGLError(gl, "in the union views", error))
      {
        return false;
      }

      // Per query, the smallest distance: a boundary point, U.
      for (size_t k = 0; k < size; ++k)
      {
        const size_t q = group[begin + k];
        const float* view = &depth[k * static_cast<size_t>(n) * n * 6];
        const size_t pixels = static_cast<size_t>(n) * n * 6;
        double best = HUGE_VAL;
        size_t at = 0;
        for (size_t p = 0; p < pixels; ++p)
        {
          const bool seen = fromInside || view[p] < 1.0f;
          if (seen && view[p] * far[q] < best)
          {
            best = view[p] * far[q];
            at = p;
          }
        }
        UnionGPUAnswer& result = answers[q];
        result.Passes = passes;
        result.Estimate = best;
        const int v = static_cast<int>(at / (static_cast<size_t>(n) * n));
        const int row = static_cast<int>(at / n % n), column = static_cast<int>(at % n);
        const double x = 2.0 * (column + 0.5) / n - 1, y = 2.0 * (row + 0.5) / n - 1;
        double direction[3], length2 = 0;
        for (int a = 0; a < 3; ++a)
        {
          direction[a] = x * frame[v][a] + y * frame[v][3 + a] + frame[v][6 + a];
          length2 += direction[a] * direction[a];
        }
        UnionAnswer& a = result.Answer;
        a.Inside = fromInside;
        a.Distance = fromInside ? -best : best;
        for (int c = 0; c < 3; ++c)
        {
          a.Closest[c] = queries[3 * q + c] + best * direction[c] / std::sqrt(length2);
        }
        if (images && q + 1 == count)
        {
          images->resize(pixels);
          for (size_t p = 0; p < pixels; ++p)
          {
            (*images)[p] = !fromInside && view[p] >= 1.0f ? std::numeric_limits<float>::quiet_NaN()
                                                          : static_cast<float>(view[p] * far[q]);
          }
        }
      }
      rendered += size;
      if (settings.Progress && !settings.Progress(0.5 * rendered / std::max<size_t>(1, count)))
      {
        error = "aborted";
        return false;
      }
    }
  }

  // Certification (exact, over the queries in parallel), or the image-space answer, in
  // blocks of queries between which progress is told.
  auto finish = [&](int64_t begin, int64_t end)
  {
    for (int64_t q = begin; q < end; ++q)
    {
      UnionGPUAnswer& result = answers[q];
      const double* o = &queries[3 * q];
      const double best = result.Estimate;
      if (settings.Certify || best == HUGE_VAL)
      {
        // The exact search of the faces nearer than U (slightly above, for the float
        // depth); the full search when U was not above the answer.
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
        continue;
      }
      // Image space only: U's point, in the piece whose face holds it (the face plane
      // nearest the point), and what a pixel's angle can hide: the true closest point's
      // direction is within half a pixel's diagonal of a pixel centre, and a boundary
      // point at distance U that far off the ray is U tan(alpha) away (a face across the
      // ray gives far less, a crease in the union about that much; a gap of free space
      // narrower than a pixel, anything).
      UnionAnswer& a = result.Answer;
      double nearest = HUGE_VAL;
      for (size_t i = 0; i < m; ++i)
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
      result.ErrorBound = best * std::sqrt(2.0) / n + far[q] * 1e-6;
      result.Certified = false;
    }
  };
  const int64_t block = 64;
  for (int64_t begin = 0; begin < static_cast<int64_t>(count); begin += block)
  {
    const int64_t end = std::min<int64_t>(count, begin + block);
    if (settings.For)
    {
      settings.For(end - begin, 1, [&](int64_t b, int64_t e) { finish(begin + b, begin + e); });
    }
    else
    {
      finish(begin, end);
    }
    if (settings.Progress && !settings.Progress(0.5 + 0.5 * end / count))
    {
      error = "aborted";
      return false;
    }
  }
  if (frames)
  {
    frames->assign(&frame[0][0], &frame[0][0] + 54);
  }
  return NoGLError(gl, "after the union views", error);
}

} // namespace vtkdf
