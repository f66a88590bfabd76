// Irradiance from the sky divided by pi, per normal height: the cosine-
// weighted mean of the radiance over the hemisphere around the normal. A
// fullscreen pass's body: fullscreen_entry.frag or .comp runs it per texel.
#include "shared_layout.h"
#include "sampling.glsl"
#include "sky.glsl"

struct PassOutputs {
  vec4 irradianceOverPi;
};

const uint kSampleCount = 1024u;

PassOutputs shadePixel(ivec2 texel) {
  const vec3 normal = directionAtHeight(tableValue(float(texel.x) + 0.5, float(kSkyTableWidth), -1.0, 1.0));
  const mat3 basis = basisAround(normal);
  vec3 sum = vec3(0.0);
  for (uint i = 0u; i < kSampleCount; ++i)
    sum += skyRadiance(basis * cosineSampleHemisphere(hammersley(i, kSampleCount)));
  return PassOutputs(vec4(sum / float(kSampleCount), 1.0));
}
