// Cook-Torrance with GGX, Smith-GGX visibility and Schlick's Fresnel, and
// glTF's punctual light falloff (KHR_lights_punctual, "Range Property").
// Needs sampling.glsl and the light buffer. The KHR_materials_* lobes a
// variant is built with add their terms through hooks: each lobe's file
// (glsl/lobe_<name>.glsl, expanded below by #include_lobes) defines
// `<name>Lobe<Hook>` functions and the LOBES_<HOOK> macros call them for the
// variant's lobes (lobeDefines, lib/frame/frame_plan.cpp; docs/PIPELINE.md,
// "What a lobe is made of").
#include "lobes.glsl"

struct Surface {
  vec3 albedo;
  float metallic;
  float roughness;
  vec3 normal;  // world, unit
  vec3 view;    // world, unit, toward the eye
  float nDotV;
  vec3 f0;      // reflectance at normal incidence
  float f90;    // at grazing incidence: 1, or less with the specular lobe's weight (lobe_specular.glsl)
  // KHR_materials_transmission's share (lobe_transmission.glsl): the part of
  // the diffuse lobe its BTDF replaces; 0 on an opaque surface.
  float transmission;
  // Each lobe's value (<NAME>_LOBE_SLOT), as its Apply hook leaves it; a
  // lobe of the variant the material lacks holds its "no effect" value.
  vec4 lobes[LOBE_SLOTS];
};

Surface makeSurface(vec3 albedo, float metallic, float roughness, vec3 normal, vec3 view) {
  Surface s;
  s.albedo = albedo;
  s.metallic = metallic;
  // Below 0.03 GGX's peak outgrows half floats for point lights.
  s.roughness = max(roughness, 0.03);
  s.normal = normal;
  s.view = view;
  s.nDotV = max(dot(normal, view), 1e-4);
  s.f0 = mix(vec3(0.04), albedo, metallic);  // 0.04: glTF's dielectric reflectance (IOR 1.5)
  s.f90 = 1.0;
  s.transmission = 0.0;
  for (int i = 0; i < LOBE_SLOTS; ++i) s.lobes[i] = vec4(0.0);
  return s;
}

#include_lobes ""

// The surface's Fresnel at the angle between the view and a half vector
// (V.H): Schlick's over f0 and f90, then the lobes' (an iridescent film's;
// the specification's F). What reflects is F; what enters the surface,
// toward its diffuse lobe or its BTDF, 1 - F.
vec3 surfaceFresnel(Surface s, float vDotH) {
  vec3 fresnel = s.f0 + (s.f90 - s.f0) * pow(1.0 - vDotH, 5.0);
  LOBES_FRESNEL(s, fresnel);
  return fresnel;
}

// What the layers over the base (KHR_materials_sheen) leave of the light
// the base sends from a direction at `nDotL` (absolute) toward the eye; 1
// without a layer. Clearcoat, with its own normal, layers in the passes
// (lobe_clearcoat.glsl clearcoatLayer).
float baseLayerScale(Surface s, float nDotL) {
  float scale = 1.0;
  LOBES_LAYER_SCALE(s, scale, nDotL);
  return scale;
}

vec3 cookTorrance(Surface s, vec3 toLight) {
  const float nDotL = dot(s.normal, toLight);
  if (nDotL <= 0.0) return vec3(0.0);
  const vec3 halfVector = normalize(toLight + s.view);
  const float nDotH = max(dot(s.normal, halfVector), 0.0);
  const float vDotH = max(dot(s.view, halfVector), 0.0);
  const float alpha = s.roughness * s.roughness;
  const float a2 = alpha * alpha;
  const float d = (nDotH * nDotH) * (a2 - 1.0) + 1.0;
  const float distribution = a2 / (kPi * d * d);
  const vec3 fresnel = surfaceFresnel(s, vDotH);
  float specularTerm = distribution * smithGgxVisibility(s.nDotV, nDotL, alpha);
  LOBES_SPECULAR_TERM(s, specularTerm, alpha, toLight, halfVector, nDotL);
  const vec3 specular = specularTerm * fresnel;
  // A transmissive surface's diffuse lobe keeps the share not transmitted.
  const vec3 diffuse = (1.0 - fresnel) * (1.0 - s.metallic) * (1.0 - s.transmission) * s.albedo / kPi;
  vec3 reflected = (diffuse + specular) * (nDotL * baseLayerScale(s, nDotL));
  LOBES_LAYER_LIGHT(s, reflected, nDotL, nDotH);
  return reflected;
}

// Falloff of `light` at `position` (inverse square, range window, spot
// cone); sets `toLight` to the unit direction toward the light.
float lightAttenuation(GpuLight light, vec3 position, out vec3 toLight) {
  const int type = light.type;
  if (type == kLightDirectional) {
    toLight = -light.direction;
    return 1.0;
  }
  const vec3 offset = light.position - position;
  const float distanceSquared = max(dot(offset, offset), 1e-30);
  const float distance = sqrt(distanceSquared);
  toLight = offset / distance;
  float attenuation = 1.0 / distanceSquared;
  const float range = light.range;
  if (range > 0.0) attenuation *= clamp(1.0 - pow(distance / range, 4.0), 0.0, 1.0);
  if (type == kLightSpot) {
    const float cosOuter = light.cosOuterCone, cosInner = light.cosInnerCone;
    const float scale = 1.0 / max(cosInner - cosOuter, 1e-3);
    const float t = clamp((dot(light.direction, -toLight) - cosOuter) * scale, 0.0, 1.0);
    attenuation *= t * t;
  }
  return attenuation;
}
