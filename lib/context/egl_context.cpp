// EGL with no surface: the device platform first (EGL_EXT_platform_device,
// so --device N can pick a GPU), then Mesa's surfaceless platform.
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstring>
#include <string>
#include <vector>

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
  // Released only where it is current: releasing EGL on a thread where an
  // OSMesa context is current would clear the current context the two
  // drivers share (libglapi), under OSMesa's feet.
  ~EglContext() override {
    if (eglGetCurrentContext() == context_) release();
    eglDestroyContext(display_, context_);
  }
  bool makeCurrent() override { return eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_) == EGL_TRUE; }
  void release() override { eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT); }
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

// What a device can be chosen by: its DRM device and render-node files,
// its driver and renderer names (EGL_EXT_device_persistent_id /
// EGL_EXT_device_query_name) and every extension it lists
// (EGL_MESA_device_software for llvmpipe).
struct DeviceNames {
  std::string label;  // "EGL device 0 (/dev/dri/card0)"
  std::vector<std::string> names;
};

DeviceNames deviceNames(int index, EGLDeviceEXT device, const char* deviceExtensions) {
  DeviceNames result{"EGL device " + std::to_string(index), {}};
  auto queryString = reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
  if (queryString == nullptr) return result;
  const char* extensions = deviceExtensions;
  auto query = [&](EGLint name, const char* needs) -> const char* {
    if (needs != nullptr && !hasExtension(extensions, needs)) return nullptr;
    const char* value = queryString(device, name);
    eglGetError();  // a name this device lacks is no error of ours
    return value;
  };
  const char* drm = query(EGL_DRM_DEVICE_FILE_EXT, "EGL_EXT_device_drm");
  const char* renderNode = query(EGL_DRM_RENDER_NODE_FILE_EXT, "EGL_EXT_device_drm_render_node");
  const char* driver = query(EGL_DRIVER_NAME_EXT, "EGL_EXT_device_persistent_id");
  const char* renderer = query(EGL_RENDERER_EXT, "EGL_EXT_device_query_name");
  for (const char* name : {drm, renderNode, driver, renderer})
    if (name != nullptr && *name != '\0') result.names.emplace_back(name);
  if (extensions != nullptr) {
    std::string list = extensions;
    for (std::size_t start = 0; start < list.size();) {
      std::size_t end = list.find(' ', start);
      if (end == std::string::npos) end = list.size();
      if (end > start) result.names.push_back(list.substr(start, end - start));
      start = end + 1;
    }
  }
  if (drm != nullptr)
    result.label += std::string(" (") + drm + ")";
  else if (extensions != nullptr)
    result.label += std::string(" (") + extensions + ")";
  return result;
}

std::unique_ptr<PlatformContext> tryDevicePlatform(int wanted, const std::string& wantedName,
                                                   std::vector<std::string>& attempts) {
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  auto queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  auto queryString = reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
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
    std::string list;  // the devices there are, with their names, for the message
    for (int i = 0; i < count; ++i) {
      const char* extensions = queryString != nullptr ? queryString(devices[i], EGL_EXTENSIONS) : nullptr;
      (list += list.empty() ? "" : "; ") += deviceNames(i, devices[i], extensions).label;
    }
    attempts.push_back("EGL device " + std::to_string(wanted) + ": only " + std::to_string(count) +
                       " device(s) exist (0.." + std::to_string(count - 1) + "): " + list);
    return nullptr;
  }
  std::string known;  // for the message when no device has the wanted name
  bool named = false;
  for (int i = 0; i < count; ++i) {
    if (wanted >= 0 && i != wanted) continue;
    const char* extensions = queryString != nullptr ? queryString(devices[i], EGL_EXTENSIONS) : nullptr;
    const DeviceNames device = deviceNames(i, devices[i], extensions);
    if (!wantedName.empty()) {
      bool matches = false;
      for (const std::string& name : device.names) matches = matches || name == wantedName;
      std::string list;
      for (const std::string& name : device.names) (list += list.empty() ? "" : ", ") += name;
      (known += known.empty() ? "" : "; ") += std::to_string(i) + ": " + list;
      if (!matches) continue;
      named = true;
    }
    EGLDisplay display = platformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
    if (auto context = contextOnDisplay(display, device.label, attempts)) return context;
  }
  if (!wantedName.empty() && !named)
    attempts.push_back("EGL device named '" + wantedName + "': no device has that name (" + known + ")");
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

std::unique_ptr<PlatformContext> createEglContext(int device, const std::string& deviceName, bool deviceFallback,
                                                  std::vector<std::string>& attempts) {
  if (auto context = tryDevicePlatform(device, deviceName, attempts)) return context;
  // A specific device was asked for: no silent fallback.
  if ((device >= 0 || !deviceName.empty()) && !deviceFallback) return nullptr;
  return trySurfacelessPlatform(attempts);
}

}  // namespace headlight::detail
