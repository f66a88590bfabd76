#pragma once
// The accessor reader: glTF accessors (sparse included) to vectors, every
// byte checked to lie inside its buffer before it is read. It depends only
// on the parsed model, so it can be tested and fuzzed on its own.
//
// tinygltf parses, but it trusts the file: it does not check that an accessor
// stays inside its bufferView or that a stride can hold an element.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "gltf/common.hpp"

namespace headlight::gltf {

// One allowed layout of an attribute: glTF's componentType and type codes.
struct AccessorFormat {
  int componentType;
  int type;
  bool normalized;
};

std::string formatName(const AccessorFormat& format);  // "normalized UNSIGNED_BYTE VEC2"

inline constexpr AccessorFormat kFloatVec2{TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2, false};
inline constexpr AccessorFormat kFloatVec3{TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, false};
inline constexpr AccessorFormat kFloatVec4{TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC4, false};
inline constexpr AccessorFormat kPositionFormats[]{kFloatVec3};
inline constexpr AccessorFormat kNormalFormats[]{kFloatVec3};
inline constexpr AccessorFormat kTangentFormats[]{kFloatVec4};
inline constexpr AccessorFormat kTexcoordFormats[]{
    kFloatVec2, AccessorFormat{TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_TYPE_VEC2, true},
    AccessorFormat{TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_VEC2, true}};
// COLOR_0: float or normalized unsigned byte/short, RGB or RGBA (glTF 3.7.2.1).
inline constexpr AccessorFormat kColorFormats[]{kFloatVec3,
                                                kFloatVec4,
                                                {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_TYPE_VEC3, true},
                                                {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_TYPE_VEC4, true},
                                                {TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_VEC3, true},
                                                {TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_VEC4, true}};
// KHR_mesh_quantization's additions (its table): integer and normalized
// integer positions and texcoords, normalized integer normals and tangents.
inline constexpr AccessorFormat kQuantizedPositionFormats[]{
    kFloatVec3,
    {TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_TYPE_VEC3, false},
    {TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_TYPE_VEC3, true},
    {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_TYPE_VEC3, false},
    {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_TYPE_VEC3, true},
    {TINYGLTF_COMPONENT_TYPE_SHORT, TINYGLTF_TYPE_VEC3, false},
    {TINYGLTF_COMPONENT_TYPE_SHORT, TINYGLTF_TYPE_VEC3, true},
    {TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_VEC3, false},
    {TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_VEC3, true}};
inline constexpr AccessorFormat kQuantizedNormalFormats[]{kFloatVec3,
                                                          {TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_TYPE_VEC3, true},
                                                          {TINYGLTF_COMPONENT_TYPE_SHORT, TINYGLTF_TYPE_VEC3, true}};
inline constexpr AccessorFormat kQuantizedTangentFormats[]{kFloatVec4,
                                                           {TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_TYPE_VEC4, true},
                                                           {TINYGLTF_COMPONENT_TYPE_SHORT, TINYGLTF_TYPE_VEC4, true}};
inline constexpr AccessorFormat kQuantizedTexcoordFormats[]{
    kFloatVec2,
    {TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_TYPE_VEC2, false},
    {TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_TYPE_VEC2, true},
    {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_TYPE_VEC2, false},
    {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_TYPE_VEC2, true},
    {TINYGLTF_COMPONENT_TYPE_SHORT, TINYGLTF_TYPE_VEC2, false},
    {TINYGLTF_COMPONENT_TYPE_SHORT, TINYGLTF_TYPE_VEC2, true},
    {TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_VEC2, false},
    {TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_VEC2, true}};
// Morph target deltas (core glTF, and quantized: the same table).
inline constexpr AccessorFormat kPositionDeltaFormats[]{kFloatVec3,
                                                        {TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_TYPE_VEC3, false},
                                                        {TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_TYPE_VEC3, true},
                                                        {TINYGLTF_COMPONENT_TYPE_SHORT, TINYGLTF_TYPE_VEC3, false},
                                                        {TINYGLTF_COMPONENT_TYPE_SHORT, TINYGLTF_TYPE_VEC3, true}};
inline constexpr AccessorFormat kDirectionDeltaFormats[]{kFloatVec3,
                                                         {TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_TYPE_VEC3, true},
                                                         {TINYGLTF_COMPONENT_TYPE_SHORT, TINYGLTF_TYPE_VEC3, true}};
// Skins: JOINTS_n and WEIGHTS_n, inverseBindMatrices.
inline constexpr AccessorFormat kJointFormats[]{{TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_TYPE_VEC4, false},
                                                {TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_VEC4, false}};
inline constexpr AccessorFormat kWeightFormats[]{kFloatVec4,
                                                 {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_TYPE_VEC4, true},
                                                 {TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_VEC4, true}};
inline constexpr AccessorFormat kMatrixFormats[]{{TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_MAT4, false}};
// EXT_mesh_gpu_instancing: TRANSLATION and SCALE as positions are, ROTATION
// float or normalized signed integers.
inline constexpr AccessorFormat kInstanceRotationFormats[]{kFloatVec4,
                                                           {TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_TYPE_VEC4, true},
                                                           {TINYGLTF_COMPONENT_TYPE_SHORT, TINYGLTF_TYPE_VEC4, true}};

inline constexpr AccessorFormat kIndexFormats[]{
    AccessorFormat{TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_TYPE_SCALAR, false},
    AccessorFormat{TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_SCALAR, false},
    AccessorFormat{TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, false}};

// An accessor whose every byte has been checked to lie inside its buffer.
struct CheckedAccessor {
  int index = -1;
  const unsigned char* data = nullptr;  // nullptr: all zeros (before sparse)
  std::size_t stride = 0;
  std::size_t count = 0;
  int componentType = 0;
  bool normalized = false;
  // Sparse substitution, tightly packed as glTF requires.
  std::size_t sparseCount = 0;
  const unsigned char* sparseIndices = nullptr;
  int sparseIndexComponentType = 0;
  const unsigned char* sparseValues = nullptr;
  std::size_t elementSize = 0;
};

class AccessorReader {
 public:
  explicit AccessorReader(const Source& source) : source_(source) {}

