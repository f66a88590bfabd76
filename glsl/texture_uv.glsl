// The UV a texture samples, every input a parameter: the set the material
// names (TEXCOORD_1 where `secondSet`; (0, 0) if the primitive has none,
// as for TEXCOORD_0), through its KHR_texture_transform rows. Variants
// without HAS_TEXTURE_TRANSFORM skip the matrix: most materials have none,
// and identity rows would cost the same. gbuffer.frag and
// shadow_transmittance.frag pass their own varyings (texcoord1 is read only
// with HAS_TEXCOORDS_1).
vec2 textureUvOf(vec2 texcoord0, vec2 texcoord1, bool secondSet, vec4 rowU, vec4 rowV) {
#ifdef HAS_TEXCOORDS_1
  const vec2 uv = secondSet ? texcoord1 : texcoord0;
#else
  const vec2 uv = secondSet ? vec2(0.0) : texcoord0;
#endif
#ifdef HAS_TEXTURE_TRANSFORM
  return vec2(dot(rowU.xyz, vec3(uv, 1.0)), dot(rowV.xyz, vec3(uv, 1.0)));
#else
  return uv;
#endif
}
