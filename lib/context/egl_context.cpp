// EGL with no surface: the device platform first (EGL_EXT_platform_device,
// so --device N can pick a GPU), then Mesa's surfaceless platform.
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstring>
#include <string>

#include "context/backend.hpp"
#include "context/hex_code.hpp"

namespace headlight::detail {
namespace {

bool hasExtension(const char* list, const char* name) {
  if (list == nullptr) return false;
  const std::size_t length = std::strlen(name);
  for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += length) {
    const bool startsWord = p == list || p[-1] == ' ';
    const bool endsWord = p[length] == ' ' || p[length] == '\0';
    if (startsWord && endsWord) return true;
  }
  return false;
}

std::string eglErrorName(EGLint error) {
  switch (error) {
    case EGL_NOT_INITIALIZED:
      return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS:
      return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC:
      return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE:
      return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG:
      return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT:
      return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY:
      return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH:
      return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER:
      return "EGL_BAD_PARAMETER";
    default:
      return "EGL error " + detail::hexCode(unsigned(error));
  }
}

class EglContext final : public PlatformContext {
 public:
  EglContext(EGLDisplay display, EGLContext context, std::string description)
      : display_(display), context_(context), description_(std::move(description)) {}
  // The display is not terminated: EGL displays are shared by every context
  // of the process on the same device, and terminating it here would pull it
  // from under another headlight::Context.
  ~EglContext() override {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display_, context_);
  }
  void makeCurrent() override { eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_); }
  GlProc procAddress(const char* name) const override { return eglGetProcAddress(name); }
  std::string description() const override { return description_; }

 private:
  EGLDisplay display_;
  EGLContext context_;
  std::string description_;
};

// Makes a 4.5 core debug context with no surface on `display`, or says why not.
std::unique_ptr<PlatformContext> contextOnDisplay(EGLDisplay display, const std::string& label,
                                                  std::vector<std::string>& attempts) {
  EGLint major = 0, minor = 0;
  if (display == EGL_NO_DISPLAY || !eglInitialize(display, &major, &minor)) {
    attempts.push_back(label + ": eglInitialize failed (" + eglErrorName(eglGetError()) + ")");
    return nullptr;
  }
  const char* extensions = eglQueryString(display, EGL_EXTENSIONS);
  if (!hasExtension(extensions, "EGL_KHR_surfaceless_context")) {
    attempts.push_back(label + ": no EGL_KHR_surfaceless_context");
    return nullptr;
  }
  if (!eglBindAPI(EGL_OPENGL_API)) {
    attempts.push_back(label + ": eglBindAPI(EGL_OPENGL_API) failed (" + eglErrorName(eglGetError()) + ")");
    return nullptr;
  }
  EGLConfig config = EGL_NO_CONFIG_KHR;
  if (!hasExtension(extensions, "EGL_KHR_no_config_context")) {
    const EGLint configAttribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    EGLint count = 0;
    if (!eglChooseConfig(display, configAttribs, &config, 1, &count) || count == 0) {
      attempts.push_back(label + ": no EGL config with EGL_OPENGL_BIT");
      return nullptr;
    }
  }
  const EGLint contextAttribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                   4,
                                   EGL_CONTEXT_MINOR_VERSION,
                                   5,
                                   EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                   EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                   EGL_CONTEXT_OPENGL_DEBUG,
                                   EGL_TRUE,
                                   EGL_NONE};
  EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, contextAttribs);
  if (context == EGL_NO_CONTEXT) {
    attempts.push_back(label + ": eglCreateContext(4.5 core) failed (" + eglErrorName(eglGetError()) + ")");
    return nullptr;
  }
  if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
    attempts.push_back(label + ": eglMakeCurrent failed (" + eglErrorName(eglGetError()) + ")");
    eglDestroyContext(display, context);
    return nullptr;
  }
  attempts.push_back(label + ": EGL " + std::to_string(major) + "." + std::to_string(minor) + ", ok");
  return std::make_unique<EglContext>(display, context, label);
}

std::string deviceLabel(int index, EGLDeviceEXT device) {
  auto queryString = reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
  std::string label = "EGL device " + std::to_string(index);
  if (queryString == nullptr) return label;
  if (const char* drm = queryString(device, EGL_DRM_DEVICE_FILE_EXT)) return label + " (" + drm + ")";
  if (const char* extensions = queryString(device, EGL_EXTENSIONS)) return label + " (" + extensions + ")";
  return label;
}

std::unique_ptr<PlatformContext> tryDevicePlatform(int wanted, std::vector<std::string>& attempts) {
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  auto queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  auto platformDisplay =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (!hasExtension(client, "EGL_EXT_platform_device") || queryDevices == nullptr || platformDisplay == nullptr) {
    attempts.push_back("EGL device platform: EGL_EXT_platform_device not offered");
    return nullptr;
  }
  EGLDeviceEXT devices[16];
  EGLint count = 0;
  if (!queryDevices(16, devices, &count) || count == 0) {
    attempts.push_back("EGL device platform: eglQueryDevicesEXT found no device");
    return nullptr;
  }
  if (wanted >= count) {
    attempts.push_back("EGL device " + std::to_string(wanted) + ": only " + std::to_string(count) +
                       " device(s) exist (0.." + std::to_string(count - 1) + ")");
    return nullptr;
  }
  for (int i = 0; i < count; ++i) {
    if (wanted >= 0 && i != wanted) continue;
    const std::string label = deviceLabel(i, devices[i]);
    EGLDisplay display = platformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
    if (auto context = contextOnDisplay(display, label, attempts)) return context;
  }
  return nullptr;
}

std::unique_ptr<PlatformContext> trySurfacelessPlatform(std::vector<std::string>& attempts) {
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  auto platformDisplay =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (!hasExtension(client, "EGL_MESA_platform_surfaceless") || platformDisplay == nullptr) {
    attempts.push_back("EGL surfaceless platform: EGL_MESA_platform_surfaceless not offered");
    return nullptr;
  }
  EGLDisplay display = platformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  return contextOnDisplay(display, "EGL surfaceless", attempts);
}

}  // namespace

std::unique_ptr<PlatformContext> createEglContext(int device, std::vector<std::string>& attempts) {
  if (auto context = tryDevicePlatform(device, attempts)) return context;
  if (device >= 0) return nullptr;  // a specific device was asked for: no silent fallback
  return trySurfacelessPlatform(attempts);
}

}  // namespace headlight::detail
