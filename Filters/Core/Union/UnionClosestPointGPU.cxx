#include "UnionClosestPointGPU.h"

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
    this->GL.DeleteBuffers(1, &this->Buffer);
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
  std::vector<GLsizei> count(u.Pieces.size());
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
    count[i] = static_cast<GLsizei>(vertices.size() / 3) - first[i];
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

  // The six views: one depth-stencil texture array, layered.
  gl.GenTextures(1, &objects.DepthStencil);
  gl.BindTexture(GL_TEXTURE_2D_ARRAY, objects.DepthStencil);
  gl.TexStorage3D(GL_TEXTURE_2D_ARRAY, 1, GL_DEPTH32F_STENCIL8, n, n, 6);
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
  objects.Queries.resize(u.Pieces.size());
  gl.GenQueries(static_cast<GLsizei>(objects.Queries.size()), objects.Queries.data());

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
  const GLint queryLocation = gl.GetUniformLocation(objects.Program, "Query");
  const GLint nearLocation = gl.GetUniformLocation(objects.Program, "Near");
  const GLint farLocation = gl.GetUniformLocation(objects.Program, "Far");
  const GLint biasLocation = gl.GetUniformLocation(objects.Program, "Bias");
  gl.Viewport(0, 0, n, n);
  gl.Enable(GL_DEPTH_TEST);
  gl.Enable(GL_STENCIL_TEST);
  gl.Enable(GL_CULL_FACE);
  gl.Disable(GL_BLEND);
  gl.ColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);

  std::vector<float> depth(static_cast<size_t>(n) * n * 6);
  answers.assign(queries.size() / 3, UnionGPUAnswer());
  for (size_t q = 0; q < answers.size(); ++q)
  {
    const double* o = &queries[3 * q];
    UnionGPUAnswer& result = answers[q];
    // Far: the farthest corner (a convex piece's farthest point is a corner).
    double far = 0;
    std::vector<size_t> containing, others;
    for (size_t i = 0; i < u.Pieces.size(); ++i)
    {
      const ConvexPiece& piece = u.Pieces[i];
      double f2 = 0;
      for (int a = 0; a < 3; ++a)
      {
        const double g = std::max(std::fabs(o[a] - piece.Lo[a]), std::fabs(piece.Hi[a] - o[a]));
        f2 += g * g;
      }
      far = std::max(far, std::sqrt(f2));
      (u.PieceContains(i, o) ? containing : others).push_back(i);
    }
    far = far * 1.001 + 1e-30;
    const bool inside = !containing.empty();
    gl.Uniform3f(queryLocation,
      static_cast<float>(o[0] - centre[0]),
      static_cast<float>(o[1] - centre[1]),
      static_cast<float>(o[2] - centre[2]));
    gl.Uniform1f(nearLocation, static_cast<float>(far * 1e-7));
    gl.Uniform1f(farLocation, static_cast<float>(far));
    gl.Uniform1f(biasLocation, 0.0f);
    gl.DepthMask(GL_TRUE);
    gl.ClearBufferfi(GL_DEPTH_STENCIL, 0, inside ? 0.0f : 1.0f, 0);
    if (!inside)
    {
      // The nearest surface: front faces, less test.
      gl.CullFace(GL_BACK);
      gl.DepthFunc(GL_LESS);
      gl.StencilFunc(GL_ALWAYS, 0, 0xff);
      gl.StencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
      for (size_t i = 0; i < u.Pieces.size(); ++i)
      {
        gl.DrawArrays(GL_TRIANGLES, first[i], count[i]);
      }
      result.Passes = 1;
    }
    else
    {
      // Zero hops: the pieces holding O, their back faces once, greater test.
      gl.CullFace(GL_FRONT);
      gl.DepthFunc(GL_GREATER);
      gl.StencilFunc(GL_ALWAYS, 0, 0xff);
      gl.StencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
      for (size_t i : containing)
      {
        gl.DrawArrays(GL_TRIANGLES, first[i], count[i]);
      }
      // Then the others, round after round, until a round changes nothing.
      const size_t rounds = others.size() + 1;
      for (size_t round = 0; round < rounds && !others.empty(); ++round)
      {
        for (size_t k = 0; k < others.size(); ++k)
        {
          const size_t i = others[k];
          // Front faces that pierce or touch the boundary open the window (stencil 1).
          gl.DepthMask(GL_FALSE);
          gl.CullFace(GL_BACK);
          gl.DepthFunc(GL_LEQUAL);
          gl.Uniform1f(biasLocation, static_cast<float>(settings.TouchBias));
          gl.StencilFunc(GL_ALWAYS, 1, 0xff);
          gl.StencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
          gl.DrawArrays(GL_TRIANGLES, first[i], count[i]);
          // Back faces in the window, greater test; every back-face fragment closes it.
          gl.DepthMask(GL_TRUE);
          gl.CullFace(GL_FRONT);
          gl.DepthFunc(GL_GREATER);
          gl.Uniform1f(biasLocation, 0.0f);
          gl.StencilFunc(GL_EQUAL, 1, 0xff);
          gl.StencilOp(GL_KEEP, GL_ZERO, GL_ZERO);
          gl.BeginQuery(GL_ANY_SAMPLES_PASSED, objects.Queries[k]);
          gl.DrawArrays(GL_TRIANGLES, first[i], count[i]);
          gl.EndQuery(GL_ANY_SAMPLES_PASSED);
        }
        ++result.Passes;
        bool changed = false;
        for (size_t k = 0; k < others.size(); ++k)
        {
          GLuint64 passed = 0;
          gl.GetQueryObjectui64v(objects.Queries[k], GL_QUERY_RESULT, &passed);
          changed = changed || passed != 0;
        }
        if (!changed)
        {
          break;
        }
      }
    }
    gl.GetTextureImage(objects.DepthStencil,
      0,
      GL_DEPTH_COMPONENT,
      GL_FLOAT,
      static_cast<GLsizei>(depth.size() * sizeof(float)),
      depth.data());
    if (!NoGLError(gl, "in the union views", error))
    {
      return false;
    }

    // The smallest distance: a boundary point, U.
    double best = HUGE_VAL;
    size_t at = 0;
    for (size_t p = 0; p < depth.size(); ++p)
    {
      const bool seen = inside ? true : depth[p] < 1.0f;
      if (seen && depth[p] * far < best)
      {
        best = depth[p] * far;
        at = p;
      }
    }
    const int view = static_cast<int>(at / (static_cast<size_t>(n) * n));
    const int row = static_cast<int>(at / n % n), column = static_cast<int>(at % n);
    const double x = 2.0 * (column + 0.5) / n - 1, y = 2.0 * (row + 0.5) / n - 1;
    double direction[3], length2 = 0;
    for (int a = 0; a < 3; ++a)
    {
      direction[a] = x * frame[view][a] + y * frame[view][3 + a] + frame[view][6 + a];
      length2 += direction[a] * direction[a];
    }
    result.Estimate = best;
    if (images && q + 1 == answers.size())
    {
      images->resize(depth.size());
      for (size_t p = 0; p < depth.size(); ++p)
      {
        (*images)[p] = !inside && depth[p] >= 1.0f ? std::numeric_limits<float>::quiet_NaN()
                                                   : static_cast<float>(depth[p] * far);
      }
    }
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
    // Image space only: the pixel's point, and what a pixel's angle can hide: the true
    // closest point's direction is within half a pixel's diagonal of a pixel centre, and
    // a boundary point at distance U that far off the ray is U tan(alpha) away (a face
    // across the ray gives far less, a crease in the union about that much; a gap of
    // free space narrower than a pixel, anything).
    UnionAnswer& a = result.Answer;
    a.Inside = inside;
    a.Distance = inside ? -best : best;
    for (int c = 0; c < 3; ++c)
    {
      a.Closest[c] = o[c] + best * direction[c] / std::sqrt(length2);
    }
    double nearest = HUGE_VAL;
    for (size_t i = 0; i < u.Pieces.size(); ++i)
    {
      // The piece whose face holds the point: the nearest face plane among the pieces.
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
    result.ErrorBound = best * std::sqrt(2.0) / n + far * 1e-6;
    result.Certified = false;
  }
  if (frames)
  {
    frames->assign(&frame[0][0], &frame[0][0] + 54);
  }
  gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
  gl.BindVertexArray(0);
  gl.UseProgram(0);
  gl.Disable(GL_STENCIL_TEST);
  gl.Disable(GL_CULL_FACE);
  gl.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  gl.DepthMask(GL_TRUE);
  return NoGLError(gl, "after the union views", error);
}

} // namespace vtkdf
