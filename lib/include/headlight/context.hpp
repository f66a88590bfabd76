#pragma once
// A headless OpenGL 4.5 core context: no window, no surface, rendering only
// into the renderer's own framebuffers. Create one per thread and keep it for
// as many scenes and frames as you like; it is current on the creating thread.
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace headlight {

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
  std::string renderer() const;     // GL_RENDERER
  std::string version() const;      // GL_VERSION
  // What was tried before this context was made, one line per attempt.
  const std::vector<std::string>& attempts() const;

  // Makes this context current on the calling thread (it already is after
  // construction).
  void makeCurrent();

  // Reports the GL errors collected since the last call (KHR_debug messages
  // of type ERROR, plus glGetError), naming `operation`. Under
  // GlErrorPolicy::Throw it throws GlError; under Warn it prints them.
  void checkErrors(std::string_view operation);
  // Errors collected so far (and not yet reported), for tests.
  std::size_t pendingErrorCount() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace headlight
