#include "headlight/context.hpp"

#include <glad/gl.h>

#include <iostream>
#include <memory>
#include <mutex>

#include "context/backend.hpp"
#include "context/context_access.hpp"
#include "context/hex_code.hpp"
#include "headlight/error.hpp"

namespace headlight {

std::string_view backendName(Backend backend) {
  switch (backend) {
    case Backend::Auto:
      return "auto";
    case Backend::Egl:
      return "egl";
    case Backend::OSMesa:
      return "osmesa";
  }
  return "?";
}

Backend parseBackend(std::string_view name) {
  for (Backend backend : {Backend::Auto, Backend::Egl, Backend::OSMesa})
    if (name == backendName(backend)) return backend;
  throw SettingsError("backend: expected auto, egl or osmesa, got '" + std::string(name) + "'");
}

namespace {

// Every Context owns its table of GL entry points (glad --mx): the pointers
// EGL hands out (glvnd's libGLdispatch stubs on Debian) only dispatch to EGL
// contexts, OSMesa's (libglapi stubs) only to OSMesa ones, so a process-wide
// table would serve one backend's pointers to another backend's thread.
// makeCurrent() makes the context's table the calling thread's
// (gladSetCurrentGLContext, thread-local), and every glFoo() call in the
// library goes through it (subprojects/glad/generate.sh).
void loadGlEntryPoints(const detail::PlatformContext& platform, GladGLContext& table) {
  auto load = [](void* user, const char* name) -> GLADapiproc {
    return static_cast<const detail::PlatformContext*>(user)->procAddress(name);
  };
  if (gladLoadGLContextUserPtr(&table, load, const_cast<detail::PlatformContext*>(&platform)) == 0)
    throw ContextError("gladLoadGLContext: could not load OpenGL entry points from " + platform.description());
}

// The platform context each thread last made current through a Context.
// EGL's driver and libOSMesa share libglapi's current context (one per
// thread) but each keeps its own record of what it made current: switching
// from one backend to the other without releasing the first leaves that
// record stale, and the next switch back draws into the wrong context or none
// (GL_INVALID_VALUE in glDeleteProgram, shaders that fail with an empty log).
// So whatever this thread has current is released through its own API
// before another platform context is made current. A weak pointer: the
// context may be destroyed by another thread meanwhile.
// The platform context this thread has current. A thread_local with a
// destructor: at exit the main thread's copy is destroyed before static
// objects are (a function-static Context, say), so it is reached through
// currentPlatformSlot(), which is null once the slot is gone; the flag is
// trivially destructible and stays readable.
thread_local bool tCurrentPlatformGone = false;
struct CurrentPlatformSlot {
  std::weak_ptr<detail::PlatformContext> platform;
  ~CurrentPlatformSlot() { tCurrentPlatformGone = true; }
};
thread_local CurrentPlatformSlot tCurrentPlatform;

std::weak_ptr<detail::PlatformContext>* currentPlatformSlot() {
  return tCurrentPlatformGone ? nullptr : &tCurrentPlatform.platform;
}

// Whether `platform` is the one this thread has current.
bool isCurrentPlatform(const std::shared_ptr<detail::PlatformContext>& platform) {
  const auto* slot = currentPlatformSlot();
  return slot != nullptr && slot->lock() == platform;
}

// Releases the platform context this thread has current, unless it is `keep`.
void releaseCurrentPlatform(const detail::PlatformContext* keep = nullptr) {
  auto* slot = currentPlatformSlot();
  if (slot == nullptr) {
    gladSetCurrentGLContext(nullptr);
    return;
  }
  const std::shared_ptr<detail::PlatformContext> current = slot->lock();
  if (current.get() == keep && keep != nullptr) return;
  if (current) current->release();
  gladSetCurrentGLContext(nullptr);
  slot->reset();
}

void setCurrentPlatform(const std::shared_ptr<detail::PlatformContext>& platform) {
  if (auto* slot = currentPlatformSlot()) *slot = platform;
}

std::mutex& backendMutex(Backend backend) {
  static std::mutex egl, osmesa;
  return backend == Backend::OSMesa ? osmesa : egl;
}

std::string glString(GLenum name) {
  const auto* text = reinterpret_cast<const char*>(glGetString(name));
  return text != nullptr ? text : "";
}

std::string glErrorName(GLenum error) {
  switch (error) {
    case GL_INVALID_ENUM:
      return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE:
      return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION:
      return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION:
      return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY:
      return "GL_OUT_OF_MEMORY";
    default:
      return "GL error " + detail::hexCode(error);
  }
}

}  // namespace

struct Context::Impl {
  std::shared_ptr<detail::PlatformContext> platform;  // shared with tCurrentPlatform's weak pointers
  GladGLContext gl{};                                 // this context's entry points
  Backend backend = Backend::Auto;
  GlErrorPolicy errorPolicy = GlErrorPolicy::Throw;
  std::vector<std::string> attempts;
  std::string glRenderer, glVersion;  // read once: usable from any thread
  std::vector<std::string> errors;    // KHR_debug errors not yet reported

