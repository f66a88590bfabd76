// The environment map's lookups (composite.frag's HAS_ENVIRONMENT variant):
// the GPU's copy of lib/environment/equirect.hpp. Every table is
// equirectangular in map space; a world direction is first turned back by
// the map's rotation (LightingBlock). Needs shared_layout.h.
layout(binding = kUnitEnvironmentSpecular) uniform sampler2DArray environmentSpecular;
layout(binding = kUnitEnvironmentIrradiance) uniform sampler2D environmentIrradiance;
layout(binding = kUnitEnvironmentBackground) uniform sampler2D environmentBackground;

vec2 environmentUv(vec3 worldDirection) {
  const float c = lighting.environmentRotationCos, s = lighting.environmentRotationSin;
  const vec3 d = vec3(c * worldDirection.x - s * worldDirection.z, worldDirection.y,
                      s * worldDirection.x + c * worldDirection.z);
  const float kPi = 3.14159265358979;
  return vec2(atan(d.x, -d.z) / (2.0 * kPi) + 0.5, acos(clamp(d.y, -1.0, 1.0)) / kPi);
}

// The map filtered by the GGX lobe of `roughness` around `direction`:
// linear between the two nearest roughness layers.
vec3 environmentPrefiltered(vec3 direction, float roughness) {
  const vec2 uv = environmentUv(direction);
  const float layer = clamp(roughness, 0.0, 1.0) * float(textureSize(environmentSpecular, 0).z - 1);
  const float low = floor(layer);
  return mix(texture(environmentSpecular, vec3(uv, low)).rgb, texture(environmentSpecular, vec3(uv, low + 1.0)).rgb,
             layer - low);
}

// The irradiance table's first and last rows lie at the poles (equirect.hpp poleRows).
vec3 environmentIrradianceOverPi(vec3 normal) {
  const vec2 uv = environmentUv(normal);
  const float rows = float(textureSize(environmentIrradiance, 0).y);
  return texture(environmentIrradiance, vec2(uv.x, (uv.y * (rows - 1.0) + 0.5) / rows)).rgb;
}

vec3 environmentRadiance(vec3 direction) { return texture(environmentBackground, environmentUv(direction)).rgb; }
