// PCF shadow lookups. The sample point is pushed along the shading normal
// by about a texel's footprint there (normal offset), which removes acne
// without a depth bias that would detach shadows from their casters.
// HAS_SHADOW_TRANSMITTANCE variants also read each map's transmittance map
// (transmissive casters, shadow_transmittance.glsl): a receiver behind its
// nearest transmissive layer is tinted by what the layers let through. One
// lookup at the disc's centre tints the filtered opaque taps: a lookup per
// tap made AttenuationTest's cold 256x256 render 1.16x instead of 1.02x
// today's, for the same HDR-FLIP against the reference (docs/BENCHMARKS.md).

#ifdef HAS_PLANAR_SHADOWS
layout(binding = kUnitShadowMaps2D) uniform sampler2DArrayShadow shadowMaps2D;
#endif
#ifdef HAS_CUBE_SHADOWS
layout(binding = kUnitShadowMapsCube) uniform samplerCubeArrayShadow shadowMapsCube;
#endif
#ifdef HAS_SHADOW_TRANSMITTANCE
#include "shadow_transmittance.glsl"
#ifdef HAS_PLANAR_SHADOWS
layout(binding = kUnitShadowTransmittance2D) uniform sampler2DArray shadowTransmittance2D;
#endif
#ifdef HAS_CUBE_SHADOWS
layout(binding = kUnitShadowTransmittanceCube) uniform samplerCubeArray shadowTransmittanceCube;
#endif
// A map texel (summed optical depth, nearest layer's depth) as a tint for a
// receiver at `depth`: none in front of the nearest layer.
vec3 layersTint(vec4 layers, float depth) { return depth > layers.a ? shadowTransmittance(layers.rgb) : vec3(1.0); }
#endif

// A fixed 12-tap Poisson disc: repeatable, and no noise for regression diffs.
const vec2 kPoissonDisc[12] = vec2[](
    vec2(-0.326, -0.406), vec2(-0.840, -0.074), vec2(-0.696, 0.457), vec2(-0.203, 0.621),
    vec2(0.962, -0.195), vec2(0.473, -0.480), vec2(0.519, 0.767), vec2(0.185, -0.893),
    vec2(0.507, 0.064), vec2(0.896, 0.412), vec2(-0.322, -0.933), vec2(-0.792, -0.598));

// What reaches `position` of the light, per channel: 0 in shadow, 1 lit,
// tinted behind transmissive casters.
vec3 shadowVisibility(GpuLight light, vec3 position, vec3 normal, vec3 toLight) {
  if (light.castsShadows == 0 || light.shadowLayer < 0) return vec3(1.0);
  const float layer = float(light.shadowLayer);
  const float pcfRadius = lighting.pcfRadius;
  const int type = light.type;
  // Surfaces facing away from the light are dark anyway; skip the lookups.
  if (dot(normal, toLight) <= 0.0) return vec3(0.0);
#ifdef HAS_CUBE_SHADOWS
  if (type == kLightPoint) {
    const float far = light.shadowFar;
    const float distance = length(light.position - position);
    // A 90 degree face, of cubeFaceSize(shadow-map-size) texels (shadow.hpp).
    const float texel = 2.0 * distance / float(textureSize(shadowMapsCube, 0).x);
    const vec3 shifted = position + normal * (lighting.shadowNormalOffset * texel);
    const vec3 fromLight = shifted - light.position;
    const mat3 basis = basisAround(normalize(fromLight));
    const float reference = length(fromLight) / far;
    float lit = 0.0;
    for (int i = 0; i < 12; ++i) {
      const vec3 direction = fromLight + basis * vec3(kPoissonDisc[i] * pcfRadius * texel, 0.0);
      lit += texture(shadowMapsCube, vec4(direction, layer), reference);
    }
#ifdef HAS_SHADOW_TRANSMITTANCE
    return lit / 12.0 * layersTint(texture(shadowTransmittanceCube, vec4(fromLight, layer)), reference);
#else
    return vec3(lit / 12.0);
#endif
  }
#endif
#ifdef HAS_PLANAR_SHADOWS
  if (type != kLightPoint) {
    // World size of one texel (shadowTexelSize, lib/passes/shadow.cpp):
    // constant for a directional light's orthographic map, growing with
    // distance for a spot light's perspective one.
    const float distance = type == kLightSpot ? length(light.position - position) : 1.0;
    const float texel = light.shadowTexelSize * distance;
    const vec4 clip = light.shadowViewProjection * vec4(position + normal * (lighting.shadowNormalOffset * texel), 1.0);
    const vec3 ndc = clip.xyz / clip.w;
    const vec3 coordinate = ndc * 0.5 + 0.5;
    if (any(lessThan(coordinate, vec3(0.0))) || any(greaterThan(coordinate, vec3(1.0)))) return vec3(1.0);
    const float mapSize = float(lighting.shadowMapSize);
    float lit = 0.0;
    for (int i = 0; i < 12; ++i) {
      const vec2 offset = kPoissonDisc[i] * pcfRadius / mapSize;
      lit += texture(shadowMaps2D, vec4(coordinate.xy + offset, layer, coordinate.z));
    }
#ifdef HAS_SHADOW_TRANSMITTANCE
    return lit / 12.0 * layersTint(texture(shadowTransmittance2D, vec3(coordinate.xy, layer)), coordinate.z);
#else
    return vec3(lit / 12.0);
#endif
  }
#endif
  return vec3(1.0);
}
