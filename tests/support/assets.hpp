#pragma once
// The assets shared between projects, which live beside the checkout
// (../shared, or $HEADLIGHT_SHARED_DIR) in CI too. A test that needs one
// decides at registration whether it runs, so that doctest counts it as
// skipped when the file is absent:
//   TEST_CASE("..." * doctest::skip(!test::exists(test::metalRoughSpheresGltf())))
#include <filesystem>
#include <string>

namespace headlight::test {

// $HEADLIGHT_SHARED_DIR when set and not empty, else <source>/../shared.
std::filesystem::path sharedFolder();

// The Khronos sample MetalRoughSpheresNoTextures (glTF folder).
std::filesystem::path metalRoughSpheresGltf();

bool exists(const std::filesystem::path& path);

// A conformance model's glTF: gltf-conformance/MODEL/glTF/MODEL.gltf.
std::filesystem::path conformanceGltf(const std::string& model);
inline bool haveConformanceModel(const std::string& model) { return test::exists(conformanceGltf(model)); }

}  // namespace headlight::test
