// HeadlessGL: an OpenGL 4.5 core context of our own, without a window or X server.
// Tried in order: EGL device platform (NVIDIA headless), EGL surfaceless (Mesa),
// OSMesa. GL entry points come from libepoxy on the EGL routes and from OSMesa itself on
// the last one (GLFunctions.h).
#ifndef vtkdf_HeadlessGL_h
#define vtkdf_HeadlessGL_h

#include "GL/GLFunctions.h"

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace vtkdf
{
struct CallerContext;

class HeadlessGL
{
public:
  /// The process-wide context, created on first use; nullptr (and `error`) when no
  /// route gives OpenGL 4.5 core. Set VTKDF_GL_PLATFORM=device|surfaceless|osmesa to
  /// force one route. On a node with several GPUs, the processes of a distributed run
  /// take them in turn by their node-local rank (OMPI_COMM_WORLD_LOCAL_RANK,
  /// MPI_LOCALRANKID or SLURM_LOCALID).
  static HeadlessGL* Get(std::string& error);

  /// Whether an EGL device other than Mesa's software one is present (a hardware GPU),
  /// found without creating a context.
  static bool HasHardwareDevice();

  const std::string& Renderer() const { return this->RendererName; }
  /// The error of a pass that failed on this context, naming the renderer.
  std::string Failure(const std::string& error) const
  {
    return "The GPU backend (" + this->RendererName + ") failed: " + error;
  }
  /// The route that gave the context: "EGL device", "EGL surfaceless" or "OSMesa".
  const std::string& Platform() const { return this->PlatformName; }
  /// Whether the renderer is a software one (Mesa's llvmpipe, softpipe, OSMesa...).
  bool IsSoftware() const;
  /// How many loop iterations and loop entries one shader invocation may run in all:
  /// Mesa's llvmpipe silently ends a shader's loops (all of them together) after 65,535
  /// iterations of a SIMD vector, whose lanes' loops add up in the worst case, so a
  /// software renderer gets 65,535 over its lanes (its "N bits" over 32; 16 when it does
  /// not say), less a few for the loops a shader enters once; hardware has no limit
  /// (INT32_MAX).
  int InvocationLoopBudget() const;

  /// Makes the context current on this thread for the lifetime of the scope, after
  /// saving and releasing whatever GLX or EGL context was current (VTK's render window,
  /// a ParaView view), which it restores on exit.
  class Scope
  {
  public:
    explicit Scope(HeadlessGL& gl);
    ~Scope();
    bool Ok() const { return this->Current; }
    /// As Ok(); when the context could not be made current, `error` says so.
    bool Ok(std::string& error) const
    {
      if (!this->Current)
      {
        error = "could not make the " + this->GL.Platform() + " context current";
      }
      return this->Current;
    }
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

  private:
    std::unique_ptr<CallerContext> Caller; // released first, restored last
    HeadlessGL& GL;
    bool Current = false;
  };

  /// The GL entry points of this context (call them while a Scope is alive).
  const GLFunctions& GL() const { return this->Functions; }

  /// Compiles and links (stage enum, source) pairs; 0 and the logs on failure. A
  /// source's //DF::SampleGrid line becomes the grid's uniforms, its
  /// //DF::TriangleDistance line the exact point-to-triangle distance (GridUniforms.h).
  unsigned BuildProgram(const std::vector<std::pair<unsigned, const char*>>& stages,
    std::string& log) const;

  ~HeadlessGL();

private:
  HeadlessGL() = default;
  bool TryEGLDevice(std::string& why);
  bool TryEGLSurfaceless(std::string& why);
  bool TryOSMesa(std::string& why);
  bool CreateEGLContext(void* display, std::string& why);
  bool MakeCurrent();
  void Release();

  std::string RendererName, PlatformName;
  void* Display = nullptr; // EGLDisplay
  void* Context = nullptr; // EGLContext or OSMesaContext
  bool UsesOSMesa = false;
  GLFunctions Functions;
  std::vector<unsigned char> OSMesaBuffer;
};

} // namespace vtkdf

#endif
