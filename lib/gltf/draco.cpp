#include "gltf/draco.hpp"

#include <algorithm>
#include <cstring>
#include <map>

#if HEADLIGHT_HAS_DRACO
#include <draco/compression/decode.h>
#endif

namespace headlight::gltf {

namespace {

constexpr const char* kDraco = "KHR_draco_mesh_compression";

// Little-endian fields and Draco's varints (LEB128, at most 5 bytes for 32 bits).
class StreamReader {
 public:
  explicit StreamReader(std::span<const unsigned char> bytes) : bytes_(bytes) {}

  bool byte(std::uint32_t& value) {
    if (at_ >= bytes_.size()) return false;
    value = bytes_[at_++];
    return true;
  }
  bool u32(std::uint32_t& value) {
    if (bytes_.size() - at_ < 4) return false;
    std::memcpy(&value, bytes_.data() + at_, 4);
    at_ += 4;
    return true;
  }
  bool varint(std::uint32_t& value) {
    value = 0;
    for (int shift = 0; shift < 35; shift += 7) {
      std::uint32_t next = 0;
      if (!byte(next)) return false;
      value |= (next & 0x7f) << shift;
      if ((next & 0x80) == 0) return shift < 28 || next < 16;  // no more than 32 bits
    }
    return false;
  }
  // Draco wrote fixed 32-bit counts before bitstream 2.0 (2.2 for the sequential coder).
  bool count(std::uint32_t& value, bool fixed) { return fixed ? u32(value) : varint(value); }

 private:
  std::span<const unsigned char> bytes_;
  std::size_t at_ = 0;
};

}  // namespace

bool dracoDecoding() { return HEADLIGHT_HAS_DRACO != 0; }

// The header (Draco's PointCloudDecoder::DecodeHeader): "DRACO", version
// major and minor, encoder type (1: triangular mesh), method (0: sequential,
// 1: edgebreaker), 16-bit flags; then the connectivity's counts.
std::string peekDracoCounts(std::span<const unsigned char> stream, DracoCounts& counts) {
  constexpr std::size_t kHeaderBytes = 11;
  if (stream.size() < kHeaderBytes || std::memcmp(stream.data(), "DRACO", 5) != 0) {
    return "is not a Draco stream (no 'DRACO' header)";
  }
  const unsigned version = unsigned(stream[5]) << 8 | stream[6];
  const unsigned type = stream[7], method = stream[8];
  const unsigned flags = unsigned(stream[9]) | unsigned(stream[10]) << 8;
  if (stream[5] < 1 || version > 0x0202) {
    return "has Draco bitstream version " + std::to_string(stream[5]) + "." + std::to_string(stream[6]) +
           ", expected 1.0..2.2";
  }
  if (type != 1) return "holds a Draco point cloud or unknown geometry (type " + std::to_string(type) + "), not a mesh";
  // Metadata sits before the counts and its size is not stated up front.
  if (flags & 0x8000) return "carries Draco metadata, which is not read (its size cannot be bounded before decoding)";
  StreamReader reader(stream.subspan(kHeaderBytes));
  std::uint32_t faces = 0, vertices = 0, added = 0, traversal = 0;
  bool read = false;
  if (method == 0) {
    read = reader.count(faces, version < 0x0202) && reader.count(vertices, version < 0x0202);
  } else if (method == 1) {
    read = reader.byte(traversal) && (version >= 0x0202 || reader.count(added, version < 0x0200)) &&
           reader.count(vertices, version < 0x0200) && reader.count(faces, version < 0x0200);
  } else {
    return "has Draco encoding method " + std::to_string(method) + ", expected 0 (sequential) or 1 (edgebreaker)";
  }
  if (!read) return "ends inside its Draco header";
  counts.faces = faces;
  counts.vertices = std::uint64_t(vertices) + added;
  return {};
}

#if !HEADLIGHT_HAS_DRACO

void decodeDracoPrimitives(tinygltf::Model&, const Source&, const ResourceLimits&) {}

#else

namespace {

template <typename T>
void convertPoints(const draco::PointAttribute& attribute, std::size_t points, int components, unsigned char* out,
                   bool& converted) {
  T values[16];
  for (std::size_t point = 0; point < points && converted; ++point) {
    converted = attribute.ConvertValue<T>(attribute.mapped_index(draco::PointIndex(std::uint32_t(point))),
                                          std::int8_t(components), values);
    std::memcpy(out + point * sizeof(T) * std::size_t(components), values, sizeof(T) * std::size_t(components));
  }
}

class PrimitiveDecoder {
 public:
  PrimitiveDecoder(tinygltf::Model& model, const Source& source, const ResourceLimits& limits)
      : model_(model), source_(source), limits_(limits) {}

