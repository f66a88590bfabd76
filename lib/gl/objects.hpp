#pragma once
// Move-only owners of GL object names. The destructor deletes the name; a
// moved-from object owns nothing. No glCreate*/glDelete* outside this file
// pair (STYLE.md, practice 1). All objects are made with GL 4.5's
// direct-state-access calls, so creating one changes no bound state.
#include <glad/gl.h>

#include <span>
#include <string>
#include <string_view>
#include <utility>

namespace headlight::gl {

// Owns one name; Deleter is a function that deletes one name.
template <void (*Delete)(GLuint)>
class Name {
 public:
  Name() = default;
  explicit Name(GLuint id) : id_(id) {}
  ~Name() { reset(); }
  Name(Name&& other) noexcept : id_(std::exchange(other.id_, 0)) {}
  Name& operator=(Name&& other) noexcept {
    if (this != &other) {
      reset();
      id_ = std::exchange(other.id_, 0);
    }
    return *this;
  }
  Name(const Name&) = delete;
  Name& operator=(const Name&) = delete;

  GLuint id() const { return id_; }
  explicit operator bool() const { return id_ != 0; }

 private:
  void reset() {
    if (id_ != 0) Delete(id_);
    id_ = 0;
  }
  GLuint id_ = 0;
};

void deleteTexture(GLuint id);
void deleteBuffer(GLuint id);
void deleteFramebuffer(GLuint id);
void deleteVertexArray(GLuint id);
void deleteProgram(GLuint id);
void deleteShader(GLuint id);
void deleteSampler(GLuint id);

class Texture {
 public:
  Texture() = default;
  // An immutable-storage texture (glTextureStorage*): target is
  // GL_TEXTURE_2D, GL_TEXTURE_2D_ARRAY or GL_TEXTURE_CUBE_MAP_ARRAY; layers
  // is the array size (6 per cube for cube arrays), ignored for 2D.
  Texture(GLenum target, GLenum internalFormat, int width, int height, int layers = 1, int levels = 1);
  GLuint id() const { return name_.id(); }
  GLenum internalFormat() const { return internalFormat_; }
  int width() const { return width_; }
  int height() const { return height_; }
  explicit operator bool() const { return bool(name_); }
  void bind(int unit) const { glBindTextureUnit(GLuint(unit), id()); }

 private:
  Name<deleteTexture> name_;
  GLenum internalFormat_ = 0;
  int width_ = 0;
  int height_ = 0;
};

class Buffer {
 public:
  Buffer() = default;
  // Immutable storage of `bytes` (glNamedBufferStorage), updatable with
  // update(); data may be null.
  Buffer(std::size_t bytes, const void* data);
  template <class T>
  explicit Buffer(std::span<const T> items) : Buffer(items.size_bytes(), items.data()) {}

  void update(const void* data, std::size_t bytes, std::size_t offset = 0) const;
  template <class T>
  void update(const T& value) const { update(&value, sizeof(T)); }
  void bindUniform(int binding) const { glBindBufferBase(GL_UNIFORM_BUFFER, GLuint(binding), id()); }
  void bindStorage(int binding) const { glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GLuint(binding), id()); }
  GLuint id() const { return name_.id(); }
  std::size_t size() const { return size_; }
  explicit operator bool() const { return bool(name_); }

 private:
  Name<deleteBuffer> name_;
  std::size_t size_ = 0;
};

class Framebuffer {
 public:
  Framebuffer();  // creates an empty framebuffer object
  // Attaches `texture` (level 0); layer >= 0 attaches one layer of an array.
  void attach(GLenum attachment, const Texture& texture, int layer = -1);
  // Passes that keep a framebuffer across frames detach their targets when
  // done: an attached texture's storage outlives its deletion (GL 4.5,
  // 5.1.3), so a dropped target would stay resident.
  void detach(GLenum attachment) { glNamedFramebufferTexture(id(), attachment, 0, 0); }
  // Declares which colour attachments fragment outputs 0..n-1 write.
  void setDrawBuffers(std::span<const GLenum> buffers);
  // Throws GlError naming `what` if the framebuffer is incomplete.
  void checkComplete(std::string_view what) const;
  void bind() const { glBindFramebuffer(GL_FRAMEBUFFER, id()); }
  GLuint id() const { return name_.id(); }

 private:
  Name<deleteFramebuffer> name_;
};

class VertexArray {
 public:
  VertexArray();
  GLuint id() const { return name_.id(); }
  void bind() const { glBindVertexArray(id()); }

 private:
  Name<deleteVertexArray> name_;
};

class Sampler {
 public:
  Sampler();
  GLuint id() const { return name_.id(); }
  void set(GLenum parameter, GLint value) const { glSamplerParameteri(id(), parameter, value); }
  void bind(int unit) const { glBindSampler(GLuint(unit), id()); }

 private:
  Name<deleteSampler> name_;
};

// A linked program. Throws GlError with the info log (and the source's name)
// if a stage fails to compile or the program fails to link.
class Program {
 public:
  struct Stage {
    GLenum type;
    std::string name;    // for error messages, e.g. "gbuffer.frag"
    std::string source;  // complete source, #version first
  };
  Program() = default;
  explicit Program(std::span<const Stage> stages);
  GLuint id() const { return name_.id(); }
  void use() const { glUseProgram(id()); }
  explicit operator bool() const { return bool(name_); }

 private:
  Name<deleteProgram> name_;
};

}  // namespace headlight::gl
