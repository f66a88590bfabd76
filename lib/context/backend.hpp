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
  virtual bool makeCurrent() = 0;  // false: the platform refused (say, current on another thread)
  // Makes no context of this platform current on the calling thread.
  virtual void release() = 0;
  virtual GlProc procAddress(const char* name) const = 0;
  virtual std::string description() const = 0;
};

// Each appends a line per attempt to `attempts` ("EGL device 0: ...") and
// returns null if no context could be made; it never throws for a missing
// driver, so that Backend::Auto can go on to the next backend. `device` < 0
// and an empty `deviceName` mean the first device that works; a device asked
// for that fails falls back to the surfaceless platform only with
// `deviceFallback` (ContextOptions::deviceFallback).
std::unique_ptr<PlatformContext> createEglContext(int device, const std::string& deviceName, bool deviceFallback,
                                                  std::vector<std::string>& attempts);
// libOSMesa is opened with dlopen here, on first use: linking it would load
// Mesa's LLVM into every process, EGL users and `headlight --version` included.
std::unique_ptr<PlatformContext> createOSMesaContext(std::vector<std::string>& attempts);

}  // namespace headlight::detail
