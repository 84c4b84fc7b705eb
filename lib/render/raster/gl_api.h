#pragma once
// The OpenGL 3.3 core functions sdgbehave calls, loaded through the back
// end's GetProcAddress (OSMesa today, EGL on GPU boxes) so the same GL code
// serves both and no libGL is linked.
#include <GL/glcorearb.h>

#include <functional>
#include <string>

namespace sdg {

#define SDG_GL_FUNCTIONS(X)                                                                   \
  X(PFNGLGETSTRINGPROC, glGetString)                                                          \
  X(PFNGLGETERRORPROC, glGetError)                                                            \
  X(PFNGLGETINTEGERVPROC, glGetIntegerv)                                                      \
  X(PFNGLVIEWPORTPROC, glViewport)                                                            \
  X(PFNGLSCISSORPROC, glScissor)                                                              \
  X(PFNGLCLEARBUFFERFVPROC, glClearBufferfv)                                                  \
  X(PFNGLCLEARBUFFERUIVPROC, glClearBufferuiv)                                                \
  X(PFNGLENABLEPROC, glEnable)                                                                \
  X(PFNGLDISABLEPROC, glDisable)                                                              \
  X(PFNGLDEPTHFUNCPROC, glDepthFunc)                                                          \
  X(PFNGLCOLORMASKPROC, glColorMask)                                                          \
  X(PFNGLDEPTHMASKPROC, glDepthMask)                                                          \
  X(PFNGLCULLFACEPROC, glCullFace)                                                            \
  X(PFNGLPOLYGONOFFSETPROC, glPolygonOffset)                                                  \
  X(PFNGLGENFRAMEBUFFERSPROC, glGenFramebuffers)                                              \
  X(PFNGLBINDFRAMEBUFFERPROC, glBindFramebuffer)                                              \
  X(PFNGLFRAMEBUFFERTEXTURE2DPROC, glFramebufferTexture2D)                                    \
  X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, glCheckFramebufferStatus)                                \
  X(PFNGLDELETEFRAMEBUFFERSPROC, glDeleteFramebuffers)                                        \
  X(PFNGLGENTEXTURESPROC, glGenTextures)                                                      \
  X(PFNGLBINDTEXTUREPROC, glBindTexture)                                                      \
  X(PFNGLTEXIMAGE2DPROC, glTexImage2D)                                                        \
  X(PFNGLTEXPARAMETERIPROC, glTexParameteri)                                                  \
  X(PFNGLTEXPARAMETERFVPROC, glTexParameterfv)                                                \
  X(PFNGLGENERATEMIPMAPPROC, glGenerateMipmap)                                                \
  X(PFNGLDELETETEXTURESPROC, glDeleteTextures)                                                \
  X(PFNGLACTIVETEXTUREPROC, glActiveTexture)                                                  \
  X(PFNGLDRAWBUFFERSPROC, glDrawBuffers)                                                      \
  X(PFNGLREADBUFFERPROC, glReadBuffer)                                                        \
  X(PFNGLREADPIXELSPROC, glReadPixels)                                                        \
  X(PFNGLPIXELSTOREIPROC, glPixelStorei)                                                      \
  X(PFNGLGENVERTEXARRAYSPROC, glGenVertexArrays)                                              \
  X(PFNGLBINDVERTEXARRAYPROC, glBindVertexArray)                                              \
  X(PFNGLDELETEVERTEXARRAYSPROC, glDeleteVertexArrays)                                        \
  X(PFNGLGENBUFFERSPROC, glGenBuffers)                                                        \
  X(PFNGLBINDBUFFERPROC, glBindBuffer)                                                        \
  X(PFNGLBUFFERDATAPROC, glBufferData)                                                        \
  X(PFNGLDELETEBUFFERSPROC, glDeleteBuffers)                                                  \
  X(PFNGLMAPBUFFERRANGEPROC, glMapBufferRange)                                                \
  X(PFNGLUNMAPBUFFERPROC, glUnmapBuffer)                                                      \
  X(PFNGLENABLEVERTEXATTRIBARRAYPROC, glEnableVertexAttribArray)                              \
  X(PFNGLVERTEXATTRIBPOINTERPROC, glVertexAttribPointer)                                      \
  X(PFNGLDRAWELEMENTSPROC, glDrawElements)                                                    \
  X(PFNGLDRAWELEMENTSINSTANCEDPROC, glDrawElementsInstanced)                                  \
  X(PFNGLVERTEXATTRIBIPOINTERPROC, glVertexAttribIPointer)                                    \
  X(PFNGLVERTEXATTRIBDIVISORPROC, glVertexAttribDivisor)                                      \
  X(PFNGLCREATESHADERPROC, glCreateShader)                                                    \
  X(PFNGLSHADERSOURCEPROC, glShaderSource)                                                    \
  X(PFNGLCOMPILESHADERPROC, glCompileShader)                                                  \
  X(PFNGLGETSHADERIVPROC, glGetShaderiv)                                                      \
  X(PFNGLGETSHADERINFOLOGPROC, glGetShaderInfoLog)                                            \
  X(PFNGLCREATEPROGRAMPROC, glCreateProgram)                                                  \
  X(PFNGLATTACHSHADERPROC, glAttachShader)                                                    \
  X(PFNGLLINKPROGRAMPROC, glLinkProgram)                                                      \
  X(PFNGLGETPROGRAMIVPROC, glGetProgramiv)                                                    \
  X(PFNGLGETPROGRAMINFOLOGPROC, glGetProgramInfoLog)                                          \
  X(PFNGLUSEPROGRAMPROC, glUseProgram)                                                        \
  X(PFNGLDELETESHADERPROC, glDeleteShader)                                                    \
  X(PFNGLDELETEPROGRAMPROC, glDeleteProgram)                                                  \
  X(PFNGLGETUNIFORMLOCATIONPROC, glGetUniformLocation)                                        \
  X(PFNGLUNIFORM1IPROC, glUniform1i)                                                          \
  X(PFNGLUNIFORM1UIPROC, glUniform1ui)                                                        \
  X(PFNGLUNIFORM1FPROC, glUniform1f)                                                          \
  X(PFNGLUNIFORM2FPROC, glUniform2f)                                                          \
  X(PFNGLUNIFORM3FPROC, glUniform3f)                                                          \
  X(PFNGLUNIFORM2FVPROC, glUniform2fv)                                                        \
  X(PFNGLUNIFORM3FVPROC, glUniform3fv)                                                        \
  X(PFNGLUNIFORM4FVPROC, glUniform4fv)                                                        \
  X(PFNGLUNIFORM1FVPROC, glUniform1fv)                                                        \
  X(PFNGLUNIFORM1IVPROC, glUniform1iv)                                                        \
  X(PFNGLUNIFORMMATRIX4FVPROC, glUniformMatrix4fv)                                            \
  X(PFNGLUNIFORMMATRIX3FVPROC, glUniformMatrix3fv)                                            \
  X(PFNGLDRAWARRAYSPROC, glDrawArrays)                                                        \
  X(PFNGLLOGICOPPROC, glLogicOp)                                            \
  X(PFNGLFINISHPROC, glFinish)

struct GlApi {
#define SDG_DECLARE_GL(type, name) type name = nullptr;
  SDG_GL_FUNCTIONS(SDG_DECLARE_GL)
#undef SDG_DECLARE_GL

  // Resolves every function; returns the name of the first one missing, or "".
  std::string load(const std::function<void*(const char*)>& getProc);
};

}  // namespace sdg
