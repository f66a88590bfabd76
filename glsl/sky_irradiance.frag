// Irradiance from the sky divided by pi, per normal height: the cosine-
// weighted mean of the radiance over the hemisphere around the normal.
#include "shared_layout.h"
#include "sampling.glsl"
#include "sky.glsl"

layout(location = 0) out vec4 outIrradianceOverPi;

const uint kSampleCount = 1024u;

void main() {
  const vec3 normal = directionAtHeight(tableValue(gl_FragCoord.x, float(kSkyTableWidth), -1.0, 1.0));
  const mat3 basis = basisAround(normal);
  vec3 sum = vec3(0.0);
  for (uint i = 0u; i < kSampleCount; ++i)
    sum += skyRadiance(basis * cosineSampleHemisphere(hammersley(i, kSampleCount)));
  outIrradianceOverPi = vec4(sum / float(kSampleCount), 1.0);
}
