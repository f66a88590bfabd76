#include "compressed_inputs.hpp"

#include <cmath>
#include <cstring>
#include <stdexcept>

#include "hostile_inputs.hpp"
#include "support/encoding.hpp"

#if HEADLIGHT_HAS_DRACO
#include <draco/compression/encode.h>
#include <draco/mesh/mesh.h>
#endif
#if HEADLIGHT_HAS_MESHOPT
#include <meshoptimizer.h>
#endif

namespace headlight::test::compressed {

using nlohmann::json;

const bool kDracoAvailable = HEADLIGHT_HAS_DRACO != 0;
const bool kMeshoptAvailable = HEADLIGHT_HAS_MESHOPT != 0;

namespace {

template <typename T>
void append(std::vector<unsigned char>& bytes, const std::vector<T>& values) {
  const auto* raw = reinterpret_cast<const unsigned char*>(values.data());
  bytes.insert(bytes.end(), raw, raw + values.size() * sizeof(T));
  while (bytes.size() % 4 != 0) bytes.push_back(0);
}

json positionAccessor(const KnownMesh& mesh) {
  glm::vec3 low(1e30f), high(-1e30f);
  for (const glm::vec3& p : mesh.positions) low = glm::min(low, p), high = glm::max(high, p);
  return {{"componentType", 5126}, {"type", "VEC3"}, {"count", mesh.positions.size()},
          {"min", {low.x, low.y, low.z}}, {"max", {high.x, high.y, high.z}}};
}

// The document around one primitive: accessors 0 POSITION, 1 NORMAL, 2 TEXCOORD_0, 3 indices.
json meshDocument(const KnownMesh& mesh) {
  json document = {{"asset", {{"version", "2.0"}}},
                   {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}}},
                                                 {"indices", 3}, {"mode", 4}}}}}}},
                   {"nodes", {{{"mesh", 0}}}},
                   {"scenes", {{{"nodes", {0}}}}},
                   {"scene", 0}};
  document["accessors"] = {positionAccessor(mesh),
                           {{"componentType", 5126}, {"type", "VEC3"}, {"count", mesh.normals.size()}},
                           {{"componentType", 5126}, {"type", "VEC2"}, {"count", mesh.uvs.size()}},
                           {{"componentType", 5123}, {"type", "SCALAR"}, {"count", mesh.indices.size()}}};
  return document;
}

}  // namespace

KnownMesh torus() {
  constexpr int kAround = 16, kTube = 8;
  constexpr float kPi = 3.14159265f;
  KnownMesh mesh;
  for (int i = 0; i <= kAround; ++i) {
    for (int j = 0; j <= kTube; ++j) {
      const float u = float(i) / kAround, v = float(j) / kTube;
      const float a = u * 2 * kPi, b = v * 2 * kPi;
      const glm::vec3 centre(std::cos(a), 0.0f, std::sin(a));
      const glm::vec3 normal = std::cos(b) * centre + std::sin(b) * glm::vec3(0, 1, 0);
      mesh.positions.push_back(centre + 0.4f * normal);
      mesh.normals.push_back(normal);
      mesh.uvs.emplace_back(u, v);
    }
  }
  for (int i = 0; i < kAround; ++i) {
    for (int j = 0; j < kTube; ++j) {
      const auto at = [](int a, int b) { return std::uint16_t(a * (kTube + 1) + b); };
      mesh.indices.insert(mesh.indices.end(), {at(i, j), at(i, j + 1), at(i + 1, j)});
      mesh.indices.insert(mesh.indices.end(), {at(i + 1, j), at(i, j + 1), at(i + 1, j + 1)});
    }
  }
  return mesh;
}

