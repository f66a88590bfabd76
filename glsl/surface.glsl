// Reading a shading point from the G-buffer, shared by the direct-light and
// composite passes. Needs brdf.glsl and the G-buffer samplers below.
#include "lobe_specular.glsl"

layout(binding = kUnitGbufferPosition) uniform sampler2D gbufferPosition;
layout(binding = kUnitGbufferNormal) uniform sampler2D gbufferNormal;
layout(binding = kUnitGbufferAlbedo) uniform sampler2D gbufferAlbedo;
layout(binding = kUnitGbufferMaterial) uniform sampler2D gbufferMaterial;
#ifdef HAS_IRIDESCENCE_LOBE
layout(binding = kUnitIridescenceLobe) uniform sampler2D gbufferIridescence;
#endif
#ifdef HAS_SHEEN_LOBE
layout(binding = kUnitSheenLobe) uniform sampler2D gbufferSheen;  // sheen colour (sRGB8), roughness
#endif
#ifdef HAS_ANISOTROPY_LOBE
layout(binding = kUnitAnisotropyLobe) uniform sampler2D gbufferAnisotropy;  // world direction, strength
#endif

// Direction from the surface toward the eye.
vec3 viewDirection(vec3 worldPosition) {
  // Orthographic: the same for every pixel, the camera's +Z axis in world.
  if (frame.cameraPosition.w > 0.5) return normalize(vec3(frame.view[0][2], frame.view[1][2], frame.view[2][2]));
  return normalize(frame.cameraPosition.xyz - worldPosition);
}

Surface surfaceAt(ivec2 pixel, vec3 worldPosition) {
  const vec4 material = texelFetch(gbufferMaterial, pixel, 0);
  Surface surface = makeSurface(texelFetch(gbufferAlbedo, pixel, 0).rgb, material.x, material.y,
                                texelFetch(gbufferNormal, pixel, 0).xyz, viewDirection(worldPosition));
#ifdef HAS_IRIDESCENCE_LOBE
  applyIridescence(surface, texelFetch(gbufferIridescence, pixel, 0));
#endif
#if defined(HAS_SPECULAR_LOBE) && !defined(BLEND_FORWARD)
  applySpecularLobe(surface, texelFetch(specularLobeTarget, pixel, 0));
#endif
#ifdef HAS_SHEEN_LOBE
  const vec4 sheen = texelFetch(gbufferSheen, pixel, 0);
  surface.sheenColor = sheen.rgb;
  surface.sheenRoughness = sheen.a;
#endif
#ifdef HAS_ANISOTROPY_LOBE
  const vec4 anisotropy = texelFetch(gbufferAnisotropy, pixel, 0);
  surface.anisotropyTangent = anisotropy.xyz;
  surface.anisotropyStrength = anisotropy.w;
#endif
  return surface;
}
