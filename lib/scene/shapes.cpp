#include "headlight/shapes.hpp"

#include <cmath>
#include <cstdint>

namespace headlight {
namespace {

constexpr float kPi = 3.14159265358979f;

void appendVertex(Primitive& primitive, const glm::vec3& position, const glm::vec3& normal, const glm::vec2& texcoord) {
  primitive.positions.push_back(position);
  primitive.normals.push_back(normal);
  primitive.texcoords.push_back(texcoord);
  primitive.bounds.extend(position);
}

void appendQuad(Primitive& primitive, const glm::vec3& corner, const glm::vec3& edgeU, const glm::vec3& edgeV) {
  const glm::vec3 normal = glm::normalize(glm::cross(edgeU, edgeV));
  const auto first = static_cast<std::uint32_t>(primitive.positions.size());
  appendVertex(primitive, corner, normal, {0.0f, 1.0f});
  appendVertex(primitive, corner + edgeU, normal, {1.0f, 1.0f});
  appendVertex(primitive, corner + edgeU + edgeV, normal, {1.0f, 0.0f});
  appendVertex(primitive, corner + edgeV, normal, {0.0f, 0.0f});
  for (std::uint32_t quadVertex : {0u, 1u, 2u, 0u, 2u, 3u}) {
    primitive.indices.push_back(first + quadVertex);
  }
}

}  // namespace

Primitive makeQuad(const glm::vec3& corner, const glm::vec3& edgeU, const glm::vec3& edgeV) {
  Primitive quad;
  appendQuad(quad, corner, edgeU, edgeV);
  return quad;
}

Primitive makeFloor(float halfSize) {
  return makeQuad({-halfSize, 0, -halfSize}, {0, 0, 2 * halfSize}, {2 * halfSize, 0, 0});
}

Primitive makeBox(const glm::vec3& size) {
  Primitive box;
  const glm::vec3 half = size * 0.5f;
  const glm::vec3 x{size.x, 0.0f, 0.0f}, y{0.0f, size.y, 0.0f}, z{0.0f, 0.0f, size.z};
  appendQuad(box, {-half.x, -half.y, half.z}, x, y);   // +Z
  appendQuad(box, {half.x, -half.y, -half.z}, -x, y);  // -Z
  appendQuad(box, {half.x, -half.y, half.z}, -z, y);   // +X
  appendQuad(box, {-half.x, -half.y, -half.z}, z, y);  // -X
  appendQuad(box, {-half.x, half.y, half.z}, x, -z);   // +Y
  appendQuad(box, {-half.x, -half.y, -half.z}, x, z);  // -Y
  return box;
}

Primitive makeUvSphere(float radius, int segments, int rings, const glm::vec3& center) {
  Primitive sphere;
  for (int ring = 0; ring <= rings; ++ring) {
    const float v = static_cast<float>(ring) / static_cast<float>(rings);
    const float polar = v * kPi;  // 0 at +Y
    for (int segment = 0; segment <= segments; ++segment) {
      const float u = static_cast<float>(segment) / static_cast<float>(segments);
      const float azimuth = u * 2.0f * kPi;
      const glm::vec3 normal{std::sin(polar) * std::sin(azimuth), std::cos(polar), std::sin(polar) * std::cos(azimuth)};
      appendVertex(sphere, center + normal * radius, normal, {u, v});
    }
  }
  const auto rowLength = static_cast<std::uint32_t>(segments + 1);
  for (std::uint32_t ring = 0; ring < static_cast<std::uint32_t>(rings); ++ring) {
    for (std::uint32_t segment = 0; segment < static_cast<std::uint32_t>(segments); ++segment) {
      const std::uint32_t topLeft = ring * rowLength + segment;
      const std::uint32_t bottomLeft = topLeft + rowLength;
      for (std::uint32_t index : {topLeft, bottomLeft, bottomLeft + 1, topLeft, bottomLeft + 1, topLeft + 1}) {
        sphere.indices.push_back(index);
      }
    }
  }
  return sphere;
}

Primitive makeSquare(const glm::vec3& center, const glm::vec3& normal, float halfSize) {
  // Two edges spanning the plane, ordered so that cross(edgeU, edgeV) = normal.
  const glm::vec3 helper = std::abs(normal.y) > 0.5f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  const glm::vec3 u = glm::normalize(glm::cross(helper, normal)) * halfSize;
  const glm::vec3 v = glm::normalize(glm::cross(normal, u)) * halfSize;
  return makeQuad(center - u - v, 2.0f * u, 2.0f * v);
}

}  // namespace headlight
