#include "gltf/animation_pose.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <span>
#include <string_view>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "gltf/accessors.hpp"

namespace headlight::gltf {

namespace {

constexpr AccessorFormat kTimeFormats[]{{TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_SCALAR, false}};
// glTF 2.0's sampler output table (3.11): rotations and morph weights float
// or normalized integers. Translations and scales take the integer formats
// KHR_mesh_quantization adds (the quantized positions' table).
constexpr AccessorFormat kRotationFormats[]{kFloatVec4,
                                            {TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_TYPE_VEC4, true},
                                            {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_TYPE_VEC4, true},
                                            {TINYGLTF_COMPONENT_TYPE_SHORT, TINYGLTF_TYPE_VEC4, true},
                                            {TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_VEC4, true}};
constexpr AccessorFormat kMorphWeightFormats[]{{TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_SCALAR, false},
                                               {TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_TYPE_SCALAR, true},
                                               {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_TYPE_SCALAR, true},
                                               {TINYGLTF_COMPONENT_TYPE_SHORT, TINYGLTF_TYPE_SCALAR, true},
                                               {TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_SCALAR, true}};

// One row per animated property a channel's target.path names.
struct AnimatedPath {
  std::string_view name;
  int components;  // per accessor element
  std::span<const AccessorFormat> formats;
  std::array<float, 4> rest;  // glTF's default where the node gives none (weights: zeros)
};
constexpr AnimatedPath kPaths[]{
    {"translation", 3, kQuantizedPositionFormats, {0.0f, 0.0f, 0.0f, 0.0f}},
    {"rotation", 4, kRotationFormats, {0.0f, 0.0f, 0.0f, 1.0f}},
    {"scale", 3, kQuantizedPositionFormats, {1.0f, 1.0f, 1.0f, 0.0f}},
    {"weights", 1, kMorphWeightFormats, {0.0f, 0.0f, 0.0f, 0.0f}},
};

const AnimatedPath* findPath(const std::string& name) {
  const auto row =
      std::find_if(std::begin(kPaths), std::end(kPaths), [&](const AnimatedPath& p) { return p.name == name; });
  return row == std::end(kPaths) ? nullptr : row;
}

// Elements [first, first + count) of `accessor` (checked to hold them), not
// the rest: an accessor with no bufferView (zeros plus sparse values) may
// claim any count, so reading it whole could allocate without bound. Memory
// is count elements plus the sparse indices, which lie in the file.
template <int N>
std::vector<float> elementsOf(const AccessorReader& reader, const CheckedAccessor& accessor, std::size_t first,
                              std::size_t count) {
  CheckedAccessor window = accessor;
  window.count = count;
  window.sparseCount = 0;
  if (window.data != nullptr) window.data += first * accessor.stride;
  std::vector<glm::vec<N, float>> values = reader.readFloats<N>(window);
  if (accessor.sparseCount != 0) {
    const auto indexSize =
        static_cast<std::size_t>(tinygltf::GetComponentSizeInBytes(std::uint32_t(accessor.sparseIndexComponentType)));
    CheckedAccessor indices;
    indices.index = accessor.index;
    indices.data = accessor.sparseIndices;
    indices.stride = indices.elementSize = indexSize;
    indices.count = accessor.sparseCount;
    indices.componentType = accessor.sparseIndexComponentType;
    const std::vector<std::uint32_t> targets = reader.readIndices(indices);
    for (std::size_t k = 0; k < targets.size(); ++k) {
      if (targets[k] >= accessor.count) {
        reader.source().fail("accessor " + std::to_string(accessor.index) + " sparse index " + std::to_string(k) +
                             " is " + std::to_string(targets[k]) + ", expected < count " +
                             std::to_string(accessor.count));
      }
      if (targets[k] < first || targets[k] - first >= count) continue;
      CheckedAccessor value = window;
      value.data = accessor.sparseValues + k * accessor.elementSize;
      value.stride = accessor.elementSize;
      value.count = 1;
      values[targets[k] - first] = reader.readFloats<N>(value)[0];
    }
  }
  std::vector<float> flat;
  for (const auto& value : values) {
    for (int c = 0; c < N; ++c) flat.push_back(value[c]);
  }
  return flat;
}

// Elements [first, first + count) of an output accessor with `components`
// floats each, flattened.
std::vector<float> outputElements(const AccessorReader& reader, const CheckedAccessor& output, int components,
                                  std::size_t first, std::size_t count) {
  switch (components) {
    case 1:
      return elementsOf<1>(reader, output, first, count);
    case 3:
      return elementsOf<3>(reader, output, first, count);
    default:
      return elementsOf<4>(reader, output, first, count);
  }
}

// The value the sampler's output holds at its first input time: elements
// [0, perKeyframe), or for CUBICSPLINE (in-tangent, value, out-tangent per
// keyframe) [perKeyframe, 2 perKeyframe). Output and input counts must agree.
std::vector<float> firstKeyframe(const AccessorReader& reader, const tinygltf::AnimationSampler& sampler,
                                 const AnimatedPath& path, std::size_t perKeyframe) {
  const CheckedAccessor input = reader.check(sampler.input, "sampler input", kTimeFormats);
  const float firstTime = elementsOf<1>(reader, input, 0, 1)[0];
  const CheckedAccessor output = reader.check(sampler.output, "sampler output", path.formats);
  const std::size_t perInput = (sampler.interpolation == "CUBICSPLINE" ? 3 : 1) * perKeyframe;
  if (!std::isfinite(firstTime) || output.count / perInput != input.count || output.count % perInput != 0) {
    reader.source().fail("sampler output count does not match its input");
  }
  const std::size_t first = sampler.interpolation == "CUBICSPLINE" ? perKeyframe : 0;
  return outputElements(reader, output, path.components, first, perKeyframe);
}

// The static value: the node's own, else glTF's default; for weights the
// node's, else the mesh's, else zeros, one per morph target.
std::vector<float> staticValue(const Source& source, const tinygltf::Node& node, const AnimatedPath& path) {
  if (path.name != "weights") {
    const std::vector<double>& given = path.name == "translation" ? node.translation
                                       : path.name == "rotation"  ? node.rotation
                                                                  : node.scale;
    if (given.empty()) return {path.rest.begin(), path.rest.begin() + path.components};
    return {given.begin(), given.end()};
  }
  source.checkIndex(node.mesh, source.model.meshes, "weights channel's node", "mesh");
  const tinygltf::Mesh& mesh = source.model.meshes[std::size_t(node.mesh)];
  const std::size_t targets = mesh.primitives.empty() ? 0 : mesh.primitives[0].targets.size();
  const std::vector<double>& given = !node.weights.empty() ? node.weights : mesh.weights;
  if (given.empty()) return std::vector<float>(targets, 0.0f);
  if (given.size() != targets) return {};  // the loader refuses such a mesh; here it differs
  return {given.begin(), given.end()};
}

// Half a step of a normalized integer format (what quantizing the pose can
// change), 0 for floats and plain integers.
float quantum(int componentType, bool normalized) {
  if (!normalized) return 0.0f;
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
      return 0.5f / 127.0f;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 0.5f / 255.0f;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
      return 0.5f / 32767.0f;
    default:
      return 0.5f / 65535.0f;
  }
}

// Equal within 1e-5 of the larger magnitude (1e-5 absolute near zero), or
// half a step of a normalized format. A float keeps 2^-24 = 6e-8 of its
// value, and exporters that recompose transforms add a few such steps: 1e-5
// is far above that and far below anything visible (10 micrometres at 1 m).
bool same(const std::vector<float>& keyframe, const std::vector<float>& pose, float step, float sign = 1.0f) {
  if (keyframe.size() != pose.size()) return false;
  for (std::size_t i = 0; i < pose.size(); ++i) {
    const float a = sign * keyframe[i], b = pose[i];
    const float tolerance = std::max(1e-5f * std::max({1.0f, std::abs(a), std::abs(b)}), step);
    if (!std::isfinite(a) || !(std::abs(a - b) <= tolerance)) return false;
  }
  return true;
}

bool channelDiffers(const AccessorReader& reader, const tinygltf::Animation& animation,
                    const tinygltf::AnimationChannel& channel) {
  const Source& source = reader.source();
  source.checkIndex(channel.sampler, animation.samplers, "channel", "sampler");
  source.checkIndex(channel.target_node, source.model.nodes, "channel", "node");  // -1: an extension's target
  const tinygltf::Node& node = source.model.nodes[std::size_t(channel.target_node)];
  const AnimatedPath* path = findPath(channel.target_path);
  if (path == nullptr || !node.matrix.empty()) return true;  // glTF forbids animating a node with a matrix
  const std::vector<float> pose = staticValue(source, node, *path);
  const std::size_t perKeyframe = path->components == 1 ? pose.size() : 1;
  if (pose.empty() || pose.size() != perKeyframe * std::size_t(path->components)) return true;
  const tinygltf::AnimationSampler& sampler = animation.samplers[std::size_t(channel.sampler)];
  const std::vector<float> keyframe = firstKeyframe(reader, sampler, *path, perKeyframe);
  const tinygltf::Accessor& output = source.model.accessors[std::size_t(sampler.output)];
  const float step =
      quantum(output.componentType, output.normalized && output.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT);
  const bool rotation = path->name == "rotation";
  return !same(keyframe, pose, step) && !(rotation && same(keyframe, pose, step, -1.0f));
}

// Where `time` falls among a sampler's keyframe times: keyframe `index` and
// the share `s` of the way to the next (0 before the first keyframe and at
// or after the last, where `index` is the last), and the interval's length.
struct KeyframeSpan {
  std::size_t index = 0;
  float s = 0.0f;
  float interval = 0.0f;
};

KeyframeSpan findKeyframes(const AccessorReader& reader, const CheckedAccessor& input, double time,
                           const std::string& who) {
  auto timeAt = [&](std::size_t k) {
    const float t = elementsOf<1>(reader, input, k, 1)[0];
    if (!std::isfinite(t)) reader.source().fail(who + ": keyframe time " + std::to_string(k) + " is not finite");
    return double(t);
  };
  const std::size_t last = input.count - 1;
  if (time <= timeAt(0)) return {};
  if (time >= timeAt(last)) return {last, 0.0f, 0.0f};
  // The last keyframe at or before `time`: t(low) <= time < t(high).
  std::size_t low = 0, high = last;
  while (high - low > 1) {
    const std::size_t middle = low + (high - low) / 2;
    (timeAt(middle) <= time ? low : high) = middle;
  }
  const double start = timeAt(low), end = timeAt(high);
  if (!(end > start)) {
    reader.source().fail(who + ": keyframe times " + std::to_string(low) + " and " + std::to_string(high) +
                         " do not increase (" + std::to_string(start) + ", " + std::to_string(end) + ")");
  }
  return {low, float((time - start) / (end - start)), float(end - start)};
}

// glTF's (x, y, z, w) as a quaternion, and back.
glm::quat quaternion(const float* v) { return glm::quat(v[3], v[0], v[1], v[2]); }

// The value `channel` of `animation` samples at `time`, `perKeyframe`
// elements of `path.components` floats.
std::vector<float> sampleChannel(const AccessorReader& reader, const tinygltf::AnimationSampler& sampler,
                                 const AnimatedPath& path, std::size_t perKeyframe, double time,
                                 const std::string& who) {
  const bool cubic = sampler.interpolation == "CUBICSPLINE";
  if (!cubic && sampler.interpolation != "LINEAR" && sampler.interpolation != "STEP")
    reader.source().fail(who + ": interpolation '" + sampler.interpolation + "' is not LINEAR, STEP or CUBICSPLINE");
  const CheckedAccessor input = reader.check(sampler.input, who + " sampler input", kTimeFormats);
  const CheckedAccessor output = reader.check(sampler.output, who + " sampler output", path.formats);
  const std::size_t perInput = (cubic ? 3 : 1) * perKeyframe;
  if (input.count == 0 || output.count % perInput != 0 || output.count / perInput != input.count) {
    reader.source().fail(who + ": sampler output accessor " + std::to_string(sampler.output) + " has " +
                         countOf(output.count, "element") + ", expected " + std::to_string(perInput) +
                         " for each of input accessor " + std::to_string(sampler.input) + "'s " +
                         countOf(input.count, "keyframe"));
  }
  const KeyframeSpan span = findKeyframes(reader, input, time, who);
  const int n = path.components;
  const std::size_t width = perKeyframe * std::size_t(n);
  // A keyframe's value (for CUBICSPLINE its middle third) and, with
  // `tangent` -1 / +1, its in- / out-tangent.
  auto keyframe = [&](std::size_t k, int tangent) {
    const std::size_t first = cubic ? (3 * k + std::size_t(1 + tangent)) * perKeyframe : k * perKeyframe;
    return outputElements(reader, output, n, first, perKeyframe);
  };
  std::vector<float> value = keyframe(span.index, 0);
  const bool between = span.s > 0.0f;
  if (between && sampler.interpolation == "LINEAR") {
    const std::vector<float> next = keyframe(span.index + 1, 0);
    if (path.name == "rotation") {
      glm::quat a = quaternion(value.data()), b = quaternion(next.data());
      if (glm::dot(a, b) < 0.0f) b = -b;  // the short way round
      const glm::quat q = glm::normalize(glm::slerp(a, b, span.s));
      value = {q.x, q.y, q.z, q.w};
    } else {
      for (std::size_t i = 0; i < width; ++i) value[i] += span.s * (next[i] - value[i]);
    }
  } else if (between && cubic) {
    const std::vector<float> out = keyframe(span.index, 1), next = keyframe(span.index + 1, 0),
                             in = keyframe(span.index + 1, -1);
    const float t = span.s, t2 = t * t, t3 = t2 * t, d = span.interval;
    for (std::size_t i = 0; i < width; ++i)
      value[i] = (2 * t3 - 3 * t2 + 1) * value[i] + (t3 - 2 * t2 + t) * d * out[i] + (-2 * t3 + 3 * t2) * next[i] +
                 (t3 - t2) * d * in[i];
  }
  if (path.name == "rotation") {
    const glm::quat q = quaternion(value.data());
    const float length = glm::length(q);
    if (!(length > 1e-12f) || !std::isfinite(length)) reader.source().fail(who + ": the rotation has no direction");
    value = {q.x / length, q.y / length, q.z / length, q.w / length};
  }
  for (const float v : value)
    if (!std::isfinite(v)) reader.source().fail(who + ": a sampled value is not finite");
  return value;
}

}  // namespace

