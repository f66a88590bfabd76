// KHR_materials_sheen in the G-buffer pass (gbuffer.frag, and its blend
// variant): the material's sheen colour (linear) and roughness, the
// specification's factor times texture (colour: an sRGB texture's RGB,
// roughness: a linear texture's A). A material without sheen has factors
// 0, its "no effect" value. Needs gbuffer.frag's textureUv and the
// material block.
#ifdef SHEEN_COLOR_TEXCOORD_1
#define SHEEN_COLOR_SET true
#else
#define SHEEN_COLOR_SET false
#endif
#ifdef SHEEN_ROUGHNESS_TEXCOORD_1
#define SHEEN_ROUGHNESS_SET true
#else
#define SHEEN_ROUGHNESS_SET false
#endif
#ifdef HAS_SHEEN_COLOR_TEXTURE
layout(binding = kUnitSheenColorTexture) uniform sampler2D sheenColorTexture;
#endif
#ifdef HAS_SHEEN_ROUGHNESS_TEXTURE
layout(binding = kUnitSheenRoughnessTexture) uniform sampler2D sheenRoughnessTexture;
#endif

// Sheen colour (rgb) and roughness (a), 0..1.
vec4 sheenLobeOfMaterial(vec3 normal) {
  vec4 sheen = material.sheenFactors;
#ifdef HAS_SHEEN_COLOR_TEXTURE
  sheen.rgb *= texture(sheenColorTexture,
                       textureUv(SHEEN_COLOR_SET, material.sheenColorTransformU, material.sheenColorTransformV)).rgb;
#endif
#ifdef HAS_SHEEN_ROUGHNESS_TEXTURE
  sheen.a *= texture(sheenRoughnessTexture, textureUv(SHEEN_ROUGHNESS_SET, material.sheenRoughnessTransformU,
                                                     material.sheenRoughnessTransformV)).a;
#endif
  return clamp(sheen, 0.0, 1.0);
}