  void run() {
    for (std::size_t mesh = 0; mesh < model_.meshes.size(); ++mesh) {
      auto& primitives = model_.meshes[mesh].primitives;
      for (std::size_t primitive = 0; primitive < primitives.size(); ++primitive) {
        const auto found = primitives[primitive].extensions.find(kDraco);
        if (found == primitives[primitive].extensions.end()) continue;
        name_ = "mesh " + std::to_string(mesh) + " primitive " + std::to_string(primitive);
        decode(primitives[primitive], found->second);
      }
    }
  }

 private:
  [[noreturn]] void fail(const std::string& problem) const { source_.fail(name_ + " " + kDraco + ": " + problem); }

  int index(const tinygltf::Value& value, const std::string& what) const {
    if (!value.IsNumber() || value.GetNumberAsDouble() < 0 || value.GetNumberAsDouble() > 2147483647.0 ||
        value.GetNumberAsDouble() != double(value.GetNumberAsInt())) {
      fail(what + " is not a non-negative integer");
    }
    return value.GetNumberAsInt();
  }

  std::span<const unsigned char> streamBytes(int viewIndex) const {
    source_.checkIndex(viewIndex, model_.bufferViews, name_ + " " + kDraco, "bufferView");
    const tinygltf::BufferView& view = model_.bufferViews[std::size_t(viewIndex)];
    source_.checkIndex(view.buffer, model_.buffers, "bufferView " + std::to_string(viewIndex), "buffer");
    const auto& data = model_.buffers[std::size_t(view.buffer)].data;
    if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset) {
      fail("bufferView " + std::to_string(viewIndex) + " spans bytes " + std::to_string(view.byteOffset) + ".." +
           std::to_string(view.byteOffset + view.byteLength) + " of buffer " + std::to_string(view.buffer) +
           ", which has " + std::to_string(data.size()));
    }
    return {data.data() + view.byteOffset, view.byteLength};
  }

  // The header's counts against max-triangles (with the streams before it),
  // before Draco allocates for them: faces as triangles, points as the
  // vertices the geometry reader allows (3 a triangle).
  void reserve(std::span<const unsigned char> stream, int viewIndex) {
    DracoCounts counts;
    const std::string problem = peekDracoCounts(stream, counts);
    if (!problem.empty()) fail("bufferView " + std::to_string(viewIndex) + " " + problem);
    const auto triangles = std::uint64_t(limits_.maxTriangles);
    if (counts.faces > triangles - std::min(triangles, faces_) ||
        counts.vertices > 3 * triangles - std::min(3 * triangles, vertices_)) {
      source_.failLimit(name_ + " " + kDraco + ": bufferView " + std::to_string(viewIndex) + " states " +
                            std::to_string(counts.faces) + " faces and " + std::to_string(counts.vertices) +
                            " points, and with the " + std::to_string(faces_) +
                            " faces decoded before it that is more than max-triangles " + std::to_string(triangles) +
                            " (3 points a triangle); raise max-triangles",
                        "max-triangles");
    }
    faces_ += counts.faces;
    vertices_ += counts.vertices;
  }

