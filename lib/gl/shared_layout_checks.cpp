// std140 offsets the GLSL side assumes, checked where C++ compiles them.
//
// Why a new member needs no line here: C++ and GLSL declare each block from
// the same member list (glsl/shared_layout.h), glm's types align to 4 bytes
// and std140's alignments are never smaller, so every std140 offset is at
// least the C++ one, and equal for all members exactly when std140 inserts
// no padding; then, and only then, the GL's block size equals sizeof. The GL
// layout test (tests/layout_gl_tests.cpp) checks that size for every block
// of HL_UNIFORM_BLOCKS on every program, so it proves every offset. The
// generated check below catches the commonest slip (a block that does not
// end on a 16-byte row) without GL; the member asserts after it are kept as
// compile-time documentation of the layouts passes rely on.
#include <cstddef>
#include <initializer_list>

#include "shared_layout.h"

namespace headlight::gpu {

static_assert(sizeof(FrameBlock) == 3 * 64 + 3 * 16);
static_assert(offsetof(FrameBlock, projection) == 64);
static_assert(offsetof(FrameBlock, cameraPosition) == 192);
static_assert(offsetof(FrameBlock, depthToViewZ) == 224);
static_assert(sizeof(GpuObject) == 144);                         // std430 array stride: two mat4 and a uvec4
static_assert(sizeof(MaterialBlock) == 224 + 7 * 16 + 24 * 16);  // + the KHR_materials_* factors and transforms
static_assert(offsetof(MaterialBlock, factors) == 32);
static_assert(offsetof(MaterialBlock, alphaCutoff) == 48);
static_assert(offsetof(MaterialBlock, baseColorTransformU) == 64);
static_assert(offsetof(MaterialBlock, emissiveTransformV) == 208);
static_assert(sizeof(SsgiBlock) == kMaxKernelSamples * 16 + 32);
static_assert(offsetof(SsgiBlock, radiusWorld) == kMaxKernelSamples * 16);
static_assert(offsetof(SsgiBlock, indirectStrength) == kMaxKernelSamples * 16 + 12);
static_assert(offsetof(SsgiBlock, sampleCount) == kMaxKernelSamples * 16 + 16);
static_assert(offsetof(SsgiBlock, downsample) == kMaxKernelSamples * 16 + 20);
static_assert(sizeof(SsgiBitmaskBlock) == 48 + 3 * 16);  // + the light field's grid
static_assert(offsetof(SsgiBitmaskBlock, lightFieldOrigin) == 48);
static_assert(sizeof(GpuLightProbe) == kLightFieldMapSize * kLightFieldMapSize * 16 * 3 / 2);
static_assert(offsetof(SsgiBitmaskBlock, indirectStrength) == 12);
static_assert(offsetof(SsgiBitmaskBlock, sliceCount) == 16);
static_assert(offsetof(SsgiBitmaskBlock, rotationIndex) == 28);
static_assert(offsetof(SsgiBitmaskBlock, skyStepCount) == 32);
static_assert(sizeof(LightingBlock) == 32);
static_assert(offsetof(LightingBlock, pcfRadius) == 8);
static_assert(offsetof(LightingBlock, shadowNormalOffset) == 12);
static_assert(offsetof(LightingBlock, shadowMapSize) == 16);
static_assert(offsetof(LightingBlock, environmentRotationCos) == 20);
static_assert(offsetof(LightingBlock, environmentBackground) == 28);
static_assert(sizeof(SsgiBlurBlock) == 32);
static_assert(offsetof(SsgiBlurBlock, ssgiDownsample) == 4);
static_assert(sizeof(ShadowBlock) == 96);
static_assert(sizeof(SkyBlock) == 48);
// std430: a vec3 starts a 16-byte row and the scalar after it fills the row;
// the array stride is the struct's size, five rows and a mat4.
static_assert(sizeof(GpuLight) == 5 * 16 + 64);
static_assert(offsetof(GpuLight, range) == 12);
static_assert(offsetof(GpuLight, direction) == 16);
static_assert(offsetof(GpuLight, type) == 28);
static_assert(offsetof(GpuLight, radiance) == 32);
static_assert(offsetof(GpuLight, castsShadows) == 44);
static_assert(offsetof(GpuLight, cosOuterCone) == 48);
static_assert(offsetof(GpuLight, shadowLayer) == 56);
static_assert(offsetof(GpuLight, shadowTexelSize) == 64);
static_assert(offsetof(GpuLight, shadowViewProjection) == 80);

#define HL_BLOCK_FILLS_ROWS(block, name, binding) \
  static_assert(sizeof(block) % 16 == 0, #block " does not end on a 16-byte std140 row");
HL_UNIFORM_BLOCKS(HL_BLOCK_FILLS_ROWS)
#undef HL_BLOCK_FILLS_ROWS

// Two passes' inputs must never share a unit, nor two blocks a binding:
// checked over the lists themselves, so a new row is checked too.
constexpr bool allDistinct(std::initializer_list<int> values) {
  for (const int* a = values.begin(); a != values.end(); ++a)
    for (const int* b = a + 1; b != values.end(); ++b)
      if (*a == *b) return false;
  return true;
}
#define HL_UNIT_VALUE(name, unit) name,
#define HL_BINDING_VALUE(block, name, binding) name,
static_assert(allDistinct({HL_TEXTURE_UNITS(HL_UNIT_VALUE)}), "two texture units share a number");
static_assert(allDistinct({HL_IMAGE_UNITS(HL_UNIT_VALUE)}), "two image units share a number");
static_assert(allDistinct({HL_UNIFORM_BLOCKS(HL_BINDING_VALUE)}), "two uniform blocks share a binding");
static_assert(allDistinct({HL_STORAGE_BLOCKS(HL_BINDING_VALUE)}), "two storage blocks share a binding");
// Each block's kBinding is its row's.
#define HL_BLOCK_BINDING_MATCHES(block, name, binding) static_assert(block::kBinding == binding);
HL_UNIFORM_BLOCKS(HL_BLOCK_BINDING_MATCHES)
HL_STORAGE_BLOCKS(HL_BLOCK_BINDING_MATCHES)
#undef HL_UNIT_VALUE
#undef HL_BINDING_VALUE
#undef HL_BLOCK_BINDING_MATCHES

}  // namespace headlight::gpu
