#include "gltf/meshopt.hpp"

#include <algorithm>
#include <cstring>

#include <nlohmann/json.hpp>

#if HEADLIGHT_HAS_MESHOPT
#include <meshoptimizer.h>
#endif

namespace headlight::gltf {

namespace {

constexpr const char* kMeshopt = "EXT_meshopt_compression";

}  // namespace

bool meshoptDecoding() { return HEADLIGHT_HAS_MESHOPT != 0; }

#if !HEADLIGHT_HAS_MESHOPT

void decodeMeshoptViews(tinygltf::Model&, const Source&, const std::vector<int>&, const ResourceLimits&) {}

#else

namespace {

enum class Mode { Attributes, Triangles, Indices };
enum class Filter { None, Octahedral, Quaternion, Exponential };

struct MeshoptView {
  int buffer = -1;
  std::size_t byteOffset = 0, byteLength = 0, byteStride = 0, count = 0;
  Mode mode = Mode::Attributes;
  Filter filter = Filter::None;
};

class ViewDecoder {
 public:
  ViewDecoder(tinygltf::Model& model, const Source& source, const std::vector<int>& placeholders,
              const ResourceLimits& limits)
      : model_(model), source_(source), placeholders_(placeholders), limit_(maxMemoryBytes(limits)) {}

  void run() {
    const std::size_t views = model_.bufferViews.size();
    for (std::size_t index = 0; index < views; ++index) {
      tinygltf::BufferView& view = model_.bufferViews[index];
      name_ = "bufferView " + std::to_string(index);
      const auto found = view.extensions.find(kMeshopt);
      if (found != view.extensions.end()) {
        decode(view, parse(found->second), int(index));
      } else if (isPlaceholder(view.buffer)) {
        source_.fail(name_ + " refers to buffer " + std::to_string(view.buffer) +
                     ", a placeholder without data (no uri), but has no " + kMeshopt + " to decode");
      }
    }
  }

 private:
  bool isPlaceholder(int buffer) const {
    return std::find(placeholders_.begin(), placeholders_.end(), buffer) != placeholders_.end();
  }

  [[noreturn]] void fail(const std::string& problem) const { source_.fail(name_ + " " + kMeshopt + ": " + problem); }

  std::size_t count(const tinygltf::Value& object, const char* key, bool required, std::size_t fallback = 0) const {
    if (!object.Has(key)) {
      if (required) fail(std::string("has no ") + key);
      return fallback;
    }
    const tinygltf::Value& value = object.Get(key);
    const double number = value.IsNumber() ? value.GetNumberAsDouble() : -1.0;
    if (!value.IsNumber() || number < 0 || number > 9.0e15 || number != double(std::int64_t(number))) {
      fail(std::string(key) + " is not a non-negative integer");
    }
    return std::size_t(number);
  }

  std::string text(const tinygltf::Value& object, const char* key, const char* fallback) const {
    if (!object.Has(key)) return fallback;
    if (!object.Get(key).IsString()) fail(std::string(key) + " is not a string");
    return object.Get(key).Get<std::string>();
  }

  MeshoptView parse(const tinygltf::Value& object) const {
    if (!object.IsObject()) fail("is not an object");
    MeshoptView view;
    view.buffer = int(std::min<std::size_t>(count(object, "buffer", true), std::size_t(1) << 30));
    view.byteOffset = count(object, "byteOffset", false);
    view.byteLength = count(object, "byteLength", true);
    view.byteStride = count(object, "byteStride", true);
    view.count = count(object, "count", true);
    const std::string mode = text(object, "mode", "");
    if (mode == "ATTRIBUTES")
      view.mode = Mode::Attributes;
    else if (mode == "TRIANGLES")
      view.mode = Mode::Triangles;
    else if (mode == "INDICES")
      view.mode = Mode::Indices;
    else
      fail("mode is '" + mode + "', expected ATTRIBUTES, TRIANGLES or INDICES");
    const std::string filter = text(object, "filter", "NONE");
    if (filter == "NONE")
      view.filter = Filter::None;
    else if (filter == "OCTAHEDRAL")
      view.filter = Filter::Octahedral;
    else if (filter == "QUATERNION")
      view.filter = Filter::Quaternion;
    else if (filter == "EXPONENTIAL")
      view.filter = Filter::Exponential;
    else
      fail("filter is '" + filter + "', expected NONE, OCTAHEDRAL, QUATERNION or EXPONENTIAL");
    return view;
  }

  // The spec's rules for the extension object, in its order.
  void checkLayout(const tinygltf::BufferView& parent, const MeshoptView& view) const {
    const std::string stride = "byteStride " + std::to_string(view.byteStride);
    if (view.count == 0) fail("count is 0, expected at least 1");
    if (parent.byteStride != 0 && parent.byteStride != view.byteStride) {
      fail(stride + " differs from the bufferView's byteStride " + std::to_string(parent.byteStride));
    }
    if (view.mode == Mode::Attributes && (view.byteStride == 0 || view.byteStride % 4 != 0 || view.byteStride > 256)) {
      fail(stride + " for ATTRIBUTES, expected a multiple of 4 in 4..256");
    }
    if (view.mode == Mode::Triangles && view.count % 3 != 0) {
      fail("count " + std::to_string(view.count) + " for TRIANGLES, expected a multiple of 3");
    }
    if (view.mode != Mode::Attributes && view.byteStride != 2 && view.byteStride != 4) {
      fail(stride + " for indices, expected 2 or 4");
    }
    if (view.mode != Mode::Attributes && view.filter != Filter::None) fail("a filter on indices, expected NONE");
    if (view.filter == Filter::Octahedral && view.byteStride != 4 && view.byteStride != 8) {
      fail(stride + " for OCTAHEDRAL, expected 4 or 8");
    }
    if (view.filter == Filter::Quaternion && view.byteStride != 8) fail(stride + " for QUATERNION, expected 8");
    if (view.filter == Filter::Exponential && view.byteStride % 4 != 0) {
      fail(stride + " for EXPONENTIAL, expected a multiple of 4");
    }
  }

