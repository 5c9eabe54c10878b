// GLFunctions: the OpenGL entry points the GPU backends call, as a table of function
// pointers filled once per context. On the EGL routes they come from libepoxy; under
// OSMesa they come from OSMesaGetProcAddress, because libepoxy sends core GL 1.x calls
// to libGL, which never sees an OSMesa context.
#ifndef vtkdf_GLFunctions_h
#define vtkdf_GLFunctions_h

#include <epoxy/gl.h>

#include <cstdio>
#include <cstdlib>
#include <string>

namespace vtkdf
{

// X(pointer type, name without the gl prefix), one per function used.
#define VTKDF_GL_FUNCTIONS(X)                                                                      \
  X(PFNGLBINDBUFFERRANGEPROC, BindBufferRange)                                                     \
  X(PFNGLBINDIMAGETEXTUREPROC, BindImageTexture)                                                   \
  X(PFNGLBUFFERSUBDATAPROC, BufferSubData)                                                         \
  X(PFNGLCLEARBUFFERDATAPROC, ClearBufferData)                                                     \
  X(PFNGLCLEARTEXIMAGEPROC, ClearTexImage)                                                         \
  X(PFNGLCOPYIMAGESUBDATAPROC, CopyImageSubData)                                                   \
  X(PFNGLDISPATCHCOMPUTEPROC, DispatchCompute)                                                     \
  X(PFNGLGETBUFFERSUBDATAPROC, GetBufferSubData)                                                   \
  X(PFNGLGETINTEGER64VPROC, GetInteger64v)                                                         \
  X(PFNGLGETTEXTUREIMAGEPROC, GetTextureImage)                                                     \
  X(PFNGLMEMORYBARRIERPROC, MemoryBarrier)                                                         \
  X(PFNGLTEXTURESUBIMAGE3DPROC, TextureSubImage3D)                                                 \
  X(PFNGLUNIFORM1DPROC, Uniform1d)                                                                 \
  X(PFNGLUNIFORM2UIVPROC, Uniform2uiv)                                                             \
  X(PFNGLUNIFORM3DPROC, Uniform3d)                                                                 \
  X(PFNGLUNIFORM3IPROC, Uniform3i)                                                                 \
  X(PFNGLATTACHSHADERPROC, AttachShader)                                                           \
  X(PFNGLBEGINQUERYPROC, BeginQuery)                                                               \
  X(PFNGLBINDBUFFERPROC, BindBuffer)                                                               \
  X(PFNGLBINDBUFFERBASEPROC, BindBufferBase)                                                       \
  X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                                                     \
  X(PFNGLBINDTEXTUREPROC, BindTexture)                                                             \
  X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                                                     \
  X(PFNGLBUFFERDATAPROC, BufferData)                                                               \
  X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus)                                       \
  X(PFNGLCLEARBUFFERFVPROC, ClearBufferfv)                                                         \
  X(PFNGLCLEARBUFFERIVPROC, ClearBufferiv)                                                         \
  X(PFNGLCOMPILESHADERPROC, CompileShader)                                                         \
  X(PFNGLCREATEPROGRAMPROC, CreateProgram)                                                         \
  X(PFNGLCREATESHADERPROC, CreateShader)                                                           \
  X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                                                         \
  X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)                                               \
  X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                                                         \
  X(PFNGLDELETEQUERIESPROC, DeleteQueries)                                                         \
  X(PFNGLDELETESHADERPROC, DeleteShader)                                                           \
  X(PFNGLDELETETEXTURESPROC, DeleteTextures)                                                       \
  X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)                                               \
  X(PFNGLDEPTHFUNCPROC, DepthFunc)                                                                 \
  X(PFNGLDISABLEPROC, Disable)                                                                     \
  X(PFNGLDRAWARRAYSINSTANCEDPROC, DrawArraysInstanced)                                             \
  X(PFNGLENABLEPROC, Enable)                                                                       \
  X(PFNGLENABLEVERTEXATTRIBARRAYPROC, EnableVertexAttribArray)                                     \
  X(PFNGLENDQUERYPROC, EndQuery)                                                                   \
  X(PFNGLFINISHPROC, Finish)                                                                       \
  X(PFNGLFRAMEBUFFERTEXTUREPROC, FramebufferTexture)                                               \
  X(PFNGLGENBUFFERSPROC, GenBuffers)                                                               \
  X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers)                                                     \
  X(PFNGLGENQUERIESPROC, GenQueries)                                                               \
  X(PFNGLGENTEXTURESPROC, GenTextures)                                                             \
  X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays)                                                     \
  X(PFNGLGETERRORPROC, GetError)                                                                   \
  X(PFNGLGETINTEGERVPROC, GetIntegerv)                                                             \
  X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)                                                 \
  X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                                                           \
  X(PFNGLGETQUERYOBJECTUI64VPROC, GetQueryObjectui64v)                                             \
  X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)                                                   \
  X(PFNGLGETSHADERIVPROC, GetShaderiv)                                                             \
  X(PFNGLGETSTRINGPROC, GetString)                                                                 \
  X(PFNGLGETSTRINGIPROC, GetStringi)                                                               \
  X(PFNGLGETTEXTURESUBIMAGEPROC, GetTextureSubImage)                                               \
  X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)                                               \
  X(PFNGLLINKPROGRAMPROC, LinkProgram)                                                             \
  X(PFNGLPIXELSTOREIPROC, PixelStorei)                                                             \
  X(PFNGLSHADERSOURCEPROC, ShaderSource)                                                           \
  X(PFNGLTEXSTORAGE3DPROC, TexStorage3D)                                                           \
  X(PFNGLUNIFORM1FPROC, Uniform1f)                                                                 \
  X(PFNGLUNIFORM1IPROC, Uniform1i)                                                                 \
  X(PFNGLUNIFORM2IPROC, Uniform2i)                                                                 \
  X(PFNGLUNIFORM3FPROC, Uniform3f)                                                                 \
  X(PFNGLUSEPROGRAMPROC, UseProgram)                                                               \
  X(PFNGLVERTEXATTRIBIPOINTERPROC, VertexAttribIPointer)                                           \
  X(PFNGLVIEWPORTPROC, Viewport)                                                                   \
  X(PFNGLCLEARBUFFERFIPROC, ClearBufferfi)                                                         \
  X(PFNGLCOLORMASKPROC, ColorMask)                                                                 \
  X(PFNGLCULLFACEPROC, CullFace)                                                                   \
  X(PFNGLDEPTHMASKPROC, DepthMask)                                                                 \
  X(PFNGLDRAWBUFFERPROC, DrawBuffer)                                                               \
  X(PFNGLREADBUFFERPROC, ReadBuffer)                                                               \
  X(PFNGLSTENCILFUNCPROC, StencilFunc)                                                             \
  X(PFNGLSTENCILOPPROC, StencilOp)                                                                 \
  X(PFNGLUNIFORMMATRIX3FVPROC, UniformMatrix3fv)                                                   \
  X(PFNGLVERTEXATTRIBPOINTERPROC, VertexAttribPointer)

