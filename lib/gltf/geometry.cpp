#include "gltf/geometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "gltf/pose.hpp"
#include "headlight/scene_loader.hpp"

namespace headlight::gltf {

int attributeAccessor(const tinygltf::Primitive& primitive, const char* attribute) {
  const auto found = primitive.attributes.find(attribute);
  return found == primitive.attributes.end() ? -1 : found->second;
}

GeometryReader::GeometryReader(const Source& source, const ResourceLimits& limits)
    : source_(source),
      accessors_(source),
      limits_(limits),
      quantized_(std::find(source.model.extensionsUsed.begin(), source.model.extensionsUsed.end(),
                           "KHR_mesh_quantization") != source.model.extensionsUsed.end()) {}

// Every vertex decoded counts against --max-triangles before its memory is
// allocated (3 vertices per allowed triangle at most).
void GeometryReader::reserveVertices(std::size_t count, int accessorIndex, const std::string& user) {
  const auto allowed = static_cast<std::uint64_t>(limits_.maxTriangles) * 3;
  if (count > allowed - std::min<std::uint64_t>(allowed, decodedVertices_)) {
    source_.failLimit(user + " accessor " + std::to_string(accessorIndex) + " has " + std::to_string(count) +
                          " vertices, and with the " + std::to_string(decodedVertices_) +
                          " before it that is more than the " + std::to_string(allowed) + " (3 x max-triangles " +
                          std::to_string(limits_.maxTriangles) + ") allowed; raise max-triangles",
                      "max-triangles");
  }
  decodedVertices_ += count;
}

// The deltas of every morph target that moves the primitive (a weight other
// than 0) are decoded vertices as much as its own: they count against the
// same budget, before the primitive's first vertex is read (`vertexCount`:
// its POSITION accessor's count). A 36 KB file of 300 targets over 30M
// vertices took 38 s and 1.8 GB before the frame's triangle count refused it
// (issue 32).
void GeometryReader::reserveMorphDeltas(const tinygltf::Primitive& source, const std::vector<float>& weights,
                                        std::size_t vertexCount, const std::string& primitiveName) {
  std::uint64_t deltas = 0;
  for (std::size_t k = 0; k < std::min(weights.size(), source.targets.size()); ++k) {
    if (weights[k] == 0.0f) continue;
    const auto& target = source.targets[k];
    // As applyMorphTargets: NORMAL and TANGENT deltas only where the primitive has the attribute.
    const std::uint64_t sets = target.count("POSITION") +
                               (source.attributes.count("NORMAL") != 0 ? target.count("NORMAL") : 0) +
                               (source.attributes.count("TANGENT") != 0 ? target.count("TANGENT") : 0);
    deltas += sets * vertexCount;
  }
  if (deltas == 0) return;
  const auto allowed = static_cast<std::uint64_t>(limits_.maxTriangles) * 3;
  if (deltas > allowed - std::min<std::uint64_t>(allowed, decodedVertices_)) {
    source_.failLimit(primitiveName + "'s morph targets move " + std::to_string(vertexCount) + " vertices by " +
                          std::to_string(deltas) + " deltas, and with the " + std::to_string(decodedVertices_) +
                          " vertices decoded before them that is more than the " + std::to_string(allowed) +
                          " (3 x max-triangles " + std::to_string(limits_.maxTriangles) +
                          ") allowed; raise max-triangles",
                      "max-triangles");
  }
  decodedVertices_ += deltas;
}

void GeometryReader::reserveTriangles(std::size_t count, const std::string& primitiveName) {
  const auto allowed = static_cast<std::uint64_t>(limits_.maxTriangles);
  if (count > allowed - std::min<std::uint64_t>(allowed, decodedTriangles_)) {
    source_.failLimit(primitiveName + " has " + std::to_string(count) + " triangles, and with the " +
                          std::to_string(decodedTriangles_) + " before it that is more than max-triangles " +
                          std::to_string(allowed) + "; raise max-triangles",
                      "max-triangles");
  }
  decodedTriangles_ += count;
}

std::vector<glm::vec3> GeometryReader::readPositions(int accessorIndex, const std::string& primitiveName) {
  const CheckedAccessor accessor =
      accessors_.check(accessorIndex, primitiveName + " POSITION",
                       quantized_ ? std::span<const AccessorFormat>(kQuantizedPositionFormats)
                                  : std::span<const AccessorFormat>(kPositionFormats));
  reserveVertices(accessor.count, accessorIndex, primitiveName + " POSITION");
  std::vector<glm::vec3> positions = accessors_.readFloats<3>(accessor);
  for (std::size_t vertex = 0; vertex < positions.size(); ++vertex) {
    const glm::vec3& p = positions[vertex];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
      source_.fail("accessor " + std::to_string(accessorIndex) + " (POSITION of " + primitiveName +
                   ") has a non-finite value at element " + std::to_string(vertex));
    }
  }
  // Indices are 32-bit; more vertices than that could not all be drawn.
  if (positions.size() > std::numeric_limits<std::uint32_t>::max()) {
    source_.fail(primitiveName + " has " + std::to_string(positions.size()) +
                 " vertices, more than 32-bit indices reach");
  }
  return positions;
}

