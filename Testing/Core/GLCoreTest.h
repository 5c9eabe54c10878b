// GLCoreTest: the GL context of the cores' GPU tests, or why there is none.
#ifndef vtkdf_GLCoreTest_h
#define vtkdf_GLCoreTest_h

#include "GL/HeadlessGL.h"

#include <cstdio>
#include <string>

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
} // namespace vtkdf::coretest

#endif
