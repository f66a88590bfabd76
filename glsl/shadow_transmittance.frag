// A transmissive caster in a light's transmittance map (lib/passes/shadow.hpp):
// drawn after the light's depth map, tested against it without writing it,
// so only layers in front of the first opaque surface count. Output: what
// the layer adds to the map's optical depth (rgb, summed) and its depth
// from the light (a, the map keeps the nearest): receivers nearer the light
// than that are not behind any transmissive layer. The depth is the depth
// map's (point lights: linear distance / far). Feature #defines as the
// G-buffer's: the base colour and transmission textures, their sets and
// transforms, COLOR_0, MASK cut-outs.
#include "shared_layout.h"
#include "shadow_transmittance.glsl"

layout(location = 0) in vec3 vWorldPosition;
layout(location = 3) in vec3 vWorldNormal;
#ifdef HAS_TEXCOORDS
layout(location = 4) in vec2 vTexcoord0;
#endif
#ifdef HAS_TEXCOORDS_1
layout(location = 5) in vec2 vTexcoord1;
#endif
#ifdef HAS_VERTEX_COLORS
layout(location = 6) in vec4 vColor;
#endif
#ifdef HAS_BASE_COLOR_TEXTURE
layout(binding = kUnitBaseColorTexture) uniform sampler2D baseColorTexture;
#endif
#ifdef HAS_TRANSMISSION_TEXTURE
layout(binding = kUnitTransmissionTexture) uniform sampler2D transmissionTexture;
#endif

layout(location = 0) out vec4 outLayer;

#ifdef HAS_TEXCOORDS
#include "texture_uv.glsl"
// The UV a texture samples at this fragment, as gbuffer.frag's (texture_uv.glsl).
vec2 textureUv(bool secondSet, vec4 rowU, vec4 rowV) {
#ifdef HAS_TEXCOORDS_1
  return textureUvOf(vTexcoord0, vTexcoord1, secondSet, rowU, rowV);
#else
  return textureUvOf(vTexcoord0, vec2(0.0), secondSet, rowU, rowV);
#endif
}
#endif

#ifdef BASE_COLOR_TEXCOORD_1
#define BASE_COLOR_SET true
#else
#define BASE_COLOR_SET false
#endif
#ifdef TRANSMISSION_TEXCOORD_1
#define TRANSMISSION_SET true
#else
#define TRANSMISSION_SET false
#endif

void main() {
  vec4 baseColor = material.baseColorFactor;
#if defined(HAS_BASE_COLOR_TEXTURE) && defined(HAS_TEXCOORDS)
  baseColor *= texture(baseColorTexture,
                       textureUv(BASE_COLOR_SET, material.baseColorTransformU, material.baseColorTransformV));
#endif
#ifdef HAS_VERTEX_COLORS
  baseColor *= vColor;
#endif
#ifdef ALPHA_MASK
  if (baseColor.a < material.alphaCutoff) discard;
#endif
  float transmission = material.transmissionFactors.x;
#if defined(HAS_TRANSMISSION_TEXTURE) && defined(HAS_TEXCOORDS)
  transmission *= texture(transmissionTexture, textureUv(TRANSMISSION_SET, material.transmissionTransformU,
                                                         material.transmissionTransformV)).r;
#endif
  const vec4 origin = shadowView.lightOrigin;
  const vec3 toLight = origin.w > 0.0 ? normalize(origin.xyz - vWorldPosition) : -origin.xyz;
  const float distanceFromLight = origin.w > 0.0 ? length(vWorldPosition - origin.xyz) : dot(vWorldPosition, origin.xyz);
  const float normalLength = length(vWorldNormal);
  // A normal of no length gives no side: the light crosses it as a thin wall would, head on.
  const float cosine = normalLength > 0.0 ? dot(vWorldNormal / normalLength, toLight) : 1.0;
  const bool volume = material.transmissionFactors.y > 0.0;
  const vec3 extinction = volumeExtinction(material.attenuationColor.rgb, material.transmissionFactors.w);
  const vec3 layer = shadowLayerOpticalDepth(baseColor.rgb, material.factors.x, transmission,
                                             material.transmissionFactors.z, cosine, volume, extinction,
                                             distanceFromLight);
  const float far = shadowView.lightPositionFar.w;
  const float depth = far > 0.0 ? length(vWorldPosition - shadowView.lightPositionFar.xyz) / far : gl_FragCoord.z;
  gl_FragDepth = depth;
  outLayer = vec4(layer, depth);
}
