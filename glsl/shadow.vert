// Shadow pass vertex stage: world position for the distance a point light's
// cube stores, light clip space for rasterisation. ALPHA_MASK variants (masked
// materials) also pass the texcoord their cut-out is sampled at: the base
// colour's set and KHR_texture_transform, as gbuffer.frag's textureUv (the
// transform is affine, so applying it per vertex is the same).
// SHADOW_TRANSMITTANCE variants (transmissive casters, shadow_transmittance.frag)
// pass the world normal, both texcoord sets and COLOR_0 as they are: that
// stage samples the base colour and transmission textures, each at its own
// set and transform.
#include "shared_layout.h"

layout(location = kAttributePosition) in vec3 inPosition;
layout(location = kAttributeObjectIndex) in uint inObjectIndex;
layout(location = 0) out vec3 vWorldPosition;
#ifdef SHADOW_TRANSMITTANCE
layout(location = kAttributeNormal) in vec3 inNormal;
layout(location = 3) out vec3 vWorldNormal;
#ifdef HAS_TEXCOORDS
layout(location = kAttributeTexcoord) in vec2 inTexcoord;
layout(location = 4) out vec2 vTexcoord0;
#endif
#ifdef HAS_TEXCOORDS_1
layout(location = kAttributeTexcoord1) in vec2 inTexcoord1;
layout(location = 5) out vec2 vTexcoord1;
#endif
#ifdef HAS_VERTEX_COLORS
layout(location = kAttributeColor) in vec4 inColor;
layout(location = 6) out vec4 vColor;
#endif
#elif defined(ALPHA_MASK) && defined(HAS_TEXCOORDS)
layout(location = kAttributeTexcoord) in vec2 inTexcoord;
layout(location = 1) out vec2 vTexcoord;
#endif
#if !defined(SHADOW_TRANSMITTANCE) && defined(ALPHA_MASK) && defined(HAS_TEXCOORDS_1)
layout(location = kAttributeTexcoord1) in vec2 inTexcoord1;
#endif
#if !defined(SHADOW_TRANSMITTANCE) && defined(ALPHA_MASK) && defined(HAS_VERTEX_COLORS)
layout(location = kAttributeColor) in vec4 inColor;
layout(location = 2) out float vColorAlpha;
#endif

void main() {
  const GpuObject object = objects.objectList[inObjectIndex];
  const vec4 world = object.worldFromLocal * vec4(inPosition, 1.0);
  vWorldPosition = world.xyz;
#ifdef SHADOW_TRANSMITTANCE
  vWorldNormal = mat3(object.normalFromLocal) * inNormal;
#ifdef HAS_TEXCOORDS
  vTexcoord0 = inTexcoord;
#endif
#ifdef HAS_TEXCOORDS_1
  vTexcoord1 = inTexcoord1;
#endif
#ifdef HAS_VERTEX_COLORS
  vColor = inColor;
#endif
#elif defined(ALPHA_MASK) && defined(HAS_TEXCOORDS)
#if defined(BASE_COLOR_TEXCOORD_1) && defined(HAS_TEXCOORDS_1)
  vec2 uv = inTexcoord1;
#elif defined(BASE_COLOR_TEXCOORD_1)
  vec2 uv = vec2(0.0);  // no such set: (0, 0), as gbuffer.frag
#else
  vec2 uv = inTexcoord;
#endif
#ifdef HAS_TEXTURE_TRANSFORM
  uv = vec2(dot(material.baseColorTransformU.xyz, vec3(uv, 1.0)), dot(material.baseColorTransformV.xyz, vec3(uv, 1.0)));
#endif
  vTexcoord = uv;
#endif
#if !defined(SHADOW_TRANSMITTANCE) && defined(ALPHA_MASK) && defined(HAS_VERTEX_COLORS)
  vColorAlpha = inColor.a;
#endif
  gl_Position = shadowView.lightViewProjection * world;
}
