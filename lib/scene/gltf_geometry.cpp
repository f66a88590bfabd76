#include "scene/gltf_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "headlight/scene_loader.hpp"

namespace headlight::gltf {

int attributeAccessor(const tinygltf::Primitive& primitive, const char* attribute) {
  const auto found = primitive.attributes.find(attribute);
  return found == primitive.attributes.end() ? -1 : found->second;
}

// Every vertex decoded counts against --max-triangles before its memory is
// allocated (3 vertices per allowed triangle at most).
void GeometryReader::reserveVertices(std::size_t count, int accessorIndex, const std::string& user) {
  const auto allowed = static_cast<std::uint64_t>(limits_.maxTriangles) * 3;
  if (count > allowed - std::min<std::uint64_t>(allowed, decodedVertices_)) {
    source_.failLimit(user + " accessor " + std::to_string(accessorIndex) + " has " + std::to_string(count) +
                      " vertices, and with the " + std::to_string(decodedVertices_) +
                      " before it that is more than the " + std::to_string(allowed) + " (3 x --max-triangles " +
                      std::to_string(limits_.maxTriangles) + ") allowed; raise --max-triangles");
  }
  decodedVertices_ += count;
}

void GeometryReader::reserveTriangles(std::size_t count, const std::string& primitiveName) {
  const auto allowed = static_cast<std::uint64_t>(limits_.maxTriangles);
  if (count > allowed - std::min<std::uint64_t>(allowed, decodedTriangles_)) {
    source_.failLimit(primitiveName + " has " + std::to_string(count) + " triangles, and with the " +
                      std::to_string(decodedTriangles_) + " before it that is more than --max-triangles " +
                      std::to_string(allowed) + "; raise --max-triangles");
  }
  decodedTriangles_ += count;
}

std::vector<glm::vec3> GeometryReader::readPositions(int accessorIndex, const std::string& primitiveName) {
  const CheckedAccessor accessor = accessors_.check(accessorIndex, primitiveName + " POSITION", kPositionFormats);
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

std::vector<std::uint32_t> GeometryReader::readTriangleIndices(int accessorIndex, const std::string& primitiveName,
                                                               std::size_t vertexCount) {
  std::vector<std::uint32_t> indices;
  if (accessorIndex < 0) {
    reserveTriangles(vertexCount / 3, primitiveName);
    indices.resize(vertexCount);
    for (std::size_t vertex = 0; vertex < vertexCount; ++vertex) {
      indices[vertex] = static_cast<std::uint32_t>(vertex);
    }
  } else {
    const CheckedAccessor accessor = accessors_.check(accessorIndex, primitiveName + " indices", kIndexFormats);
    reserveTriangles(accessor.count / 3, primitiveName);
    indices = accessors_.readIndices(accessor);
    for (std::size_t position = 0; position < indices.size(); ++position) {
      if (indices[position] >= vertexCount) {
        source_.fail(primitiveName + ": index " + std::to_string(position) + " of accessor " +
                     std::to_string(accessorIndex) + " is " + std::to_string(indices[position]) +
                     ", but the primitive has " + countOf(vertexCount, "vertex") + " (expected < " +
                     std::to_string(vertexCount) + ")");
      }
    }
  }
  if (indices.size() % 3 != 0) {
    source_.fail(primitiveName + " has " + std::to_string(indices.size()) +
                 (accessorIndex < 0 ? " vertices and no indices" : " indices in accessor " + std::to_string(accessorIndex)) +
                 ", expected a multiple of 3 for TRIANGLES");
  }
  return indices;
}

namespace {

// Normals from the file are normalised; any that cannot be (zero, NaN) are
// replaced by generated ones rather than reaching the shader.
void repairNormals(Primitive& primitive) {
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

}  // namespace

Primitive GeometryReader::read(const tinygltf::Primitive& source, const std::string& primitiveName) {
  Primitive primitive;
  const int positionAccessor = attributeAccessor(source, "POSITION");
  if (positionAccessor < 0) {
    source_.fail(primitiveName + " has no POSITION attribute");
  }
  primitive.positions = readPositions(positionAccessor, primitiveName);
  const std::size_t vertexCount = primitive.positions.size();
  primitive.indices = readTriangleIndices(source.indices, primitiveName, vertexCount);
  if (const int normals = attributeAccessor(source, "NORMAL"); normals >= 0) {
    primitive.normals =
        accessors_.readAttribute<3>(normals, primitiveName + " NORMAL", kNormalFormats, vertexCount, positionAccessor);
    repairNormals(primitive);
  } else {
    generateNormals(primitive);
  }
  if (const int texcoords = attributeAccessor(source, "TEXCOORD_0"); texcoords >= 0) {
    primitive.texcoords = accessors_.readAttribute<2>(texcoords, primitiveName + " TEXCOORD_0", kTexcoordFormats,
                                                      vertexCount, positionAccessor);
  }
  // Missing tangents stay missing: the G-buffer shader derives a tangent
  // frame from screen-space derivatives instead.
  if (const int tangents = attributeAccessor(source, "TANGENT"); tangents >= 0) {
    primitive.tangents = accessors_.readAttribute<4>(tangents, primitiveName + " TANGENT", kTangentFormats,
                                                     vertexCount, positionAccessor);
  }
  for (const glm::vec3& position : primitive.positions) {
    primitive.bounds.extend(position);
  }
  return primitive;
}

}  // namespace headlight::gltf
