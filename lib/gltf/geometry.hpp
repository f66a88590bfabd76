#pragma once
// Primitives: a glTF mesh primitive's accessors to a Primitive (positions,
// indices, normals, texcoords, tangents), each vertex and triangle counted
// against --max-triangles before its memory is allocated.
#include <cstdint>
#include <string>

#include "gltf/accessors.hpp"
#include "headlight/limits.hpp"
#include "headlight/scene.hpp"

namespace headlight::gltf {

// The accessor a primitive names for `attribute`, or -1.
int attributeAccessor(const tinygltf::Primitive& primitive, const char* attribute);

// What a node poses its mesh with (gltf_pose): morph weights (empty: none)
// and its skin's joint matrices (nullptr: not skinned).
struct Pose {
  std::vector<float> weights;
  const std::vector<glm::mat4>* joints = nullptr;
};

class GeometryReader {
 public:
  GeometryReader(const Source& source, const ResourceLimits& limits);

  // The geometry of `primitive` (named `primitiveName` in messages), whose
  // mode must be TRIANGLES, TRIANGLE_STRIP or TRIANGLE_FAN (made a triangle
  // list), in `pose`. TEXCOORD_1 is decoded only with `readTexcoord1` (a
  // material drawn with it samples that set). Throws SceneError or LimitError.
  Primitive read(const tinygltf::Primitive& primitive, const std::string& primitiveName, const Pose& pose = {},
                 bool readTexcoord1 = false);

  const AccessorReader& accessors() const { return accessors_; }

 private:
  void reserveVertices(std::size_t count, int accessorIndex, const std::string& user);
  void reserveTriangles(std::size_t count, const std::string& primitiveName);
  void reserveMorphDeltas(const tinygltf::Primitive& source, const std::vector<float>& weights, std::size_t vertexCount,
                          const std::string& primitiveName);
  std::vector<glm::vec3> readPositions(int accessorIndex, const std::string& primitiveName);
  std::vector<glm::vec4> readColors(int accessorIndex, const std::string& primitiveName, std::size_t vertexCount,
                                    int positionAccessor);
  std::vector<std::uint32_t> readVertexOrder(int accessorIndex, const std::string& primitiveName,
                                             std::size_t vertexCount);
  std::vector<std::uint32_t> readElementIndices(const tinygltf::Primitive& source, const std::string& primitiveName,
                                                std::size_t vertexCount);

  const Source& source_;
  AccessorReader accessors_;
  ResourceLimits limits_;
  bool quantized_;  // KHR_mesh_quantization in extensionsUsed: its formats are allowed
  std::uint64_t decodedVertices_ = 0;
  std::uint64_t decodedTriangles_ = 0;
};

}  // namespace headlight::gltf
