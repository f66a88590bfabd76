#include "support/assets.hpp"

#include <cstdlib>

namespace fs = std::filesystem;

namespace headlight::test {

fs::path sharedFolder() {
  if (const char* shared = std::getenv("HEADLIGHT_SHARED_DIR"); shared != nullptr && *shared != '\0') return shared;
  return fs::path(HEADLIGHT_SOURCE_DIR) / ".." / "shared";
}

fs::path conformanceGltf(const std::string& model) {
  return sharedFolder() / "gltf-conformance" / model / "glTF" / (model + ".gltf");
}

fs::path metalRoughSpheresGltf() {
  return sharedFolder() / "anchors-assets" / "MetalRoughSpheresNoTextures" / "glTF" /
         "MetalRoughSpheresNoTextures.gltf";
}

bool exists(const fs::path& path) {
  std::error_code ignored;
  return fs::exists(path, ignored);
}

}  // namespace headlight::test
