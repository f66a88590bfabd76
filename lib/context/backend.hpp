#pragma once
// The platform half of a Context: EGL or OSMesa. These translation units
// include the platform headers and never glad's, which would clash with
// <GL/gl.h>; lib/context/context.cpp does the GL half.
#include <memory>
#include <string>
#include <vector>

namespace headlight::detail {

using GlProc = void (*)();

class PlatformContext {
 public:
  virtual ~PlatformContext() = default;
  virtual void makeCurrent() = 0;
  virtual GlProc procAddress(const char* name) const = 0;
  virtual std::string description() const = 0;
};

// Each appends a line per attempt to `attempts` ("EGL device 0: ...") and
// returns null if no context could be made; it never throws for a missing
// driver, so that Backend::Auto can go on to the next backend.
std::unique_ptr<PlatformContext> createEglContext(int device, std::vector<std::string>& attempts);
std::unique_ptr<PlatformContext> createOSMesaContext(std::vector<std::string>& attempts);

}  // namespace headlight::detail
