#include "gl/objects.hpp"

#include <vector>

#include "headlight/error.hpp"
#include "context/hex_code.hpp"

namespace headlight::gl {

void deleteTexture(GLuint id) { glDeleteTextures(1, &id); }
void deleteBuffer(GLuint id) { glDeleteBuffers(1, &id); }
void deleteFramebuffer(GLuint id) { glDeleteFramebuffers(1, &id); }
void deleteVertexArray(GLuint id) { glDeleteVertexArrays(1, &id); }
void deleteProgram(GLuint id) { glDeleteProgram(id); }
void deleteShader(GLuint id) { glDeleteShader(id); }
void deleteSampler(GLuint id) { glDeleteSamplers(1, &id); }

Texture::Texture(GLenum target, GLenum internalFormat, int width, int height, int layers, int levels)
    : internalFormat_(internalFormat), width_(width), height_(height) {
  GLuint id = 0;
  glCreateTextures(target, 1, &id);
  name_ = Name<deleteTexture>(id);
  if (target == GL_TEXTURE_2D || target == GL_TEXTURE_CUBE_MAP)
    glTextureStorage2D(id, levels, internalFormat, width, height);
  else
    glTextureStorage3D(id, levels, internalFormat, width, height, layers);
}

Buffer::Buffer(std::size_t bytes, const void* data) : size_(bytes) {
  GLuint id = 0;
  glCreateBuffers(1, &id);
  name_ = Name<deleteBuffer>(id);
  glNamedBufferStorage(id, GLsizeiptr(bytes), data, GL_DYNAMIC_STORAGE_BIT);
}

void Buffer::update(const void* data, std::size_t bytes, std::size_t offset) const {
  glNamedBufferSubData(id(), GLintptr(offset), GLsizeiptr(bytes), data);
}

Framebuffer::Framebuffer() {
  GLuint id = 0;
  glCreateFramebuffers(1, &id);
  name_ = Name<deleteFramebuffer>(id);
}

void Framebuffer::attach(GLenum attachment, const Texture& texture, int layer) {
  if (layer < 0)
    glNamedFramebufferTexture(id(), attachment, texture.id(), 0);
  else
    glNamedFramebufferTextureLayer(id(), attachment, texture.id(), 0, layer);
}

void Framebuffer::setDrawBuffers(std::span<const GLenum> buffers) {
  if (buffers.empty())
    glNamedFramebufferDrawBuffer(id(), GL_NONE);
  else
    glNamedFramebufferDrawBuffers(id(), GLsizei(buffers.size()), buffers.data());
}

void Framebuffer::checkComplete(std::string_view what) const {
  GLenum status = glCheckNamedFramebufferStatus(id(), GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE)
    throw GlError("glCheckNamedFramebufferStatus: " + std::string(what) +
                  " framebuffer is incomplete (status " + detail::hexCode(status) + ")");
}

VertexArray::VertexArray() {
  GLuint id = 0;
  glCreateVertexArrays(1, &id);
  name_ = Name<deleteVertexArray>(id);
}

Sampler::Sampler() {
  GLuint id = 0;
  glCreateSamplers(1, &id);
  name_ = Name<deleteSampler>(id);
}

namespace {

std::string infoLog(GLuint object, bool isProgram) {
  GLint length = 0;
  if (isProgram)
    glGetProgramiv(object, GL_INFO_LOG_LENGTH, &length);
  else
    glGetShaderiv(object, GL_INFO_LOG_LENGTH, &length);
  std::string log(std::size_t(std::max(length, 1)), '\0');
  if (isProgram)
    glGetProgramInfoLog(object, length, nullptr, log.data());
  else
    glGetShaderInfoLog(object, length, nullptr, log.data());
  while (!log.empty() && (log.back() == '\0' || log.back() == '\n')) log.pop_back();
  return log;
}

Name<deleteShader> compileStage(const Program::Stage& stage) {
  Name<deleteShader> shader(glCreateShader(stage.type));
  const char* source = stage.source.c_str();
  glShaderSource(shader.id(), 1, &source, nullptr);
  glCompileShader(shader.id());
  GLint ok = GL_FALSE;
  glGetShaderiv(shader.id(), GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE)
    throw GlError("glCompileShader: " + stage.name + " failed to compile:\n" + infoLog(shader.id(), false));
  return shader;
}

}  // namespace

Program::Program(std::span<const Stage> stages) {
  std::vector<Name<deleteShader>> shaders;
  std::string names;
  for (const Stage& stage : stages) {
    shaders.push_back(compileStage(stage));
    names += (names.empty() ? "" : " + ") + stage.name;
  }
  name_ = Name<deleteProgram>(glCreateProgram());
  for (const auto& shader : shaders) glAttachShader(id(), shader.id());
  glLinkProgram(id());
  GLint ok = GL_FALSE;
  glGetProgramiv(id(), GL_LINK_STATUS, &ok);
  for (const auto& shader : shaders) glDetachShader(id(), shader.id());
  if (ok != GL_TRUE) throw GlError("glLinkProgram: " + names + " failed to link:\n" + infoLog(id(), true));
}

}  // namespace headlight::gl
