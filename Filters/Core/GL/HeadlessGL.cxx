#include "GL/HeadlessGL.h"

#include "GL/GridUniforms.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>
#include <epoxy/glx.h>

#include <algorithm>
#include <cctype>
#include <climits>
#include <cstdlib>
#include <cstring>
#include <dlfcn.h>
#include <mutex>

namespace vtkdf
{
namespace
{
// OSMesa, loaded at run time so that the library is optional.
using OSMesaContextPtr = void*;
using CreateAttribsFn = OSMesaContextPtr (*)(const int*, OSMesaContextPtr);
using MakeCurrentFn = unsigned char (*)(OSMesaContextPtr, void*, unsigned, int, int);
using GetProcFn = void* (*)(const char*);
using DestroyFn = void (*)(OSMesaContextPtr);
using GetCurrentFn = OSMesaContextPtr (*)();
struct OSMesaApi
{
  void* Library = nullptr;
  CreateAttribsFn CreateContextAttribs = nullptr;
  MakeCurrentFn MakeCurrent = nullptr;
  GetProcFn GetProcAddress = nullptr;
  DestroyFn DestroyContext = nullptr;
  GetCurrentFn GetCurrentContext = nullptr;
};
OSMesaApi OSMesa;

bool Loaded(const char* soname)
{
  void* handle = dlopen(soname, RTLD_LAZY | RTLD_NOLOAD);
  if (handle)
  {
    dlclose(handle);
    return true;
  }
  return false;
}

/// This process's rank among the processes of a distributed run on its node, from the
/// launchers' environment (OpenMPI, MPICH, Slurm); 0 when there is none.
int NodeLocalRank()
{
  for (const char* name : { "OMPI_COMM_WORLD_LOCAL_RANK", "MPI_LOCALRANKID", "SLURM_LOCALID" })
  {
    if (const char* value = std::getenv(name))
    {
      char* end = nullptr;
      const long rank = std::strtol(value, &end, 10);
      if (end != value && rank >= 0 && rank < 1 << 20)
      {
        return static_cast<int>(rank);
      }
    }
  }
  return 0;
}

std::string EGLErrorText()
{
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "EGL error 0x%x", eglGetError());
  return buffer;
}
} // namespace

// The caller's current GLX or EGL context (VTK's render window, a ParaView view),
// released for the lifetime of this object and made current again at its end: making
// our context current while another API's context is current on the thread fails
// (Mesa: EGL_BAD_ACCESS), and the caller expects to find its own context afterwards.
struct CallerContext
{
  EGLDisplay EglDisplay = EGL_NO_DISPLAY;
  EGLContext EglContext = EGL_NO_CONTEXT;
  EGLSurface EglDraw = EGL_NO_SURFACE, EglRead = EGL_NO_SURFACE;
  EGLenum EglApi = EGL_OPENGL_ES_API;
  ::Display* GlxDisplay = nullptr;
  GLXContext GlxContext = nullptr;
  GLXDrawable GlxDraw = 0, GlxRead = 0;

