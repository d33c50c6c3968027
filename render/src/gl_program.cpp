#include "gl_program.hpp"

#include <stdexcept>
#include <string>
#include <vector>

namespace gs::render::detail {
namespace {

std::string shaderLog(GLuint shader) {
  GLint length = 0;
  glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
  std::vector<char> log(static_cast<std::size_t>(std::max(length, 1)));
  glGetShaderInfoLog(shader, static_cast<GLsizei>(log.size()), nullptr, log.data());
  return log.data();
}

GLuint compile(const char* name, GLenum stage, const char* source) {
  const GLuint shader = glCreateShader(stage);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    const std::string log = shaderLog(shader);
    glDeleteShader(shader);
    throw std::runtime_error(std::string("cannot compile the ") + name +
                             (stage == GL_VERTEX_SHADER     ? " vertex"
                              : stage == GL_GEOMETRY_SHADER ? " geometry"
                                                            : " fragment") +
                             " shader: " + log);
  }
  return shader;
}

/// `program` after glLinkProgram; deletes it and throws with the log when it did not link.
GLuint linked(const char* name, GLuint program) {
  GLint ok = GL_FALSE;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    GLint length = 0;
    glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
    std::vector<char> log(static_cast<std::size_t>(std::max(length, 1)));
    glGetProgramInfoLog(program, static_cast<GLsizei>(log.size()), nullptr, log.data());
    glDeleteProgram(program);
    throw std::runtime_error(std::string("cannot link the ") + name + " program: " + log.data());
  }
  return program;
}

}  // namespace

GLuint buildProgram(const char* name, const char* vertexSource, const char* fragmentSource,
                    const char* geometrySource) {
  const GLuint vs = compile(name, GL_VERTEX_SHADER, vertexSource);
  GLuint fs = 0, gs = 0;
  try {
    fs = compile(name, GL_FRAGMENT_SHADER, fragmentSource);
    if (geometrySource != nullptr) gs = compile(name, GL_GEOMETRY_SHADER, geometrySource);
  } catch (...) {
    glDeleteShader(vs);
    if (fs != 0) glDeleteShader(fs);
    throw;
  }
  const GLuint program = glCreateProgram();
  glAttachShader(program, vs);
  glAttachShader(program, fs);
  if (gs != 0) glAttachShader(program, gs);
  glLinkProgram(program);
  glDeleteShader(vs);
  glDeleteShader(fs);
  if (gs != 0) glDeleteShader(gs);
  return linked(name, program);
}

GLuint buildComputeProgram(const char* name, const char* source) {
  const GLuint cs = compile(name, GL_COMPUTE_SHADER, source);
  const GLuint program = glCreateProgram();
  glAttachShader(program, cs);
  glLinkProgram(program);
  glDeleteShader(cs);
  return linked(name, program);
}

}  // namespace gs::render::detail
