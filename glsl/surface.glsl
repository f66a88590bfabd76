// A shading point's Surface with its lobes, shared by the lighting passes:
// read from the G-buffer (the direct-light and composite passes: surfaceAt)
// or, in the forward passes (FORWARD_SHADING: blend.glsl,
// transmission.glsl), from the material gbuffer.frag evaluates. Either way
// each lobe is one vec4, as its G-buffer target holds it
// (lobe_*_material.glsl computes it), and applyLobes is the one place that
// puts the lobes on a Surface. Needs brdf.glsl.
#include "lobe_specular.glsl"

#ifndef FORWARD_SHADING
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
#endif

// Direction from the surface toward the eye.
vec3 viewDirection(vec3 worldPosition) {
  // Orthographic: the same for every pixel, the camera's +Z axis in world.
  if (frame.cameraPosition.w > 0.5) return normalize(vec3(frame.view[0][2], frame.view[1][2], frame.view[2][2]));
  return normalize(frame.cameraPosition.xyz - worldPosition);
}

// The lobes' values at a shading point; those the variant has no lobe for
// are never read.
struct LobeValues {
  vec4 iridescence;  // strength, thickness, film IOR, base IOR
  vec4 specular;     // dielectric F0 colour, specular weight
  vec4 sheen;        // colour, roughness
  vec4 anisotropy;   // world direction, strength
};

void applyLobes(inout Surface surface, LobeValues lobes) {
#ifdef HAS_IRIDESCENCE_LOBE
  applyIridescence(surface, lobes.iridescence);
#endif
#ifdef HAS_SPECULAR_LOBE
  applySpecularLobe(surface, lobes.specular);
#endif
#ifdef HAS_SHEEN_LOBE
  surface.sheenColor = lobes.sheen.rgb;
  surface.sheenRoughness = lobes.sheen.a;
#endif
#ifdef HAS_ANISOTROPY_LOBE
  surface.anisotropyTangent = lobes.anisotropy.xyz;
  surface.anisotropyStrength = lobes.anisotropy.w;
#endif
}

#ifdef FORWARD_SHADING
// The specular and clearcoat lobes' values for this fragment: set by
// gbuffer.frag's main (it computes them for the G-buffer) before shading.
#ifdef HAS_SPECULAR_LOBE
vec4 forwardSpecularLobe;
#endif
#ifdef HAS_CLEARCOAT_LOBE
vec4 forwardClearcoatLobe;
#endif
// The other lobes' values from the material (lobe_*_material.glsl, defined
// later in gbuffer.frag).
#ifdef HAS_IRIDESCENCE_LOBE
vec4 materialIridescence();
#endif
#ifdef HAS_SHEEN_LOBE
vec4 sheenMaterial();
#endif
#ifdef HAS_ANISOTROPY_LOBE
vec4 anisotropyMaterial(vec3 shadingNormal);
#endif

// The material's lobes at this fragment, whose shading normal is `normal`.
LobeValues forwardLobes(vec3 normal) {
  LobeValues lobes = LobeValues(vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0));
#ifdef HAS_IRIDESCENCE_LOBE
  lobes.iridescence = materialIridescence();
#endif
#ifdef HAS_SPECULAR_LOBE
  lobes.specular = forwardSpecularLobe;
#endif
#ifdef HAS_SHEEN_LOBE
  lobes.sheen = sheenMaterial();
#endif
#ifdef HAS_ANISOTROPY_LOBE
  lobes.anisotropy = anisotropyMaterial(normal);
#endif
  return lobes;
}
#else
// The G-buffer's lobe targets at `pixel`.
LobeValues lobesAt(ivec2 pixel) {
  LobeValues lobes = LobeValues(vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0));
#ifdef HAS_IRIDESCENCE_LOBE
  lobes.iridescence = texelFetch(gbufferIridescence, pixel, 0);
#endif
#ifdef HAS_SPECULAR_LOBE
  lobes.specular = texelFetch(specularLobeTarget, pixel, 0);
#endif
#ifdef HAS_SHEEN_LOBE
  lobes.sheen = texelFetch(gbufferSheen, pixel, 0);
#endif
#ifdef HAS_ANISOTROPY_LOBE
  lobes.anisotropy = texelFetch(gbufferAnisotropy, pixel, 0);
#endif
  return lobes;
}

Surface surfaceAt(ivec2 pixel, vec3 worldPosition) {
  const vec4 material = texelFetch(gbufferMaterial, pixel, 0);
  Surface surface = makeSurface(texelFetch(gbufferAlbedo, pixel, 0).rgb, material.x, material.y,
                                texelFetch(gbufferNormal, pixel, 0).xyz, viewDirection(worldPosition));
  applyLobes(surface, lobesAt(pixel));
  return surface;
}
#endif