json plainGltf(const KnownMesh& mesh) {
  std::vector<unsigned char> bytes;
  std::vector<std::size_t> offsets;
  offsets.push_back(bytes.size()), append(bytes, mesh.positions);
  offsets.push_back(bytes.size()), append(bytes, mesh.normals);
  offsets.push_back(bytes.size()), append(bytes, mesh.uvs);
  offsets.push_back(bytes.size()), append(bytes, mesh.indices);
  offsets.push_back(bytes.size());
  json document = meshDocument(mesh);
  document["buffers"] = {{{"byteLength", bytes.size()}, {"uri", "data:application/octet-stream;base64," + base64(bytes)}}};
  for (std::size_t view = 0; view < 4; ++view) {
    document["bufferViews"].push_back(
        {{"buffer", 0}, {"byteOffset", offsets[view]}, {"byteLength", offsets[view + 1] - offsets[view]}});
    document["accessors"][view]["bufferView"] = view;
  }
  return document;
}

#if HEADLIGHT_HAS_DRACO

namespace {

template <typename T>
int addAttribute(draco::Mesh& target, draco::GeometryAttribute::Type type, const std::vector<T>& values) {
  draco::GeometryAttribute attribute;
  attribute.Init(type, nullptr, std::uint8_t(sizeof(T) / sizeof(float)), draco::DT_FLOAT32, false, sizeof(T), 0);
  const int id = target.AddAttribute(attribute, true, std::uint32_t(values.size()));
  for (std::size_t i = 0; i < values.size(); ++i) {
    target.attribute(id)->SetAttributeValue(draco::AttributeValueIndex(std::uint32_t(i)), &values[i]);
  }
  target.attribute(id)->set_unique_id(std::uint32_t(id));
  return id;
}

}  // namespace

std::vector<unsigned char> dracoStream(const KnownMesh& mesh, bool edgebreaker) {
  draco::Mesh target;
  target.set_num_points(std::uint32_t(mesh.positions.size()));
  addAttribute(target, draco::GeometryAttribute::POSITION, mesh.positions);
  addAttribute(target, draco::GeometryAttribute::NORMAL, mesh.normals);
  addAttribute(target, draco::GeometryAttribute::TEX_COORD, mesh.uvs);
  for (std::size_t i = 0; i < mesh.indices.size(); i += 3) {
    target.AddFace({draco::PointIndex(mesh.indices[i]), draco::PointIndex(mesh.indices[i + 1]),
                    draco::PointIndex(mesh.indices[i + 2])});
  }
  draco::Encoder encoder;
  encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, 14);
  encoder.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, 10);
  encoder.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, 12);
  encoder.SetEncodingMethod(edgebreaker ? draco::MESH_EDGEBREAKER_ENCODING : draco::MESH_SEQUENTIAL_ENCODING);
  draco::EncoderBuffer buffer;
  if (!encoder.EncodeMeshToBuffer(target, &buffer).ok()) throw std::runtime_error("draco encoding failed");
  return {buffer.data(), buffer.data() + buffer.size()};
}

#else

std::vector<unsigned char> dracoStream(const KnownMesh&, bool) { return {}; }

#endif

