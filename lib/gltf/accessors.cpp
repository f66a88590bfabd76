#include "gltf/accessors.hpp"

#include <algorithm>
#include <array>
#include <cstring>

namespace headlight::gltf {

std::string countOf(std::size_t count, const char* noun) {
  const std::string_view word(noun);
  // "vertex" -> "vertices", "index" -> "indices"; the rest take an s.
  if (count != 1 && word.size() >= 2 && word.substr(word.size() - 2) == "ex")
    return std::to_string(count) + " " + std::string(word.substr(0, word.size() - 2)) + "ices";
  return std::to_string(count) + " " + noun + (count == 1 ? "" : "s");
}

std::string componentTypeName(int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
      return "BYTE";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return "UNSIGNED_BYTE";
    case TINYGLTF_COMPONENT_TYPE_SHORT:
      return "SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return "UNSIGNED_SHORT";
    case TINYGLTF_COMPONENT_TYPE_INT:
      return "INT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      return "UNSIGNED_INT";
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return "FLOAT";
    default:
      return "componentType " + std::to_string(componentType);
  }
}

std::string typeName(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return "SCALAR";
    case TINYGLTF_TYPE_VEC2:
      return "VEC2";
    case TINYGLTF_TYPE_VEC3:
      return "VEC3";
    case TINYGLTF_TYPE_VEC4:
      return "VEC4";
    case TINYGLTF_TYPE_MAT2:
      return "MAT2";
    case TINYGLTF_TYPE_MAT3:
      return "MAT3";
    case TINYGLTF_TYPE_MAT4:
      return "MAT4";
    default:
      return "type " + std::to_string(type);
  }
}

std::string modeName(int mode) {
  static constexpr std::array<const char*, 7> kNames{"POINTS",    "LINES",          "LINE_LOOP",   "LINE_STRIP",
                                                     "TRIANGLES", "TRIANGLE_STRIP", "TRIANGLE_FAN"};
  return mode >= 0 && mode < 7 ? kNames[static_cast<std::size_t>(mode)] : "unknown";
}

std::string formatName(const AccessorFormat& format) {
  return (format.normalized ? "normalized " : "") + componentTypeName(format.componentType) + " " +
         typeName(format.type);
}

namespace {

// start + stride * (count - 1) + elementSize, or false where it overflows.
bool accessEnd(std::size_t start, std::size_t stride, std::size_t count, std::size_t elementSize, std::size_t& end) {
  std::size_t span = 0;
  return count > 0 && !__builtin_mul_overflow(stride, count - 1, &span) && !__builtin_add_overflow(span, start, &end) &&
         !__builtin_add_overflow(end, elementSize, &end);
}

std::size_t componentSize(int componentType) {
  const int size = tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(componentType));
  return size > 0 ? static_cast<std::size_t>(size) : 0;
}

std::uint32_t readIndexValue(const unsigned char* at, int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return *at;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      std::uint16_t value;
      std::memcpy(&value, at, sizeof value);
      return value;
    }
    default: {
      std::uint32_t value;
      std::memcpy(&value, at, sizeof value);
      return value;
    }
  }
}

template <typename T>
T load(const unsigned char* at) {
  T value;
  std::memcpy(&value, at, sizeof value);
  return value;
}

// One component as a float. Normalized integers follow glTF's table
// (3.11 "Animations"/KHR_mesh_quantization): c / max, and for signed types
// max(c / max, -1) so that both -128 and -127 are -1.
float decodeComponent(const unsigned char* at, int componentType, bool normalized) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const float value = load<std::int8_t>(at);
      return normalized ? std::max(value / 127.0f, -1.0f) : value;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return normalized ? *at / 255.0f : *at;
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      const float value = load<std::int16_t>(at);
      return normalized ? std::max(value / 32767.0f, -1.0f) : value;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      const float value = load<std::uint16_t>(at);
      return normalized ? value / 65535.0f : value;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      return static_cast<float>(load<std::uint32_t>(at));
    default:
      return load<float>(at);
  }
}

void decodeFloats(const unsigned char* at, int componentType, bool normalized, int componentCount, float* out) {
  const std::size_t size = componentSize(componentType);
  for (int component = 0; component < componentCount; ++component) {
    out[component] = decodeComponent(at + size * static_cast<std::size_t>(component), componentType, normalized);
  }
}

}  // namespace