  CallerContext()
  {
    // Only ask a library already in the process: otherwise it has no current context,
    // and asking would make libepoxy load (or fail to load) it.
    if (Loaded("libGL.so.1") || Loaded("libGLX.so.0"))
    {
      this->GlxContext = glXGetCurrentContext();
      if (this->GlxContext)
      {
        this->GlxDisplay = glXGetCurrentDisplay();
        this->GlxDraw = glXGetCurrentDrawable();
        this->GlxRead = glXGetCurrentReadDrawable();
        glXMakeContextCurrent(this->GlxDisplay, 0, 0, nullptr);
      }
    }
    if (Loaded("libEGL.so.1"))
    {
      this->EglApi = eglQueryAPI();
      this->EglContext = eglGetCurrentContext();
      if (this->EglContext != EGL_NO_CONTEXT)
      {
        this->EglDisplay = eglGetCurrentDisplay();
        this->EglDraw = eglGetCurrentSurface(EGL_DRAW);
        this->EglRead = eglGetCurrentSurface(EGL_READ);
        eglMakeCurrent(this->EglDisplay, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      }
    }
  }
  ~CallerContext()
  {
    if (this->EglContext != EGL_NO_CONTEXT)
    {
      eglBindAPI(this->EglApi);
      eglMakeCurrent(this->EglDisplay, this->EglDraw, this->EglRead, this->EglContext);
    }
    if (this->GlxContext)
    {
      glXMakeContextCurrent(this->GlxDisplay, this->GlxDraw, this->GlxRead, this->GlxContext);
    }
  }
  CallerContext(const CallerContext&) = delete;
  CallerContext& operator=(const CallerContext&) = delete;
};

HeadlessGL::Scope::Scope(HeadlessGL& gl)
  : Caller(new CallerContext)
  , GL(gl)
{
  this->Current = gl.MakeCurrent();
}

HeadlessGL::Scope::~Scope()
{
  this->GL.Release();
  // Caller, destroyed next, makes the caller's context current again.
}

HeadlessGL* HeadlessGL::Get(std::string& error)
{
  static std::mutex lock;
  static std::unique_ptr<HeadlessGL> instance;
  static bool tried = false;
  static std::string failure;
  std::lock_guard<std::mutex> guard(lock);
  if (!tried)
  {
    tried = true;
    // Each route makes its new context current to check it.
    CallerContext caller;
    std::unique_ptr<HeadlessGL> gl(new HeadlessGL);
    const char* forced = std::getenv("VTKDF_GL_PLATFORM");
    const std::string only = forced ? forced : "";
    std::string why, reasons;
    bool ok = false;
    if (!ok && (only.empty() || only == "device"))
    {
      ok = gl->TryEGLDevice(why);
      reasons += ok ? "" : "EGL device: " + why + "; ";
    }
    if (!ok && (only.empty() || only == "surfaceless"))
    {
      ok = gl->TryEGLSurfaceless(why);
      reasons += ok ? "" : "EGL surfaceless: " + why + "; ";
    }
    if (!ok && (only.empty() || only == "osmesa"))
    {
      ok = gl->TryOSMesa(why);
      reasons += ok ? "" : "OSMesa: " + why;
    }
    if (ok)
    {
      instance = std::move(gl);
    }
    else
    {
      failure = "no OpenGL 4.5 core context could be created (" + reasons + ")";
    }
  }
  error = failure;
  return instance.get();
}

bool HeadlessGL::CreateEGLContext(void* display, std::string& why)
{
  EGLDisplay dpy = static_cast<EGLDisplay>(display);
  EGLint major = 0, minor = 0;
  if (!eglInitialize(dpy, &major, &minor))
  {
    why = "eglInitialize failed (" + EGLErrorText() + ")";
    return false;
  }
  if (!eglBindAPI(EGL_OPENGL_API))
  {
    why = "no desktop OpenGL API";
    eglTerminate(dpy);
    return false;
  }
  const EGLint configAttribs[] = {
    EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE
  };
  EGLConfig config = nullptr;
  EGLint numConfigs = 0;
  eglChooseConfig(dpy, configAttribs, &config, 1, &numConfigs);
  const EGLint contextAttribs[] = { EGL_CONTEXT_MAJOR_VERSION,
    4,
    EGL_CONTEXT_MINOR_VERSION,
    5,
    EGL_CONTEXT_OPENGL_PROFILE_MASK,
    EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
    EGL_NONE };
  EGLContext ctx = eglCreateContext(
    dpy, numConfigs > 0 ? config : EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, contextAttribs);
  if (ctx == EGL_NO_CONTEXT)
  {
    why = "no OpenGL 4.5 core context (" + EGLErrorText() + ")";
    eglTerminate(dpy);
    return false;
  }
  this->Display = dpy;
  this->Context = ctx;
  if (!this->MakeCurrent())
  {
    why = "eglMakeCurrent without a surface failed (" + EGLErrorText() + ")";
    eglDestroyContext(dpy, ctx);
    eglTerminate(dpy);
    this->Display = this->Context = nullptr;
    return false;
  }
  this->Functions.LoadFromEpoxy();
  const char* renderer = reinterpret_cast<const char*>(this->Functions.GetString(GL_RENDERER));
  this->RendererName = renderer ? renderer : "unknown";
  this->Release();
  return true;
}

bool HeadlessGL::IsSoftware() const
{
  std::string renderer = this->RendererName;
  std::transform(renderer.begin(), renderer.end(), renderer.begin(), ::tolower);
  bool software = this->PlatformName == "OSMesa";
  for (const char* name : { "llvmpipe", "softpipe", "swrast", "software", "svga3d" })
  {
    software = software || renderer.find(name) != std::string::npos;
  }
  return software;
}

int HeadlessGL::InvocationLoopBudget() const
{
  if (!this->IsSoftware())
  {
    return INT32_MAX;
  }
  int lanes = 16;
  const size_t at = this->RendererName.find(" bits)");
  if (at != std::string::npos)
  {
    size_t from = at;
    while (from > 0 && std::isdigit(static_cast<unsigned char>(this->RendererName[from - 1])))
    {
      --from;
    }
    if (from < at)
    {
      lanes = std::max(1, std::atoi(this->RendererName.substr(from, at - from).c_str()) / 32);
    }
  }
  return 65535 / lanes - 16;
}

bool HeadlessGL::HasHardwareDevice()
{
  if (!epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_device_enumeration") &&
    !epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_device_base"))
  {
    return false;
  }
  EGLDeviceEXT devices[16];
  EGLint count = 0;
  if (!eglQueryDevicesEXT(16, devices, &count))
  {
    return false;
  }
  for (EGLint d = 0; d < count; ++d)
  {
    const char* ext = eglQueryDeviceStringEXT(devices[d], EGL_EXTENSIONS);
    if (!(ext && std::strstr(ext, "EGL_MESA_device_software")))
    {
      return true;
    }
  }
  return false;
}

bool HeadlessGL::TryEGLDevice(std::string& why)
{
  if (!epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_device_enumeration") &&
    !epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_device_base"))
  {
    why = "EGL_EXT_device_enumeration is missing";
    return false;
  }
  EGLDeviceEXT devices[16];
  EGLint count = 0;
  if (!eglQueryDevicesEXT(16, devices, &count) || count == 0)
  {
    why = "no EGL device";
    return false;
  }
  // Hardware devices first; Mesa's software device last.
  std::vector<EGLDeviceEXT> ordered;
  for (int pass = 0; pass < 2; ++pass)
  {
    for (EGLint d = 0; d < count; ++d)
    {
      const char* ext = eglQueryDeviceStringEXT(devices[d], EGL_EXTENSIONS);
      const bool software = ext && std::strstr(ext, "EGL_MESA_device_software");
      if (software == (pass == 1))
      {
        ordered.push_back(devices[d]);
      }
    }
    // The ranks of a distributed run on one node spread over its GPUs: rank r of the node
    // starts with hardware device r modulo their number.
    if (pass == 0 && ordered.size() > 1)
    {
      const size_t first = static_cast<size_t>(NodeLocalRank()) % ordered.size();
      std::rotate(ordered.begin(), ordered.begin() + first, ordered.end());
    }
  }
  for (EGLDeviceEXT device : ordered)
  {
    EGLDisplay dpy = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, device, nullptr);
    if (dpy != EGL_NO_DISPLAY && this->CreateEGLContext(dpy, why))
    {
      this->PlatformName = "EGL device";
      return true;
    }
  }
  return false;
}

bool HeadlessGL::TryEGLSurfaceless(std::string& why)
{
  if (!epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_MESA_platform_surfaceless"))
  {
    why = "EGL_MESA_platform_surfaceless is missing";
    return false;
  }
  EGLDisplay dpy =
    eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  if (dpy == EGL_NO_DISPLAY || !this->CreateEGLContext(dpy, why))
  {
    why = why.empty() ? "no surfaceless display" : why;
    return false;
  }
  this->PlatformName = "EGL surfaceless";
  return true;
}

bool HeadlessGL::TryOSMesa(std::string& why)
{
  OSMesa.Library = dlopen("libOSMesa.so.8", RTLD_NOW | RTLD_GLOBAL);
  if (!OSMesa.Library)
  {
    why = "libOSMesa.so.8 not found";
    return false;
  }
  OSMesa.CreateContextAttribs =
    reinterpret_cast<CreateAttribsFn>(dlsym(OSMesa.Library, "OSMesaCreateContextAttribs"));
  OSMesa.MakeCurrent = reinterpret_cast<MakeCurrentFn>(dlsym(OSMesa.Library, "OSMesaMakeCurrent"));
  OSMesa.GetProcAddress =
    reinterpret_cast<GetProcFn>(dlsym(OSMesa.Library, "OSMesaGetProcAddress"));
  OSMesa.DestroyContext =
    reinterpret_cast<DestroyFn>(dlsym(OSMesa.Library, "OSMesaDestroyContext"));
  OSMesa.GetCurrentContext =
    reinterpret_cast<GetCurrentFn>(dlsym(OSMesa.Library, "OSMesaGetCurrentContext"));
  if (!OSMesa.CreateContextAttribs || !OSMesa.MakeCurrent || !OSMesa.GetProcAddress)
  {
    why = "libOSMesa lacks OSMesaCreateContextAttribs";
    return false;
  }
  // OSMESA_FORMAT, OSMESA_RGBA, OSMESA_PROFILE, OSMESA_CORE_PROFILE, version 4.5.
  const int attribs[] = { 0x22, 0x1908, 0x33, 0x34, 0x36, 4, 0x37, 5, 0 };
  OSMesaContextPtr ctx = OSMesa.CreateContextAttribs(attribs, nullptr);
  if (!ctx)
  {
    why = "OSMesaCreateContextAttribs(4.5 core) failed";
    return false;
  }
  this->Context = ctx;
  this->UsesOSMesa = true;
  this->OSMesaBuffer.assign(4, 0);
  if (!this->MakeCurrent())
  {
    why = "OSMesaMakeCurrent failed";
    return false;
  }
  // Every entry point from OSMesa itself (see GLFunctions.h).
  std::string missing;
  if (!this->Functions.Load([](const char* name) { return OSMesa.GetProcAddress(name); }, missing))
  {
    why = "OSMesaGetProcAddress does not know " + missing;
    this->Release();
    OSMesa.DestroyContext(ctx);
    this->Context = nullptr;
    this->UsesOSMesa = false;
    return false;
  }
  const GLubyte* renderer = this->Functions.GetString(GL_RENDERER);
  this->RendererName = renderer ? reinterpret_cast<const char*>(renderer) : "unknown";
  this->PlatformName = "OSMesa";
  this->Release();
  return true;
}

bool HeadlessGL::MakeCurrent()
{
  if (this->UsesOSMesa)
  {
    return OSMesa.MakeCurrent(this->Context, this->OSMesaBuffer.data(), GL_UNSIGNED_BYTE, 1, 1);
  }
  eglBindAPI(EGL_OPENGL_API);
  return eglMakeCurrent(static_cast<EGLDisplay>(this->Display),
           EGL_NO_SURFACE,
           EGL_NO_SURFACE,
           static_cast<EGLContext>(this->Context)) == EGL_TRUE;
}

void HeadlessGL::Release()
{
  if (this->UsesOSMesa)
  {
    // OSMesa has no release call; the next MakeCurrent of anyone replaces it.
    return;
  }
  eglMakeCurrent(
    static_cast<EGLDisplay>(this->Display), EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
}

HeadlessGL::~HeadlessGL()
{
  if (this->Context && !this->UsesOSMesa)
  {
    eglDestroyContext(
      static_cast<EGLDisplay>(this->Display), static_cast<EGLContext>(this->Context));
  }
}

unsigned HeadlessGL::BuildProgram(const std::vector<std::pair<unsigned, const char*>>& stages,
  std::string& log) const
{
  const GLFunctions& gl = this->Functions;
  const GLuint program = gl.CreateProgram();
  std::vector<GLuint> shaders;
  bool ok = true;
  for (const auto& stage : stages)
  {
    const GLuint shader = gl.CreateShader(stage.first);
    const std::string source = WithSharedCode(stage.second);
    const char* text = source.c_str();
    gl.ShaderSource(shader, 1, &text, nullptr);
    gl.CompileShader(shader);
    GLint status = 0;
    gl.GetShaderiv(shader, GL_COMPILE_STATUS, &status);
    if (!status)
    {
      char text[4096];
      gl.GetShaderInfoLog(shader, sizeof(text), nullptr, text);
      log += std::string("shader compilation failed:\n") + text;
      ok = false;
    }
    gl.AttachShader(program, shader);
    shaders.push_back(shader);
  }
  if (ok)
  {
    gl.LinkProgram(program);
    GLint status = 0;
    gl.GetProgramiv(program, GL_LINK_STATUS, &status);
    if (!status)
    {
      char text[4096];
      gl.GetProgramInfoLog(program, sizeof(text), nullptr, text);
      log += std::string("program link failed:\n") + text;
      ok = false;
    }
  }
  for (GLuint shader : shaders)
  {
    gl.DeleteShader(shader);
  }
  if (!ok)
  {
    gl.DeleteProgram(program);
    return 0;
  }
  return program;
}

} // namespace vtkdf
