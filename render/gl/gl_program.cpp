#include "render/gl/gl_program.h"

#include <optional>
#include <string>
#include <string_view>

#include "base/error.h"
#include "render/gl/shader_sources.h"

namespace cutaway {
namespace {

std::string shader_log(GLuint shader) {
  GLint length = 0;
  glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<size_t>(length > 0 ? length : 0), '\0');
  if (length > 0) glGetShaderInfoLog(shader, length, nullptr, log.data());
  while (!log.empty() && (log.back() == '\0' || log.back() == '\n')) log.pop_back();
  return log;
}

std::string program_log(GLuint program) {
  GLint length = 0;
  glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<size_t>(length > 0 ? length : 0), '\0');
  if (length > 0) glGetProgramInfoLog(program, length, nullptr, log.data());
  while (!log.empty() && (log.back() == '\0' || log.back() == '\n')) log.pop_back();
  return log;
}

GLuint compile(GLenum stage, std::string_view file) {
  const std::optional<std::string_view> source = shader_source(file);
  if (!source) throw InternalError("no embedded shader named '" + std::string(file) + "'");
  const std::string_view text = *source;
  const GLchar* data = text.data();
  const GLint length = static_cast<GLint>(text.size());
  const GLuint shader = glCreateShader(stage);
  glShaderSource(shader, 1, &data, &length);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    const std::string log = shader_log(shader);
    glDeleteShader(shader);
    throw EnvironmentError("shaders/" + std::string(file) + ": compile error:\n" + log);
  }
  return shader;
}

}  // namespace

GlProgram::GlProgram(std::string_view vertex_file, std::string_view fragment_file) {
  const GLuint vs = compile(GL_VERTEX_SHADER, vertex_file);
  GLuint fs = 0;
  try {
    fs = compile(GL_FRAGMENT_SHADER, fragment_file);
  } catch (...) {
    glDeleteShader(vs);
    throw;
  }
  link({vs, fs},
       "shaders/" + std::string(vertex_file) + " + shaders/" + std::string(fragment_file));
}

GlProgram::GlProgram(std::string_view compute_file) {
  link({compile(GL_COMPUTE_SHADER, compute_file)}, "shaders/" + std::string(compute_file));
}

void GlProgram::link(std::initializer_list<GLuint> shaders, const std::string& files) {
  id_ = glCreateProgram();
  for (GLuint shader : shaders) glAttachShader(id_, shader);
  glLinkProgram(id_);
  for (GLuint shader : shaders) glDeleteShader(shader);  // flagged; freed with the program
  GLint ok = GL_FALSE;
  glGetProgramiv(id_, GL_LINK_STATUS, &ok);
  if (!ok) {
    const std::string log = program_log(id_);
    glDeleteProgram(id_);
    id_ = 0;
    throw EnvironmentError(files + ": link error:\n" + log);
  }
}

GlProgram::~GlProgram() {
  if (id_) glDeleteProgram(id_);
}

GLint GlProgram::uniform(const char* name) const {
  const GLint location = glGetUniformLocation(id_, name);
  if (location < 0)
    throw InternalError(std::string("shader program has no active uniform '") + name + "'");
  return location;
}

}  // namespace cutaway
