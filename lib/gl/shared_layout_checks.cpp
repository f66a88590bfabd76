// std140 offsets the GLSL side assumes, checked where C++ compiles them:
// a member added to glsl/shared_layout.h with a hidden padding fails here.
#include <cstddef>
#include <initializer_list>

#include "shared_layout.h"

namespace headlight::gpu {

static_assert(sizeof(FrameBlock) == 3 * 64 + 3 * 16);
static_assert(offsetof(FrameBlock, projection) == 64);
static_assert(offsetof(FrameBlock, cameraPosition) == 192);
static_assert(offsetof(FrameBlock, nearFar) == 224);
static_assert(sizeof(ObjectBlock) == 128);
static_assert(sizeof(MaterialBlock) == 48);
static_assert(offsetof(MaterialBlock, factors) == 32);
static_assert(sizeof(SsgiBlock) == kMaxKernelSamples * 16 + 32);
static_assert(offsetof(SsgiBlock, params) == kMaxKernelSamples * 16);
static_assert(offsetof(SsgiBlock, counts) == kMaxKernelSamples * 16 + 16);
static_assert(sizeof(LightingBlock) == 32);
static_assert(sizeof(SsgiBlurBlock) == 16);
static_assert(sizeof(ShadowBlock) == 80);
static_assert(sizeof(SkyBlock) == 48);
// std430 array stride of GpuLight: four vec4 and a mat4, no padding.
static_assert(sizeof(GpuLight) == 4 * 16 + 64);
static_assert(offsetof(GpuLight, shadowViewProjection) == 64);

// Two passes' inputs must never share a unit, nor two blocks a binding.
constexpr bool allDistinct(std::initializer_list<int> values) {
  for (const int* a = values.begin(); a != values.end(); ++a)
    for (const int* b = a + 1; b != values.end(); ++b)
      if (*a == *b) return false;
  return true;
}
static_assert(allDistinct({kUnitGbufferPosition, kUnitGbufferNormal, kUnitGbufferAlbedo, kUnitGbufferMaterial,
                           kUnitGbufferEmissive, kUnitSsgiNoise, kUnitSsgi, kUnitBrdfLut, kUnitSkyPrefiltered,
                           kUnitSkyIrradiance, kUnitShadowMaps2D, kUnitShadowMapsCube, kUnitBaseColorTexture,
                           kUnitMetallicRoughnessTexture, kUnitNormalTexture, kUnitOcclusionTexture,
                           kUnitEmissiveTexture, kUnitDirect, kUnitDirectDiffuse}));
static_assert(allDistinct({FrameBlock::kBinding, ObjectBlock::kBinding, MaterialBlock::kBinding, SsgiBlock::kBinding,
                           LightingBlock::kBinding, ShadowBlock::kBinding, SkyBlock::kBinding,
                           SsgiBlurBlock::kBinding}));

}  // namespace headlight::gpu
