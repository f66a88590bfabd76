// Tangents for normal mapping when a file has none, following MikkTSpace's
// published description (Mikkelsen 2008, "Simulation of Wrinkled Surfaces
// Revisited"): each triangle corner gets the triangle's UV-gradient tangent
// projected into the plane of the corner's normal, weighted by the corner's
// angle; corners whose vertices agree in position, normal and UV and whose
// triangles agree in handedness are summed; the sum is orthonormalised
// against the normal, and w holds the handedness (glTF: bitangent =
// cross(normal, tangent.xyz) * w, pointing up the image). A vertex used with both handednesses is
// split in two, as MikkTSpace's per-corner output would be.
#include <algorithm>
#include <array>
#include <cstdint>
#include <cmath>
#include <map>

#include "headlight/scene_loader.hpp"

namespace headlight {

namespace {

// Below this |dU1 dV2 - dU2 dV1| a triangle's UVs are degenerate (zero UV
// area): it has no tangent direction to give.
constexpr float kMinUvArea = 1e-20f;

// A unit vector perpendicular to `normal`, for vertices no triangle gives a
// tangent (all their triangles have degenerate UVs).
glm::vec3 anyPerpendicular(const glm::vec3& normal) {
  const glm::vec3 axis = std::abs(normal.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  return glm::normalize(axis - normal * glm::dot(normal, axis));
}

float cornerAngle(const glm::vec3& at, const glm::vec3& a, const glm::vec3& b) {
  const glm::vec3 u = a - at, v = b - at;
  const float lengths = glm::length(u) * glm::length(v);
  return lengths > 0.0f ? std::acos(glm::clamp(glm::dot(u, v) / lengths, -1.0f, 1.0f)) : 0.0f;
}

// The vertex attributes MikkTSpace compares, and the handedness.
using VertexKey = std::array<float, 9>;

}  // namespace

void generateTangents(Primitive& primitive) { generateTangents(primitive, TextureRef{}); }

void generateTangents(Primitive& primitive, const TextureRef& normalMap) {
  const std::size_t vertexCount = primitive.positions.size();
  const std::vector<glm::vec2>& set = normalMap.texCoord == 1 ? primitive.texcoords1 : primitive.texcoords;
  if (primitive.normals.size() != vertexCount || set.size() != vertexCount) {
    return;
  }
  // The UVs the normal map is sampled at: a transformed map's tangent space
  // turns with its UVs.
  std::vector<glm::vec2> uvs = set;
  if (!normalMap.transform.identity()) {
    for (glm::vec2& uv : uvs) uv = normalMap.transform.apply(uv);
  }
  const std::size_t cornerCount = primitive.indices.size();
  // Group of each (welded vertex, handedness), its angle-weighted sum.
  std::map<std::pair<VertexKey, bool>, std::size_t> groupOf;
  std::vector<glm::vec3> sums;
  std::vector<std::size_t> cornerGroup(cornerCount, SIZE_MAX);
  std::vector<char> cornerFlipped(cornerCount, 0);
  for (std::size_t corner = 0; corner + 2 < cornerCount; corner += 3) {
    const std::uint32_t i[3] = {primitive.indices[corner], primitive.indices[corner + 1], primitive.indices[corner + 2]};
    const glm::vec3 e1 = primitive.positions[i[1]] - primitive.positions[i[0]];
    const glm::vec3 e2 = primitive.positions[i[2]] - primitive.positions[i[0]];
    const glm::vec2 d1 = uvs[i[1]] - uvs[i[0]];
    const glm::vec2 d2 = uvs[i[2]] - uvs[i[0]];
    const float uvArea = d1.x * d2.y - d2.x * d1.y;
    if (!(std::abs(uvArea) > kMinUvArea)) continue;
    // The directions of increasing u and v on the triangle's plane.
    const glm::vec3 tangent = (e1 * d2.y - e2 * d1.y) / uvArea;
    const glm::vec3 bitangent = (e2 * d1.x - e1 * d2.x) / uvArea;
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t v = i[c];
      const glm::vec3& normal = primitive.normals[v];
      glm::vec3 projected = tangent - normal * glm::dot(normal, tangent);
      const float length = glm::length(projected);
      if (!(length > 0.0f) || !std::isfinite(length)) continue;
      projected /= length;
      // glTF's v runs down the image and MikkTSpace's up: w = +1 when
      // cross(normal, tangent) points up the image, toward decreasing v, as
      // the tangents in the Khronos sample models (NormalTangentMirrorTest) do.
      const bool flipped = glm::dot(glm::cross(normal, tangent), bitangent) > 0.0f;
      const glm::vec3& p = primitive.positions[v];
      const glm::vec2& uv = uvs[v];
      const VertexKey key{p.x, p.y, p.z, normal.x, normal.y, normal.z, uv.x, uv.y, 0.0f};
      auto [group, inserted] = groupOf.try_emplace({key, flipped}, sums.size());
      if (inserted) sums.emplace_back(0.0f);
      const float angle = cornerAngle(p, primitive.positions[i[(c + 1) % 3]], primitive.positions[i[(c + 2) % 3]]);
      // A zero-angle corner still votes a little, so a sliver's vertex gets a direction.
      sums[group->second] += std::max(angle, 1e-6f) * projected;
      cornerGroup[corner + static_cast<std::size_t>(c)] = group->second;
      cornerFlipped[corner + static_cast<std::size_t>(c)] = flipped;
    }
  }
  primitive.tangents.assign(vertexCount, glm::vec4(0.0f));
  std::vector<char> assigned(vertexCount, 0);
  std::map<std::pair<std::uint32_t, std::size_t>, std::uint32_t> split;  // (vertex, group) -> new vertex
  for (std::size_t corner = 0; corner < cornerCount; ++corner) {
    if (cornerGroup[corner] == SIZE_MAX) continue;
    const std::uint32_t v = primitive.indices[corner];
    const glm::vec3& normal = primitive.normals[v];
    glm::vec3 sum = sums[cornerGroup[corner]];
    sum -= normal * glm::dot(normal, sum);
    const float length = glm::length(sum);
    const glm::vec3 unit = length > 0.0f && std::isfinite(length) ? sum / length : anyPerpendicular(normal);
    const glm::vec4 tangent(unit, cornerFlipped[corner] ? -1.0f : 1.0f);
    if (!assigned[v]) {
      assigned[v] = 1;
      primitive.tangents[v] = tangent;
    } else if (primitive.tangents[v].w != tangent.w) {
      // Both handednesses meet at this vertex: the other one gets a copy.
      auto [copy, inserted] = split.try_emplace({v, cornerGroup[corner]}, std::uint32_t(primitive.positions.size()));
      if (inserted) {
        primitive.positions.push_back(primitive.positions[v]);
        primitive.normals.push_back(primitive.normals[v]);
        if (!primitive.texcoords.empty()) primitive.texcoords.push_back(primitive.texcoords[v]);
        if (!primitive.texcoords1.empty()) primitive.texcoords1.push_back(primitive.texcoords1[v]);
        if (!primitive.colors.empty()) primitive.colors.push_back(primitive.colors[v]);
        primitive.tangents.push_back(tangent);
      }
      primitive.indices[corner] = copy->second;
    }
  }
  for (std::size_t v = 0; v < vertexCount; ++v) {
    if (!assigned[v]) primitive.tangents[v] = glm::vec4(anyPerpendicular(primitive.normals[v]), 1.0f);
  }
}

}  // namespace headlight