struct GLFunctions
{
#define VTKDF_GL_MEMBER(type, name) type name = nullptr;
  VTKDF_GL_FUNCTIONS(VTKDF_GL_MEMBER)
#undef VTKDF_GL_MEMBER

  /// Whether the current context lists the extension.
  bool HasExtension(const char* name) const
  {
    GLint count = 0;
    this->GetIntegerv(GL_NUM_EXTENSIONS, &count);
    for (GLint i = 0; i < count; ++i)
    {
      const GLubyte* extension = this->GetStringi(GL_EXTENSIONS, static_cast<GLuint>(i));
      if (extension && std::string(reinterpret_cast<const char*>(extension)) == name)
      {
        return true;
      }
    }
    return false;
  }

  /// The libepoxy dispatch pointers (each resolves itself on first call).
  void LoadFromEpoxy()
  {
#define VTKDF_GL_EPOXY(type, name) this->name = gl##name;
    VTKDF_GL_FUNCTIONS(VTKDF_GL_EPOXY)
#undef VTKDF_GL_EPOXY
  }

  /// Asks `resolve` for every function; false and the first missing name otherwise.
  template<typename Resolver>
  bool Load(Resolver resolve, std::string& missing)
  {
#define VTKDF_GL_RESOLVE(type, name)                                                               \
  this->name = reinterpret_cast<type>(resolve("gl" #name));                                        \
  if (!this->name)                                                                                 \
  {                                                                                                \
    missing = "gl" #name;                                                                          \
    return false;                                                                                  \
  }
    VTKDF_GL_FUNCTIONS(VTKDF_GL_RESOLVE)
#undef VTKDF_GL_RESOLVE
    return true;
  }
};

/// The largest range of a buffer that one shader storage block may see: the driver's
/// GL_MAX_SHADER_STORAGE_BLOCK_SIZE, or less when the environment variable
/// VTKDF_MAX_SSBO_BYTES says so (the tests set it to run the slab loops on small grids).
inline GLint64 MaxStorageBlock(const GLFunctions& gl)
{
  GLint64 maxBlock = 0;
  gl.GetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &maxBlock);
  if (const char* forced = std::getenv("VTKDF_MAX_SSBO_BYTES"))
  {
    const long long limit = std::atoll(forced);
    maxBlock = limit > 0 && limit < maxBlock ? limit : maxBlock;
  }
  return maxBlock;
}

/// Buffers indexed by voxel are bound a slab of z at a time, so that no bound range
/// exceeds the storage block limit (MaxStorageBlock): the number of z slices per slab
/// (with one slice of margin on each side), or 0 when not even one fits.
/// `bytesPerVoxel` is the largest element size among the buffers.
inline int64_t SlabSlices(const GLFunctions& gl,
  int64_t slice,
  int64_t bytesPerVoxel,
  int64_t nz,
  GLint& alignment)
{
  const GLint64 maxBlock = MaxStorageBlock(gl);
  gl.GetIntegerv(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT, &alignment);
  const int64_t slices = (maxBlock - 2 * alignment) / (slice * bytesPerVoxel) - 2;
  return slices < 1 || alignment % 8 != 0 ? 0 : (slices < nz ? slices : nz);
}

/// Binds voxels [from, to) of a buffer of `elementBytes` elements per voxel to `binding`,
/// from an aligned offset; returns the element (of `unitBytes`) the range starts at.
inline int64_t BindVoxelRange(const GLFunctions& gl,
  GLuint binding,
  GLuint buffer,
  int64_t from,
  int64_t to,
  int64_t elementBytes,
  int64_t unitBytes,
  GLint alignment)
{
  const int64_t begin = from * elementBytes / alignment * alignment;
  gl.BindBufferRange(GL_SHADER_STORAGE_BUFFER, binding, buffer, begin, to * elementBytes - begin);
  return begin / unitBytes;
}

/// False, with `error` naming the OpenGL error and `where` it surfaced, when the GL
/// reports one; checked once at the end of each GPU pass.
inline bool NoGLError(const GLFunctions& gl, const char* where, std::string& error)
{
  const GLenum status = gl.GetError();
  if (status == GL_NO_ERROR)
  {
    return true;
  }
  char code[16];
  std::snprintf(code, sizeof(code), "0x%x", static_cast<unsigned>(status));
  error = std::string("OpenGL error ") + code + " " + where;
  return false;
}

} // namespace vtkdf

#endif
