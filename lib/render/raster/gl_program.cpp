#include "render/raster/renderer_internal.h"

#include "core/diagnostics.h"
#include "render/raster/shaders.h"

namespace sdg::raster_detail {

unsigned compile(const GlApi& gl, GLenum type, std::initializer_list<const char*> sources) {
  unsigned shader = gl.glCreateShader(type);
  std::vector<const char*> parts(sources);
  gl.glShaderSource(shader, GLsizei(parts.size()), parts.data(), nullptr);
  gl.glCompileShader(shader);
  GLint ok = 0;
  gl.glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[4096];
    gl.glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    throw RunError(std::string("renderer: shader compilation failed: ") + log);
  }
  return shader;
}

unsigned link(const GlApi& gl, const char* vertex, const char* fragmentBody, bool common, const char* defines) {
  unsigned vs = compile(gl, GL_VERTEX_SHADER, {vertex});
  unsigned fs = common ? compile(gl, GL_FRAGMENT_SHADER,
                                 {shaders::kFragmentHeader, defines, shaders::kCommonFunctions, fragmentBody})
                       : compile(gl, GL_FRAGMENT_SHADER, {fragmentBody});
  unsigned program = gl.glCreateProgram();
  gl.glAttachShader(program, vs);
  gl.glAttachShader(program, fs);
  gl.glLinkProgram(program);
  gl.glDeleteShader(vs);
  gl.glDeleteShader(fs);
  GLint ok = 0;
  gl.glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[4096];
    gl.glGetProgramInfoLog(program, sizeof log, nullptr, log);
    throw RunError(std::string("renderer: shader linking failed: ") + log);
  }
  return program;
}

Eigen::Matrix4f toFloat(const Matrix4d& m) { return m.cast<float>(); }

void setMatrix(const GlApi& gl, int location, const Matrix4d& m) {
  Eigen::Matrix4f f = toFloat(m);  // Eigen is column-major, as GL expects
  gl.glUniformMatrix4fv(location, 1, GL_FALSE, f.data());
}

}  // namespace sdg::raster_detail
