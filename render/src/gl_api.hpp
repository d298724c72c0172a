#pragma once
// The OpenGL 3.3 core entry points the renderer uses, loaded through GlContext::proc_address.
//
// Nothing in sutura links libGL or calls a gl* symbol directly: OSMesa and the window system's
// libGL each resolve their own functions, so both can live in one process. glcorearb.h is
// included without GL_GLEXT_PROTOTYPES, so it declares only types and constants and any
// direct gl* call fails to compile.
#include <GL/glcorearb.h>

#include "sutura/render/context.hpp"

namespace sutura::render {

// X-macro: X(pointer type from glcorearb.h, name without the "gl" prefix).
#define SUTURA_GL_FUNCTIONS(X)                                               \
  X(PFNGLACTIVETEXTUREPROC, ActiveTexture)                                   \
  X(PFNGLATTACHSHADERPROC, AttachShader)                                     \
  X(PFNGLBINDBUFFERPROC, BindBuffer)                                         \
  X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                               \
  X(PFNGLBINDRENDERBUFFERPROC, BindRenderbuffer)                             \
  X(PFNGLBINDTEXTUREPROC, BindTexture)                                       \
  X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                               \
  X(PFNGLBLITFRAMEBUFFERPROC, BlitFramebuffer)                               \
  X(PFNGLBUFFERDATAPROC, BufferData)                                         \
  X(PFNGLBUFFERSUBDATAPROC, BufferSubData)                                   \
  X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus)                 \
  X(PFNGLCLEARPROC, Clear)                                                   \
  X(PFNGLCLEARCOLORPROC, ClearColor)                                         \
  X(PFNGLCLEARDEPTHPROC, ClearDepth)                                         \
  X(PFNGLCOMPILESHADERPROC, CompileShader)                                   \
  X(PFNGLCREATEPROGRAMPROC, CreateProgram)                                   \
  X(PFNGLCREATESHADERPROC, CreateShader)                                     \
  X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                                   \
  X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)                         \
  X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                                   \
  X(PFNGLDELETERENDERBUFFERSPROC, DeleteRenderbuffers)                       \
  X(PFNGLDELETESHADERPROC, DeleteShader)                                     \
  X(PFNGLDELETETEXTURESPROC, DeleteTextures)                                 \
  X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)                         \
  X(PFNGLDEPTHFUNCPROC, DepthFunc)                                           \
  X(PFNGLDEPTHMASKPROC, DepthMask)                                           \
  X(PFNGLDISABLEPROC, Disable)                                               \
  X(PFNGLDRAWARRAYSPROC, DrawArrays)                                         \
  X(PFNGLDRAWELEMENTSPROC, DrawElements)                                     \
  X(PFNGLENABLEPROC, Enable)                                                 \
  X(PFNGLENABLEVERTEXATTRIBARRAYPROC, EnableVertexAttribArray)               \
  X(PFNGLFRAMEBUFFERRENDERBUFFERPROC, FramebufferRenderbuffer)               \
  X(PFNGLGENBUFFERSPROC, GenBuffers)                                         \
  X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers)                               \
  X(PFNGLGENRENDERBUFFERSPROC, GenRenderbuffers)                             \
  X(PFNGLGENTEXTURESPROC, GenTextures)                                       \
  X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays)                               \
  X(PFNGLGETERRORPROC, GetError)                                             \
  X(PFNGLGETINTEGERVPROC, GetIntegerv)                                       \
  X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)                           \
  X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                                     \
  X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)                             \
  X(PFNGLGETSHADERIVPROC, GetShaderiv)                                       \
  X(PFNGLGETSTRINGPROC, GetString)                                           \
  X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)                         \
  X(PFNGLLINKPROGRAMPROC, LinkProgram)                                       \
  X(PFNGLPIXELSTOREIPROC, PixelStorei)                                       \
  X(PFNGLPOLYGONOFFSETPROC, PolygonOffset)                                   \
  X(PFNGLREADBUFFERPROC, ReadBuffer)                                         \
  X(PFNGLREADPIXELSPROC, ReadPixels)                                         \
  X(PFNGLRENDERBUFFERSTORAGEPROC, RenderbufferStorage)                       \
  X(PFNGLRENDERBUFFERSTORAGEMULTISAMPLEPROC, RenderbufferStorageMultisample) \
  X(PFNGLSCISSORPROC, Scissor)                                               \
  X(PFNGLSHADERSOURCEPROC, ShaderSource)                                     \
  X(PFNGLTEXIMAGE2DPROC, TexImage2D)                                         \
  X(PFNGLTEXPARAMETERIPROC, TexParameteri)                                   \
  X(PFNGLUNIFORM1FPROC, Uniform1f)                                           \
  X(PFNGLUNIFORM1IPROC, Uniform1i)                                           \
  X(PFNGLUNIFORM2FPROC, Uniform2f)                                           \
  X(PFNGLUNIFORM3FPROC, Uniform3f)                                           \
  X(PFNGLUNIFORM4FPROC, Uniform4f)                                           \
  X(PFNGLUNIFORMMATRIX4FVPROC, UniformMatrix4fv)                             \
  X(PFNGLUSEPROGRAMPROC, UseProgram)                                         \
  X(PFNGLVERTEXATTRIBPOINTERPROC, VertexAttribPointer)                       \
  X(PFNGLVIEWPORTPROC, Viewport)

/// Function table for one context. Use as `gl.DrawArrays(...)`; only valid while that
/// context is current.
struct GlApi {
#define SUTURA_GL_DECLARE(type, name) type name = nullptr;
  SUTURA_GL_FUNCTIONS(SUTURA_GL_DECLARE)
#undef SUTURA_GL_DECLARE

  /// Resolves every entry point of the (current) context and checks that it reports at
  /// least OpenGL 3.3. Throws GlError naming the first missing function or the version found.
  explicit GlApi(const GlContext& context);

  /// Throws GlError("<what>: GL error 0x...") if glGetError reports an error (draining the
  /// error queue so later checks start clean).
  void check(const char* what) const;
};

}  // namespace sutura::render
