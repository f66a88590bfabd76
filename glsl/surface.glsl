// A shading point's Surface with its lobes, shared by the lighting passes:
// read from the G-buffer (the direct-light and composite passes: surfaceAt)
// or, in the forward passes (FORWARD_SHADING: blend.glsl,
// transmission.glsl), from the material gbuffer.frag evaluates. Either way
// each lobe is one vec4, as its G-buffer target holds it
// (lobe_<name>_material.glsl computes it), put in the Surface's slot by
// LOBES_AT or LOBES_OF_MATERIAL, and applyLobes is the one place that puts
// the lobes on a Surface. Needs brdf.glsl.

#ifndef FORWARD_SHADING
layout(binding = kUnitGbufferPosition) uniform sampler2D gbufferPosition;
layout(binding = kUnitGbufferNormal) uniform sampler2D gbufferNormal;
layout(binding = kUnitGbufferAlbedo) uniform sampler2D gbufferAlbedo;
layout(binding = kUnitGbufferMaterial) uniform sampler2D gbufferMaterial;
#endif

// Direction from the surface toward the eye.
vec3 viewDirection(vec3 worldPosition) {
  // Orthographic: the same for every pixel, the camera's +Z axis in world.
  if (frame.cameraPosition.w > 0.5) return normalize(vec3(frame.view[0][2], frame.view[1][2], frame.view[2][2]));
  return normalize(frame.cameraPosition.xyz - worldPosition);
}

// The lobes' values (surface.lobes, filled by LOBES_AT or
// LOBES_OF_MATERIAL) put on the surface by each lobe's Apply hook.
void applyLobes(inout Surface surface) { LOBES_APPLY(surface); }

#ifdef FORWARD_SHADING
// The clearcoat lobe's value for this fragment: set by gbuffer.frag's main
// (before the base's normal map) before shading.
#ifdef HAS_CLEARCOAT_LOBE
vec4 forwardClearcoatLobe;
#endif

// The material's lobes at this fragment, whose shading normal is `normal`
// (lobe_<name>_material.glsl, which gbuffer.frag expands before this file).
void applyMaterialLobes(inout Surface surface, vec3 normal) {
  LOBES_OF_MATERIAL(surface.lobes, normal);
  applyLobes(surface);
}
#else
Surface surfaceAt(ivec2 pixel, vec3 worldPosition) {
  const vec4 material = texelFetch(gbufferMaterial, pixel, 0);
  Surface surface = makeSurface(texelFetch(gbufferAlbedo, pixel, 0).rgb, material.x, material.y,
                                texelFetch(gbufferNormal, pixel, 0).xyz, viewDirection(worldPosition));
  LOBES_AT(surface.lobes, pixel);
  applyLobes(surface);
  return surface;
}
#endif
