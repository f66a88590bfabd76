// Image-based ambient light from the procedural sky, or from an environment
// map under HAS_ENVIRONMENT (split sum: the BRDF table and the sky tables of
// lib/passes/environment.hpp, or the map's, environment.glsl), shared by the
// composite pass (G-buffer surfaces) and the blend pass (alphaMode BLEND
// surfaces). Needs brdf.glsl and the lighting block.

layout(binding = kUnitBrdfLut) uniform sampler2D brdfLut;
layout(binding = kUnitSkyPrefiltered) uniform sampler2D skyPrefiltered;
layout(binding = kUnitSkyIrradiance) uniform sampler2D skyIrradiance;
#ifdef HAS_ENVIRONMENT
#include "environment.glsl"
#endif

// Texture coordinate of value v in [low, high] for a table whose first and
// last texel centres stand for low and high (see tableValue()).
float tableCoordinate(float v, float low, float high, float size) {
  return (clamp((v - low) / (high - low), 0.0, 1.0) * (size - 1.0) + 0.5) / size;
}

vec3 prefilteredSky(vec3 direction, float roughness) {
#ifdef HAS_ENVIRONMENT
  return environmentPrefiltered(direction, roughness);
#endif
  const vec2 size = vec2(textureSize(skyPrefiltered, 0));
  return texture(skyPrefiltered, vec2(tableCoordinate(direction.y, -1.0, 1.0, size.x),
                                      tableCoordinate(roughness, 0.0, 1.0, size.y))).rgb;
}

vec3 skyIrradianceOverPi(vec3 normal) {
#ifdef HAS_ENVIRONMENT
  return environmentIrradianceOverPi(normal);
#endif
  const float width = float(textureSize(skyIrradiance, 0).x);
  return texture(skyIrradiance, vec2(tableCoordinate(normal.y, -1.0, 1.0, width), 0.5)).rgb;
}

// `reflected` turned by `angle` radians toward `normal`, in their plane
// (unturned where they are parallel: no plane).
vec3 bentReflection(vec3 reflected, vec3 normal, float angle) {
  const vec3 towardNormal = normal - reflected * dot(normal, reflected);
  const float length2 = dot(towardNormal, towardNormal);
  if (angle == 0.0 || length2 < 1e-8) return reflected;
  return normalize(reflected * cos(angle) + towardNormal * (sin(angle) * inversesqrt(length2)));
}

// `skyVisibility` occludes the diffuse (and sheen) sky light, the
// cosine-weighted share of the hemisphere open to the sky;
// `specularVisibility` the specular, the share of the GGX lobe about the
// reflection that escapes (ssgi_bitmask.frag; the same number where no pass
// estimates it), and `specularBend` turns the reflection toward the normal
// by that many radians, to the mean direction of the part that escapes.
// The split-sum specular albedo: the share of light from every direction
// the specular lobe reflects toward the eye (f0 scale + f90 bias from the
// BRDF table). What it leaves enters the surface: the diffuse lobe's and
// the BTDF's weight (lobe_transmission.glsl transmissionThroughput).
vec3 specularAlbedoOf(Surface surface) {
  const float size = float(kBrdfLutSize);
  float tableRoughness = surface.roughness;
  LOBES_ALBEDO_ROUGHNESS(surface, tableRoughness);
  const vec2 scaleBias = texture(brdfLut, vec2(tableCoordinate(surface.nDotV, 0.0, 1.0, size),
                                               tableCoordinate(tableRoughness, 0.0, 1.0, size))).rg;
  vec3 specularAlbedo = surface.f0 * scaleBias.x + surface.f90 * scaleBias.y;
  LOBES_SPECULAR_ALBEDO(surface, specularAlbedo, scaleBias);
  return specularAlbedo;
}

// The lobes' layers over the ambient (sheen's), which read prefilteredSky.
#include_lobes "_ambient"

vec3 ambientLight(Surface surface, float materialOcclusion, float skyVisibility, float specularVisibility,
                  float specularBend, vec3 indirect) {
  const vec3 specularAlbedo = specularAlbedoOf(surface);
  // A transmissive surface's diffuse lobe keeps the share not transmitted.
  const vec3 diffuseWeight = (1.0 - specularAlbedo) * (1.0 - surface.metallic) * (1.0 - surface.transmission);
  const vec3 diffuseIbl = diffuseWeight * surface.albedo * skyIrradianceOverPi(surface.normal);
  vec3 reflected = reflect(-surface.view, surface.normal);
  LOBES_REFLECTION(surface, reflected);
  reflected = bentReflection(reflected, surface.normal, specularBend);
  const vec3 specularIbl = specularAlbedo * prefilteredSky(reflected, surface.roughness);
  vec3 ambient = diffuseIbl * skyVisibility + specularIbl * specularVisibility;
  LOBES_AMBIENT_LAYER(surface, ambient, skyVisibility);
  return ambient * lighting.skyIntensity * materialOcclusion + indirect;
}

// One visibility for both (the passes without SSGI pass 1).
vec3 ambientLight(Surface surface, float materialOcclusion, float skyVisibility, vec3 indirect) {
  return ambientLight(surface, materialOcclusion, skyVisibility, skyVisibility, 0.0, indirect);
}