  // The compressed bytes, checked to lie inside a buffer with data.
  std::span<const unsigned char> compressed(const MeshoptView& view) const {
    source_.checkIndex(view.buffer, model_.buffers, name_ + " " + kMeshopt, "buffer");
    if (isPlaceholder(view.buffer)) {
      fail("reads buffer " + std::to_string(view.buffer) + ", a placeholder without data (no uri)");
    }
    const std::vector<unsigned char>& data = model_.buffers[std::size_t(view.buffer)].data;
    if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset) {
      fail("reads bytes " + std::to_string(view.byteOffset) + ".." + std::to_string(view.byteOffset + view.byteLength) +
           " of buffer " + std::to_string(view.buffer) + ", which has " + std::to_string(data.size()));
    }
    return {data.data() + view.byteOffset, view.byteLength};
  }

  // count x byteStride, equal to the parent's byteLength and within
  // max-memory with the views decoded before it, before it is allocated.
  std::size_t reserve(const tinygltf::BufferView& parent, const MeshoptView& view) {
    std::size_t bytes = 0;
    if (__builtin_mul_overflow(view.count, view.byteStride, &bytes) || bytes != parent.byteLength) {
      fail("count " + std::to_string(view.count) + " x byteStride " + std::to_string(view.byteStride) +
           " is not the bufferView's byteLength " + std::to_string(parent.byteLength));
    }
    if (bytes > limit_ - std::min(limit_, decoded_)) {
      source_.failLimit(name_ + " " + kMeshopt + " decodes to " + std::to_string(bytes) + " bytes, and with the " +
                            std::to_string(decoded_) + " decoded before it that is more than max-memory allows (" +
                            std::to_string(limit_ >> 20) + " MiB); raise max-memory",
                        "max-memory");
    }
    decoded_ += bytes;
    return bytes;
  }

  // TRIANGLES and INDICES streams decode to indices of byteStride bytes,
  // which the specification asks to match the index accessors' size: a
  // 4-byte stream read as UNSIGNED_SHORT drew every other index as 0 (issue 32).
  void checkIndexAccessors(int viewIndex, const MeshoptView& view) const {
    if (view.mode == Mode::Attributes) return;
    for (std::size_t index = 0; index < model_.accessors.size(); ++index) {
      const tinygltf::Accessor& accessor = model_.accessors[index];
      if (accessor.bufferView != viewIndex) continue;
      const int size = tinygltf::GetComponentSizeInBytes(std::uint32_t(accessor.componentType));
      if (size != int(view.byteStride))
        fail("byteStride " + std::to_string(view.byteStride) + " for " +
             (view.mode == Mode::Triangles ? "TRIANGLES" : "INDICES") + ", but accessor " + std::to_string(index) +
             " reads the view as " + std::to_string(size) + "-byte components; expected the same size");
    }
  }

  void decode(tinygltf::BufferView& parent, const MeshoptView& view, int viewIndex) {
    checkLayout(parent, view);
    checkIndexAccessors(viewIndex, view);
    const std::span<const unsigned char> input = compressed(view);
    const std::size_t bytes = reserve(parent, view);
    tinygltf::Buffer output;
    output.name = name_ + " decoded";
    output.data.resize(bytes);
    int status = 0;
    switch (view.mode) {
      case Mode::Attributes:
        status =
            meshopt_decodeVertexBuffer(output.data.data(), view.count, view.byteStride, input.data(), input.size());
        break;
      case Mode::Triangles:
        status = meshopt_decodeIndexBuffer(output.data.data(), view.count, view.byteStride, input.data(), input.size());
        break;
      case Mode::Indices:
        status =
            meshopt_decodeIndexSequence(output.data.data(), view.count, view.byteStride, input.data(), input.size());
        break;
    }
    if (status != 0) {
      fail("the " + std::to_string(input.size()) + "-byte stream does not decode to " + std::to_string(view.count) +
           " elements of " + std::to_string(view.byteStride) + " bytes (meshoptimizer error " + std::to_string(status) +
           ")");
    }
    if (view.filter == Filter::Octahedral) meshopt_decodeFilterOct(output.data.data(), view.count, view.byteStride);
    if (view.filter == Filter::Quaternion) meshopt_decodeFilterQuat(output.data.data(), view.count, view.byteStride);
    if (view.filter == Filter::Exponential) meshopt_decodeFilterExp(output.data.data(), view.count, view.byteStride);
    // The decoded bytes become the view's: everything reading the view
    // (accessors, their checks) sees plain data.
    parent.buffer = int(model_.buffers.size());
    parent.byteOffset = 0;
    model_.buffers.push_back(std::move(output));
  }

  tinygltf::Model& model_;
  const Source& source_;
  const std::vector<int>& placeholders_;
  std::uint64_t limit_;
  std::uint64_t decoded_ = 0;
  std::string name_;
};

}  // namespace

void decodeMeshoptViews(tinygltf::Model& model, const Source& source, const std::vector<int>& placeholders,
                        const ResourceLimits& limits) {
  const auto& used = model.extensionsUsed;
  if (std::find(used.begin(), used.end(), kMeshopt) == used.end() && placeholders.empty()) {
    bool any = false;
    for (const tinygltf::BufferView& view : model.bufferViews) any = any || view.extensions.count(kMeshopt) != 0;
    if (!any) return;
  }
  ViewDecoder(model, source, placeholders, limits).run();
}

#endif

}  // namespace headlight::gltf