AccessorReader::ViewBytes AccessorReader::checkedBufferView(int viewIndex, const std::string& user) const {
  const tinygltf::Model& model = source_.model;
  source_.checkIndex(viewIndex, model.bufferViews, user, "bufferView");
  const tinygltf::BufferView& view = model.bufferViews[static_cast<std::size_t>(viewIndex)];
  const std::string viewName = "bufferView " + std::to_string(viewIndex);
  source_.checkIndex(view.buffer, model.buffers, viewName, "buffer");
  const std::vector<unsigned char>& buffer = model.buffers[static_cast<std::size_t>(view.buffer)].data;
  if (view.byteOffset > buffer.size() || view.byteLength > buffer.size() - view.byteOffset) {
    source_.fail(viewName + " spans bytes " + std::to_string(view.byteOffset) + ".." +
                 std::to_string(view.byteOffset + view.byteLength) + " of buffer " + std::to_string(view.buffer) +
                 ", which has " + std::to_string(buffer.size()));
  }
  // glTF: 4..252 and a multiple of 4, so that every element is aligned.
  if (view.byteStride != 0 && (view.byteStride < 4 || view.byteStride > 252 || view.byteStride % 4 != 0)) {
    source_.fail(viewName + " has byteStride " + std::to_string(view.byteStride) +
                 ", expected a multiple of 4 in 4..252");
  }
  return {buffer.data() + view.byteOffset, view.byteLength, view.byteStride};
}

void AccessorReader::checkFormat(const tinygltf::Accessor& accessor, int accessorIndex, const std::string& user,
                                 std::span<const AccessorFormat> allowed) const {
  const bool found = std::any_of(allowed.begin(), allowed.end(), [&](const AccessorFormat& format) {
    return format.componentType == accessor.componentType && format.type == accessor.type &&
           (format.normalized == accessor.normalized || format.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT);
  });
  if (!found) {
    std::string expected;
    for (const AccessorFormat& format : allowed) {
      expected += (expected.empty() ? "" : " or ") + formatName(format);
    }
    source_.fail(user + " accessor " + std::to_string(accessorIndex) + " is " +
                 formatName({accessor.componentType, accessor.type,
                             accessor.normalized && accessor.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT}) +
                 ", expected " + expected);
  }
}

// Checks that `count` elements of `elementSize` bytes, `stride` apart from
// `start`, lie inside the view, in the message format users grep for.
void AccessorReader::checkRange(const std::string& reader, std::size_t start, std::size_t stride, std::size_t count,
                                std::size_t elementSize, int viewIndex, std::size_t viewSize) const {
  std::size_t end = 0;
  const bool representable = accessEnd(start, stride, count, elementSize, end);
  if (!representable || end > viewSize) {
    const std::string endText = representable ? std::to_string(end) : "(beyond 2^64)";
    source_.fail(reader + " reads bytes " + std::to_string(start) + ".." + endText + " of bufferView " +
                 std::to_string(viewIndex) + ", which has " + std::to_string(viewSize));
  }
}

void AccessorReader::checkSparse(const tinygltf::Accessor& accessor, int accessorIndex,
                                 CheckedAccessor& checked) const {
  const std::string name = "accessor " + std::to_string(accessorIndex) + " sparse";
  const auto& sparse = accessor.sparse;
  if (sparse.count < 1 || static_cast<std::size_t>(sparse.count) > accessor.count) {
    source_.fail(name + " count is " + std::to_string(sparse.count) + ", expected 1.." +
                 std::to_string(accessor.count));
  }
  if (sparse.indices.byteOffset < 0 || sparse.values.byteOffset < 0) {
    source_.fail(name + " has a negative byteOffset");
  }
  const int indexType = sparse.indices.componentType;
  if (indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
    source_.fail(name + " indices are " + componentTypeName(indexType) +
                 ", expected UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT");
  }
  const auto count = static_cast<std::size_t>(sparse.count);
  const ViewBytes indices = checkedBufferView(sparse.indices.bufferView, name + " indices");
  checkRange(name + " indices", static_cast<std::size_t>(sparse.indices.byteOffset), componentSize(indexType), count,
             componentSize(indexType), sparse.indices.bufferView, indices.size);
  const ViewBytes values = checkedBufferView(sparse.values.bufferView, name + " values");
  checkRange(name + " values", static_cast<std::size_t>(sparse.values.byteOffset), checked.elementSize, count,
             checked.elementSize, sparse.values.bufferView, values.size);
  checked.sparseCount = count;
  checked.sparseIndexComponentType = indexType;
  checked.sparseIndices = indices.data + sparse.indices.byteOffset;
  checked.sparseValues = values.data + sparse.values.byteOffset;
}

