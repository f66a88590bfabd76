// libFuzzer target for the glTF loader (issue 10). Each input is written to
// a file (the loader reads paths) as .glb when it starts with the GLB magic,
// else .gltf, and loaded with default limits, then posed by its first
// animation at two times. A SceneError or LimitError is
// the expected answer to a bad file; anything else escaping, a crash or a
// sanitizer report is a finding. Built and run by tools/fuzz.sh.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>

#include "headlight/error.hpp"
#include "headlight/scene_loader.hpp"

namespace {
// This process's two scratch files, removed when it exits normally (libFuzzer
// ends a timed run with exit()); a crash leaves them, beside its reproducer.
struct ScratchFiles {
  std::string base = "/tmp/headlight-fuzz-" + std::to_string(getpid());
  ~ScratchFiles() {
    std::remove((base + ".glb").c_str());
    std::remove((base + ".gltf").c_str());
  }
};

std::string scratchPath(const char* extension) {
  static const ScratchFiles files;
  return files.base + extension;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const bool binary = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
  const std::string path = scratchPath(binary ? ".glb" : ".gltf");
  if (std::FILE* file = std::fopen(path.c_str(), "wb")) {
    if (size > 0) std::fwrite(data, 1, size, file);
    std::fclose(file);
  } else {
    return 0;
  }
  headlight::ResourceLimits limits;
  limits.maxMemoryMiB = 512;  // a fuzzer process must stay small
  limits.maxTexels = 1 << 22;
  try {
    (void)headlight::loadGltf(path, {}, limits);
  } catch (const headlight::SceneError&) {
  } catch (const headlight::LimitError&) {
  }
  // Posed by its first animation too, between keyframes and past the last
  // (gltf/animation_pose.cpp's sampling reads the keyframes the time needs).
  headlight::SceneLoadOptions posed;
  posed.animationTime = 0.37f;
  for (int pass = 0; pass < 2; ++pass, posed.animationTime = 1e6f) {
    try {
      (void)headlight::loadGltf(path, posed, limits);
    } catch (const headlight::SceneError&) {
    } catch (const headlight::LimitError&) {
    }
  }
  return 0;
}
