#include "render/shader.hpp"

#include <vector>

namespace stiction::render {
namespace {

GlShader compile(GLenum type, std::string_view file_name) {
  const std::string_view source = embedded_shader(file_name);
  GlShader shader(glCreateShader(type));
  const char* text = source.data();
  const auto length = static_cast<GLint>(source.size());
  glShaderSource(shader.get(), 1, &text, &length);
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

ShaderProgram::ShaderProgram(std::string_view vertex_file, std::string_view fragment_file) {
  GlShader vs = compile(GL_VERTEX_SHADER, vertex_file);
  GlShader fs = compile(GL_FRAGMENT_SHADER, fragment_file);
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
