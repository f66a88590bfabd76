#pragma once
// Primitives: a glTF mesh primitive's accessors to a Primitive (positions,
// indices, normals, texcoords, tangents), each vertex and triangle counted
// against --max-triangles before its memory is allocated.
#include <cstdint>
#include <string>

#include "headlight/limits.hpp"
#include "headlight/scene.hpp"
#include "scene/gltf_accessors.hpp"

namespace headlight::gltf {

// The accessor a primitive names for `attribute`, or -1.
int attributeAccessor(const tinygltf::Primitive& primitive, const char* attribute);

class GeometryReader {
 public:
  GeometryReader(const Source& source, const ResourceLimits& limits) : source_(source), accessors_(source), limits_(limits) {}

  // The geometry of `primitive` (named `primitiveName` in messages), whose
  // mode must be TRIANGLES, TRIANGLE_STRIP or TRIANGLE_FAN (made a triangle
  // list). Throws SceneError or LimitError.
  Primitive read(const tinygltf::Primitive& primitive, const std::string& primitiveName);

 private:
  void reserveVertices(std::size_t count, int accessorIndex, const std::string& user);
  void reserveTriangles(std::size_t count, const std::string& primitiveName);
  std::vector<glm::vec3> readPositions(int accessorIndex, const std::string& primitiveName);
  std::vector<std::uint32_t> readVertexOrder(int accessorIndex, const std::string& primitiveName,
                                             std::size_t vertexCount);
  std::vector<std::uint32_t> readTriangleIndices(const tinygltf::Primitive& source, const std::string& primitiveName,
                                                 std::size_t vertexCount);

  const Source& source_;
  AccessorReader accessors_;
  ResourceLimits limits_;
  std::uint64_t decodedVertices_ = 0;
  std::uint64_t decodedTriangles_ = 0;
};

}  // namespace headlight::gltf