// The primitive's vertex order: its indices, or 0..vertexCount-1 without.
std::vector<std::uint32_t> GeometryReader::readVertexOrder(int accessorIndex, const std::string& primitiveName,
                                                           std::size_t vertexCount) {
  if (accessorIndex < 0) {
    std::vector<std::uint32_t> order(vertexCount);
    for (std::size_t vertex = 0; vertex < vertexCount; ++vertex) {
      order[vertex] = static_cast<std::uint32_t>(vertex);
    }
    return order;
  }
  const CheckedAccessor accessor = accessors_.check(accessorIndex, primitiveName + " indices", kIndexFormats);
  std::vector<std::uint32_t> indices = accessors_.readIndices(accessor);
  for (std::size_t position = 0; position < indices.size(); ++position) {
    if (indices[position] >= vertexCount) {
      source_.fail(primitiveName + ": index " + std::to_string(position) + " of accessor " +
                   std::to_string(accessorIndex) + " is " + std::to_string(indices[position]) +
                   ", but the primitive has " + countOf(vertexCount, "vertex") + " (expected < " +
                   std::to_string(vertexCount) + ")");
    }
  }
  return indices;
}

// Strips and fans as triangle lists, with glTF's (and GL's) winding: strip
// triangle i is (i, i+1, i+2), its first two swapped for odd i; fan
// triangle i is (0, i+1, i+2).
static std::vector<std::uint32_t> triangleList(std::vector<std::uint32_t> order, int mode) {
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    return order;  // moved: no copy of a large index buffer
  }
  if (order.size() < 3) {
    return {};
  }
  std::vector<std::uint32_t> triangles;
  triangles.reserve((order.size() - 2) * 3);
  for (std::size_t i = 0; i + 2 < order.size(); ++i) {
    if (mode == TINYGLTF_MODE_TRIANGLE_FAN) {
      triangles.insert(triangles.end(), {order[0], order[i + 1], order[i + 2]});
    } else if (i % 2 == 0) {
      triangles.insert(triangles.end(), {order[i], order[i + 1], order[i + 2]});
    } else {
      triangles.insert(triangles.end(), {order[i + 1], order[i], order[i + 2]});
    }
  }
  return triangles;
}

// Line strips and loops as line lists (segment i is (i, i+1); a loop adds
// (n-1, 0)); points and lines stay as they are.
static std::vector<std::uint32_t> lineList(std::vector<std::uint32_t> order, int mode) {
  if (mode != TINYGLTF_MODE_LINE_LOOP && mode != TINYGLTF_MODE_LINE_STRIP) {
    return order;
  }
  if (order.size() < 2) {
    return {};
  }
  std::vector<std::uint32_t> lines;
  lines.reserve(order.size() * 2);
  for (std::size_t i = 0; i + 1 < order.size(); ++i) {
    lines.insert(lines.end(), {order[i], order[i + 1]});
  }
  if (mode == TINYGLTF_MODE_LINE_LOOP) {
    lines.insert(lines.end(), {order.back(), order.front()});
  }
  return lines;
}

