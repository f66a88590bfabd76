#pragma once
// Generators of hostile glTF inputs, shared by the hostile suite and the
// fuzzer's seed corpus (tests/fuzz/make_seeds.cpp): a small valid scene to
// mutate, deep JSON, GLB containers. Nothing large is stored in the tree.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace headlight::test::hostile {

// A 1x1 RGBA PNG as a data URI.
inline constexpr const char* kOnePixelPng =
    "data:image/"
    "png;base64,iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR42mNkYPhfDwAChwGA60e6kgAAAABJRU5ErkJggg==";
// The same PNG's bytes (IHDR's width at 16, height at 20, its CRC at 29).
inline std::vector<unsigned char> onePixelPngBytes() {
  return {0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44, 0x52, 0x00, 0x00,
          0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x08, 0x06, 0x00, 0x00, 0x00, 0x1f, 0x15, 0xc4, 0x89, 0x00, 0x00, 0x00,
          0x0d, 0x49, 0x44, 0x41, 0x54, 0x78, 0xda, 0x63, 0x64, 0x60, 0xf8, 0x5f, 0x0f, 0x00, 0x02, 0x87, 0x01, 0x80,
          0xeb, 0x47, 0xba, 0x92, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
}

// Three float VEC3 positions of one triangle facing +Z (36 bytes).
std::vector<unsigned char> trianglePositions();
// A valid glTF 2.0 scene: one triangle in an embedded buffer, one node.
nlohmann::json triangleScene();
// `document` with a KHR_lights_punctual point light on a new root node.
nlohmann::json withLight(nlohmann::json document, const std::vector<double>& color, double intensity);
// "[[[...]]]" nested `depth` levels.
std::string nestedArrays(int depth);
// A GLB container of the JSON text (padded) and an optional BIN chunk.
std::vector<unsigned char> glb(const std::string& json, const std::vector<unsigned char>& bin, std::uint32_t version);

}  // namespace headlight::test::hostile

namespace headlight::test::hostile {

// The static pose: node 0 draws mesh 1, a triangle with one morph target
// (POSITION deltas +Z, weight 0.5); node 1 draws mesh 2 skinned to joint
// node 2 (rotated 90 degrees about +Z, identity inverseBindMatrices; node 1's
// own translation of 100 is ignored, as glTF says); node 3 draws mesh 0
// twice through EXT_mesh_gpu_instancing (TRANSLATION 0 and +3 X).
nlohmann::json posedScene();

}  // namespace headlight::test::hostile
