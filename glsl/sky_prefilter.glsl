// The sky filtered by GGX lobes around a direction, for the split sum's
// first factor (with N = V = R, as usual). Row = roughness level. A
// fullscreen pass's body: fullscreen_entry.frag or .comp runs it per texel.
#include "shared_layout.h"
#include "sampling.glsl"
#include "sky.glsl"

struct PassOutputs {
  vec4 radiance;
};

const uint kSampleCount = 512u;

PassOutputs shadePixel(ivec2 texel) {
  const vec2 centre = vec2(texel) + 0.5;
  const vec3 reflected = directionAtHeight(tableValue(centre.x, float(kSkyTableWidth), -1.0, 1.0));
  const float roughness = tableValue(centre.y, float(kSkyRoughnessLevels), 0.0, 1.0);
  const float alpha = roughness * roughness;
  const mat3 basis = basisAround(reflected);
  vec3 sum = vec3(0.0);
  float weight = 0.0;
  for (uint i = 0u; i < kSampleCount; ++i) {
    const vec3 halfVector = basis * importanceSampleGgx(hammersley(i, kSampleCount), alpha);
    const vec3 light = reflect(-reflected, halfVector);
    const float nDotL = dot(reflected, light);
    if (nDotL <= 0.0) continue;
    sum += skyRadiance(light) * nDotL;
    weight += nDotL;
  }
  return PassOutputs(vec4(sum / max(weight, 1e-7), 1.0));
}