// How many elements (points, segments, triangles) `orderCount` vertices
// make in `mode`; each counts once against max-triangles.
static std::size_t elementCount(int mode, std::size_t orderCount) {
  switch (mode) {
    case TINYGLTF_MODE_POINTS:
      return orderCount;
    case TINYGLTF_MODE_LINE:
      return orderCount / 2;
    case TINYGLTF_MODE_LINE_LOOP:
      return orderCount >= 2 ? orderCount : 0;
    case TINYGLTF_MODE_LINE_STRIP:
      return orderCount >= 2 ? orderCount - 1 : 0;
    case TINYGLTF_MODE_TRIANGLES:
      return orderCount / 3;
    default:
      return orderCount >= 3 ? orderCount - 2 : 0;  // strips and fans
  }
}

std::vector<std::uint32_t> GeometryReader::readElementIndices(const tinygltf::Primitive& source,
                                                              const std::string& primitiveName,
                                                              std::size_t vertexCount) {
  const int accessorIndex = source.indices;
  const std::size_t orderCount = accessorIndex < 0
                                     ? vertexCount
                                     : accessors_.check(accessorIndex, primitiveName + " indices", kIndexFormats).count;
  reserveTriangles(elementCount(source.mode, orderCount), primitiveName);
  const std::size_t multiple = source.mode == TINYGLTF_MODE_TRIANGLES ? 3 : (source.mode == TINYGLTF_MODE_LINE ? 2 : 1);
  if (orderCount % multiple != 0) {
    source_.fail(
        primitiveName + " has " + std::to_string(orderCount) +
        (accessorIndex < 0 ? " vertices and no indices" : " indices in accessor " + std::to_string(accessorIndex)) +
        ", expected a multiple of " + std::to_string(multiple) + " for " + modeName(source.mode));
  }
  std::vector<std::uint32_t> order = readVertexOrder(accessorIndex, primitiveName, vertexCount);
  if (source.mode <= TINYGLTF_MODE_LINE_STRIP) {
    return lineList(std::move(order), source.mode);
  }
  return triangleList(std::move(order), source.mode);
}

namespace {

// Normals from the file are normalised; any that cannot be (zero, NaN) are
// replaced by generated ones rather than reaching the shader.
void repairNormals(Primitive& primitive) {
  // Points and lines have no faces to generate from: an unusable normal
  // becomes 0, which gbuffer.frag turns toward the camera.
  const bool faces = primitive.mode == PrimitiveMode::Triangles;
  bool allUsable = true;
  for (glm::vec3& normal : primitive.normals) {
    const float length = glm::length(normal);
    if (std::isfinite(length) && length > 1e-12f) {
      normal /= length;
    } else {
      allUsable = false;
      if (!faces) normal = glm::vec3(0.0f);
    }
  }
  if (!allUsable && faces) {
    Primitive generated;
    generated.positions = primitive.positions;
    generated.indices = primitive.indices;
    generateNormals(generated);
    for (std::size_t vertex = 0; vertex < primitive.normals.size(); ++vertex) {
      const float length = glm::length(primitive.normals[vertex]);
      if (!(std::isfinite(length) && std::abs(length - 1.0f) < 1e-3f)) {
        primitive.normals[vertex] = generated.normals[vertex];
      }
    }
  }
}

}  // namespace

std::vector<glm::vec4> GeometryReader::readColors(int accessorIndex, const std::string& primitiveName,
                                                  std::size_t vertexCount, int positionAccessor) {
  const std::string user = primitiveName + " COLOR_0";
  const CheckedAccessor accessor = accessors_.check(accessorIndex, user, kColorFormats);
  if (accessor.count != vertexCount) {
    source_.fail(user + " accessor " + std::to_string(accessorIndex) + " has " + std::to_string(accessor.count) +
                 " elements, but POSITION accessor " + std::to_string(positionAccessor) + " has " +
                 std::to_string(vertexCount));
  }
  std::vector<glm::vec4> colors;
  if (source_.model.accessors[std::size_t(accessorIndex)].type == TINYGLTF_TYPE_VEC3) {
    for (const glm::vec3& rgb : accessors_.readFloats<3>(accessor)) colors.emplace_back(rgb, 1.0f);
  } else {
    colors = accessors_.readFloats<4>(accessor);
  }
  for (std::size_t vertex = 0; vertex < colors.size(); ++vertex) {
    const glm::vec4& c = colors[vertex];
    if (!std::isfinite(c.r) || !std::isfinite(c.g) || !std::isfinite(c.b) || !std::isfinite(c.a)) {
      source_.fail(user + " (accessor " + std::to_string(accessorIndex) + ") has a non-finite value at element " +
                   std::to_string(vertex));
    }
  }
  return colors;
}

