// KHR_materials_specular and KHR_materials_ior in the lighting passes
// (direct_light.frag and composite.frag through surface.glsl, and
// the forward passes; docs/PIPELINE.md, "Material lobes"). The specular lobe's
// attachment holds the dielectric F0 colour, min(((ior - 1) / (ior + 1))^2 *
// specularColor, 1), in rgb and the specular weight in a
// (lobe_specular_material.glsl). The specification's dielectric Fresnel
// is then weight * Schlick(F0 colour, 1), mixed by metallic with the
// metal's Schlick(base colour, 1). Schlick is linear in (F0, F90), so the
// mix is one Schlick with
//   f0 = mix(weight * F0 colour, albedo, metallic), f90 = mix(weight, 1, metallic)
// and cookTorrance and ambientLight (which read f0 and f90) need nothing
// else. The diffuse lobe keeps brdf.glsl's (1 - F) per channel, which for a
// dielectric is the specification's 1 - weight * F (per channel where the
// specification takes the largest channel: a coloured F0 tints the diffuse
// lobe toward its complement instead of darkening it evenly). Needs brdf.glsl.
#ifndef FORWARD_SHADING
layout(binding = kUnitSpecularLobe) uniform sampler2D specularLobeTarget;
#endif

// The lobe's one hook (brdf.glsl): f0 and f90 from its value.
vec4 specularLobeApply(inout Surface s, vec4 lobe) {
  const float weight = lobe.a;
  s.f0 = mix(lobe.rgb * weight, s.albedo, s.metallic);
  s.f90 = mix(weight, 1.0, s.metallic);
  return lobe;
}
