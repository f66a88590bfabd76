#pragma once
// A headless OpenGL 4.5 core context: no window, no surface, rendering only
// into the renderer's own framebuffers. Keep it for as many scenes and frames
// as you like; it is current on the creating thread.
//
// Threads: a context is current on one thread at a time, and every GL call
// goes through the calling thread's current context. Use one Context (and
// the Renderer made with it) per thread; contexts of different backends (EGL
// on one thread, OSMesa on another) may render at the same time, since each
// Context owns its table of GL entry points. Renderers of one backend on
// several threads are safe but take turns (Mesa's llvmpipe crashed when two
// contexts of one backend drew at once). To move a context to another
// thread, call releaseCurrent() on the first and makeCurrent() on the
// second. docs/EMBEDDING.md has the rules.
#include <memory>
#include <string>
#include <string_view>
#include <vector>
#include "headlight/export.hpp"

namespace headlight HEADLIGHT_PUBLIC {

namespace detail {
struct ContextAccess;
}

enum class Backend {
  Auto,  // EGL (device platform, then surfaceless), then OSMesa
  Egl,
  OSMesa,
};

std::string_view backendName(Backend backend);  // "auto", "egl", "osmesa"
// Parses "auto", "egl" or "osmesa"; throws SettingsError otherwise.
Backend parseBackend(std::string_view name);

// What to do when the GL reports an error through KHR_debug.
enum class GlErrorPolicy {
  Throw,  // checkErrors() throws GlError (tests, --strict)
  Warn,   // checkErrors() prints a warning to stderr and goes on (CLI default)
};

struct ContextOptions {
  Backend backend = Backend::Auto;
  int eglDevice = -1;  // EGL device index (EGL_EXT_device_enumeration); -1 = first that works
  GlErrorPolicy errorPolicy = GlErrorPolicy::Throw;
  // Non-empty: the EGL device with this name: its DRM device or render-node
  // file ("/dev/dri/renderD128"), its driver or renderer name, or one of its
  // extensions ("EGL_MESA_device_software" is llvmpipe). With eglDevice >= 0
  // as well, that device must also have the name.
  std::string eglDeviceName;
  // A device asked for (eglDevice or eglDeviceName) that cannot be used is a
  // ContextError naming the devices that exist, whatever the backend: on a
  // multi-GPU node a typo must not mean hours of software rendering. True:
  // go on to the other EGL platforms and (backend auto) OSMesa instead.
  bool deviceFallback = false;
};

class Context {
 public:
  // Throws ContextError listing every backend tried and why each failed.
  explicit Context(const ContextOptions& options = {});
  ~Context();
  Context(Context&&) noexcept;
  Context& operator=(Context&&) noexcept;
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  Backend backend() const;          // Egl or OSMesa, never Auto
  std::string description() const;  // e.g. "EGL device 0 (EGL_MESA_device_software)"
  std::string renderer() const;     // GL_RENDERER (read at construction; any thread)
  std::string version() const;      // GL_VERSION (read at construction; any thread)
  // What was tried before this context was made, one line per attempt.
  const std::vector<std::string>& attempts() const;

  // Makes this context current on the calling thread (it already is after
  // construction), releasing whatever context of either backend this thread
  // had current through another Context. Throws ContextError when the
  // platform refuses (an EGL context still current on another thread).
  void makeCurrent();
  // Makes no context current on the calling thread if this one is, so that
  // another thread can make it current. No-op otherwise.
  void releaseCurrent();
  // Whether this context is the calling thread's current one.
  bool isCurrent() const;
  // Throws ContextError naming `operation` unless isCurrent().
  void requireCurrent(std::string_view operation) const;

  // Reports the GL errors collected since the last call (KHR_debug messages
  // of type ERROR, plus glGetError), naming `operation`. Under
  // GlErrorPolicy::Throw it throws GlError; under Warn it prints them.
  void checkErrors(std::string_view operation);

 private:
  friend struct detail::ContextAccess;  // the library's own access (lib/context/context_access.hpp)
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace HEADLIGHT_PUBLIC
