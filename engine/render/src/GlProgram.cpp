// Building a program from GLSL sources (declared in Shaders.h): the one place that compiles shaders.
#include <GLES3/gl3.h>

#include <string>

#include "Shaders.h"

namespace qv::shaders {

namespace {

unsigned compileShader(GLenum kind, const char* source, std::string& error) {
  const GLuint shader = glCreateShader(kind);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    char log[2048] = {};
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    error = std::string(kind == GL_VERTEX_SHADER ? "vertex" : "fragment") + " shader: " + log;
    glDeleteShader(shader);
    return 0;
  }
  return shader;
}

}  // namespace

unsigned linkProgram(const char* vertex, const char* fragment, std::string& error) {
  const unsigned vs = compileShader(GL_VERTEX_SHADER, vertex, error);
  if (vs == 0) return 0;
  const unsigned fs = compileShader(GL_FRAGMENT_SHADER, fragment, error);
  if (fs == 0) {
    glDeleteShader(vs);
    return 0;
  }
  const GLuint program = glCreateProgram();
  glAttachShader(program, vs);
  glAttachShader(program, fs);
  glLinkProgram(program);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = GL_FALSE;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    char log[2048] = {};
    glGetProgramInfoLog(program, sizeof log, nullptr, log);
    error = std::string("program link: ") + log;
    glDeleteProgram(program);
    return 0;
  }
  return program;
}

}  // namespace qv::shaders
