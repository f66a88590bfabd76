// KHR_materials_sheen over the image-based light (ambient.glsl's hook,
// expanded after its prefilteredSky): the base keeps
// sheenAmbientBaseScale, and the lobe reflects the sky prefiltered at the
// sheen roughness about the mirror direction, occluded as the diffuse sky
// light is (`skyVisibility`).
vec3 sheenLobeAmbientLayer(Surface s, vec4 sheen, vec3 ambient, float skyVisibility) {
  if (sheen.rgb == vec3(0.0)) return ambient;
  const vec3 mirrored = reflect(-s.view, s.normal);
  return ambient * sheenAmbientBaseScale(sheen.rgb, sheen.a, s.nDotV) +
         skyVisibility * sheenAmbient(sheen.rgb, sheen.a, s.nDotV, prefilteredSky(mirrored, sheen.a));
}
