#include "gl/objects.hpp"

#include <algorithm>
#include <vector>

#include "context/hex_code.hpp"
#include "headlight/error.hpp"

namespace headlight::gl {
namespace {

// glCreateTextures aside, every glCreate* of GL 4.5 has this signature.
using CreateNames = void(GLAD_API_PTR*)(GLsizei, GLuint*);
GLuint createOne(CreateNames create) {
  GLuint id = 0;
  create(1, &id);
  return id;
}

// An object destroyed on a thread where no context is current (a Renderer
// dropped on the wrong thread) leaves its name to the context's own
// destruction rather than calling through a null table.
bool haveCurrent() { return gladGetCurrentGLContext() != nullptr; }

}  // namespace

void deleteTexture(GLuint id) {
  if (haveCurrent()) glDeleteTextures(1, &id);
}
void deleteBuffer(GLuint id) {
  if (haveCurrent()) glDeleteBuffers(1, &id);
}
void deleteFramebuffer(GLuint id) {
  if (haveCurrent()) glDeleteFramebuffers(1, &id);
}
void deleteVertexArray(GLuint id) {
  if (haveCurrent()) glDeleteVertexArrays(1, &id);
}
void deleteProgram(GLuint id) {
  if (haveCurrent()) glDeleteProgram(id);
}
void deleteShader(GLuint id) {
  if (haveCurrent()) glDeleteShader(id);
}
void deleteSampler(GLuint id) {
  if (haveCurrent()) glDeleteSamplers(1, &id);
}

void deleteQuery(GLuint id) {
  if (haveCurrent()) glDeleteQueries(1, &id);
}

Texture::Texture(GLenum target, GLenum internalFormat, int width, int height, int layers, int levels)
    : target_(target), internalFormat_(internalFormat), width_(width), height_(height), layers_(layers) {
  GLuint id = 0;
  glCreateTextures(target, 1, &id);
  adopt(id);
  if (target == GL_TEXTURE_2D)
    glTextureStorage2D(id, levels, internalFormat, width, height);
  else
    glTextureStorage3D(id, levels, internalFormat, width, height, layers);
}

int fullMipChainLevels(int width, int height) {
  int levels = 1;
  for (int size = std::max(width, height); size > 1; size /= 2) ++levels;
  return levels;
}

Texture Texture::create2D(GLenum internalFormat, int width, int height, int levels) {
  return Texture(GL_TEXTURE_2D, internalFormat, width, height, 1, levels);
}

Texture Texture::create2DArray(GLenum internalFormat, int width, int height, int layers) {
  return Texture(GL_TEXTURE_2D_ARRAY, internalFormat, width, height, layers, 1);
}

Texture Texture::createCubeArray(GLenum internalFormat, int size, int cubes) {
  return Texture(GL_TEXTURE_CUBE_MAP_ARRAY, internalFormat, size, size, 6 * cubes, 1);
}

Buffer Buffer::create(std::size_t bytes, const void* data) {
  Buffer buffer;
  buffer.adopt(createOne(glCreateBuffers));
  buffer.size_ = bytes;
  glNamedBufferStorage(buffer.id(), GLsizeiptr(bytes), data, GL_DYNAMIC_STORAGE_BIT);
  return buffer;
}

Buffer Buffer::createReadback(std::size_t bytes) {
  Buffer buffer;
  buffer.adopt(createOne(glCreateBuffers));
  buffer.size_ = bytes;
  glNamedBufferStorage(buffer.id(), GLsizeiptr(bytes), nullptr, GL_MAP_READ_BIT | GL_CLIENT_STORAGE_BIT);
  return buffer;
}

void Buffer::read(void* data, std::size_t bytes, std::size_t offset) const {
  glGetNamedBufferSubData(id(), GLintptr(offset), GLsizeiptr(bytes), data);
}

const void* Buffer::mapRead() const { return glMapNamedBufferRange(id(), 0, GLsizeiptr(size_), GL_MAP_READ_BIT); }

void Buffer::unmap() const { glUnmapNamedBuffer(id()); }

Fence Fence::insert() {
  Fence fence;
  fence.sync_ = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
  return fence;
}

void Fence::wait() const {
  if (!sync_) return;
  // Flushes first, so a fence never waits on commands still in the client's queue.
  GLbitfield flags = GL_SYNC_FLUSH_COMMANDS_BIT;
  while (true) {
    const GLenum status = glClientWaitSync(sync_, flags, 1'000'000'000);  // 1 s a try
    if (status == GL_ALREADY_SIGNALED || status == GL_CONDITION_SATISFIED || status == GL_WAIT_FAILED) return;
    flags = 0;
  }
}

void Fence::reset() {
  // As the named objects: none deleted on a thread without a current context.
  if (sync_ && haveCurrent()) glDeleteSync(sync_);
  sync_ = nullptr;
}

void Buffer::update(const void* data, std::size_t bytes, std::size_t offset) const {
  glNamedBufferSubData(id(), GLintptr(offset), GLsizeiptr(bytes), data);
}

Framebuffer Framebuffer::create() {
  Framebuffer framebuffer;
  framebuffer.adopt(createOne(glCreateFramebuffers));
  return framebuffer;
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
    throw GlError("glCheckNamedFramebufferStatus: " + std::string(what) + " framebuffer is incomplete (status " +
                  detail::hexCode(status) + ")");
}

VertexArray VertexArray::create() {
  VertexArray vertexArray;
  vertexArray.adopt(createOne(glCreateVertexArrays));
  return vertexArray;
}

Query Query::create(GLenum target) {
  GLuint id = 0;
  glCreateQueries(target, 1, &id);
  if (id == 0) throw GlError("glCreateQueries returned no name");
  Query query;
  query.adopt(id);
  return query;
}

Sampler Sampler::create() {
  Sampler sampler;
  sampler.adopt(createOne(glCreateSamplers));
  return sampler;
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

Program Program::link(std::span<const Stage> stages) {
  Program program;
  std::vector<Name<deleteShader>> shaders;
  std::string names;
  for (const Stage& stage : stages) {
    shaders.push_back(compileStage(stage));
    names += (names.empty() ? "" : " + ") + stage.name;
  }
  program.adopt(glCreateProgram());
  const GLuint id = program.id();
  for (const auto& shader : shaders) glAttachShader(id, shader.id());
  glLinkProgram(id);
  GLint ok = GL_FALSE;
  glGetProgramiv(id, GL_LINK_STATUS, &ok);
  for (const auto& shader : shaders) glDetachShader(id, shader.id());
  if (ok != GL_TRUE) throw GlError("glLinkProgram: " + names + " failed to link:\n" + infoLog(id, true));
  return program;
}

}  // namespace headlight::gl
