// KHR_materials_clearcoat in the G-buffer pass (gbuffer.frag, included
// before main, after tangentFrame): the clearcoat lobe's value for this
// fragment, (clearcoat, clearcoatRoughness, octahedral coat normal), each
// texture times its factor (the specification's channels: R and G). The
// coat's normal is its own normal map's, or else the geometric normal:
// the base's normal map does not bend the coat (specification). A material
// without the extension has factor 0, and the coat then changes nothing
// (lobe_clearcoat.glsl). Needs gbuffer.frag's textureUv and tangentFrame.
#include "lobe_clearcoat.glsl"

#ifndef CLEARCOAT_SET  // as gbuffer.frag's BASE_COLOR_SET
#ifdef CLEARCOAT_TEXCOORD_1
#define CLEARCOAT_SET true
#else
#define CLEARCOAT_SET false
#endif
#endif
#ifndef CLEARCOAT_ROUGHNESS_SET  // as gbuffer.frag's BASE_COLOR_SET
#ifdef CLEARCOAT_ROUGHNESS_TEXCOORD_1
#define CLEARCOAT_ROUGHNESS_SET true
#else
#define CLEARCOAT_ROUGHNESS_SET false
#endif
#endif
#ifndef CLEARCOAT_NORMAL_SET  // as gbuffer.frag's BASE_COLOR_SET
#ifdef CLEARCOAT_NORMAL_TEXCOORD_1
#define CLEARCOAT_NORMAL_SET true
#else
#define CLEARCOAT_NORMAL_SET false
#endif
#endif
#ifdef HAS_CLEARCOAT_TEXTURE
layout(binding = kUnitClearcoatTexture) uniform sampler2D clearcoatTexture;
#endif
#ifdef HAS_CLEARCOAT_ROUGHNESS_TEXTURE
layout(binding = kUnitClearcoatRoughnessTexture) uniform sampler2D clearcoatRoughnessTexture;
#endif
#ifdef HAS_CLEARCOAT_NORMAL_TEXTURE
layout(binding = kUnitClearcoatNormalTexture) uniform sampler2D clearcoatNormalTexture;
#endif

// `geometricNormal`: the interpolated normal, facing the eye's side, before
// the base's normal map.
vec4 clearcoatLobeOfMaterial(vec3 geometricNormal) {
  float factor = material.clearcoatFactors.x;
  float roughness = material.clearcoatFactors.y;
#ifdef HAS_CLEARCOAT_TEXTURE
  factor *= texture(clearcoatTexture, textureUv(CLEARCOAT_SET, material.clearcoatTransformU,
                                                material.clearcoatTransformV)).r;
#endif
#ifdef HAS_CLEARCOAT_ROUGHNESS_TEXTURE
  roughness *= texture(clearcoatRoughnessTexture, textureUv(CLEARCOAT_ROUGHNESS_SET,
                                                            material.clearcoatRoughnessTransformU,
                                                            material.clearcoatRoughnessTransformV)).g;
#endif
  vec3 normal = geometricNormal;
#ifdef HAS_CLEARCOAT_NORMAL_TEXTURE
  const vec2 normalUv =
      textureUv(CLEARCOAT_NORMAL_SET, material.clearcoatNormalTransformU, material.clearcoatNormalTransformV);
  vec3 tangentNormal = texture(clearcoatNormalTexture, normalUv).xyz * 2.0 - 1.0;  // 0..1 encoded
  tangentNormal.xy *= material.clearcoatFactors.z;
  normal = mappedNormal(tangentFrame(geometricNormal, normalUv), tangentNormal, geometricNormal);
#endif
  return vec4(clamp(factor, 0.0, 1.0), clamp(roughness, 0.0, 1.0), octahedralEncode(normal));
}