Primitive GeometryReader::read(const tinygltf::Primitive& source, const std::string& primitiveName, const Pose& pose,
                               bool readTexcoord1) {
  using Formats = std::span<const AccessorFormat>;
  Primitive primitive;
  const int positionAccessor = attributeAccessor(source, "POSITION");
  if (positionAccessor < 0) {
    source_.fail(primitiveName + " has no POSITION attribute");
  }
  if (std::size_t(positionAccessor) < source_.model.accessors.size())  // else readPositions names the index
    reserveMorphDeltas(source, pose.weights, source_.model.accessors[std::size_t(positionAccessor)].count,
                       primitiveName);
  primitive.positions = readPositions(positionAccessor, primitiveName);
  const std::size_t vertexCount = primitive.positions.size();
  primitive.mode = source.mode == TINYGLTF_MODE_POINTS       ? PrimitiveMode::Points
                   : source.mode <= TINYGLTF_MODE_LINE_STRIP ? PrimitiveMode::Lines
                                                             : PrimitiveMode::Triangles;
  primitive.indices = readElementIndices(source, primitiveName, vertexCount);
  const int normals = attributeAccessor(source, "NORMAL");
  if (normals >= 0) {
    primitive.normals = accessors_.readAttribute<3>(
        normals, primitiveName + " NORMAL", quantized_ ? Formats(kQuantizedNormalFormats) : Formats(kNormalFormats),
        vertexCount, positionAccessor);
  }
  // Every set is read through the same formats and checks (TEXCOORD_1 only
  // when a material samples it).
  std::vector<glm::vec2>* sets[kTexcoordSets] = {&primitive.texcoords, &primitive.texcoords1};
  for (int set = 0; set < (readTexcoord1 ? 2 : 1); ++set) {
    const std::string attribute = "TEXCOORD_" + std::to_string(set);
    if (const int texcoords = attributeAccessor(source, attribute.c_str()); texcoords >= 0) {
      const Formats formats = quantized_ ? Formats(kQuantizedTexcoordFormats) : Formats(kTexcoordFormats);
      *sets[set] = accessors_.readAttribute<2>(texcoords, primitiveName + " " + attribute, formats, vertexCount,
                                               positionAccessor);
    }
  }
  // Missing tangents stay missing: the G-buffer shader derives a tangent
  // frame from screen-space derivatives instead.
  if (const int tangents = attributeAccessor(source, "TANGENT"); tangents >= 0) {
    primitive.tangents = accessors_.readAttribute<4>(
        tangents, primitiveName + " TANGENT", quantized_ ? Formats(kQuantizedTangentFormats) : Formats(kTangentFormats),
        vertexCount, positionAccessor);
  }
  if (const int colors = attributeAccessor(source, "COLOR_0"); colors >= 0) {
    primitive.colors = readColors(colors, primitiveName, vertexCount, positionAccessor);
  }
  applyMorphTargets(accessors_, source, primitiveName, pose.weights, primitive);
  if (normals >= 0) {
    repairNormals(primitive);
  }
  if (pose.joints != nullptr) {
    applySkin(accessors_, source, primitiveName, *pose.joints, primitive);
    if (normals >= 0) {
      repairNormals(primitive);  // skinning scales them
    }
  }
  if (normals < 0 && primitive.mode == PrimitiveMode::Triangles) {
    generateNormals(primitive);
  } else if (normals < 0) {
    // Points and lines without NORMAL: 0, faced toward the camera by
    // gbuffer.frag (docs/PIPELINE.md §2.2).
    primitive.normals.assign(vertexCount, glm::vec3(0.0f));
  }
  for (const glm::vec3& position : primitive.positions) {
    primitive.bounds.extend(position);
  }
  return primitive;
}

}  // namespace headlight::gltf
