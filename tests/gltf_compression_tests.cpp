// KHR_draco_mesh_compression and EXT_meshopt_compression (issue 17): files
// made here with the libraries' own encoders from a known torus, loaded, and
// compared with the torus within each codec's quantisation. Without a
// library (meson options draco, meshopt) the cases skip visibly and the
// extension is named as not rendered.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "compressed_inputs.hpp"
#include "gltf/draco.hpp"
#include "headlight/error.hpp"
#include "headlight/limits.hpp"
#include "headlight/scene_loader.hpp"
#include "support/temp_folder.hpp"

using namespace headlight;
using namespace headlight::test;
using compressed::KnownMesh;
using nlohmann::json;

namespace {

const Primitive& onlyPrimitive(const Scene& scene) {
  REQUIRE(scene.primitives.size() == 1);
  return scene.primitives[0];
}

float distance(const glm::vec3& a, const glm::vec3& b) { return glm::length(a - b); }

struct Tolerances {
  float position, normal, uv;
};

// Every decoded triangle is a source triangle (a corner rotation of it; Draco's
// edgebreaker reorders faces and points) with its corners' attributes within
// `tolerance`, and the triangle counts agree.
void checkSameTriangles(const Primitive& decoded, const KnownMesh& mesh, Tolerances tolerance) {
  REQUIRE(decoded.indices.size() == mesh.indices.size());
  REQUIRE(decoded.normals.size() == decoded.positions.size());
  REQUIRE(decoded.texcoords.size() == decoded.positions.size());
  std::vector<bool> used(mesh.indices.size() / 3, false);
  std::size_t matched = 0;
  for (std::size_t t = 0; t < decoded.indices.size(); t += 3) {
    bool found = false;
    for (std::size_t s = 0; s < used.size() && !found; ++s) {
      for (std::size_t rotation = 0; rotation < 3 && !found && !used[s]; ++rotation) {
        bool same = true;
        for (std::size_t corner = 0; corner < 3 && same; ++corner) {
          const std::uint32_t d = decoded.indices[t + corner];
          const std::uint16_t o = mesh.indices[s * 3 + (corner + rotation) % 3];
          same = distance(decoded.positions[d], mesh.positions[o]) <= tolerance.position &&
                 distance(decoded.normals[d], mesh.normals[o]) <= tolerance.normal &&
                 glm::length(decoded.texcoords[d] - mesh.uvs[o]) <= tolerance.uv;
        }
        if (same) found = used[s] = true;
      }
    }
    matched += found ? 1 : 0;
  }
  CHECK(matched == mesh.indices.size() / 3);
}

}  // namespace

TEST_CASE("Draco: the header's counts are read without decoding" * doctest::skip(!compressed::kDracoAvailable)) {
  const KnownMesh mesh = compressed::torus();
  for (const bool edgebreaker : {false, true}) {
    CAPTURE(edgebreaker);
    const std::vector<unsigned char> stream = compressed::dracoStream(mesh, edgebreaker);
    gltf::DracoCounts counts;
    CHECK(gltf::peekDracoCounts(stream, counts) == "");
    CHECK(counts.faces == 256);
    CHECK(counts.vertices >= 17 * 8);  // the torus' distinct positions at least
    CHECK(counts.vertices <= 3 * 256);
    // Cut inside the counts: named, not read past the end.
    CHECK(gltf::peekDracoCounts(std::span(stream).first(12), counts) == "ends inside its Draco header");
  }
  gltf::DracoCounts counts;
  const std::vector<unsigned char> garbage(64, 0x41);
  CHECK(gltf::peekDracoCounts(garbage, counts).find("not a Draco stream") != std::string::npos);
}

TEST_CASE("Draco: decoded positions, normals, uvs and indices match the source mesh" *
          doctest::skip(!compressed::kDracoAvailable)) {
  const KnownMesh mesh = compressed::torus();
  TempFolder folder("draco");
  for (const bool edgebreaker : {false, true}) {
    CAPTURE(edgebreaker);
    const auto path = folder.write(edgebreaker ? "edgebreaker.gltf" : "sequential.gltf",
                                   compressed::dracoGltf(mesh, edgebreaker).dump());
    const Scene scene = loadScene(path.string());
    CHECK(scene.ignored.empty());
    // 14 bits over the torus' 2.8 extent: 1.7e-4; 10-bit normals; 12-bit uvs over 0..1.
    checkSameTriangles(onlyPrimitive(scene), mesh, {1e-3f, 2e-2f, 1e-3f});
  }
}

TEST_CASE("Draco: the stated counts are bounded by max-triangles before decoding" *
          doctest::skip(!compressed::kDracoAvailable)) {
  TempFolder folder("draco-limit");
  const auto path = folder.write("torus.gltf", compressed::dracoGltf(compressed::torus()).dump());
  ResourceLimits limits;
  limits.maxTriangles = 200;
  try {
    (void)loadScene(path.string(), {}, limits);
    FAIL("expected a LimitError");
  } catch (const LimitError& error) {
    const std::string message = error.what();
    CHECK(message.find("mesh 0 primitive 0 KHR_draco_mesh_compression") != std::string::npos);
    CHECK(message.find("states 256 faces") != std::string::npos);
    CHECK(message.find("max-triangles") != std::string::npos);
  }
}

