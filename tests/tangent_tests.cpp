// Generated tangents, by MikkTSpace's rules, on hand-computed quads.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <string>
#include <vector>

#include "headlight/camera.hpp"
#include "headlight/error.hpp"
#include "headlight/scene_loader.hpp"
#include "support/assets.hpp"
#include "support/encoding.hpp"
#include "gltf_test_files.hpp"
#include "support/temp_folder.hpp"

namespace fs = std::filesystem;
using namespace headlight;
using namespace headlight::test;

namespace {

// A unit quad in the XY plane facing +Z, two triangles, with `uvs`.
Primitive quad(const std::vector<glm::vec2>& uvs) {
  Primitive primitive;
  primitive.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  primitive.normals.assign(4, glm::vec3(0, 0, 1));
  primitive.texcoords = uvs;
  primitive.indices = {0, 1, 2, 0, 2, 3};
  return primitive;
}

bool near4(const glm::vec4& a, const glm::vec4& b) {
  return glm::all(glm::lessThanEqual(glm::abs(a - b), glm::vec4(1e-5f)));
}

}  // namespace

TEST_CASE("tangents: a quad's tangent follows +u, with w = +1 when v runs down the image as glTF's does") {
  // Seen from +Z: u along +X, v along -Y (top-left UV origin, as glTF's).
  Primitive primitive = quad({{0, 1}, {1, 1}, {1, 0}, {0, 0}});
  generateTangents(primitive);
  REQUIRE(primitive.tangents.size() == 4);
  for (const glm::vec4& tangent : primitive.tangents) CHECK(near4(tangent, {1, 0, 0, 1}));
  // v along +Y instead: the bitangent cross(N, T) w must point up the image (-Y), so w = -1.
  Primitive flippedV = quad({{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  generateTangents(flippedV);
  for (const glm::vec4& tangent : flippedV.tangents) CHECK(near4(tangent, {1, 0, 0, -1}));
}

TEST_CASE("tangents: a mirrored-UV quad has w = -1, and a seam between mirrored halves splits its vertices") {
  Primitive mirrored = quad({{1, 1}, {0, 1}, {0, 0}, {1, 0}});  // u runs along -X
  generateTangents(mirrored);
  REQUIRE(mirrored.tangents.size() == 4);
  for (const glm::vec4& tangent : mirrored.tangents) CHECK(near4(tangent, {-1, 0, 0, -1}));

  // Two quads sharing the edge x = 1, the second with u mirrored (as a
  // symmetric model's UVs are): the shared vertices get one tangent per side.
  Primitive seam;
  seam.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}, {2, 1, 0}};
  seam.normals.assign(6, glm::vec3(0, 0, 1));
  seam.texcoords = {{0, 1}, {1, 1}, {1, 0}, {0, 0}, {0, 1}, {0, 0}};
  seam.indices = {0, 1, 2, 0, 2, 3, 1, 4, 5, 1, 5, 2};
  generateTangents(seam);
  CHECK(seam.positions.size() == 8);  // vertices 1 and 2 split
  CHECK(seam.tangents.size() == 8);
  for (std::size_t corner = 0; corner < seam.indices.size(); ++corner) {
    const glm::vec4& tangent = seam.tangents[seam.indices[corner]];
    CAPTURE(corner);
    CHECK(near4(tangent, corner < 6 ? glm::vec4(1, 0, 0, 1) : glm::vec4(-1, 0, 0, -1)));
  }
}

TEST_CASE("tangents: a vertex whose triangles have no UV area gets a unit tangent perpendicular to its normal") {
  Primitive primitive = quad({{0.5f, 0.5f}, {0.5f, 0.5f}, {0.5f, 0.5f}, {0.5f, 0.5f}});
  generateTangents(primitive);
  for (const glm::vec4& tangent : primitive.tangents) {
    CHECK(std::abs(glm::length(glm::vec3(tangent)) - 1.0f) < 1e-5f);
    CHECK(std::abs(glm::dot(glm::vec3(tangent), glm::vec3(0, 0, 1))) < 1e-5f);
  }
}
