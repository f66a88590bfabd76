// Scene queries and normal generation: the parts of the scene model that are
// plain geometry, shared by the glTF loader and the built-in scenes.
#include "headlight/scene.hpp"

#include <cmath>
#include <cstddef>
#include <cstdio>

#include "headlight/scene_loader.hpp"

namespace headlight {

namespace {

bool isFinite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Normalises `sum`, dividing by its largest component first so that sums
// near float's range neither overflow nor underflow in the length. A vertex
// no usable triangle touches (or whose faces cancel) gets +Z, the documented
// fallback, rather than a NaN that the shader would spread.
glm::vec3 unitOrPlusZ(const glm::vec3& sum) {
  const float largest = glm::max(glm::abs(sum.x), glm::max(glm::abs(sum.y), glm::abs(sum.z)));
  if (!(largest > 0.0f) || !std::isfinite(largest)) {
    return {0.0f, 0.0f, 1.0f};
  }
  const glm::vec3 unit = glm::normalize(sum / largest);
  return isFinite(unit) ? unit : glm::vec3(0.0f, 0.0f, 1.0f);
}

}  // namespace

std::string IgnoredFeature::describe() const {
  if (noun.empty()) {
    return feature + (first.empty() ? "" : " (" + first + ")") + " " + effect;
  }
  const std::string counted = std::to_string(count) + " " + noun + (count == 1 ? "" : "s");
  // A feature that is its own element ("animation") is counted, not repeated.
  if (feature == noun) {
    const bool plural = count != 1 && effect.rfind("is ", 0) == 0;
    return counted + " (first: " + first + ") " + (plural ? "are " + effect.substr(3) : effect);
  }
  return feature + " on " + counted + " (first: " + first + ") " + effect;
}

Bounds Bounds::transformed(const glm::mat4& transform) const {
  Bounds result;
  if (empty()) {
    return result;
  }
  for (int corner = 0; corner < 8; ++corner) {
    const glm::vec3 local{(corner & 1) ? max.x : min.x, (corner & 2) ? max.y : min.y, (corner & 4) ? max.z : min.z};
    result.extend(glm::vec3(transform * glm::vec4(local, 1.0f)));
  }
  return result;
}

std::string Scene::poseDescription() const {
  if (animation < 0 || std::size_t(animation) >= animations.size()) return {};
  char seconds[32];
  std::snprintf(seconds, sizeof seconds, "%g", double(animationTime));
  const std::string& name = animations[std::size_t(animation)].name;
  return "animation " + std::to_string(animation) + (name.empty() ? "" : " '" + name + "'") + " at " + seconds + " s";
}

Bounds Scene::worldBounds() const {
  Bounds world;
  for (const Instance& instance : instances) {
    world.extend(primitives[instance.primitive].bounds.transformed(instance.worldFromLocal));
  }
  return world;
}

bool Scene::hasEmissive() const {
  for (const Instance& instance : instances) {
    const int material = instance.material;
    if (material >= 0 && materials[material].emissive()) {
      return true;
    }
  }
  return false;
}

bool Scene::hasBlended() const {
  for (const Instance& instance : instances)
    if (instance.material >= 0 && std::size_t(instance.material) < materials.size() &&
        materials[std::size_t(instance.material)].blended())
      return true;
  return false;
}

std::size_t Scene::triangleCount() const {
  std::size_t triangles = 0;
  for (const Instance& instance : instances) {
    const Primitive& primitive = primitives[instance.primitive];
    if (primitive.mode == PrimitiveMode::Triangles) triangles += primitive.indices.size() / 3;
  }
  return triangles;
}

void generateNormals(Primitive& primitive) {
  const std::vector<glm::vec3>& positions = primitive.positions;
  const std::vector<std::uint32_t>& indices = primitive.indices;
  // The unnormalised cross product has length twice the triangle's area, so
  // summing it weights each face by its area without a separate multiply.
  std::vector<glm::vec3> weightedSum(positions.size(), glm::vec3(0.0f));
  for (std::size_t first = 0; first + 2 < indices.size(); first += 3) {
    const std::uint32_t a = indices[first], b = indices[first + 1], c = indices[first + 2];
    if (a >= positions.size() || b >= positions.size() || c >= positions.size()) {
      continue;  // the loader rejects these; a hand-built primitive may not
    }
    const glm::vec3 faceNormal = glm::cross(positions[b] - positions[a], positions[c] - positions[a]);
    // Degenerate and NaN/inf triangles would poison every vertex they touch.
    if (!isFinite(faceNormal) || faceNormal == glm::vec3(0.0f)) {
      continue;
    }
    weightedSum[a] += faceNormal;
    weightedSum[b] += faceNormal;
    weightedSum[c] += faceNormal;
  }
  primitive.normals.resize(positions.size());
  for (std::size_t vertex = 0; vertex < positions.size(); ++vertex) {
    primitive.normals[vertex] = unitOrPlusZ(weightedSum[vertex]);
  }
}

glm::mat3 normalMatrix(const glm::mat4& worldFromLocal) {
  const glm::mat3 linear(worldFromLocal);
  const glm::mat3 cofactor(glm::cross(linear[1], linear[2]), glm::cross(linear[2], linear[0]),
                           glm::cross(linear[0], linear[1]));
  // cofactor = det * inverse transpose: flip a mirror's sign back so normals
  // keep pointing out of the surface.
  return glm::determinant(linear) < 0.0f ? -cofactor : cofactor;
}

bool mirrors(const glm::mat4& worldFromLocal) { return glm::determinant(glm::mat3(worldFromLocal)) < 0.0f; }

}  // namespace headlight