CheckedAccessor AccessorReader::check(int accessorIndex, const std::string& user,
                                      std::span<const AccessorFormat> allowed) const {
  source_.checkIndex(accessorIndex, source_.model.accessors, user, "accessor");
  const tinygltf::Accessor& accessor = source_.model.accessors[static_cast<std::size_t>(accessorIndex)];
  checkFormat(accessor, accessorIndex, user, allowed);
  const std::string name = "accessor " + std::to_string(accessorIndex);
  if (accessor.count < 1) {
    source_.fail(name + " has count 0, expected at least 1");
  }
  CheckedAccessor checked;
  checked.index = accessorIndex;
  checked.count = accessor.count;
  checked.componentType = accessor.componentType;
  checked.normalized = accessor.normalized && accessor.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT;
  checked.elementSize =
      componentSize(accessor.componentType) *
      static_cast<std::size_t>(tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(accessor.type)));
  if (accessor.bufferView >= 0) {
    const ViewBytes view = checkedBufferView(accessor.bufferView, name);
    checked.stride = view.byteStride != 0 ? view.byteStride : checked.elementSize;
    if (checked.stride < checked.elementSize) {
      source_.fail("bufferView " + std::to_string(accessor.bufferView) + " has byteStride " +
                   std::to_string(checked.stride) + ", smaller than " + name + "'s " +
                   std::to_string(checked.elementSize) + "-byte elements");
    }
    checkRange(name, accessor.byteOffset, checked.stride, accessor.count, checked.elementSize, accessor.bufferView,
               view.size);
    checked.data = view.data + accessor.byteOffset;
  }
  if (accessor.sparse.isSparse) {
    checkSparse(accessor, accessorIndex, checked);
  }
  return checked;
}

std::uint32_t AccessorReader::sparseTarget(const CheckedAccessor& accessor, std::size_t k) const {
  const std::size_t indexSize = componentSize(accessor.sparseIndexComponentType);
  const std::uint32_t target =
      readIndexValue(accessor.sparseIndices + k * indexSize, accessor.sparseIndexComponentType);
  if (target >= accessor.count) {
    source_.fail("accessor " + std::to_string(accessor.index) + " sparse index " + std::to_string(k) + " is " +
                 std::to_string(target) + ", expected < count " + std::to_string(accessor.count));
  }
  return target;
}

// glTF's sparse substitution: element sparseIndex[k] becomes value k.
template <int N>
std::vector<glm::vec<N, float>> AccessorReader::readFloats(const CheckedAccessor& accessor) const {
  std::vector<glm::vec<N, float>> values(accessor.count, glm::vec<N, float>(0.0f));
  if (accessor.data != nullptr) {
    for (std::size_t element = 0; element < accessor.count; ++element) {
      decodeFloats(accessor.data + element * accessor.stride, accessor.componentType, accessor.normalized, N,
                   &values[element][0]);
    }
  }
  for (std::size_t k = 0; k < accessor.sparseCount; ++k) {
    decodeFloats(accessor.sparseValues + k * accessor.elementSize, accessor.componentType, accessor.normalized, N,
                 &values[sparseTarget(accessor, k)][0]);
  }
  return values;
}

template std::vector<glm::vec<1, float>> AccessorReader::readFloats<1>(const CheckedAccessor&) const;
template std::vector<glm::vec<2, float>> AccessorReader::readFloats<2>(const CheckedAccessor&) const;
template std::vector<glm::vec<3, float>> AccessorReader::readFloats<3>(const CheckedAccessor&) const;
template std::vector<glm::vec<4, float>> AccessorReader::readFloats<4>(const CheckedAccessor&) const;

std::vector<glm::mat4> AccessorReader::readMatrices(const CheckedAccessor& accessor) const {
  std::vector<glm::mat4> matrices(accessor.count, glm::mat4(0.0f));
  if (accessor.data != nullptr) {
    for (std::size_t element = 0; element < accessor.count; ++element) {
      decodeFloats(accessor.data + element * accessor.stride, accessor.componentType, false, 16,
                   &matrices[element][0][0]);
    }
  }
  for (std::size_t k = 0; k < accessor.sparseCount; ++k) {
    decodeFloats(accessor.sparseValues + k * accessor.elementSize, accessor.componentType, false, 16,
                 &matrices[sparseTarget(accessor, k)][0][0]);
  }
  return matrices;
}

std::vector<std::uint32_t> AccessorReader::readIndices(const CheckedAccessor& accessor) const {
  std::vector<std::uint32_t> indices(accessor.count, 0u);
  if (accessor.data != nullptr) {
    for (std::size_t element = 0; element < accessor.count; ++element) {
      indices[element] = readIndexValue(accessor.data + element * accessor.stride, accessor.componentType);
    }
  }
  for (std::size_t k = 0; k < accessor.sparseCount; ++k) {
    indices[sparseTarget(accessor, k)] =
        readIndexValue(accessor.sparseValues + k * accessor.elementSize, accessor.componentType);
  }
  return indices;
}

}  // namespace headlight::gltf
