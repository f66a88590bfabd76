// Writes the fuzzer's seed corpus into the folder given: the hostile
// suite's generated scenes (valid and mutated), as .gltf text and as GLB.
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <vector>

#include "compressed_inputs.hpp"
#include "hostile_inputs.hpp"
#include "support/encoding.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: make-fuzz-seeds FOLDER\n";
    return 2;
  }
  namespace hostile = headlight::test::hostile;
  const std::filesystem::path folder = argv[1];
  std::filesystem::create_directories(folder);
  auto write = [&](const std::string& name, const std::string& bytes) {
    std::ofstream(folder / name, std::ios::binary) << bytes;
  };
  nlohmann::json scene = hostile::triangleScene();
  write("triangle.gltf", scene.dump());
  const auto glb = hostile::glb(scene.dump(), {}, 2);
  write("triangle.glb", std::string(glb.begin(), glb.end()));
  write("light.gltf", hostile::withLight(scene, {1, 0.5, 0.25}, 10).dump());
  nlohmann::json textured = scene;
  textured["images"] = {{{"uri", hostile::kOnePixelPng}}};
  textured["textures"] = {{{"source", 0}}};
  textured["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
  textured["meshes"][0]["primitives"][0]["material"] = 0;
  write("textured.gltf", textured.dump());
  nlohmann::json tree = scene;
  tree["nodes"] = {
      {{"children", {1, 2}}, {"scale", {2, 2, 2}}}, {{"mesh", 0}}, {{"mesh", 0}, {"translation", {1, 0, 0}}}};
  tree["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}}};
  tree["nodes"].push_back({{"camera", 0}, {"translation", {0, 0, 4}}});
  tree["scenes"][0]["nodes"] = {0, 3};
  write("tree.gltf", tree.dump());
  // The positions in a GLB BIN chunk.
  nlohmann::json binary = scene;
  binary["buffers"][0].erase("uri");
  const auto packed = hostile::glb(binary.dump(), hostile::trianglePositions(), 2);
  write("binchunk.glb", std::string(packed.begin(), packed.end()));
  // The static pose: morph targets, a skin, EXT_mesh_gpu_instancing.
  const nlohmann::json posed = hostile::posedScene();
  write("posed.gltf", posed.dump());
  nlohmann::json strip = scene;
  strip["meshes"][0]["primitives"][0]["mode"] = 5;
  write("strip.gltf", strip.dump());
  // A normal map without TANGENT: tangents are generated (MikkTSpace's rules).
  nlohmann::json normalMapped = textured;
  normalMapped["materials"] = {{{"normalTexture", {{"index", 0}}}}};
  // The positions' bytes as UVs.
  normalMapped["accessors"].push_back({{"bufferView", 0}, {"componentType", 5126}, {"type", "VEC2"}, {"count", 3}});
  normalMapped["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = 1;
  write("normal-mapped.gltf", normalMapped.dump());
  // Compressed geometry (when the build has the encoders), and material variants.
  namespace compressed = headlight::test::compressed;
  const compressed::KnownMesh torus = compressed::torus();
  if (compressed::kDracoAvailable) {
    write("draco-edgebreaker.gltf", compressed::dracoGltf(torus, true).dump());
    write("draco-sequential.gltf", compressed::dracoGltf(torus, false).dump());
  }
  if (compressed::kMeshoptAvailable) {
    const auto meshopt = compressed::meshoptGlb(torus);
    write("meshopt.glb", std::string(meshopt.begin(), meshopt.end()));
  }
  nlohmann::json variants = compressed::plainGltf(torus);
  variants["materials"] = {{{"name", "a"}}, {{"name", "b"}}};
  variants["meshes"][0]["primitives"][0]["extensions"]["KHR_materials_variants"]["mappings"] = {
      {{"material", 1}, {"variants", {0}}}};
  variants["extensions"]["KHR_materials_variants"]["variants"] = {{{"name", "v"}}};
  write("variants.gltf", variants.dump());
  // Animations to play (the fuzzer also loads every input posed at two
  // times): LINEAR translation, STEP scale, CUBICSPLINE rotation, on the
  // triangle's node, from a second buffer.
  nlohmann::json animated = scene;
  const float keys[] = {0,
                        1,
                        /* translations */ 0,
                        0,
                        0,
                        1,
                        2,
                        3,
                        /* scales */ 1,
                        1,
                        1,
                        2,
                        2,
                        2,
                        /* rotations: in, value, out per keyframe */ 0,
                        0,
                        0,
                        0,
                        0,
                        0,
                        0,
                        1,
                        0,
                        0,
                        0,
                        0,
                        0,
                        0,
                        0,
                        0,
                        0,
                        0.6f,
                        0,
                        0.8f,
                        0,
                        0,
                        0,
                        0};
  std::vector<unsigned char> keyBytes(sizeof keys);
  std::memcpy(keyBytes.data(), keys, sizeof keys);
  animated["buffers"].push_back({{"byteLength", keyBytes.size()},
                                 {"uri", "data:application/octet-stream;base64," + headlight::test::base64(keyBytes)}});
  const int keyBuffer = int(animated["buffers"].size()) - 1;
  const int view = int(animated["bufferViews"].size());
  animated["bufferViews"].push_back({{"buffer", keyBuffer}, {"byteLength", keyBytes.size()}});
  const int first = int(animated["accessors"].size());
  animated["accessors"].push_back(
      {{"bufferView", view}, {"componentType", 5126}, {"type", "SCALAR"}, {"count", 2}, {"min", {0}}, {"max", {1}}});
  animated["accessors"].push_back(
      {{"bufferView", view}, {"byteOffset", 8}, {"componentType", 5126}, {"type", "VEC3"}, {"count", 2}});
  animated["accessors"].push_back(
      {{"bufferView", view}, {"byteOffset", 32}, {"componentType", 5126}, {"type", "VEC3"}, {"count", 2}});
  animated["accessors"].push_back(
      {{"bufferView", view}, {"byteOffset", 56}, {"componentType", 5126}, {"type", "VEC4"}, {"count", 6}});
  animated["animations"] = {{{"name", "Move"},
                             {"channels",
                              {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "translation"}}}},
                               {{"sampler", 1}, {"target", {{"node", 0}, {"path", "scale"}}}},
                               {{"sampler", 2}, {"target", {{"node", 0}, {"path", "rotation"}}}}}},
                             {"samplers",
                              {{{"input", first}, {"output", first + 1}},
                               {{"input", first}, {"output", first + 2}, {"interpolation", "STEP"}},
                               {{"input", first}, {"output", first + 3}, {"interpolation", "CUBICSPLINE"}}}}}};
  write("animated.gltf", animated.dump());
  std::cout << "seeds written to " << folder.string() << "\n";
  return 0;
}
