#include "render/shader.hpp"

#include <vector>

namespace stiction::render {
namespace {

GlShader compile(GLenum type, std::string_view file_name, std::string_view defines) {
  const std::string_view source = embedded_shader(file_name);
  // "#version" must stay the first line: the defines go after it.
  const std::size_t version_end = source.find('\n') + 1;
  const std::string_view version = source.substr(0, version_end);
  const std::string_view body = source.substr(version_end);
  // "#line 2" keeps the compiler's line numbers those of the file.
  const std::string prefix = std::string(defines) + "#line 2\n";
  const char* texts[] = {version.data(), prefix.data(), body.data()};
  const GLint lengths[] = {static_cast<GLint>(version.size()), static_cast<GLint>(prefix.size()),
                           static_cast<GLint>(body.size())};
  GlShader shader(glCreateShader(type));
  glShaderSource(shader.get(), 3, texts, lengths);
  glCompileShader(shader.get());
  GLint ok = GL_FALSE;
  glGetShaderiv(shader.get(), GL_COMPILE_STATUS, &ok);
  if (!ok) {
    GLint size = 0;
    glGetShaderiv(shader.get(), GL_INFO_LOG_LENGTH, &size);
    std::vector<char> log(static_cast<std::size_t>(size) + 1, '\0');
    glGetShaderInfoLog(shader.get(), size, nullptr, log.data());
    throw GlError("cannot compile shader " + std::string(file_name) + ":\n" + log.data());
  }
  return shader;
}

}  // namespace

ShaderProgram::ShaderProgram(std::string_view vertex_file, std::string_view fragment_file,
                             std::string_view defines) {
  GlShader vs = compile(GL_VERTEX_SHADER, vertex_file, defines);
  GlShader fs = compile(GL_FRAGMENT_SHADER, fragment_file, defines);
  program_ = GlProgram(glCreateProgram());
  glAttachShader(program_.get(), vs.get());
  glAttachShader(program_.get(), fs.get());
  glLinkProgram(program_.get());
  GLint ok = GL_FALSE;
  glGetProgramiv(program_.get(), GL_LINK_STATUS, &ok);
  if (!ok) {
    GLint size = 0;
    glGetProgramiv(program_.get(), GL_INFO_LOG_LENGTH, &size);
    std::vector<char> log(static_cast<std::size_t>(size) + 1, '\0');
    glGetProgramInfoLog(program_.get(), size, nullptr, log.data());
    throw GlError("cannot link " + std::string(vertex_file) + " + " + std::string(fragment_file) +
                  ":\n" + log.data());
  }
  glDetachShader(program_.get(), vs.get());
  glDetachShader(program_.get(), fs.get());
}

GLint ShaderProgram::location(const std::string& name) {
  auto it = locations_.find(name);
  if (it != locations_.end()) return it->second;
  const GLint loc = glGetUniformLocation(program_.get(), name.c_str());
  locations_.emplace(name, loc);
  return loc;
}

}  // namespace stiction::render