int findAnimation(const Source& source, const std::string& chosen) {
  const auto& animations = source.model.animations;
  for (std::size_t i = 0; i < animations.size(); ++i)
    if (animations[i].name == chosen) return int(i);
  if (!chosen.empty() && chosen.find_first_not_of("0123456789") == std::string::npos && chosen.size() < 10) {
    const int index = std::stoi(chosen);
    if (std::size_t(index) < animations.size()) return index;
  }
  std::vector<std::string> shown;  // "0 'Walk'": the index, and the name where there is one
  for (std::size_t i = 0; i < std::min(animations.size(), kListShown); ++i)
    shown.push_back(std::to_string(i) + (animations[i].name.empty() ? "" : " " + quotedName(animations[i].name)));
  source.fail("animation " + quotedName(chosen) + " is not in the file: " +
                  (animations.empty() ? std::string("it has no animations")
                                      : "its animations are " + joinedList(shown, animations.size())),
              {"animation"});
}

void applyAnimation(tinygltf::Model& model, const Source& source, int animationIndex, double time) {
  const tinygltf::Animation& animation = model.animations[std::size_t(animationIndex)];
  const std::string name =
      "animation " + std::to_string(animationIndex) + (animation.name.empty() ? "" : " '" + animation.name + "'");
  const AccessorReader reader(source);
  // Sampled first, written after: a node two channels target is posed by
  // both, each from the file's values.
  struct Posed {
    int node;
    const AnimatedPath* path;
    std::vector<float> value;
  };
  std::vector<Posed> posed;
  for (std::size_t c = 0; c < animation.channels.size(); ++c) {
    const tinygltf::AnimationChannel& channel = animation.channels[c];
    const std::string who = name + " channel " + std::to_string(c);
    if (channel.target_node < 0) continue;  // an extension's target (KHR_animation_pointer): named as not rendered
    source.checkIndex(channel.sampler, animation.samplers, who, "sampler");
    source.checkIndex(channel.target_node, model.nodes, who, "node");
    const tinygltf::Node& node = model.nodes[std::size_t(channel.target_node)];
    const AnimatedPath* path = findPath(channel.target_path);
    if (path == nullptr)
      source.fail(who + ": target path '" + channel.target_path + "' is not translation, rotation, scale or weights");
    if (!node.matrix.empty())
      source.fail(who + ": node " + std::to_string(channel.target_node) +
                  " has a matrix, and glTF forbids animating such a node");
    std::size_t perKeyframe = 1;
    if (path->name == "weights") {
      source.checkIndex(node.mesh, model.meshes, who + "'s node", "mesh");
      const tinygltf::Mesh& mesh = model.meshes[std::size_t(node.mesh)];
      perKeyframe = mesh.primitives.empty() ? 0 : mesh.primitives[0].targets.size();
      if (perKeyframe == 0) source.fail(who + ": weights of a mesh without morph targets");
    }
    posed.push_back(
        {channel.target_node, path,
         sampleChannel(reader, animation.samplers[std::size_t(channel.sampler)], *path, perKeyframe, time, who)});
  }
  for (const Posed& p : posed) {
    tinygltf::Node& node = model.nodes[std::size_t(p.node)];
    std::vector<double> value(p.value.begin(), p.value.end());
    if (p.path->name == "translation")
      node.translation = std::move(value);
    else if (p.path->name == "rotation")
      node.rotation = std::move(value);
    else if (p.path->name == "scale")
      node.scale = std::move(value);
    else
      node.weights = std::move(value);
  }
}

bool animationLeavesStaticPose(const tinygltf::Model& model, std::size_t animationIndex) {
  const tinygltf::Animation& animation = model.animations[animationIndex];
  if (animation.channels.empty()) return true;  // glTF requires one at least
  // The messages name no file: they are not shown (the header says why).
  const Source source{std::string(), model};
  const AccessorReader reader(source);
  try {
    return std::any_of(
        animation.channels.begin(), animation.channels.end(),
        [&](const tinygltf::AnimationChannel& channel) { return channelDiffers(reader, animation, channel); });
  } catch (const Error&) {
    return true;
  }
}

}  // namespace headlight::gltf