TEST_CASE("Draco used but not required: the stream is decoded over the fallback accessors" *
          doctest::skip(!compressed::kDracoAvailable)) {
  const KnownMesh mesh = compressed::torus();
  // The plain file's accessors with bufferViews, plus the Draco stream in buffer 1.
  json document = compressed::plainGltf(mesh);
  const json draco = compressed::dracoGltf(mesh);
  document["buffers"].push_back(draco["buffers"][0]);
  document["bufferViews"].push_back({{"buffer", 1}, {"byteLength", draco["bufferViews"][0]["byteLength"]}});
  document["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"] = {
      {"bufferView", 4}, {"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}}}};
  document["extensionsUsed"] = {"KHR_draco_mesh_compression"};
  TempFolder folder("draco-fallback");
  const Scene scene = loadScene(folder.write("fallback.gltf", document.dump()).string());
  CHECK(scene.ignored.empty());
  checkSameTriangles(onlyPrimitive(scene), mesh, {1e-3f, 2e-2f, 1e-3f});
}

TEST_CASE("meshopt: decoded streams match the source mesh (octahedral normals, placeholder buffer)" *
          doctest::skip(!compressed::kMeshoptAvailable)) {
  const KnownMesh mesh = compressed::torus();
  TempFolder folder("meshopt");
  const Scene scene = loadScene(folder.write("torus.glb", compressed::meshoptGlb(mesh)).string());
  CHECK(scene.ignored.empty());
  const Primitive& decoded = onlyPrimitive(scene);
  // The codecs are lossless and keep the order: positions, uvs exact, each
  // triangle the same (the index codec may rotate its corners, keeping the
  // winding); normals through the 8-bit octahedral filter.
  REQUIRE(decoded.positions.size() == mesh.positions.size());
  CHECK(std::equal(decoded.positions.begin(), decoded.positions.end(), mesh.positions.begin()));
  CHECK(std::equal(decoded.texcoords.begin(), decoded.texcoords.end(), mesh.uvs.begin()));
  REQUIRE(decoded.indices.size() == mesh.indices.size());
  std::size_t sameTriangles = 0;
  for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
    for (std::size_t rotation = 0; rotation < 3; ++rotation) {
      sameTriangles += decoded.indices[t] == mesh.indices[t + rotation] &&
                       decoded.indices[t + 1] == mesh.indices[t + (rotation + 1) % 3] &&
                       decoded.indices[t + 2] == mesh.indices[t + (rotation + 2) % 3];
    }
  }
  CHECK(sameTriangles == mesh.indices.size() / 3);
  float worst = 0.0f;
  for (std::size_t i = 0; i < mesh.normals.size(); ++i) worst = std::max(worst, distance(decoded.normals[i], mesh.normals[i]));
  CHECK(worst < 0.03f);
}

TEST_CASE("meshopt used but not required over real fallback data: the streams are decoded" *
          doctest::skip(!compressed::kMeshoptAvailable)) {
  const KnownMesh mesh = compressed::torus();
  json document;
  (void)compressed::meshoptGlb(mesh, &document);
  // Buffer 1 becomes real (zeroed) data: were it drawn, the torus would collapse.
  const std::size_t bytes = document["buffers"][1]["byteLength"];
  document["buffers"][1]["uri"] = "data:application/octet-stream;base64," + std::string((bytes + 2) / 3 * 4, 'A');
  document["buffers"][1]["byteLength"] = (bytes + 2) / 3 * 3;
  document["extensionsRequired"] = {"KHR_mesh_quantization"};
  TempFolder folder("meshopt-fallback");
  const Scene scene = loadScene(folder.write("torus.glb", compressed::packMeshoptGlb(document, mesh)).string());
  const Primitive& decoded = onlyPrimitive(scene);
  CHECK(std::equal(decoded.positions.begin(), decoded.positions.end(), mesh.positions.begin()));
}

TEST_CASE("meshopt: decoded bytes are bounded by max-memory before allocation" *
          doctest::skip(!compressed::kMeshoptAvailable)) {
  const KnownMesh mesh = compressed::torus();
  json document;
  (void)compressed::meshoptGlb(mesh, &document);
  // count x byteStride: 2^26 x 12 = 768 MiB, with the parent's byteLength to match.
  auto& view = document["bufferViews"][0];
  view["extensions"]["EXT_meshopt_compression"]["count"] = std::size_t(1) << 26;
  view["byteLength"] = (std::size_t(1) << 26) * 12;
  TempFolder folder("meshopt-limit");
  const auto path = folder.write("big.glb", compressed::packMeshoptGlb(document, mesh));
  ResourceLimits limits;
  limits.maxMemoryMiB = 256;
  try {
    (void)loadScene(path.string(), {}, limits);
    FAIL("expected a LimitError");
  } catch (const LimitError& error) {
    const std::string message = error.what();
    CHECK(message.find("bufferView 0 EXT_meshopt_compression decodes to 805306368 bytes") != std::string::npos);
    CHECK(message.find("max-memory") != std::string::npos);
  }
}
