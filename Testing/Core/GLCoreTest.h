// GLCoreTest: the GL context of the cores' GPU tests, or why there is none.
#ifndef vtkdf_GLCoreTest_h
#define vtkdf_GLCoreTest_h

#include "GL/GLFunctions.h"
#include "GL/HeadlessGL.h"

#include <cstdint>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

namespace vtkdf::coretest
{
/// The headless context, its renderer printed; nullptr, with "FAIL: " and the reason
/// printed, when none can be created (the test then ends with status 1).
inline vtkdf::HeadlessGL* GLContext()
{
  std::string error;
  vtkdf::HeadlessGL* gl = vtkdf::HeadlessGL::Get(error);
  if (!gl)
  {
    std::printf("FAIL: no OpenGL 4.5 context: %s\n", error.c_str());
    return nullptr;
  }
  std::printf("renderer: %s (%s)\n", gl->Renderer().c_str(), gl->Platform().c_str());
  return gl;
}

/// Runs compute shader `source` (64 invocations a group) once per item: `inputs` bound at
/// 0, `results` (resized to `count` times `resultsPerItem` doubles) at 1, the uniform
/// Count set to `count`, and `uniforms` called with the program in use. False, with
/// "FAIL: " and the reason printed, when GL fails.
inline bool RunDoubleShader(vtkdf::HeadlessGL& context,
  const std::string& source,
  const std::vector<double>& inputs,
  int count,
  int resultsPerItem,
  std::vector<double>& results,
  const std::function<void(const vtkdf::GLFunctions&, GLuint)>& uniforms = {})
{
  vtkdf::HeadlessGL::Scope scope(context);
  std::string error;
  if (!scope.Ok(error))
  {
    std::printf("FAIL: %s\n", error.c_str());
    return false;
  }
  const vtkdf::GLFunctions& gl = context.GL();
  std::string log;
  const GLuint program = context.BuildProgram({ { GL_COMPUTE_SHADER, source.c_str() } }, log);
  if (!program)
  {
    std::printf("FAIL: the program does not build: %s\n", log.c_str());
    return false;
  }
  const int64_t resultBytes = int64_t(count) * resultsPerItem * 8;
  GLuint buffers[2];
  gl.GenBuffers(2, buffers);
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, buffers[0]);
  gl.BufferData(GL_SHADER_STORAGE_BUFFER, inputs.size() * 8, inputs.data(), GL_STATIC_DRAW);
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, buffers[1]);
  gl.BufferData(GL_SHADER_STORAGE_BUFFER, resultBytes, nullptr, GL_DYNAMIC_READ);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffers[0]);
  gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, buffers[1]);
  gl.UseProgram(program);
  gl.Uniform1i(gl.GetUniformLocation(program, "Count"), count);
  if (uniforms)
  {
    uniforms(gl, program);
  }
  gl.DispatchCompute(static_cast<GLuint>((count + 63) / 64), 1, 1);
  gl.MemoryBarrier(GL_ALL_BARRIER_BITS);
  results.assign(size_t(count) * resultsPerItem, 0);
  gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, buffers[1]);
  gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, resultBytes, results.data());
  gl.DeleteBuffers(2, buffers);
  gl.DeleteProgram(program);
  return vtkdf::NoGLError(gl, "in a test's compute shader", error) ||
    (std::printf("FAIL: %s\n", error.c_str()), false);
}
} // namespace vtkdf::coretest

#endif