json dracoGltf(const KnownMesh& mesh, bool edgebreaker) {
  std::vector<unsigned char> stream = dracoStream(mesh, edgebreaker);
  json document = meshDocument(mesh);
  document["buffers"] = {{{"byteLength", stream.size()}, {"uri", "data:application/octet-stream;base64," + base64(stream)}}};
  document["bufferViews"] = {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", stream.size()}}};
  document["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"] = {
      {"bufferView", 0}, {"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}}}};
  document["extensionsUsed"] = {"KHR_draco_mesh_compression"};
  document["extensionsRequired"] = {"KHR_draco_mesh_compression"};
  return document;
}

#if HEADLIGHT_HAS_MESHOPT

namespace {

struct MeshoptStream {
  std::vector<unsigned char> bytes;
  std::size_t count, stride;
  const char* mode;
  const char* filter;
};

std::vector<MeshoptStream> meshoptStreams(const KnownMesh& mesh) {
  std::vector<MeshoptStream> streams;
  auto vertices = [&](const void* data, std::size_t count, std::size_t stride, const char* filter) {
    std::vector<unsigned char> out(meshopt_encodeVertexBufferBound(count, stride));
    out.resize(meshopt_encodeVertexBuffer(out.data(), out.size(), data, count, stride));
    streams.push_back({out, count, stride, "ATTRIBUTES", filter});
  };
  vertices(mesh.positions.data(), mesh.positions.size(), 12, "NONE");
  std::vector<float> normals4;
  for (const glm::vec3& n : mesh.normals) normals4.insert(normals4.end(), {n.x, n.y, n.z, 0.0f});
  std::vector<std::int8_t> octahedral(mesh.normals.size() * 4);
  meshopt_encodeFilterOct(octahedral.data(), mesh.normals.size(), 4, 8, normals4.data());
  vertices(octahedral.data(), mesh.normals.size(), 4, "OCTAHEDRAL");
  vertices(mesh.uvs.data(), mesh.uvs.size(), 8, "NONE");
  std::vector<unsigned char> out(meshopt_encodeIndexBufferBound(mesh.indices.size(), mesh.positions.size()));
  out.resize(meshopt_encodeIndexBuffer(out.data(), out.size(), mesh.indices.data(), mesh.indices.size()));
  streams.push_back({out, mesh.indices.size(), 2, "TRIANGLES", "NONE"});
  return streams;
}

}  // namespace

std::vector<unsigned char> packMeshoptGlb(const json& document, const KnownMesh& mesh) {
  std::vector<unsigned char> bin;
  for (const MeshoptStream& stream : meshoptStreams(mesh)) append(bin, stream.bytes);
  return hostile::glb(document.dump(), bin, 2);
}

std::vector<unsigned char> meshoptGlb(const KnownMesh& mesh, json* documentOut) {
  json document = meshDocument(mesh);
  document["accessors"][1] = {{"componentType", 5120}, {"normalized", true}, {"type", "VEC3"},
                              {"count", mesh.normals.size()}};
  std::vector<unsigned char> bin;
  std::size_t placeholderBytes = 0;
  for (const MeshoptStream& stream : meshoptStreams(mesh)) {
    const bool vertexData = std::string(stream.mode) == "ATTRIBUTES";
    json view = {{"buffer", 1}, {"byteOffset", placeholderBytes}, {"byteLength", stream.count * stream.stride}};
    if (vertexData) view["byteStride"] = stream.stride;
    view["extensions"]["EXT_meshopt_compression"] = {{"buffer", 0},        {"byteOffset", bin.size()},
                                                     {"byteLength", stream.bytes.size()}, {"byteStride", stream.stride},
                                                     {"count", stream.count}, {"mode", stream.mode}};
    if (std::string(stream.filter) != "NONE") view["extensions"]["EXT_meshopt_compression"]["filter"] = stream.filter;
    document["bufferViews"].push_back(view);
    document["accessors"][document["bufferViews"].size() - 1]["bufferView"] = document["bufferViews"].size() - 1;
    append(bin, stream.bytes);
    placeholderBytes += (stream.count * stream.stride + 3) / 4 * 4;
  }
  document["buffers"] = {{{"byteLength", bin.size()}},
                         {{"byteLength", placeholderBytes}, {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}}};
  document["extensionsUsed"] = {"EXT_meshopt_compression", "KHR_mesh_quantization"};
  document["extensionsRequired"] = {"EXT_meshopt_compression", "KHR_mesh_quantization"};
  if (documentOut != nullptr) *documentOut = document;
  return hostile::glb(document.dump(), bin, 2);
}

#else

std::vector<unsigned char> packMeshoptGlb(const json&, const KnownMesh&) { return {}; }
std::vector<unsigned char> meshoptGlb(const KnownMesh&, json*) { return {}; }

#endif

}  // namespace headlight::test::compressed