  const Source& source() const { return source_; }

  // Validates everything about accessor `accessorIndex` that reading it
  // depends on (index, format among `allowed`, count, bufferView range,
  // stride, sparse ranges); `user` names who reads it in messages.
  CheckedAccessor check(int accessorIndex, const std::string& user, std::span<const AccessorFormat> allowed) const;

  // Elements as floats: FLOAT as is, normalized integers as glTF maps them
  // (unsigned to 0..1, signed to -1..1), other integers by value. N = 1..4.
  template <int N>
  std::vector<glm::vec<N, float>> readFloats(const CheckedAccessor& accessor) const;

  // A MAT4 accessor as matrices (glTF's column-major order, as GLM's).
  std::vector<glm::mat4> readMatrices(const CheckedAccessor& accessor) const;

  // An index accessor (UNSIGNED_BYTE/SHORT/INT) as 32-bit values.
  std::vector<std::uint32_t> readIndices(const CheckedAccessor& accessor) const;

  // check() plus: the accessor has `vertexCount` elements, as the POSITION
  // accessor `positionAccessor` of the same primitive has.
  template <int N>
  std::vector<glm::vec<N, float>> readAttribute(int accessorIndex, const std::string& user,
                                                std::span<const AccessorFormat> allowed, std::size_t vertexCount,
                                                int positionAccessor) const {
    const CheckedAccessor accessor = check(accessorIndex, user, allowed);
    if (accessor.count != vertexCount) {
      source_.fail(user + " accessor " + std::to_string(accessorIndex) + " has " + countOf(accessor.count, "element") +
                   ", but POSITION accessor " + std::to_string(positionAccessor) + " has " +
                   std::to_string(vertexCount));
    }
    return readFloats<N>(accessor);
  }

 private:
  struct ViewBytes {
    const unsigned char* data;
    std::size_t size;
    std::size_t byteStride;
  };
  ViewBytes checkedBufferView(int viewIndex, const std::string& user) const;
  void checkFormat(const tinygltf::Accessor& accessor, int accessorIndex, const std::string& user,
                   std::span<const AccessorFormat> allowed) const;
  void checkRange(const std::string& reader, std::size_t start, std::size_t stride, std::size_t count,
                  std::size_t elementSize, int viewIndex, std::size_t viewSize) const;
  void checkSparse(const tinygltf::Accessor& accessor, int accessorIndex, CheckedAccessor& checked) const;
  // Element k of the sparse substitution's target, checked < count.
  std::uint32_t sparseTarget(const CheckedAccessor& accessor, std::size_t k) const;

  const Source& source_;
};

}  // namespace headlight::gltf
