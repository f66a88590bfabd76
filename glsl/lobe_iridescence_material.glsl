// KHR_materials_iridescence's film from the material, in gbuffer.frag (the
// G-buffer pass writes it to the lobe's attachment; the blend pass lights it
// directly): needs gbuffer.frag's textureUv and the material block.
#ifdef IRIDESCENCE_TEXCOORD_1
#define IRIDESCENCE_SET true
#else
#define IRIDESCENCE_SET false
#endif
#ifdef IRIDESCENCE_THICKNESS_TEXCOORD_1
#define IRIDESCENCE_THICKNESS_SET true
#else
#define IRIDESCENCE_THICKNESS_SET false
#endif
#ifdef HAS_IRIDESCENCE_TEXTURE
layout(binding = kUnitIridescenceTexture) uniform sampler2D iridescenceTexture;
#endif
#ifdef HAS_IRIDESCENCE_THICKNESS_TEXTURE
layout(binding = kUnitIridescenceThicknessTexture) uniform sampler2D iridescenceThicknessTexture;
#endif

// The film as the lobe's attachment holds it (lobe_iridescence.glsl):
// strength, thickness (nm), the film's IOR, the base's IOR. A material
// without the extension has factor 0 (fillExtensionFactors): no film.
vec4 iridescenceLobeOfMaterial(vec3 normal) {
  float strength = material.iridescenceFactors.x;
  // Without a thickness texture the film is the maximum thick (the specification).
  float thickness = material.iridescenceFactors.w;
#ifdef HAS_IRIDESCENCE_TEXTURE
  strength *= texture(iridescenceTexture,
                      textureUv(IRIDESCENCE_SET, material.iridescenceTransformU, material.iridescenceTransformV)).r;
#endif
#ifdef HAS_IRIDESCENCE_THICKNESS_TEXTURE
  const vec2 thicknessUv = textureUv(IRIDESCENCE_THICKNESS_SET, material.iridescenceThicknessTransformU,
                                     material.iridescenceThicknessTransformV);
  thickness = mix(material.iridescenceFactors.z, material.iridescenceFactors.w,
                  texture(iridescenceThicknessTexture, thicknessUv).g);
#endif
  // transmissionFactors.z: Material::ior, the base's (KHR_materials_ior).
  return vec4(clamp(strength, 0.0, 1.0), clamp(thickness, 0.0, kMaxFilmThicknessNm),
              min(material.iridescenceFactors.y, kMaxIridescenceIor), min(material.transmissionFactors.z, kMaxIridescenceIor));
}
