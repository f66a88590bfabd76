// OSMesa: Mesa's off-screen API. It insists on a client colour buffer, so a
// 1x1 one is bound; the renderer only draws into its own framebuffers.
//
// libOSMesa is not linked: it links Mesa's LLVM, whose loading and static
// initialisation every process would pay for (headlight --version, EGL
// users). It is opened with dlopen the first time an OSMesa context is asked
// for, and stays open for the rest of the process (its contexts' entry points
// live in it). <GL/osmesa.h> is only read for the types.
#include <GL/osmesa.h>
#include <dlfcn.h>

#include <array>
#include <cstdint>
#include <mutex>
#include <string>
#include <type_traits>

#include "context/backend.hpp"

namespace headlight::detail {
namespace {

struct OSMesaLibrary {
  decltype(&OSMesaCreateContextAttribs) createContextAttribs = nullptr;
  decltype(&OSMesaMakeCurrent) makeCurrent = nullptr;
  decltype(&OSMesaDestroyContext) destroyContext = nullptr;
  decltype(&OSMesaGetProcAddress) getProcAddress = nullptr;
  std::string error;  // why it could not be opened; empty when it was
};

// The soname first (what the -dev package's libOSMesa.so points at), then the
// unversioned name for a system that has only that.
constexpr const char* kLibraryNames[] = {"libOSMesa.so.8", "libOSMesa.so"};

const OSMesaLibrary& osmesaLibrary() {
  static OSMesaLibrary library;
  static std::once_flag once;
  std::call_once(once, [] {
    void* handle = nullptr;
    for (const char* name : kLibraryNames) {
      if ((handle = dlopen(name, RTLD_NOW | RTLD_LOCAL)) != nullptr) break;
      const char* why = dlerror();
      library.error += std::string(library.error.empty() ? "" : "; ") + (why != nullptr ? why : name);
    }
    if (handle == nullptr) return;
    auto symbol = [&](auto& function, const char* name) {
      function = reinterpret_cast<std::remove_reference_t<decltype(function)>>(dlsym(handle, name));
      if (function == nullptr) library.error += std::string(library.error.empty() ? "" : "; ") + "no " + name;
    };
    library.error.clear();
    symbol(library.createContextAttribs, "OSMesaCreateContextAttribs");
    symbol(library.makeCurrent, "OSMesaMakeCurrent");
    symbol(library.destroyContext, "OSMesaDestroyContext");
    symbol(library.getProcAddress, "OSMesaGetProcAddress");
  });
  return library;
}

class OSMesaPlatformContext final : public PlatformContext {
 public:
  OSMesaPlatformContext(const OSMesaLibrary& library, OSMesaContext context) : library_(library), context_(context) {}
  ~OSMesaPlatformContext() override { library_.destroyContext(context_); }
  bool makeCurrent() override {
    return library_.makeCurrent(context_, pixel_.data(), GL_UNSIGNED_BYTE, 1, 1) == GL_TRUE;
  }
  void release() override { library_.makeCurrent(nullptr, nullptr, 0, 0, 0); }
  GlProc procAddress(const char* name) const override { return library_.getProcAddress(name); }
  std::string description() const override { return "OSMesa"; }

 private:
  const OSMesaLibrary& library_;
  OSMesaContext context_;
  std::array<std::uint8_t, 4> pixel_{};
};

}  // namespace

std::unique_ptr<PlatformContext> createOSMesaContext(std::vector<std::string>& attempts) {
  const OSMesaLibrary& library = osmesaLibrary();
  if (!library.error.empty()) {
    attempts.push_back("OSMesa: cannot open libOSMesa (" + library.error + ")");
    return nullptr;
  }
  const int attribs[] = {OSMESA_FORMAT,
                         OSMESA_RGBA,
                         OSMESA_DEPTH_BITS,
                         0,
                         OSMESA_PROFILE,
                         OSMESA_CORE_PROFILE,
                         OSMESA_CONTEXT_MAJOR_VERSION,
                         4,
                         OSMESA_CONTEXT_MINOR_VERSION,
                         5,
                         0};
  OSMesaContext context = library.createContextAttribs(attribs, nullptr);
  if (context == nullptr) {
    attempts.push_back("OSMesa: OSMesaCreateContextAttribs(4.5 core) returned no context");
    return nullptr;
  }
  auto platform = std::make_unique<OSMesaPlatformContext>(library, context);
  if (!platform->makeCurrent()) {
    attempts.push_back("OSMesa: OSMesaMakeCurrent failed");
    return nullptr;
  }
  attempts.push_back("OSMesa: ok");
  return platform;
}

}  // namespace headlight::detail
