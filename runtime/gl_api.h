// The OpenGL ES 3.0 entry points the renderer uses, loaded through the caller's
// get-proc-address. Going through a table (instead of linking libGLESv2) lets the same
// renderer run on an EGL context, an OSMesa desktop-GL context, or an integrator's own.
#pragma once
#include <GLES3/gl3.h>

#include "runtime/status.h"

namespace stipple {

#define STIPPLE_GL_FUNCTIONS(X)                                      \
    X(PFNGLGETSTRINGPROC, GetString)                                 \
    X(PFNGLGETERRORPROC, GetError)                                   \
    X(PFNGLVIEWPORTPROC, Viewport)                                   \
    X(PFNGLCLEARCOLORPROC, ClearColor)                               \
    X(PFNGLCLEARPROC, Clear)                                         \
    X(PFNGLCLEARBUFFERFVPROC, ClearBufferfv)                         \
    X(PFNGLENABLEPROC, Enable)                                       \
    X(PFNGLDISABLEPROC, Disable)                                     \
    X(PFNGLDEPTHFUNCPROC, DepthFunc)                                 \
    X(PFNGLDEPTHMASKPROC, DepthMask)                                 \
    X(PFNGLBLENDFUNCPROC, BlendFunc)                                 \
    X(PFNGLCREATESHADERPROC, CreateShader)                           \
    X(PFNGLSHADERSOURCEPROC, ShaderSource)                           \
    X(PFNGLCOMPILESHADERPROC, CompileShader)                         \
    X(PFNGLGETSHADERIVPROC, GetShaderiv)                             \
    X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)                   \
    X(PFNGLDELETESHADERPROC, DeleteShader)                           \
    X(PFNGLCREATEPROGRAMPROC, CreateProgram)                         \
    X(PFNGLATTACHSHADERPROC, AttachShader)                           \
    X(PFNGLBINDATTRIBLOCATIONPROC, BindAttribLocation)               \
    X(PFNGLLINKPROGRAMPROC, LinkProgram)                             \
    X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                           \
    X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)                 \
    X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                         \
    X(PFNGLUSEPROGRAMPROC, UseProgram)                               \
    X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)               \
    X(PFNGLUNIFORMMATRIX4FVPROC, UniformMatrix4fv)                   \
    X(PFNGLUNIFORM1FPROC, Uniform1f)                                 \
    X(PFNGLUNIFORM4FPROC, Uniform4f)                                 \
    X(PFNGLGENBUFFERSPROC, GenBuffers)                               \
    X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                         \
    X(PFNGLBINDBUFFERPROC, BindBuffer)                               \
    X(PFNGLBUFFERDATAPROC, BufferData)                               \
    X(PFNGLBUFFERSUBDATAPROC, BufferSubData)                         \
    X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays)                     \
    X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)               \
    X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                     \
    X(PFNGLENABLEVERTEXATTRIBARRAYPROC, EnableVertexAttribArray)     \
    X(PFNGLVERTEXATTRIBPOINTERPROC, VertexAttribPointer)             \
    X(PFNGLDRAWELEMENTSPROC, DrawElements)                           \
    X(PFNGLDRAWARRAYSPROC, DrawArrays)                               \
    X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers)                     \
    X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)               \
    X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                     \
    X(PFNGLFRAMEBUFFERRENDERBUFFERPROC, FramebufferRenderbuffer)     \
    X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus)       \
    X(PFNGLGENRENDERBUFFERSPROC, GenRenderbuffers)                   \
    X(PFNGLDELETERENDERBUFFERSPROC, DeleteRenderbuffers)             \
    X(PFNGLBINDRENDERBUFFERPROC, BindRenderbuffer)                   \
    X(PFNGLRENDERBUFFERSTORAGEPROC, RenderbufferStorage)             \
    X(PFNGLDRAWBUFFERSPROC, DrawBuffers)                             \
    X(PFNGLREADBUFFERPROC, ReadBuffer)                               \
    X(PFNGLBLITFRAMEBUFFERPROC, BlitFramebuffer)                     \
    X(PFNGLREADPIXELSPROC, ReadPixels)                               \
    X(PFNGLPIXELSTOREIPROC, PixelStorei)                             \
    X(PFNGLFINISHPROC, Finish)                                       \
    X(PFNGLLINEWIDTHPROC, LineWidth)                                 \
    X(PFNGLGETFLOATVPROC, GetFloatv)                                 \
    X(PFNGLGENTEXTURESPROC, GenTextures)                             \
    X(PFNGLDELETETEXTURESPROC, DeleteTextures)                       \
    X(PFNGLBINDTEXTUREPROC, BindTexture)                             \
    X(PFNGLACTIVETEXTUREPROC, ActiveTexture)                         \
    X(PFNGLTEXIMAGE2DPROC, TexImage2D)                               \
    X(PFNGLTEXPARAMETERIPROC, TexParameteri)                         \
    X(PFNGLFRAMEBUFFERTEXTURE2DPROC, FramebufferTexture2D)           \
    X(PFNGLUNIFORM1IPROC, Uniform1i)                                 \
    X(PFNGLGETINTEGERVPROC, GetIntegerv)                             \
    X(PFNGLGETBOOLEANVPROC, GetBooleanv)                             \
    X(PFNGLISENABLEDPROC, IsEnabled)                                 \
    X(PFNGLCOLORMASKPROC, ColorMask)                                 \
    X(PFNGLBLENDFUNCSEPARATEPROC, BlendFuncSeparate)                 \
    X(PFNGLCULLFACEPROC, CullFace)                                   \
    X(PFNGLFRONTFACEPROC, FrontFace)                                 \
    X(PFNGLTEXSUBIMAGE2DPROC, TexSubImage2D)                         \
    X(PFNGLTRANSFORMFEEDBACKVARYINGSPROC, TransformFeedbackVaryings) \
    X(PFNGLBEGINTRANSFORMFEEDBACKPROC, BeginTransformFeedback)       \
    X(PFNGLENDTRANSFORMFEEDBACKPROC, EndTransformFeedback)           \
    X(PFNGLBINDBUFFERBASEPROC, BindBufferBase)                       \
    X(PFNGLMAPBUFFERRANGEPROC, MapBufferRange)                       \
    X(PFNGLUNMAPBUFFERPROC, UnmapBuffer)                             \
    X(PFNGLVERTEXATTRIBIPOINTERPROC, VertexAttribIPointer)           \
    X(PFNGLUNIFORM1FVPROC, Uniform1fv)                               \
    X(PFNGLVERTEXATTRIBDIVISORPROC, VertexAttribDivisor)             \
    X(PFNGLDRAWARRAYSINSTANCEDPROC, DrawArraysInstanced)             \
    X(PFNGLUNIFORM4FVPROC, Uniform4fv)                               \
    X(PFNGLFLUSHPROC, Flush)                                         \
    X(PFNGLSCISSORPROC, Scissor)

struct GlApi {
#define STIPPLE_GL_MEMBER(type, name) type name = nullptr;
    STIPPLE_GL_FUNCTIONS(STIPPLE_GL_MEMBER)
#undef STIPPLE_GL_MEMBER
    bool desktop = false;  // a desktop GL context (OSMesa): needs point-size/sprite enables
};

using GetProcAddress = void* (*)(const char* name);

// Fills every entry. Fails with gl_error naming the first missing function.
[[nodiscard]] Status load_gl_api(GetProcAddress get_proc, GlApi* gl);

}  // namespace stipple
