#include "gltf/pose.hpp"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <map>
#include <span>
#include <type_traits>

#include "gltf/geometry.hpp"

namespace headlight::gltf {

namespace {

bool finite(const glm::vec4& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && std::isfinite(v.w);
}
bool finite(const glm::vec3& v) { return finite(glm::vec4(v, 0.0f)); }

template <int N>
void requireFinite(const Source& source, const std::vector<glm::vec<N, float>>& values, const std::string& what) {
  for (std::size_t element = 0; element < values.size(); ++element) {
    glm::vec4 padded(0.0f);
    for (int c = 0; c < N; ++c) padded[c] = values[element][c];
    if (!finite(padded)) {
      source.fail(what + " has a non-finite value at element " + std::to_string(element));
    }
  }
}

int targetAccessor(const std::map<std::string, int>& target, const char* attribute) {
  const auto found = target.find(attribute);
  return found == target.end() ? -1 : found->second;
}

}  // namespace

std::vector<float> morphWeights(const Source& source, int nodeIndex, int meshIndex) {
  const tinygltf::Node& node = source.model.nodes[static_cast<std::size_t>(nodeIndex)];
  const tinygltf::Mesh& mesh = source.model.meshes[static_cast<std::size_t>(meshIndex)];
  const bool fromNode = !node.weights.empty();
  const std::vector<double>& weights = fromNode ? node.weights : mesh.weights;
  std::vector<float> result;
  bool any = false;
  for (std::size_t k = 0; k < weights.size(); ++k) {
    if (!std::isfinite(weights[k])) {
      source.fail((fromNode ? "node " + std::to_string(nodeIndex) : "mesh " + std::to_string(meshIndex)) + " weight " +
                  std::to_string(k) + " is not finite");
    }
    result.push_back(static_cast<float>(weights[k]));
    any = any || weights[k] != 0.0;
  }
  return any ? result : std::vector<float>{};
}

void applyMorphTargets(const AccessorReader& accessors, const tinygltf::Primitive& source,
                       const std::string& primitiveName, const std::vector<float>& weights, Primitive& primitive) {
  if (weights.empty()) {
    return;
  }
  const Source& file = accessors.source();
  if (source.targets.size() != weights.size()) {
    file.fail(primitiveName + " has " + countOf(source.targets.size(), "morph target") + ", but its weights have " +
              countOf(weights.size(), "value"));
  }
  const std::size_t vertexCount = primitive.positions.size();
  const int positionAccessor = attributeAccessor(source, "POSITION");
  for (std::size_t k = 0; k < weights.size(); ++k) {
    const float weight = weights[k];
    if (weight == 0.0f) continue;
    const auto& target = source.targets[k];
    const std::string name = primitiveName + " target " + std::to_string(k);
    if (const int deltas = targetAccessor(target, "POSITION"); deltas >= 0) {
      const auto values =
          accessors.readAttribute<3>(deltas, name + " POSITION", kPositionDeltaFormats, vertexCount, positionAccessor);
      requireFinite(file, values, name + " POSITION accessor " + std::to_string(deltas));
      for (std::size_t v = 0; v < vertexCount; ++v) primitive.positions[v] += weight * values[v];
    }
    if (const int deltas = targetAccessor(target, "NORMAL"); deltas >= 0 && !primitive.normals.empty()) {
      const auto values =
          accessors.readAttribute<3>(deltas, name + " NORMAL", kDirectionDeltaFormats, vertexCount, positionAccessor);
      requireFinite(file, values, name + " NORMAL accessor " + std::to_string(deltas));
      for (std::size_t v = 0; v < vertexCount; ++v) primitive.normals[v] += weight * values[v];
    }
    if (const int deltas = targetAccessor(target, "TANGENT"); deltas >= 0 && !primitive.tangents.empty()) {
      const auto values =
          accessors.readAttribute<3>(deltas, name + " TANGENT", kDirectionDeltaFormats, vertexCount, positionAccessor);
      requireFinite(file, values, name + " TANGENT accessor " + std::to_string(deltas));
      for (std::size_t v = 0; v < vertexCount; ++v) {
        primitive.tangents[v] =
            glm::vec4(glm::vec3(primitive.tangents[v]) + weight * values[v], primitive.tangents[v].w);
      }
    }
  }
  for (std::size_t v = 0; v < vertexCount; ++v) {
    if (!finite(primitive.positions[v])) {
      file.fail(primitiveName + " morphed POSITION is not finite at vertex " + std::to_string(v));
    }
  }
}

std::vector<glm::mat4> jointMatrices(const AccessorReader& accessors, const NodeWalk& walk, int skinIndex) {
  const Source& source = accessors.source();
  const tinygltf::Skin& skin = source.model.skins[static_cast<std::size_t>(skinIndex)];
  const std::string name = "skin " + std::to_string(skinIndex);
  if (skin.joints.empty()) {
    source.fail(name + " has no joints");
  }
  // Not read (the joints' own nodes place them), but an index past the nodes is a malformed file.
  if (skin.skeleton != -1) {
    source.checkIndex(skin.skeleton, source.model.nodes, name + " skeleton", "node");
  }
  std::vector<glm::mat4> inverseBind(skin.joints.size(), glm::mat4(1.0f));  // glTF: identity when absent
  if (skin.inverseBindMatrices >= 0) {
    const CheckedAccessor accessor =
        accessors.check(skin.inverseBindMatrices, name + " inverseBindMatrices", kMatrixFormats);
    if (accessor.count != skin.joints.size()) {
      source.fail(name + " inverseBindMatrices accessor " + std::to_string(skin.inverseBindMatrices) + " has " +
                  countOf(accessor.count, "matrix") + ", but the skin has " + countOf(skin.joints.size(), "joint"));
    }
    inverseBind = accessors.readMatrices(accessor);
  }
  std::vector<glm::mat4> joints(skin.joints.size());
  for (std::size_t joint = 0; joint < skin.joints.size(); ++joint) {
    source.checkIndex(skin.joints[joint], source.model.nodes, name + " joint " + std::to_string(joint), "node");
    joints[joint] = walk.worldTransform(skin.joints[joint]) * inverseBind[joint];
    for (int column = 0; column < 4; ++column) {
      if (!finite(joints[joint][column])) {
        source.fail(name + " joint " + std::to_string(joint) + " has a non-finite matrix");
      }
    }
  }
  return joints;
}

void applySkin(const AccessorReader& accessors, const tinygltf::Primitive& source, const std::string& primitiveName,
               const std::vector<glm::mat4>& joints, Primitive& primitive) {
  const Source& file = accessors.source();
  const std::size_t vertexCount = primitive.positions.size();
  const int positionAccessor = attributeAccessor(source, "POSITION");
  std::vector<glm::mat4> skinning(vertexCount, glm::mat4(0.0f));
  std::vector<float> totals(vertexCount, 0.0f);
  for (int set = 0;; ++set) {
    const std::string jointsName = "JOINTS_" + std::to_string(set), weightsName = "WEIGHTS_" + std::to_string(set);
    const int jointsAccessor = attributeAccessor(source, jointsName.c_str());
    const int weightsAccessor = attributeAccessor(source, weightsName.c_str());
    if (jointsAccessor < 0 && weightsAccessor < 0) break;
    if (jointsAccessor < 0 || weightsAccessor < 0) {
      file.fail(primitiveName + " has " + (jointsAccessor < 0 ? weightsName : jointsName) + " without " +
                (jointsAccessor < 0 ? jointsName : weightsName));
    }
    const auto jointValues = accessors.readAttribute<4>(jointsAccessor, primitiveName + " " + jointsName, kJointFormats,
                                                        vertexCount, positionAccessor);
    const auto weightValues = accessors.readAttribute<4>(weightsAccessor, primitiveName + " " + weightsName,
                                                         kWeightFormats, vertexCount, positionAccessor);
    for (std::size_t v = 0; v < vertexCount; ++v) {
      for (int c = 0; c < 4; ++c) {
        const float weight = weightValues[v][c];
        if (!std::isfinite(weight) || weight < 0.0f) {
          file.fail(primitiveName + " " + weightsName + " accessor " + std::to_string(weightsAccessor) +
                    " has weight " + std::to_string(weight) + " at vertex " + std::to_string(v) +
                    ", expected finite and >= 0");
        }
        if (weight == 0.0f) continue;
        const auto joint = static_cast<std::size_t>(jointValues[v][c]);
        if (joint >= joints.size()) {
          file.fail(primitiveName + " " + jointsName + " accessor " + std::to_string(jointsAccessor) + " names joint " +
                    std::to_string(joint) + " at vertex " + std::to_string(v) + ", but the skin has " +
                    countOf(joints.size(), "joint"));
        }
        skinning[v] += weight * joints[joint];
        totals[v] += weight;
      }
    }
  }
  for (std::size_t v = 0; v < vertexCount; ++v) {
    // glTF asks weights to sum to 1; they are normalised, and a vertex with
    // none stays where it is.
    const glm::mat4 matrix = totals[v] > 0.0f ? skinning[v] / totals[v] : glm::mat4(1.0f);
    primitive.positions[v] = glm::vec3(matrix * glm::vec4(primitive.positions[v], 1.0f));
    if (!primitive.normals.empty()) {
      primitive.normals[v] = normalMatrix(matrix) * primitive.normals[v];
    }
    if (!primitive.tangents.empty()) {
      primitive.tangents[v] = glm::vec4(glm::mat3(matrix) * glm::vec3(primitive.tangents[v]), primitive.tangents[v].w);
    }
    if (!finite(primitive.positions[v])) {
      file.fail(primitiveName + " skinned POSITION is not finite at vertex " + std::to_string(v));
    }
  }
}

std::vector<glm::mat4> instanceTransforms(const AccessorReader& accessors, const Source& source, int nodeIndex,
                                          const std::function<void(std::size_t count)>& checkCount) {
  const tinygltf::Node& node = source.model.nodes[static_cast<std::size_t>(nodeIndex)];
  const auto extension = node.extensions.find("EXT_mesh_gpu_instancing");
  if (extension == node.extensions.end() || !extension->second.Has("attributes")) {
    return {};
  }
  const std::string name = "node " + std::to_string(nodeIndex) + " EXT_mesh_gpu_instancing";
  const tinygltf::Value& attributes = extension->second.Get("attributes");
  auto accessorOf = [&](const char* attribute) {
    if (!attributes.Has(attribute)) return -1;
    const tinygltf::Value& value = attributes.Get(attribute);
    if (!value.IsInt() && !value.IsNumber()) source.fail(name + " " + attribute + " is not an accessor index");
    return value.GetNumberAsInt();
  };
  std::size_t count = 0;
  auto read = [&](const char* attribute, std::span<const AccessorFormat> formats, auto tag) {
    constexpr int N = decltype(tag)::value;
    std::vector<glm::vec<N, float>> values;
    if (const int accessor = accessorOf(attribute); accessor >= 0) {
      const CheckedAccessor checked = accessors.check(accessor, name + " " + attribute, formats);
      if (count != 0 && checked.count != count) {
        source.fail(name + " " + attribute + " accessor " + std::to_string(accessor) + " has " +
                    countOf(checked.count, "element") + ", but the other attributes have " + std::to_string(count));
      }
      count = checked.count;
      checkCount(count);
      values = accessors.readFloats<N>(checked);
      requireFinite(source, values, name + " " + attribute + " accessor " + std::to_string(accessor));
    }
    return values;
  };
  const auto translations = read("TRANSLATION", kPositionFormats, std::integral_constant<int, 3>{});
  const auto rotations = read("ROTATION", kInstanceRotationFormats, std::integral_constant<int, 4>{});
  const auto scales = read("SCALE", kPositionFormats, std::integral_constant<int, 3>{});
  std::vector<glm::mat4> transforms(count, glm::mat4(1.0f));
  for (std::size_t i = 0; i < count; ++i) {
    glm::mat4 local(1.0f);
    if (!translations.empty()) local = glm::translate(local, translations[i]);
    if (!rotations.empty()) {
      const glm::vec4& r = rotations[i];  // x, y, z, w
      const float length = glm::length(r);
      if (!(length > 0.0f)) source.fail(name + " ROTATION " + std::to_string(i) + " is a zero quaternion");
      local *= glm::mat4_cast(glm::quat(r.w, r.x, r.y, r.z) / length);
    }
    if (!scales.empty()) local = glm::scale(local, scales[i]);
    transforms[i] = local;
  }
  return transforms;
}

}  // namespace headlight::gltf
