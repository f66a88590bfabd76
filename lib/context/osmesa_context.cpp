// OSMesa: Mesa's off-screen API. It insists on a client colour buffer, so a
// 1x1 one is bound; the renderer only draws into its own framebuffers.
#include <GL/osmesa.h>

#include <array>
#include <cstdint>

#include "context/backend.hpp"

namespace headlight::detail {
namespace {

class OSMesaPlatformContext final : public PlatformContext {
 public:
  explicit OSMesaPlatformContext(OSMesaContext context) : context_(context) {}
  ~OSMesaPlatformContext() override { OSMesaDestroyContext(context_); }
  void makeCurrent() override { OSMesaMakeCurrent(context_, pixel_.data(), GL_UNSIGNED_BYTE, 1, 1); }
  GlProc procAddress(const char* name) const override { return OSMesaGetProcAddress(name); }
  std::string description() const override { return "OSMesa"; }

 private:
  OSMesaContext context_;
  std::array<std::uint8_t, 4> pixel_{};
};

}  // namespace

std::unique_ptr<PlatformContext> createOSMesaContext(std::vector<std::string>& attempts) {
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
  OSMesaContext context = OSMesaCreateContextAttribs(attribs, nullptr);
  if (context == nullptr) {
    attempts.push_back("OSMesa: OSMesaCreateContextAttribs(4.5 core) returned no context");
    return nullptr;
  }
  auto platform = std::make_unique<OSMesaPlatformContext>(context);
  platform->makeCurrent();
  attempts.push_back("OSMesa: ok");
  return platform;
}

}  // namespace headlight::detail