  // A new buffer and bufferView holding `bytes`; accessor `accessorIndex`
  // reads them from offset 0.
  void pointAccessorAt(int accessorIndex, std::vector<unsigned char> bytes) {
    tinygltf::BufferView view;
    view.buffer = int(model_.buffers.size());
    view.byteLength = bytes.size();
    tinygltf::Buffer buffer;
    buffer.name = name_ + " Draco-decoded";
    buffer.data = std::move(bytes);
    model_.buffers.push_back(std::move(buffer));
    tinygltf::Accessor& accessor = model_.accessors[std::size_t(accessorIndex)];
    accessor.bufferView = int(model_.bufferViews.size());
    accessor.byteOffset = 0;
    model_.bufferViews.push_back(view);
  }

  // True when the accessor still needs the stream's data; an accessor that
  // two primitives decode from different streams is refused.
  bool claim(int accessorIndex, int viewIndex, const std::string& user) {
    source_.checkIndex(accessorIndex, model_.accessors, name_ + " " + user, "accessor");
    auto [entry, inserted] = decodedFrom_.try_emplace(accessorIndex, viewIndex);
    if (!inserted && entry->second != viewIndex) {
      fail(user + " accessor " + std::to_string(accessorIndex) + " is decoded from bufferView " +
           std::to_string(entry->second) + " by another primitive, and from bufferView " + std::to_string(viewIndex) +
           " here");
    }
    return inserted;
  }

  void writeIndices(const draco::Mesh& mesh, int accessorIndex) {
    const tinygltf::Accessor& accessor = model_.accessors[std::size_t(accessorIndex)];
    const std::size_t count = std::size_t(mesh.num_faces()) * 3;
    if (accessor.count != count) {
      fail("indices accessor " + std::to_string(accessorIndex) + " has count " + std::to_string(accessor.count) +
           ", but the stream decodes " + std::to_string(mesh.num_faces()) + " faces (" + std::to_string(count) +
           " indices)");
    }
    const int size = tinygltf::GetComponentSizeInBytes(std::uint32_t(accessor.componentType));
    if (size != 1 && size != 2 && size != 4) {
      fail("indices accessor " + std::to_string(accessorIndex) + " is " + componentTypeName(accessor.componentType) +
           ", expected UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT");
    }
    const std::uint64_t reach = size == 4 ? (std::uint64_t(1) << 32) : (std::uint64_t(1) << (8 * size));
    std::vector<unsigned char> bytes(count * std::size_t(size));
    for (std::uint32_t face = 0; face < mesh.num_faces(); ++face) {
      for (int corner = 0; corner < 3; ++corner) {
        const std::uint32_t value = mesh.face(draco::FaceIndex(face))[corner].value();
        if (value >= reach) {
          fail("point index " + std::to_string(value) + " does not fit indices accessor " +
               std::to_string(accessorIndex) + "'s " + componentTypeName(accessor.componentType));
        }
        std::memcpy(bytes.data() + (std::size_t(face) * 3 + std::size_t(corner)) * std::size_t(size), &value,
                    std::size_t(size));  // little-endian: the low bytes
      }
    }
    pointAccessorAt(accessorIndex, std::move(bytes));
  }

