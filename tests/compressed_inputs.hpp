#pragma once
// Compressed glTF files made by the test code from one known mesh (a torus),
// with the encoders of the libraries the loader decodes with: Draco's
// encoder (KHR_draco_mesh_compression) and meshoptimizer's
// (EXT_meshopt_compression). Shared by the unit, gl and hostile suites and the
// fuzzer's seeds. Compiled to stubs that report `available` false when the
// build lacks a library (meson options draco, meshopt): tests skip visibly.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace headlight::test::compressed {

extern const bool kDracoAvailable;
extern const bool kMeshoptAvailable;

struct KnownMesh {
  std::vector<glm::vec3> positions, normals;
  std::vector<glm::vec2> uvs;
  std::vector<std::uint16_t> indices;  // triangle list
};

// A torus (major radius 1, minor 0.4) about +Y: 17 x 9 vertices with seams, 256 triangles.
KnownMesh torus();

// The mesh as a plain .gltf (float attributes, UNSIGNED_SHORT indices, one data-URI buffer).
nlohmann::json plainGltf(const KnownMesh& mesh);

// Draco's bitstream of the mesh; attribute unique ids 0 POSITION, 1 NORMAL,
// 2 TEXCOORD_0. `edgebreaker` false: the sequential coder.
std::vector<unsigned char> dracoStream(const KnownMesh& mesh, bool edgebreaker);

// A .gltf whose primitive is the Draco stream (accessors without bufferView),
// KHR_draco_mesh_compression required.
nlohmann::json dracoGltf(const KnownMesh& mesh, bool edgebreaker = true);

// A .glb whose four bufferViews (positions, octahedral-filtered BYTE normals,
// uvs, TRIANGLES indices) are meshopt streams in the BIN chunk, over a
// placeholder buffer 1 without data (EXT_meshopt_compression and
// KHR_mesh_quantization required). `document` receives the JSON, to mutate
// and pack again with packMeshoptGlb.
std::vector<unsigned char> meshoptGlb(const KnownMesh& mesh, nlohmann::json* document = nullptr);
std::vector<unsigned char> packMeshoptGlb(const nlohmann::json& document, const KnownMesh& mesh);

}  // namespace headlight::test::compressed
