// The sky filtered by GGX lobes around a direction, for the split sum's
// first factor (with N = V = R, as usual). Row = roughness level.
#include "shared_layout.h"
#include "sampling.glsl"
#include "sky.glsl"

layout(location = 0) out vec4 outRadiance;

const uint kSampleCount = 512u;

void main() {
  const vec3 reflected = directionAtHeight(tableValue(gl_FragCoord.x, float(kSkyTableWidth), -1.0, 1.0));
  const float roughness = tableValue(gl_FragCoord.y, float(kSkyRoughnessLevels), 0.0, 1.0);
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
  outRadiance = vec4(sum / max(weight, 1e-7), 1.0);
}