  void writeAttribute(const draco::Mesh& mesh, const std::string& attribute, int uniqueId, int accessorIndex) {
    const draco::PointAttribute* decoded = mesh.GetAttributeByUniqueId(std::uint32_t(uniqueId));
    const std::string user = attribute + " accessor " + std::to_string(accessorIndex);
    if (decoded == nullptr)
      fail(attribute + " is Draco attribute " + std::to_string(uniqueId) + ", which the stream lacks");
    const tinygltf::Accessor& accessor = model_.accessors[std::size_t(accessorIndex)];
    const int components = tinygltf::GetNumComponentsInType(std::uint32_t(accessor.type));
    const int size = tinygltf::GetComponentSizeInBytes(std::uint32_t(accessor.componentType));
    if (components < 1 || components > 16 || size < 1) fail(user + " has no valid type and componentType");
    if (decoded->num_components() != components) {
      fail(user + " is " + typeName(accessor.type) + ", but Draco attribute " + std::to_string(uniqueId) + " has " +
           std::to_string(int(decoded->num_components())) + " components");
    }
    if (accessor.count != mesh.num_points()) {
      fail(user + " has count " + std::to_string(accessor.count) + ", but the stream decodes " +
           std::to_string(mesh.num_points()) + " points");
    }
    std::vector<unsigned char> bytes(accessor.count * std::size_t(components) * std::size_t(size));
    bool converted = true;
    switch (accessor.componentType) {
      case TINYGLTF_COMPONENT_TYPE_BYTE:
        convertPoints<std::int8_t>(*decoded, accessor.count, components, bytes.data(), converted);
        break;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        convertPoints<std::uint8_t>(*decoded, accessor.count, components, bytes.data(), converted);
        break;
      case TINYGLTF_COMPONENT_TYPE_SHORT:
        convertPoints<std::int16_t>(*decoded, accessor.count, components, bytes.data(), converted);
        break;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
        convertPoints<std::uint16_t>(*decoded, accessor.count, components, bytes.data(), converted);
        break;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        convertPoints<std::uint32_t>(*decoded, accessor.count, components, bytes.data(), converted);
        break;
      case TINYGLTF_COMPONENT_TYPE_FLOAT:
        convertPoints<float>(*decoded, accessor.count, components, bytes.data(), converted);
        break;
      default:
        fail(user + " is " + componentTypeName(accessor.componentType) + ", which Draco data cannot fill");
    }
    if (!converted)
      fail("Draco attribute " + std::to_string(uniqueId) + " does not convert to " + user + "'s " +
           componentTypeName(accessor.componentType));
    pointAccessorAt(accessorIndex, std::move(bytes));
  }

  void decode(tinygltf::Primitive& primitive, const tinygltf::Value& extension) {
    if (!extension.IsObject() || !extension.Has("bufferView") || !extension.Has("attributes") ||
        !extension.Get("attributes").IsObject()) {
      fail("expected an object with bufferView and attributes");
    }
    if (primitive.mode != TINYGLTF_MODE_TRIANGLES) {
      fail("mode " + modeName(primitive.mode) + " is not decoded; Draco primitives are read as TRIANGLES only");
    }
    if (primitive.indices < 0) fail("the primitive has no indices accessor for the stream's faces");
    const int viewIndex = index(extension.Get("bufferView"), "bufferView");
    const std::span<const unsigned char> stream = streamBytes(viewIndex);
    reserve(stream, viewIndex);
    draco::DecoderBuffer buffer;
    buffer.Init(reinterpret_cast<const char*>(stream.data()), stream.size());
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
    if (!decoded.ok())
      fail("bufferView " + std::to_string(viewIndex) + " does not decode: " + decoded.status().error_msg_string());
    const draco::Mesh& mesh = *decoded.value();
    if (claim(primitive.indices, viewIndex, "indices")) writeIndices(mesh, primitive.indices);
    const tinygltf::Value& attributes = extension.Get("attributes");
    for (const std::string& attribute : attributes.Keys()) {
      const auto accessor = primitive.attributes.find(attribute);
      if (accessor == primitive.attributes.end()) {
        fail("lists attribute " + attribute + ", which the primitive's attributes lack");
      }
      const int uniqueId = index(attributes.Get(attribute), "attributes." + attribute);
      if (claim(accessor->second, viewIndex, attribute)) writeAttribute(mesh, attribute, uniqueId, accessor->second);
    }
  }

  tinygltf::Model& model_;
  const Source& source_;
  const ResourceLimits& limits_;
  std::uint64_t faces_ = 0, vertices_ = 0;
  std::map<int, int> decodedFrom_;  // accessor -> the Draco bufferView it was decoded from
  std::string name_;
};

}  // namespace

void decodeDracoPrimitives(tinygltf::Model& model, const Source& source, const ResourceLimits& limits) {
  PrimitiveDecoder(model, source, limits).run();
}

#endif

}  // namespace headlight::gltf
