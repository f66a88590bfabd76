// Split-sum BRDF table (Karis 2013): for (N.V, roughness) the scale and bias
// that turn F0 into the directional albedo of GGX specular. A fullscreen
// pass's body: fullscreen_entry.frag or .comp runs it per texel.
#include "shared_layout.h"
#include "sampling.glsl"

struct PassOutputs {
  vec4 scaleBias;  // RG; the table is RG16F
};

const uint kSampleCount = 512u;  // half-float output; 512 keeps the noise below its precision

PassOutputs shadePixel(ivec2 texel) {
  const vec2 centre = vec2(texel) + 0.5;
  const float nDotV = max(tableValue(centre.x, float(kBrdfLutSize), 0.0, 1.0), 1e-4);
  const float roughness = tableValue(centre.y, float(kBrdfLutSize), 0.0, 1.0);
  const float alpha = roughness * roughness;
  const vec3 view = vec3(sqrt(1.0 - nDotV * nDotV), 0.0, nDotV);
  vec2 scaleBias = vec2(0.0);
  for (uint i = 0u; i < kSampleCount; ++i) {
    const vec3 halfVector = importanceSampleGgx(hammersley(i, kSampleCount), alpha);
    const vec3 light = reflect(-view, halfVector);
    const float nDotL = light.z, nDotH = max(halfVector.z, 0.0), vDotH = max(dot(view, halfVector), 0.0);
    if (nDotL <= 0.0) continue;
    // pdf(L) = D * N.H / (4 V.H), so BRDF * N.L / pdf = 4 V * V.H * N.L / N.H.
    const float weight = 4.0 * smithGgxVisibility(nDotV, nDotL, alpha) * vDotH * nDotL / max(nDotH, 1e-7);
    const float fresnel = pow(1.0 - vDotH, 5.0);
    scaleBias += vec2((1.0 - fresnel) * weight, fresnel * weight);
  }
  return PassOutputs(vec4(scaleBias / float(kSampleCount), 0.0, 0.0));
}
