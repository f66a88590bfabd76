// glTF 2.0 (.gltf, .glb) to Scene, through tinygltf for the JSON and the
// buffers and OpenImageIO (in the image module) for the images.
//
// tinygltf parses, but it trusts the file: it does not check that an accessor
// stays inside its bufferView, that indices stay inside the vertex count, or
// that a URI stays inside the asset's folder. Everything here checks before
// it reads, and every failure is a SceneError that starts with the file name
// and names the glTF element, so a malformed file is a message, never a
// crash or a silently wrong picture.
#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <iterator>
#include <limits>
#include <map>
#include <span>
#include <string>
#include <tuple>
#include <vector>
// Debian's libtinygltf.so carries the implementation (and its JSON parser),
// so this file only includes the declarations: no TINYGLTF_IMPLEMENTATION.
#include <tiny_gltf.h>

#include "headlight/error.hpp"
#include "headlight/limits.hpp"
#include "output/fingerprint.hpp"
#include "headlight/scene_loader.hpp"
#include "image_io/texture_decode.hpp"
#include "scene/gltf_prescan.hpp"

namespace headlight {

namespace fs = std::filesystem;

namespace {

constexpr std::string_view kBuiltinPrefix = "builtin:";

// Largest texture side accepted: GL 4.5 guarantees only 16384, and a larger
// claim in a file header is far more likely corruption than a real texture.
constexpr int kMaxImageSide = 16384;

// Extensions this loader understands; a file that *requires* any other one
// cannot be drawn correctly, so it is refused rather than drawn wrongly.
constexpr std::array<std::string_view, 2> kSupportedExtensions{"KHR_lights_punctual",
                                                               "KHR_materials_emissive_strength"};

// tinygltf's messages are newline-separated lines; a SceneError is one line.
std::string oneLine(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) {
    text.pop_back();
  }
  std::string::size_type newline;
  while ((newline = text.find('\n')) != std::string::npos) {
    text.replace(newline, 1, "; ");
  }
  return text;
}

std::string lowercase(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

// ---- File access -------------------------------------------------------------
//
// tinygltf reaches the file system only through these callbacks. They keep
// every URI inside the asset's folder (unless allowed), skip tinygltf's
// default wordexp() shell expansion of file names taken from the file, and
// skip its fallback of looking in the current directory.

struct FileAccess {
  fs::path assetFolder;   // canonical
  std::string uriPrefix;  // assetFolder + "/": what tinygltf puts before a URI
  bool allowExternalPaths = false;
  std::string refusal;  // set when a URI was refused; reported after parsing
};

bool isInside(const fs::path& path, const fs::path& folder) {
  auto [folderEnd, pathPosition] = std::mismatch(folder.begin(), folder.end(), path.begin(), path.end());
  return folderEnd == folder.end();
}

std::string expandFilePath(const std::string& path, void*) { return path; }

// tinygltf joins the asset folder and the URI even when the URI is absolute
// ("/assets//data/x.png"); an absolute URI means itself.
std::string effectivePath(const std::string& path, const FileAccess& access) {
  if (path.rfind(access.uriPrefix, 0) == 0 && path.size() > access.uriPrefix.size() &&
      path[access.uriPrefix.size()] == '/') {
    return path.substr(access.uriPrefix.size());
  }
  return path;
}

// Records (and returns true for) a URI outside the asset folder while that is
// not allowed, so that the error names the rule rather than "file not found".
bool refuseOutside(const std::string& path, FileAccess& access) {
  if (access.allowExternalPaths) {
    return false;
  }
  const std::string target = effectivePath(path, access);
  std::error_code canonicalError;
  const fs::path resolved = fs::weakly_canonical(target, canonicalError);
  if (!canonicalError && isInside(resolved, access.assetFolder)) {
    return false;
  }
  const std::string uri = path.rfind(access.uriPrefix, 0) == 0 ? path.substr(access.uriPrefix.size()) : path;
  if (access.refusal.empty()) {
    access.refusal = "URI '" + uri + "' resolves to " + resolved.string() + ", outside the asset folder " +
                     access.assetFolder.string() +
                     "; pass allow-external-paths (SceneLoadOptions::allowExternalPaths) to allow it";
  }
  return true;
}

bool fileExists(const std::string& path, void* userData) {
  auto& access = *static_cast<FileAccess*>(userData);
  // tinygltf also tries "./<uri>"; only the asset-relative candidate counts.
  if (path.rfind(access.uriPrefix, 0) != 0) {
    return false;
  }
  if (refuseOutside(path, access)) {
    return false;
  }
  std::error_code error;
  return fs::is_regular_file(effectivePath(path, access), error);
}

bool readWholeFile(std::vector<unsigned char>* bytes, std::string* error, const std::string& path, void* userData) {
  auto& access = *static_cast<FileAccess*>(userData);
  if (refuseOutside(path, access)) {
    *error = access.refusal;
    return false;
  }
  std::ifstream file(effectivePath(path, access), std::ios::binary);
  if (!file) {
    *error = "cannot open " + path;
    return false;
  }
  bytes->assign(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
  return true;
}

// ---- Images ------------------------------------------------------------------

struct ImageDecoding {
  const tinygltf::Model* model = nullptr;  // the model tinygltf is filling
  std::string failure;                     // set when an image is refused
};

// tinygltf passes an image stored in a bufferView as a pointer into the
// buffer without checking the view's range, so the range is checked here,
// before the first byte is touched.
std::string checkImageBufferView(const tinygltf::Model& model, const tinygltf::Image& image) {
  const tinygltf::BufferView& view = model.bufferViews[static_cast<std::size_t>(image.bufferView)];
  const std::size_t bufferSize = model.buffers[static_cast<std::size_t>(view.buffer)].data.size();
  if (view.byteOffset > bufferSize || view.byteLength > bufferSize - view.byteOffset) {
    return "its bufferView " + std::to_string(image.bufferView) + " spans bytes " + std::to_string(view.byteOffset) +
           ".." + std::to_string(view.byteOffset + view.byteLength) + " of buffer " + std::to_string(view.buffer) +
           ", which has " + std::to_string(bufferSize);
  }
  return {};
}

// tinygltf calls this while it parses; it only keeps the encoded bytes, so
// that nothing is decoded before the whole file's structure has been checked
// (GltfReader::readImages decodes them last).
bool keepEncodedImage(tinygltf::Image* image, const int imageIndex, std::string* error, std::string*, int, int,
                      const unsigned char* bytes, int size, void* userData) {
  auto& decoding = *static_cast<ImageDecoding*>(userData);
  std::string problem;
  if (image->bufferView >= 0) {
    problem = checkImageBufferView(*decoding.model, *image);
  }
  if (problem.empty() && size <= 0) {
    problem = "it is empty";
  }
  if (problem.empty()) {
    image->image.assign(bytes, bytes + size);
    image->width = image->height = -1;  // not decoded yet
    image->component = 0;
    return true;
  }
  {
    decoding.failure =
        "image " + std::to_string(imageIndex) + (image->name.empty() ? "" : " '" + image->name + "'") + ": " + problem;
    if (error != nullptr) {
      *error += decoding.failure + "\n";
    }
    return false;
  }
  return true;
}

// ---- Names for messages ----------------------------------------------------

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

std::string countOf(std::size_t count, const char* noun) {
  return std::to_string(count) + " " + noun + (count == 1 ? "" : "s");
}

// ---- Accessors ---------------------------------------------------------------

// One allowed layout of an attribute: glTF's componentType and type codes.
struct AccessorFormat {
  int componentType;
  int type;
  bool normalized;
};

constexpr AccessorFormat kFloatVec2{TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2, false};
constexpr AccessorFormat kFloatVec3{TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, false};
constexpr AccessorFormat kFloatVec4{TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC4, false};
constexpr std::array<AccessorFormat, 1> kPositionFormats{kFloatVec3};
constexpr std::array<AccessorFormat, 1> kNormalFormats{kFloatVec3};
constexpr std::array<AccessorFormat, 1> kTangentFormats{kFloatVec4};
constexpr std::array<AccessorFormat, 3> kTexcoordFormats{
    kFloatVec2, AccessorFormat{TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_TYPE_VEC2, true},
    AccessorFormat{TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_VEC2, true}};
constexpr std::array<AccessorFormat, 3> kIndexFormats{
    AccessorFormat{TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_TYPE_SCALAR, false},
    AccessorFormat{TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_SCALAR, false},
    AccessorFormat{TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, false}};

std::string formatName(const AccessorFormat& format) {
  return (format.normalized ? "normalized " : "") + componentTypeName(format.componentType) + " " +
         typeName(format.type);
}

// An accessor whose every byte has been checked to lie inside its buffer.
struct CheckedAccessor {
  int index = -1;
  const unsigned char* data = nullptr;  // nullptr: all zeros (before sparse)
  std::size_t stride = 0;
  std::size_t count = 0;
  int componentType = 0;
  // Sparse substitution, tightly packed as glTF requires.
  std::size_t sparseCount = 0;
  const unsigned char* sparseIndices = nullptr;
  int sparseIndexComponentType = 0;
  const unsigned char* sparseValues = nullptr;
  std::size_t elementSize = 0;
};

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

// Converts one element to floats: FLOAT as is, normalized unsigned integers
// to 0..1 as glTF defines.
void decodeFloats(const unsigned char* at, int componentType, int componentCount, float* out) {
  for (int component = 0; component < componentCount; ++component) {
    switch (componentType) {
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        out[component] = at[component] / 255.0f;
        break;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        std::uint16_t value;
        std::memcpy(&value, at + 2 * component, sizeof value);
        out[component] = value / 65535.0f;
        break;
      }
      default:
        std::memcpy(out + component, at + 4 * component, sizeof(float));
        break;
    }
  }
}

// ---- The reader -----------------------------------------------------------------

// Key of a primitive's geometry: its POSITION, NORMAL, TEXCOORD_0, TANGENT and
// indices accessors. Primitives with equal keys share decoding work.
using GeometryKey = std::tuple<int, int, int, int, int>;

class GltfReader {
 public:
  // `warnings`: tinygltf's, quoted when an image turns out to be missing.
  GltfReader(std::string file, tinygltf::Model& model, std::string warnings, Scene& scene, const ResourceLimits& limits)
      : file_(std::move(file)), model_(model), warnings_(std::move(warnings)), scene_(scene), limits_(limits) {}

  // Structure first, images last: a file that is refused is refused before
  // any image is decoded.
  void read() {
    checkRequiredExtensions();
    for (std::size_t material = 0; material < model_.materials.size(); ++material) {
      scene_.materials.push_back(readMaterial(static_cast<int>(material)));
    }
    lights_ = punctualLights();
    checkNodeTree();
    for (int root : rootNodes()) {
      traverse(root);
    }
    readImages();
  }

 private:
  [[noreturn]] void fail(const std::string& message) const { throw SceneError(file_ + ": " + message); }
  // `setting`: the limit's setting the message names (Error::settings()).
  [[noreturn]] void failLimit(const std::string& message, const std::string& setting) const {
    throw LimitError(file_ + ": " + message, {setting});
  }

  // Every vertex and triangle decoded counts against --max-triangles before
  // its memory is allocated (3 vertices per allowed triangle at most).
  void reserveVertices(std::size_t count, int accessorIndex, const std::string& user) {
    const auto allowed = static_cast<std::uint64_t>(limits_.maxTriangles) * 3;
    if (count > allowed - std::min<std::uint64_t>(allowed, decodedVertices_)) {
      failLimit(user + " accessor " + std::to_string(accessorIndex) + " has " + std::to_string(count) +
                " vertices, and with the " + std::to_string(decodedVertices_) + " before it that is more than the " +
                std::to_string(allowed) + " (3 x max-triangles " + std::to_string(limits_.maxTriangles) +
                ") allowed; raise max-triangles", "max-triangles");
    }
    decodedVertices_ += count;
  }

  void reserveTriangles(std::size_t count, const std::string& primitiveName) {
    const auto allowed = static_cast<std::uint64_t>(limits_.maxTriangles);
    if (count > allowed - std::min<std::uint64_t>(allowed, decodedTriangles_)) {
      failLimit(primitiveName + " has " + std::to_string(count) + " triangles, and with the " +
                std::to_string(decodedTriangles_) + " before it that is more than max-triangles " +
                std::to_string(allowed) + "; raise max-triangles", "max-triangles");
    }
    decodedTriangles_ += count;
  }

  template <typename Container>
  void checkIndex(int index, const Container& container, const std::string& user, const char* noun) const {
    if (index < 0 || static_cast<std::size_t>(index) >= container.size()) {
      fail(user + " refers to " + noun + " " + std::to_string(index) + ", but the file has " +
           countOf(container.size(), noun));
    }
  }

  void checkRequiredExtensions() const {
    for (const std::string& required : model_.extensionsRequired) {
      if (std::find(kSupportedExtensions.begin(), kSupportedExtensions.end(), required) == kSupportedExtensions.end()) {
        fail("requires extension " + required + ", which is not supported (supported: " +
             std::string(kSupportedExtensions[0]) + ", " + std::string(kSupportedExtensions[1]) + ")");
      }
    }
  }

  // ---- Buffers and accessors

  struct ViewBytes {
    const unsigned char* data;
    std::size_t size;
    std::size_t byteStride;
  };

  ViewBytes checkedBufferView(int viewIndex, const std::string& user) const {
    checkIndex(viewIndex, model_.bufferViews, user, "bufferView");
    const tinygltf::BufferView& view = model_.bufferViews[static_cast<std::size_t>(viewIndex)];
    const std::string viewName = "bufferView " + std::to_string(viewIndex);
    checkIndex(view.buffer, model_.buffers, viewName, "buffer");
    const std::vector<unsigned char>& buffer = model_.buffers[static_cast<std::size_t>(view.buffer)].data;
    if (view.byteOffset > buffer.size() || view.byteLength > buffer.size() - view.byteOffset) {
      fail(viewName + " spans bytes " + std::to_string(view.byteOffset) + ".." +
           std::to_string(view.byteOffset + view.byteLength) + " of buffer " + std::to_string(view.buffer) +
           ", which has " + std::to_string(buffer.size()));
    }
    // glTF: 4..252 and a multiple of 4, so that every element is aligned.
    if (view.byteStride != 0 && (view.byteStride < 4 || view.byteStride > 252 || view.byteStride % 4 != 0)) {
      fail(viewName + " has byteStride " + std::to_string(view.byteStride) + ", expected a multiple of 4 in 4..252");
    }
    return {buffer.data() + view.byteOffset, view.byteLength, view.byteStride};
  }

  void checkFormat(const tinygltf::Accessor& accessor, int accessorIndex, const std::string& user,
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
      fail(user + " accessor " + std::to_string(accessorIndex) + " is " +
           formatName({accessor.componentType, accessor.type,
                       accessor.normalized && accessor.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT}) +
           ", expected " + expected);
    }
  }

  // Checks that `count` elements of `elementSize` bytes, `stride` apart from
  // `start`, lie inside the view, in the message format users grep for.
  void checkRange(const std::string& reader, std::size_t start, std::size_t stride, std::size_t count,
                  std::size_t elementSize, int viewIndex, std::size_t viewSize) const {
    std::size_t end = 0;
    const bool representable = accessEnd(start, stride, count, elementSize, end);
    if (!representable || end > viewSize) {
      const std::string endText = representable ? std::to_string(end) : "(beyond 2^64)";
      fail(reader + " reads bytes " + std::to_string(start) + ".." + endText + " of bufferView " +
           std::to_string(viewIndex) + ", which has " + std::to_string(viewSize));
    }
  }

  void checkSparse(const tinygltf::Accessor& accessor, int accessorIndex, CheckedAccessor& checked) const {
    const std::string name = "accessor " + std::to_string(accessorIndex) + " sparse";
    const auto& sparse = accessor.sparse;
    if (sparse.count < 1 || static_cast<std::size_t>(sparse.count) > accessor.count) {
      fail(name + " count is " + std::to_string(sparse.count) + ", expected 1.." + std::to_string(accessor.count));
    }
    if (sparse.indices.byteOffset < 0 || sparse.values.byteOffset < 0) {
      fail(name + " has a negative byteOffset");
    }
    const int indexType = sparse.indices.componentType;
    if (indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
      fail(name + " indices are " + componentTypeName(indexType) +
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

  // Validates everything about an accessor that reading it depends on; only
  // a CheckedAccessor is ever read.
  CheckedAccessor checkedAccessor(int accessorIndex, const std::string& user,
                                  std::span<const AccessorFormat> allowed) const {
    checkIndex(accessorIndex, model_.accessors, user, "accessor");
    const tinygltf::Accessor& accessor = model_.accessors[static_cast<std::size_t>(accessorIndex)];
    checkFormat(accessor, accessorIndex, user, allowed);
    const std::string name = "accessor " + std::to_string(accessorIndex);
    if (accessor.count < 1) {
      fail(name + " has count 0, expected at least 1");
    }
    CheckedAccessor checked;
    checked.index = accessorIndex;
    checked.count = accessor.count;
    checked.componentType = accessor.componentType;
    checked.elementSize =
        componentSize(accessor.componentType) *
        static_cast<std::size_t>(tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(accessor.type)));
    if (accessor.bufferView >= 0) {
      const ViewBytes view = checkedBufferView(accessor.bufferView, name);
      checked.stride = view.byteStride != 0 ? view.byteStride : checked.elementSize;
      if (checked.stride < checked.elementSize) {
        fail("bufferView " + std::to_string(accessor.bufferView) + " has byteStride " + std::to_string(checked.stride) +
             ", smaller than " + name + "'s " + std::to_string(checked.elementSize) + "-byte elements");
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

  // Applies glTF's sparse substitution: element sparseIndex[k] becomes value k.
  template <typename Write>
  void applySparse(const CheckedAccessor& accessor, Write write) const {
    const std::size_t indexSize = componentSize(accessor.sparseIndexComponentType);
    for (std::size_t k = 0; k < accessor.sparseCount; ++k) {
      const std::uint32_t target =
          readIndexValue(accessor.sparseIndices + k * indexSize, accessor.sparseIndexComponentType);
      if (target >= accessor.count) {
        fail("accessor " + std::to_string(accessor.index) + " sparse index " + std::to_string(k) + " is " +
             std::to_string(target) + ", expected < count " + std::to_string(accessor.count));
      }
      write(target, accessor.sparseValues + k * accessor.elementSize);
    }
  }

  template <int N>
  std::vector<glm::vec<N, float>> readFloats(const CheckedAccessor& accessor) const {
    std::vector<glm::vec<N, float>> values(accessor.count, glm::vec<N, float>(0.0f));
    if (accessor.data != nullptr) {
      for (std::size_t element = 0; element < accessor.count; ++element) {
        decodeFloats(accessor.data + element * accessor.stride, accessor.componentType, N, &values[element][0]);
      }
    }
    applySparse(accessor, [&](std::uint32_t target, const unsigned char* at) {
      decodeFloats(at, accessor.componentType, N, &values[target][0]);
    });
    return values;
  }

  std::vector<std::uint32_t> readIndices(const CheckedAccessor& accessor) const {
    std::vector<std::uint32_t> indices(accessor.count, 0u);
    if (accessor.data != nullptr) {
      for (std::size_t element = 0; element < accessor.count; ++element) {
        indices[element] = readIndexValue(accessor.data + element * accessor.stride, accessor.componentType);
      }
    }
    applySparse(accessor, [&](std::uint32_t target, const unsigned char* at) {
      indices[target] = readIndexValue(at, accessor.componentType);
    });
    return indices;
  }

  // ---- Primitives

  static int attributeAccessor(const tinygltf::Primitive& primitive, const char* attribute) {
    const auto found = primitive.attributes.find(attribute);
    return found == primitive.attributes.end() ? -1 : found->second;
  }

  template <int N>
  std::vector<glm::vec<N, float>> readAttribute(int accessorIndex, const std::string& user,
                                                std::span<const AccessorFormat> allowed, std::size_t vertexCount,
                                                int positionAccessor) const {
    const CheckedAccessor accessor = checkedAccessor(accessorIndex, user, allowed);
    if (accessor.count != vertexCount) {
      fail(user + " accessor " + std::to_string(accessorIndex) + " has " + countOf(accessor.count, "element") +
           ", but POSITION accessor " + std::to_string(positionAccessor) + " has " + std::to_string(vertexCount));
    }
    return readFloats<N>(accessor);
  }

  std::vector<glm::vec3> readPositions(int accessorIndex, const std::string& primitiveName) {
    const CheckedAccessor accessor = checkedAccessor(accessorIndex, primitiveName + " POSITION", kPositionFormats);
    reserveVertices(accessor.count, accessorIndex, primitiveName + " POSITION");
    std::vector<glm::vec3> positions = readFloats<3>(accessor);
    for (std::size_t vertex = 0; vertex < positions.size(); ++vertex) {
      const glm::vec3& p = positions[vertex];
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
        fail("accessor " + std::to_string(accessorIndex) + " (POSITION of " + primitiveName +
             ") has a non-finite value at element " + std::to_string(vertex));
      }
    }
    // Indices are 32-bit; more vertices than that could not all be drawn.
    if (positions.size() > std::numeric_limits<std::uint32_t>::max()) {
      fail(primitiveName + " has " + std::to_string(positions.size()) + " vertices, more than 32-bit indices reach");
    }
    return positions;
  }

  std::vector<std::uint32_t> readTriangleIndices(int accessorIndex, const std::string& primitiveName,
                                                 std::size_t vertexCount) {
    std::vector<std::uint32_t> indices;
    if (accessorIndex < 0) {
      reserveTriangles(vertexCount / 3, primitiveName);
      indices.resize(vertexCount);
      for (std::size_t vertex = 0; vertex < vertexCount; ++vertex) {
        indices[vertex] = static_cast<std::uint32_t>(vertex);
      }
    } else {
      const CheckedAccessor accessor = checkedAccessor(accessorIndex, primitiveName + " indices", kIndexFormats);
      reserveTriangles(accessor.count / 3, primitiveName);
      indices = readIndices(accessor);
      for (std::size_t position = 0; position < indices.size(); ++position) {
        if (indices[position] >= vertexCount) {
          fail(primitiveName + ": index " + std::to_string(position) + " of accessor " + std::to_string(accessorIndex) +
               " is " + std::to_string(indices[position]) + ", but the primitive has " +
               countOf(vertexCount, "vertex") + " (expected < " + std::to_string(vertexCount) + ")");
        }
      }
    }
    if (indices.size() % 3 != 0) {
      fail(primitiveName + " has " + std::to_string(indices.size()) +
           (accessorIndex < 0 ? " vertices and no indices" : " indices in accessor " + std::to_string(accessorIndex)) +
           ", expected a multiple of 3 for TRIANGLES");
    }
    return indices;
  }

  // Normals from the file are normalised; any that cannot be (zero, NaN) are
  // replaced by generated ones rather than reaching the shader.
  static void repairNormals(Primitive& primitive) {
    bool allUsable = true;
    for (glm::vec3& normal : primitive.normals) {
      const float length = glm::length(normal);
      if (std::isfinite(length) && length > 1e-12f) {
        normal /= length;
      } else {
        allUsable = false;
      }
    }
    if (!allUsable) {
      Primitive generated{primitive.positions, {}, {}, {}, primitive.indices, {}};
      generateNormals(generated);
      for (std::size_t vertex = 0; vertex < primitive.normals.size(); ++vertex) {
        const float length = glm::length(primitive.normals[vertex]);
        if (!(std::isfinite(length) && std::abs(length - 1.0f) < 1e-3f)) {
          primitive.normals[vertex] = generated.normals[vertex];
        }
      }
    }
  }

  Primitive readGeometry(const tinygltf::Primitive& source, const std::string& primitiveName) {
    Primitive primitive;
    const int positionAccessor = attributeAccessor(source, "POSITION");
    if (positionAccessor < 0) {
      fail(primitiveName + " has no POSITION attribute");
    }
    primitive.positions = readPositions(positionAccessor, primitiveName);
    const std::size_t vertexCount = primitive.positions.size();
    primitive.indices = readTriangleIndices(source.indices, primitiveName, vertexCount);
    if (const int normals = attributeAccessor(source, "NORMAL"); normals >= 0) {
      primitive.normals =
          readAttribute<3>(normals, primitiveName + " NORMAL", kNormalFormats, vertexCount, positionAccessor);
      repairNormals(primitive);
    } else {
      generateNormals(primitive);
    }
    if (const int texcoords = attributeAccessor(source, "TEXCOORD_0"); texcoords >= 0) {
      primitive.texcoords =
          readAttribute<2>(texcoords, primitiveName + " TEXCOORD_0", kTexcoordFormats, vertexCount, positionAccessor);
    }
    // Missing tangents stay missing: the G-buffer shader derives a tangent
    // frame from screen-space derivatives instead.
    if (const int tangents = attributeAccessor(source, "TANGENT"); tangents >= 0) {
      primitive.tangents =
          readAttribute<4>(tangents, primitiveName + " TANGENT", kTangentFormats, vertexCount, positionAccessor);
    }
    for (const glm::vec3& position : primitive.positions) {
      primitive.bounds.extend(position);
    }
    return primitive;
  }

  bool materialHasTextures(int material) const {
    if (material < 0) {
      return false;
    }
    const Material& m = scene_.materials[static_cast<std::size_t>(material)];
    return m.baseColorTexture.present() || m.metallicRoughnessTexture.present() || m.normalTexture.present() ||
           m.occlusionTexture.present() || m.emissiveTexture.present();
  }

  // The geometry of a glTF primitive (decoded once per distinct set of
  // accessors) and the material it is drawn with.
  struct PlacedPrimitive {
    int geometry;
    int material;
  };

  PlacedPrimitive addPrimitive(int meshIndex, int primitiveIndex) {
    const tinygltf::Primitive& source =
        model_.meshes[static_cast<std::size_t>(meshIndex)].primitives[static_cast<std::size_t>(primitiveIndex)];
    const std::string primitiveName =
        "mesh " + std::to_string(meshIndex) + " primitive " + std::to_string(primitiveIndex);
    if (source.mode != TINYGLTF_MODE_TRIANGLES) {
      fail(primitiveName + " has mode " + modeName(source.mode) + " (" + std::to_string(source.mode) +
           "), but only TRIANGLES (4) is supported");
    }
    if (source.material != -1) {
      checkIndex(source.material, model_.materials, primitiveName, "material");
    }
    const GeometryKey key{attributeAccessor(source, "POSITION"), attributeAccessor(source, "NORMAL"),
                          attributeAccessor(source, "TEXCOORD_0"), attributeAccessor(source, "TANGENT"),
                          source.indices};
    // Files often repeat one geometry under many materials (one mesh per
    // material); it is decoded and stored once, and each use is an instance.
    auto [cached, inserted] = geometryCache_.try_emplace(key, static_cast<int>(scene_.primitives.size()));
    if (inserted) {
      scene_.primitives.push_back(readGeometry(source, primitiveName));
    }
    Primitive& primitive = scene_.primitives[static_cast<std::size_t>(cached->second)];
    // A textured material samples UVs; without TEXCOORD_0 it samples (0, 0),
    // which is glTF's answer too, so the shader always has texcoords to read.
    if (primitive.texcoords.empty() && materialHasTextures(source.material)) {
      primitive.texcoords.assign(primitive.positions.size(), glm::vec2(0.0f));
    }
    return {cached->second, source.material};
  }

  // A mesh's primitives are added once, however many nodes use the mesh.
  const std::vector<PlacedPrimitive>& meshPrimitives(int meshIndex) {
    auto [entry, inserted] = meshCache_.try_emplace(meshIndex);
    if (inserted) {
      const tinygltf::Mesh& mesh = model_.meshes[static_cast<std::size_t>(meshIndex)];
      for (std::size_t primitive = 0; primitive < mesh.primitives.size(); ++primitive) {
        entry->second.push_back(addPrimitive(meshIndex, static_cast<int>(primitive)));
      }
    }
    return entry->second;
  }

  // ---- Materials and images

  void readImages() {
    detail::TextureDecodeLimits decodeLimits{kMaxImageSide, limits_.maxTexels};
    for (std::size_t index = 0; index < model_.images.size(); ++index) {
      tinygltf::Image& source = model_.images[index];
      // An external image tinygltf could not find is only a warning to it.
      if (source.image.empty() || source.width != -1) {
        fail("image " + std::to_string(index) + (source.uri.empty() ? "" : " (uri '" + source.uri + "')") +
             " could not be loaded" + (warnings_.empty() ? "" : ": " + warnings_));
      }
      const std::vector<unsigned char> encoded = std::move(source.image);
      bool overBudget = false;
      detail::DecodedTexture decoded;
      const std::string problem =
          detail::decodeTexture(encoded.data(), encoded.size(), decodeLimits, decoded, overBudget);
      if (!problem.empty()) {
        const std::string message =
            "image " + std::to_string(index) + (source.name.empty() ? "" : " '" + source.name + "'") + ": " + problem;
        overBudget ? failLimit(message, "max-texels") : fail(message);
      }
      ImageData image;
      image.name = !source.name.empty() ? source.name : source.uri;
      image.width = decoded.width;
      image.height = decoded.height;
      image.rgba = std::move(decoded.rgba);
      scene_.images.push_back(std::move(image));
    }
  }

  static bool validWrap(int wrap) { return wrap == 33071 || wrap == 33648 || wrap == 10497; }

  static bool validFilter(int filter) { return filter == 9728 || filter == 9729 || (filter >= 9984 && filter <= 9987); }

  TextureRef readTextureRef(int textureIndex, int texCoord, const std::string& user) const {
    TextureRef ref;
    if (textureIndex < 0) {
      return ref;
    }
    checkIndex(textureIndex, model_.textures, user, "texture");
    if (texCoord != 0) {
      fail(user + " uses TEXCOORD_" + std::to_string(texCoord) + ", but only TEXCOORD_0 is supported");
    }
    const tinygltf::Texture& texture = model_.textures[static_cast<std::size_t>(textureIndex)];
    const std::string textureName = "texture " + std::to_string(textureIndex);
    if (texture.source < 0) {
      fail(textureName + " has no source image (extension-only images such as KHR_texture_basisu are not supported)");
    }
    checkIndex(texture.source, model_.images, textureName, "image");
    ref.image = texture.source;
    if (texture.sampler >= 0) {
      checkIndex(texture.sampler, model_.samplers, textureName, "sampler");
      const tinygltf::Sampler& sampler = model_.samplers[static_cast<std::size_t>(texture.sampler)];
      const std::string samplerName = "sampler " + std::to_string(texture.sampler);
      if (!validWrap(sampler.wrapS) || !validWrap(sampler.wrapT)) {
        fail(samplerName + " has wrap modes " + std::to_string(sampler.wrapS) + "/" + std::to_string(sampler.wrapT) +
             ", expected 33071, 33648 or 10497");
      }
      ref.wrapS = sampler.wrapS;
      ref.wrapT = sampler.wrapT;
      // -1 = not given: keep TextureRef's defaults (trilinear, as viewers do).
      if (sampler.minFilter != -1) {
        if (!validFilter(sampler.minFilter)) {
          fail(samplerName + " has minFilter " + std::to_string(sampler.minFilter) +
               ", expected 9728, 9729 or 9984..9987");
        }
        ref.minFilter = sampler.minFilter;
      }
      if (sampler.magFilter != -1) {
        if (sampler.magFilter != 9728 && sampler.magFilter != 9729) {
          fail(samplerName + " has magFilter " + std::to_string(sampler.magFilter) + ", expected 9728 or 9729");
        }
        ref.magFilter = sampler.magFilter;
      }
    }
    return ref;
  }

  float emissiveStrength(const tinygltf::Material& material, const std::string& materialName) const {
    const auto extension = material.extensions.find("KHR_materials_emissive_strength");
    if (extension == material.extensions.end() || !extension->second.Has("emissiveStrength")) {
      return 1.0f;
    }
    const double strength = extension->second.Get("emissiveStrength").GetNumberAsDouble();
    if (!(strength >= 0.0) || !std::isfinite(strength)) {
      fail(materialName + " has emissiveStrength " + std::to_string(strength) + ", expected >= 0");
    }
    return static_cast<float>(strength);
  }

  void readFactors(const tinygltf::Material& source, const std::string& name, Material& material) const {
    const auto& pbr = source.pbrMetallicRoughness;
    if (pbr.baseColorFactor.size() != 4) {
      fail(name + " has " + std::to_string(pbr.baseColorFactor.size()) + " baseColorFactor values, expected 4");
    }
    material.baseColorFactor =
        glm::vec4(pbr.baseColorFactor[0], pbr.baseColorFactor[1], pbr.baseColorFactor[2], pbr.baseColorFactor[3]);
    material.metallicFactor = static_cast<float>(pbr.metallicFactor);
    material.roughnessFactor = static_cast<float>(pbr.roughnessFactor);
    if (!source.emissiveFactor.empty() && source.emissiveFactor.size() != 3) {
      fail(name + " has " + std::to_string(source.emissiveFactor.size()) + " emissiveFactor values, expected 3");
    }
    if (source.emissiveFactor.size() == 3) {
      material.emissiveFactor =
          glm::vec3(source.emissiveFactor[0], source.emissiveFactor[1], source.emissiveFactor[2]) *
          emissiveStrength(source, name);
    }
    material.normalScale = static_cast<float>(source.normalTexture.scale);
    material.occlusionStrength = static_cast<float>(source.occlusionTexture.strength);
    material.doubleSided = source.doubleSided;
    const std::array<float, 9> factors{
        material.baseColorFactor.r,
        material.baseColorFactor.g,
        material.baseColorFactor.b,
        material.baseColorFactor.a,
        material.metallicFactor,
        material.roughnessFactor,
        material.emissiveFactor.r + material.emissiveFactor.g + material.emissiveFactor.b,
        material.normalScale,
        material.occlusionStrength};
    if (!std::all_of(factors.begin(), factors.end(), [](float f) { return std::isfinite(f); })) {
      fail(name + " has a non-finite factor");
    }
  }

  Material readMaterial(int materialIndex) const {
    const tinygltf::Material& source = model_.materials[static_cast<std::size_t>(materialIndex)];
    const std::string name = "material " + std::to_string(materialIndex);
    Material material;
    material.name = source.name.empty() ? name : source.name;
    readFactors(source, name, material);
    const auto& pbr = source.pbrMetallicRoughness;
    material.baseColorTexture =
        readTextureRef(pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord, name + " baseColorTexture");
    material.metallicRoughnessTexture = readTextureRef(
        pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord, name + " metallicRoughnessTexture");
    material.normalTexture =
        readTextureRef(source.normalTexture.index, source.normalTexture.texCoord, name + " normalTexture");
    material.occlusionTexture =
        readTextureRef(source.occlusionTexture.index, source.occlusionTexture.texCoord, name + " occlusionTexture");
    material.emissiveTexture =
        readTextureRef(source.emissiveTexture.index, source.emissiveTexture.texCoord, name + " emissiveTexture");
    return material;
  }

  // ---- Lights

  // tinygltf 2.7 parses KHR_lights_punctual into Model::lights; older and
  // newer versions may leave it only in Model::extensions, read the same way.
  std::vector<tinygltf::Light> punctualLights() const {
    if (!model_.lights.empty()) {
      return model_.lights;
    }
    std::vector<tinygltf::Light> lights;
    const auto extension = model_.extensions.find("KHR_lights_punctual");
    if (extension == model_.extensions.end() || !extension->second.Has("lights")) {
      return lights;
    }
    const tinygltf::Value& array = extension->second.Get("lights");
    for (std::size_t index = 0; index < array.ArrayLen(); ++index) {
      lights.push_back(lightFromJson(array.Get(static_cast<int>(index))));
    }
    return lights;
  }

  static tinygltf::Light lightFromJson(const tinygltf::Value& json) {
    tinygltf::Light light;
    auto number = [](const tinygltf::Value& object, const char* key, double fallback) {
      return object.Has(key) ? object.Get(key).GetNumberAsDouble() : fallback;
    };
    light.name = json.Has("name") ? json.Get("name").Get<std::string>() : "";
    light.type = json.Has("type") ? json.Get("type").Get<std::string>() : "";
    light.intensity = number(json, "intensity", 1.0);
    light.range = number(json, "range", 0.0);
    if (json.Has("color")) {
      for (std::size_t channel = 0; channel < json.Get("color").ArrayLen(); ++channel) {
        light.color.push_back(json.Get("color").Get(static_cast<int>(channel)).GetNumberAsDouble());
      }
    }
    if (json.Has("spot")) {
      light.spot.innerConeAngle = number(json.Get("spot"), "innerConeAngle", 0.0);
      light.spot.outerConeAngle = number(json.Get("spot"), "outerConeAngle", 0.7853981634);
    }
    return light;
  }

  static Light::Type lightType(const std::string& type, bool& known) {
    known = true;
    if (type == "directional") return Light::Type::Directional;
    if (type == "point") return Light::Type::Point;
    if (type == "spot") return Light::Type::Spot;
    known = false;
    return Light::Type::Point;
  }

  Light readLight(int lightIndex, const glm::mat4& worldFromNode, const std::string& nodeName) const {
    const tinygltf::Light& source = lights_[static_cast<std::size_t>(lightIndex)];
    const std::string name = "light " + std::to_string(lightIndex);
    Light light;
    bool knownType = false;
    light.type = lightType(source.type, knownType);
    if (!knownType) {
      fail(name + " has type '" + source.type + "', expected directional, point or spot");
    }
    light.name = source.name.empty() ? name : source.name;
    if (!source.color.empty() && source.color.size() != 3) {
      fail(name + " has " + std::to_string(source.color.size()) + " color values, expected 3");
    }
    if (source.color.size() == 3) {
      light.color = glm::vec3(source.color[0], source.color[1], source.color[2]);
    }
    light.intensity = static_cast<float>(source.intensity);
    light.range = static_cast<float>(source.range);
    light.innerConeAngle = static_cast<float>(source.spot.innerConeAngle);
    light.outerConeAngle = static_cast<float>(source.spot.outerConeAngle);
    if (!(light.intensity >= 0.0f) || !(light.range >= 0.0f) || !std::isfinite(light.intensity)) {
      fail(name + " has intensity " + std::to_string(light.intensity) + " and range " + std::to_string(light.range) +
           ", expected both >= 0");
    }
    if (light.type == Light::Type::Spot &&
        !(light.innerConeAngle >= 0.0f && light.innerConeAngle < light.outerConeAngle &&
          light.outerConeAngle <= 1.5707964f)) {
      fail(name + " has cone angles " + std::to_string(light.innerConeAngle) + ".." +
           std::to_string(light.outerConeAngle) + ", expected 0 <= inner < outer <= pi/2");
    }
    light.position = glm::vec3(worldFromNode[3]);
    const glm::vec3 direction = glm::mat3(worldFromNode) * glm::vec3(0.0f, 0.0f, -1.0f);
    const float length = glm::length(direction);
    if (light.type != Light::Type::Point && !(length > 0.0f && std::isfinite(length))) {
      fail(nodeName + " holds " + name + " but its transform has no direction (zero scale)");
    }
    if (length > 0.0f && std::isfinite(length)) {
      light.direction = direction / length;
    }
    return light;
  }

  // ---- Cameras

  // A camera's frame is a rotation and a position: glTF forbids scale on a
  // camera's nodes but files have it, so the rotation is re-orthonormalised
  // (keeping the view direction exact).
  static glm::mat4 rigidFrame(const glm::mat4& world) {
    const glm::vec3 back = glm::normalize(glm::vec3(world[2]));
    glm::vec3 right = glm::vec3(world[0]) - glm::dot(glm::vec3(world[0]), back) * back;
    right = glm::normalize(right);
    const glm::vec3 up = glm::cross(back, right);
    glm::mat4 frame(glm::vec4(right, 0.0f), glm::vec4(up, 0.0f), glm::vec4(back, 0.0f), world[3]);
    return frame;
  }

  Camera readCamera(int cameraIndex, const glm::mat4& worldFromNode, const std::string& nodeName) const {
    const tinygltf::Camera& source = model_.cameras[static_cast<std::size_t>(cameraIndex)];
    const std::string name = "camera " + std::to_string(cameraIndex);
    Camera camera;
    camera.name = !source.name.empty() ? source.name : name;
    if (source.type == "perspective") {
      const auto& p = source.perspective;
      camera.projection = Camera::Projection::Perspective;
      camera.yfov = static_cast<float>(p.yfov);
      camera.aspectRatio = static_cast<float>(p.aspectRatio);
      camera.znear = static_cast<float>(p.znear);
      camera.zfar = static_cast<float>(p.zfar);
      if (!(camera.yfov > 0.0f && camera.yfov < 3.1415926f) || !(camera.aspectRatio >= 0.0f)) {
        fail(name + " has yfov " + std::to_string(p.yfov) + " and aspectRatio " + std::to_string(p.aspectRatio) +
             ", expected 0 < yfov < pi and aspectRatio >= 0");
      }
    } else if (source.type == "orthographic") {
      const auto& o = source.orthographic;
      camera.projection = Camera::Projection::Orthographic;
      camera.xmag = static_cast<float>(o.xmag);
      camera.ymag = static_cast<float>(o.ymag);
      camera.znear = static_cast<float>(o.znear);
      camera.zfar = static_cast<float>(o.zfar);
      if (camera.xmag == 0.0f || camera.ymag == 0.0f || !std::isfinite(camera.xmag) || !std::isfinite(camera.ymag)) {
        fail(name + " has xmag " + std::to_string(o.xmag) + " and ymag " + std::to_string(o.ymag) +
             ", expected nonzero");
      }
    } else {
      fail(name + " has type '" + source.type + "', expected perspective or orthographic");
    }
    if (!(camera.znear >= 0.0f) || !(camera.zfar >= 0.0f) || (camera.zfar != 0.0f && camera.zfar <= camera.znear)) {
      fail(name + " has znear " + std::to_string(camera.znear) + " and zfar " + std::to_string(camera.zfar) +
           ", expected 0 <= znear < zfar (or zfar absent)");
    }
    if (glm::length(glm::vec3(worldFromNode[2])) == 0.0f || glm::length(glm::vec3(worldFromNode[0])) == 0.0f) {
      fail(nodeName + " holds " + name + " but its transform has zero scale");
    }
    camera.worldFromCamera = rigidFrame(worldFromNode);
    return camera;
  }

  // ---- Nodes

  glm::dmat4 localTransform(int nodeIndex) const {
    const tinygltf::Node& node = model_.nodes[static_cast<std::size_t>(nodeIndex)];
    const std::string name = "node " + std::to_string(nodeIndex);
    glm::dmat4 local(1.0);
    if (!node.matrix.empty()) {
      if (node.matrix.size() != 16) {
        fail(name + " has " + std::to_string(node.matrix.size()) + " matrix values, expected 16");
      }
      local = glm::make_mat4(node.matrix.data());  // glTF matrices are column-major, as GLM's
    } else {
      if ((!node.translation.empty() && node.translation.size() != 3) ||
          (!node.rotation.empty() && node.rotation.size() != 4) || (!node.scale.empty() && node.scale.size() != 3)) {
        fail(name + " has translation/rotation/scale of " + std::to_string(node.translation.size()) + "/" +
             std::to_string(node.rotation.size()) + "/" + std::to_string(node.scale.size()) +
             " values, expected 3/4/3");
      }
      const glm::dvec3 translation =
          node.translation.empty() ? glm::dvec3(0.0) : glm::make_vec3(node.translation.data());
      const glm::dvec3 scale = node.scale.empty() ? glm::dvec3(1.0) : glm::make_vec3(node.scale.data());
      // glTF stores quaternions as x, y, z, w; GLM's constructor takes w first.
      glm::dquat rotation(1.0, 0.0, 0.0, 0.0);
      if (!node.rotation.empty()) {
        rotation = glm::dquat(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
        const double length = glm::length(rotation);
        if (!(length > 0.0)) {
          fail(name + " has a zero rotation quaternion");
        }
        rotation /= length;
      }
      local =
          glm::translate(glm::dmat4(1.0), translation) * glm::mat4_cast(rotation) * glm::scale(glm::dmat4(1.0), scale);
    }
    for (int column = 0; column < 4; ++column) {
      for (int row = 0; row < 4; ++row) {
        if (!std::isfinite(local[column][row])) {
          fail(name + " has a non-finite transform");
        }
      }
    }
    return local;
  }

  // World transforms are composed in double and must stay where float
  // rendering stays finite (kMaxWorldMagnitude): a translation of 1e39 or
  // nested scales of 1e20 x 1e20 are finite doubles but inf or NaN as floats.
  glm::mat4 checkedWorld(int nodeIndex, const glm::dmat4& world) const {
    for (int column = 0; column < 4; ++column) {
      for (int row = 0; row < 4; ++row) {
        const double value = world[column][row];
        if (!(std::abs(value) <= kMaxWorldMagnitude)) {
          char text[32];
          std::snprintf(text, sizeof text, "%g", value);
          fail("node " + std::to_string(nodeIndex) + " has a world transform entry of " + text +
               " (its own and its ancestors' transforms together), expected magnitude at most " +
               std::to_string(static_cast<long long>(kMaxWorldMagnitude)) + " so that float rendering stays finite");
        }
      }
    }
    return glm::mat4(world);
  }

  // glTF nodes form trees: each node has at most one parent. Checking that
  // up front bounds traversal to one visit per node per listed root.
  void checkNodeTree() {
    parentOf_.assign(model_.nodes.size(), -1);
    for (std::size_t parent = 0; parent < model_.nodes.size(); ++parent) {
      const std::string parentName = "node " + std::to_string(parent);
      for (int child : model_.nodes[parent].children) {
        checkIndex(child, model_.nodes, parentName, "node");
        int& recordedParent = parentOf_[static_cast<std::size_t>(child)];
        if (recordedParent != -1) {
          fail("node " + std::to_string(child) + " is a child of both node " + std::to_string(recordedParent) +
               " and node " + std::to_string(parent) + ", but glTF nodes must form trees");
        }
        recordedParent = static_cast<int>(parent);
      }
    }
    // With one parent each, a cycle is a parent chain that comes back to
    // itself; found here, before a scene can list a node of it as a root.
    std::vector<char> state(model_.nodes.size(), 0);  // 0 unseen, 1 on this walk, 2 done
    std::vector<int> walk;
    for (std::size_t start = 0; start < model_.nodes.size(); ++start) {
      walk.clear();
      int node = static_cast<int>(start);
      while (node != -1 && state[static_cast<std::size_t>(node)] == 0) {
        state[static_cast<std::size_t>(node)] = 1;
        walk.push_back(node);
        node = parentOf_[static_cast<std::size_t>(node)];
      }
      if (node != -1 && state[static_cast<std::size_t>(node)] == 1) {
        fail("node " + std::to_string(parentOf_[static_cast<std::size_t>(node)]) + " has child node " +
             std::to_string(node) + ", which is also its ancestor: the node graph has a cycle");
      }
      for (int visited : walk) {
        state[static_cast<std::size_t>(visited)] = 2;
      }
    }
  }

  std::vector<int> rootNodes() const {
    if (model_.scenes.empty()) {
      std::vector<int> roots;  // no scene: every node without a parent
      for (std::size_t node = 0; node < model_.nodes.size(); ++node) {
        if (parentOf_[node] == -1) {
          roots.push_back(static_cast<int>(node));
        }
      }
      return roots;
    }
    int sceneIndex = model_.defaultScene;
    if (sceneIndex == -1) {
      sceneIndex = 0;
    }
    checkIndex(sceneIndex, model_.scenes, "the default scene", "scene");
    const std::string sceneName = "scene " + std::to_string(sceneIndex);
    std::vector<char> listed(model_.nodes.size(), 0);
    for (int node : model_.scenes[static_cast<std::size_t>(sceneIndex)].nodes) {
      checkIndex(node, model_.nodes, sceneName, "node");
      // glTF: a scene lists root nodes, each once; repeats would multiply
      // the node's whole subtree.
      if (listed[static_cast<std::size_t>(node)]++) {
        fail(sceneName + " lists node " + std::to_string(node) + " more than once, but scene nodes must be unique");
      }
      if (parentOf_[static_cast<std::size_t>(node)] != -1) {
        fail(sceneName + " lists node " + std::to_string(node) + " as a root, but it is a child of node " +
             std::to_string(parentOf_[static_cast<std::size_t>(node)]) + "; scene nodes must be roots");
      }
    }
    return model_.scenes[static_cast<std::size_t>(sceneIndex)].nodes;
  }

  int nodeLight(const tinygltf::Node& node, const std::string& nodeName) const {
    const auto extension = node.extensions.find("KHR_lights_punctual");
    if (extension == node.extensions.end() || !extension->second.Has("light")) {
      return -1;
    }
    const tinygltf::Value& light = extension->second.Get("light");
    const int lightIndex = light.IsNumber() || light.IsInt() ? light.GetNumberAsInt() : -1;
    checkIndex(lightIndex, lights_, nodeName + " KHR_lights_punctual", "light");
    return lightIndex;
  }

  void visit(int nodeIndex, const glm::mat4& worldFromNode) {
    const tinygltf::Node& node = model_.nodes[static_cast<std::size_t>(nodeIndex)];
    const std::string nodeName = "node " + std::to_string(nodeIndex);
    if (node.mesh >= 0) {
      checkIndex(node.mesh, model_.meshes, nodeName, "mesh");
      const std::vector<PlacedPrimitive>& placedPrimitives = meshPrimitives(node.mesh);
      if (scene_.instances.size() + placedPrimitives.size() > static_cast<std::uint64_t>(limits_.maxInstances)) {
        failLimit(nodeName + " places mesh " + std::to_string(node.mesh) + " as instance " +
                  std::to_string(scene_.instances.size() + placedPrimitives.size()) + ", more than max-instances " +
                  std::to_string(limits_.maxInstances) + "; raise max-instances", "max-instances");
      }
      for (const PlacedPrimitive& placed : placedPrimitives) {
        scene_.instances.push_back({placed.geometry, worldFromNode, placed.material});
      }
    }
    if (node.camera >= 0) {
      checkIndex(node.camera, model_.cameras, nodeName, "camera");
      scene_.cameras.push_back(readCamera(node.camera, worldFromNode, nodeName));
    }
    if (const int light = nodeLight(node, nodeName); light >= 0) {
      scene_.lights.push_back(readLight(light, worldFromNode, nodeName));
    }
  }

  // Depth-first with an explicit stack, so a deep hierarchy cannot overflow
  // the call stack; a node met again on its own path is a cycle.
  void traverse(int root) {
    struct Frame {
      int node;
      glm::dmat4 worldFromNode;
      std::size_t nextChild;
    };
    std::vector<char> onPath(model_.nodes.size(), 0);
    std::vector<Frame> stack{{root, localTransform(root), 0}};
    onPath[static_cast<std::size_t>(root)] = 1;
    visit(root, checkedWorld(root, stack.back().worldFromNode));
    while (!stack.empty()) {
      Frame& top = stack.back();
      const std::vector<int>& children = model_.nodes[static_cast<std::size_t>(top.node)].children;
      if (top.nextChild == children.size()) {
        onPath[static_cast<std::size_t>(top.node)] = 0;
        stack.pop_back();
        continue;
      }
      const int child = children[top.nextChild++];
      if (onPath[static_cast<std::size_t>(child)]) {
        fail("node " + std::to_string(top.node) + " has child node " + std::to_string(child) +
             ", which is also its ancestor: the node graph has a cycle");
      }
      const glm::dmat4 worldFromChild = top.worldFromNode * localTransform(child);
      onPath[static_cast<std::size_t>(child)] = 1;
      stack.push_back({child, worldFromChild, 0});  // invalidates `top`
      visit(child, checkedWorld(child, worldFromChild));
    }
  }

 private:
  std::string file_;
  tinygltf::Model& model_;
  std::string warnings_;
  Scene& scene_;
  ResourceLimits limits_;
  std::uint64_t decodedVertices_ = 0;
  std::uint64_t decodedTriangles_ = 0;
  std::vector<tinygltf::Light> lights_;
  std::vector<int> parentOf_;
  std::map<int, std::vector<PlacedPrimitive>> meshCache_;
  std::map<GeometryKey, int> geometryCache_;
};

// ---- Top level ---------------------------------------------------------------

// The extension is checked before reading, so that a wrong file is not read
// whole just to be refused.
std::vector<unsigned char> readAssetBytes(const fs::path& path, const std::string& file, const std::string& extension) {
  std::error_code error;
  if (!fs::exists(path, error)) {
    throw SceneError(file + ": no such file");
  }
  if (!fs::is_regular_file(path, error)) {
    throw SceneError(file + ": not a regular file, expected a .gltf or .glb file");
  }
  if (extension != ".gltf" && extension != ".glb") {
    throw SceneError(file + ": extension '" + extension + "' is not glTF, expected .gltf or .glb");
  }
  std::ifstream stream(path, std::ios::binary);
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(stream)), std::istreambuf_iterator<char>());
  if (!stream.good() && !stream.eof()) {
    throw SceneError(file + ": cannot be read");
  }
  // tinygltf's size arguments are 32-bit.
  if (bytes.size() >= std::numeric_limits<unsigned int>::max()) {
    throw SceneError(file + ": " + std::to_string(bytes.size()) + " bytes, expected less than 4 GiB");
  }
  return bytes;
}

fs::path canonicalFolderOf(const fs::path& path) {
  std::error_code error;
  const fs::path canonical = fs::weakly_canonical(fs::absolute(path, error), error);
  return (error ? fs::absolute(path, error).lexically_normal() : canonical).parent_path();
}

void parseWithTinygltf(tinygltf::Model& model, const std::vector<unsigned char>& bytes, bool binary, FileAccess& access,
                       const std::string& file, std::string& warnings) {
  tinygltf::TinyGLTF parser;
  parser.SetFsCallbacks({&fileExists, &expandFilePath, &readWholeFile, nullptr, &access});
  ImageDecoding decoding{&model, {}};
  parser.SetImageLoader(&keepEncodedImage, &decoding);
  std::string errors;
  const std::string baseDir = access.assetFolder.string();
  const bool parsed =
      binary ? parser.LoadBinaryFromMemory(&model, &errors, &warnings, bytes.data(),
                                           static_cast<unsigned int>(bytes.size()), baseDir)
             : parser.LoadASCIIFromString(&model, &errors, &warnings, reinterpret_cast<const char*>(bytes.data()),
                                          static_cast<unsigned int>(bytes.size()), baseDir);
  // Our own findings come first: they name the element precisely, where
  // tinygltf's follow-on messages may not.
  if (!access.refusal.empty()) {
    throw SceneError(file + ": " + access.refusal, {"allow-external-paths"});
  }
  if (!decoding.failure.empty()) {
    throw SceneError(file + ": " + decoding.failure);
  }
  warnings = oneLine(warnings);
  if (!parsed) {
    throw SceneError(file + ": tinygltf cannot parse it: " + oneLine(errors) +
                     (warnings.empty() ? "" : " (warnings: " + warnings + ")"));
  }
}

}  // namespace

Scene loadGltf(const fs::path& path, const SceneLoadOptions& options, const ResourceLimits& limits) {
  const std::string file = path.string();
  const std::string extension = lowercase(path.extension().string());
  const std::vector<unsigned char> bytes = readAssetBytes(path, file, extension);
  // Before tinygltf: it recurses on nesting and lets some invalid values through.
  const std::string_view json = gltf::jsonText(bytes, extension == ".glb", file);
  gltf::checkNestingDepth(json, file);
  gltf::checkStructure(json, file);

  FileAccess access;
  access.assetFolder = canonicalFolderOf(path);
  access.uriPrefix = access.assetFolder.string();
  if (access.uriPrefix.empty() || access.uriPrefix.back() != '/') {
    access.uriPrefix += '/';
  }
  access.allowExternalPaths = options.allowExternalPaths;

  tinygltf::Model model;
  std::string warnings;
  parseWithTinygltf(model, bytes, extension == ".glb", access, file, warnings);

  Scene scene;
  scene.source = file;
  scene.sourceHash = textFingerprint(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
  GltfReader(file, model, std::move(warnings), scene, limits).read();
  checkSceneRanges(scene);
  const std::uint64_t sceneBytes = estimateSceneBytes(scene);
  if (sceneBytes > maxMemoryBytes(limits)) {
    throw LimitError(file + ": the scene needs about " + std::to_string(sceneBytes >> 20) +
                         " MiB, more than max-memory allows (" + std::to_string(maxMemoryBytes(limits) >> 20) +
                         " MiB); raise max-memory",
                     {"max-memory"});
  }
  return scene;
}

Scene loadScene(const std::string& nameOrPath, const SceneLoadOptions& options, const ResourceLimits& limits) {
  if (nameOrPath.rfind(kBuiltinPrefix, 0) == 0) {
    return makeBuiltinScene(std::string_view(nameOrPath).substr(kBuiltinPrefix.size()));
  }
  return loadGltf(nameOrPath, options, limits);
}

}  // namespace headlight