  static void GLAPIENTRY onDebugMessage(GLenum, GLenum type, GLuint id, GLenum severity, GLsizei, const GLchar* message,
                                        const void* user) {
    // Only errors (and undefined behaviour) are failures; performance and
    // portability notes from the driver are not.
    if (type != GL_DEBUG_TYPE_ERROR && type != GL_DEBUG_TYPE_UNDEFINED_BEHAVIOR) return;
    auto* impl = static_cast<Impl*>(const_cast<void*>(user));
    impl->errors.push_back("KHR_debug error " + std::to_string(id) + " (severity " + detail::hexCode(severity) +
                           "): " + message);
  }

  void installDebugCallback() {
    glEnable(GL_DEBUG_OUTPUT);
    // Synchronous, so a message arrives inside the call that caused it, on
    // this thread, and checkErrors() after a pass sees all of that pass's.
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageCallback(&Impl::onDebugMessage, this);
  }
};

Context::Context(const ContextOptions& options) : impl_(std::make_unique<Impl>()) {
  impl_->errorPolicy = options.errorPolicy;
  auto& attempts = impl_->attempts;
  releaseCurrentPlatform();  // creation makes the new context current
  if (options.backend == Backend::Auto || options.backend == Backend::Egl) {
    std::lock_guard lock(backendMutex(Backend::Egl));
    impl_->platform =
        detail::createEglContext(options.eglDevice, options.eglDeviceName, options.deviceFallback, attempts);
    impl_->backend = Backend::Egl;
  }
  // A device asked for names an EGL device: OSMesa only when the caller allows a fallback.
  const bool deviceAsked = options.eglDevice >= 0 || !options.eglDeviceName.empty();
  const bool osmesaAllowed = options.backend == Backend::OSMesa ||
                             (options.backend == Backend::Auto && (!deviceAsked || options.deviceFallback));
  if (!impl_->platform && osmesaAllowed) {
    std::lock_guard lock(backendMutex(Backend::OSMesa));
    impl_->platform = detail::createOSMesaContext(attempts);
    impl_->backend = Backend::OSMesa;
  }
  if (!impl_->platform) {
    std::string message =
        "no OpenGL 4.5 core context (backend " + std::string(backendName(options.backend)) + "); tried:";
    if (deviceAsked && !osmesaAllowed && options.backend == Backend::Auto)
      attempts.push_back(
          "OSMesa: not tried, a device was asked for (--device-fallback, device_fallback=True, or "
          "ContextOptions::deviceFallback to allow it)");
    for (const auto& attempt : attempts) message += "\n  " + attempt;
    throw ContextError(message);
  }
  auto lock = detail::ContextAccess::lockBackend(*this);
  setCurrentPlatform(impl_->platform);
  loadGlEntryPoints(*impl_->platform, impl_->gl);
  gladSetCurrentGLContext(&impl_->gl);
  try {
    GLint major = 0, minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    if (major * 10 + minor < 45)
      throw ContextError(impl_->platform->description() + ": got OpenGL " + glString(GL_VERSION) + ", need 4.5 core");
    impl_->glRenderer = glString(GL_RENDERER);
    impl_->glVersion = glString(GL_VERSION);
    impl_->installDebugCallback();
    // Filtered lookups near a cube face's edge read the neighbouring face too;
    // without this, point-light shadows show the cube's seams as lines.
    glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
  } catch (...) {
    gladSetCurrentGLContext(nullptr);  // the table dies with impl_
    throw;
  }
}

Context::~Context() {
  if (!impl_) return;  // moved from
  auto lock = detail::ContextAccess::lockBackend(*this);
  if (isCurrentPlatform(impl_->platform))
    releaseCurrentPlatform();
  else if (gladGetCurrentGLContext() == &impl_->gl)
    gladSetCurrentGLContext(nullptr);
  impl_->platform.reset();
}

Context::Context(Context&&) noexcept = default;
Context& Context::operator=(Context&&) noexcept = default;

Backend Context::backend() const { return impl_->backend; }
std::string Context::description() const { return impl_->platform->description(); }
std::string Context::renderer() const { return impl_->glRenderer; }
std::string Context::version() const { return impl_->glVersion; }
const std::vector<std::string>& Context::attempts() const { return impl_->attempts; }

void Context::makeCurrent() {
  releaseCurrentPlatform(impl_->platform.get());  // another context this thread has current, of either backend
  if (!impl_->platform->makeCurrent())
    throw ContextError(impl_->platform->description() +
                       ": could not make the context current on this thread (it is current on another thread: "
                       "call releaseCurrent() there first)");
  setCurrentPlatform(impl_->platform);
  gladSetCurrentGLContext(&impl_->gl);
}

void Context::releaseCurrent() {
  if (isCurrentPlatform(impl_->platform))
    releaseCurrentPlatform();
  else if (isCurrent())
    gladSetCurrentGLContext(nullptr);
}

bool Context::isCurrent() const { return gladGetCurrentGLContext() == &impl_->gl; }

void Context::requireCurrent(std::string_view operation) const {
  if (!isCurrent())
    throw ContextError(std::string(operation) + ": the context (" + impl_->platform->description() +
                       ") is not current on this thread; call Context::makeCurrent() on this thread first "
                       "(a context is current on one thread at a time)");
}

void Context::checkErrors(std::string_view operation) {
  requireCurrent(operation);
  // glGetError catches what a driver reports without a debug message.
  // Issue 10: GL_OUT_OF_MEMORY leaves objects silently missing, so it is an
  // error under every policy (Warn only warns about the recoverable ones).
  bool outOfMemory = false;
  for (GLenum error = glGetError(); error != GL_NO_ERROR; error = glGetError()) {
    impl_->errors.push_back("glGetError: " + glErrorName(error));
    outOfMemory = outOfMemory || error == GL_OUT_OF_MEMORY;
  }
  if (impl_->errors.empty()) return;
  std::string message =
      std::string(operation) + ": OpenGL reported " + std::to_string(impl_->errors.size()) + " error(s):";
  for (const auto& error : impl_->errors) message += "\n  " + error;
  impl_->errors.clear();
  if (impl_->errorPolicy == GlErrorPolicy::Throw || outOfMemory) throw GlError(message);
  std::cerr << "headlight: warning: " << message << "\n";
}

namespace detail {

std::unique_lock<std::mutex> ContextAccess::lockBackend(const Context& context) {
  return std::unique_lock(backendMutex(context.impl_->backend));
}

std::size_t ContextAccess::pendingErrorCount(const Context& context) { return context.impl_->errors.size(); }

}  // namespace detail
}  // namespace headlight
