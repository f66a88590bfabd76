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

// Owns one name; Delete is a function that deletes one name. Every class
// below is a Name and follows the same rule: a default-constructed object
// owns nothing (empty() is true, `if (object)` is false) and only a named
// factory (`Texture::create2D`, `Framebuffer::create`, ...) creates a GL
// object, so a member declared without an initializer never allocates
// behind your back.
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
  bool empty() const { return id_ == 0; }
  explicit operator bool() const { return id_ != 0; }

 protected:
  // Deletes what is owned and takes ownership of `id` (for the factories).
  void adopt(GLuint id) {
    reset();
    id_ = id;
  }

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
void deleteQuery(GLuint id);

// The levels of a full mip chain for a width x height texture, down to 1 x 1.
int fullMipChainLevels(int width, int height);

// An immutable-storage texture (glTextureStorage*). One class for every
// target the renderer uses: the factories name the target, target() and
// layers() say which it is. Separate C++ types per target would buy little
// here: every consumer (framebuffer attachment, bind to a unit, readback)
// takes any of them.
class Texture : public Name<deleteTexture> {
 public:
  Texture() = default;  // owns nothing
  // GL_TEXTURE_2D; levels > 1 for mipmapped textures (filled by the caller).
  static Texture create2D(GLenum internalFormat, int width, int height, int levels = 1);
  // GL_TEXTURE_2D_ARRAY of `layers` layers.
  static Texture create2DArray(GLenum internalFormat, int width, int height, int layers);
  // GL_TEXTURE_CUBE_MAP_ARRAY of `cubes` cubes (6 layer-faces each).
  static Texture createCubeArray(GLenum internalFormat, int size, int cubes);

  GLenum target() const { return target_; }
  GLenum internalFormat() const { return internalFormat_; }
  int width() const { return width_; }
  int height() const { return height_; }
  int layers() const { return layers_; }  // 1 for 2D; layer-faces for cube arrays
  void bind(int unit) const { glBindTextureUnit(GLuint(unit), id()); }

 private:
  Texture(GLenum target, GLenum internalFormat, int width, int height, int layers, int levels);
  GLenum target_ = 0;
  GLenum internalFormat_ = 0;
  int width_ = 0;
  int height_ = 0;
  int layers_ = 0;
};

class Buffer : public Name<deleteBuffer> {
 public:
  Buffer() = default;  // owns nothing
  // Immutable storage of `bytes` (glNamedBufferStorage), updatable with
  // update(); data may be null.
  static Buffer create(std::size_t bytes, const void* data = nullptr);
  // Storage the GPU writes and the CPU reads back (glGetNamedBufferSubData):
  // a pixel pack buffer.
  static Buffer createReadback(std::size_t bytes);
  // Copies `bytes` from `offset` into `data`; waits for the commands that write it.
  void read(void* data, std::size_t bytes, std::size_t offset = 0) const;
  // The whole storage mapped for reading (a createReadback buffer), without
  // the copy read() makes; waits for the commands that write it. Valid until
  // unmap().
  const void* mapRead() const;
  void unmap() const;
  template <class T>
  static Buffer create(std::span<const T> items) {
    return create(items.size_bytes(), items.data());
  }

  void update(const void* data, std::size_t bytes, std::size_t offset = 0) const;
  template <class T>
  void update(const T& value) const {
    update(&value, sizeof(T));
  }
  void bindUniform(int binding) const { glBindBufferBase(GL_UNIFORM_BUFFER, GLuint(binding), id()); }
  void bindStorage(int binding) const { glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GLuint(binding), id()); }
  std::size_t size() const { return size_; }

 private:
  std::size_t size_ = 0;
};

class Framebuffer : public Name<deleteFramebuffer> {
 public:
  Framebuffer() = default;      // owns nothing
  static Framebuffer create();  // a framebuffer object with nothing attached
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
};

class VertexArray : public Name<deleteVertexArray> {
 public:
  VertexArray() = default;  // owns nothing
  static VertexArray create();
  void bind() const { glBindVertexArray(id()); }
};

class Sampler : public Name<deleteSampler> {
 public:
  Sampler() = default;  // owns nothing
  static Sampler create();
  void set(GLenum parameter, GLint value) const { glSamplerParameteri(id(), parameter, value); }
  void bind(int unit) const { glBindSampler(GLuint(unit), id()); }
};

// A query object of one target (GL_TIME_ELAPSED for the passes' GPU time).
// A fence after the commands issued so far (glFenceSync); move-only.
class Fence {
 public:
  Fence() = default;
  static Fence insert();
  Fence(Fence&& other) noexcept : sync_(std::exchange(other.sync_, nullptr)) {}
  Fence& operator=(Fence&& other) noexcept {
    if (this != &other) {
      reset();
      sync_ = std::exchange(other.sync_, nullptr);
    }
    return *this;
  }
  Fence(const Fence&) = delete;
  Fence& operator=(const Fence&) = delete;
  ~Fence() { reset(); }
  // Blocks until the GPU has passed the fence (none: at once).
  void wait() const;

 private:
  void reset();
  GLsync sync_ = nullptr;
};

class Query : public Name<deleteQuery> {
 public:
  Query() = default;  // owns nothing
  static Query create(GLenum target);
  // Blocks until the GPU has the result (after a glFinish it has).
  GLuint64 result() const {
    GLuint64 value = 0;
    glGetQueryObjectui64v(id(), GL_QUERY_RESULT, &value);
    return value;
  }
};

// A linked program. link() throws GlError with the info log (and the
// source's name) if a stage fails to compile or the program fails to link.
class Program : public Name<deleteProgram> {
 public:
  struct Stage {
    GLenum type;
    std::string name;    // for error messages, e.g. "gbuffer.frag"
    std::string source;  // complete source, #version first
  };
  Program() = default;  // owns nothing
  static Program link(std::span<const Stage> stages);
  void use() const { glUseProgram(id()); }
};

}  // namespace headlight::gl
