// BenchRender's headless context: the module's own EGL context (HeadlessGL), made current
// for the rest of the process so that VTK renders into it. Apart from BenchRender.cxx
// because epoxy's GL header (HeadlessGL's) and VTK's GLEW header cannot meet in one file.
#include "BenchRenderContext.h"

#include "GL/HeadlessGL.h"

bool MakeHeadlessContextCurrent(std::string& renderer, std::string& error)
{
  vtkdf::HeadlessGL* gl = vtkdf::HeadlessGL::Get(error);
  if (!gl)
  {
    return false;
  }
  if (gl->Platform() == "OSMesa")
  {
    // VTK loads its entry points through GLX's loader, which never sees an OSMesa context.
    error = "only an OSMesa context was found; VTK cannot render into one";
    return false;
  }
  // Never destroyed: the context stays current until the process ends.
  static auto* scope = new vtkdf::HeadlessGL::Scope(*gl);
  renderer = gl->Renderer() + " (" + gl->Platform() + ")";
  return scope->Ok(error);
}
