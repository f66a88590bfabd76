// KHR_materials_specular and KHR_materials_ior in the G-buffer pass
// (gbuffer.frag, included before main): the specular lobe's value for this
// fragment, rgb the dielectric F0 colour min(((ior - 1) / (ior + 1))^2 *
// specularColorFactor * specularColorTexture.rgb, 1) and a the specular
// weight specularFactor * specularTexture.a (the specification's
// channels). A material without either extension has (0.04, 0.04, 0.04, 1),
// glTF's defaults, and is lit as in a scene without the lobe
// (lobe_specular.glsl). Needs gbuffer.frag's textureUv.
#ifndef SPECULAR_SET  // as gbuffer.frag's BASE_COLOR_SET
#ifdef SPECULAR_TEXCOORD_1
#define SPECULAR_SET true
#else
#define SPECULAR_SET false
#endif
#endif
#ifndef SPECULAR_COLOR_SET  // as gbuffer.frag's BASE_COLOR_SET
#ifdef SPECULAR_COLOR_TEXCOORD_1
#define SPECULAR_COLOR_SET true
#else
#define SPECULAR_COLOR_SET false
#endif
#endif
#ifdef HAS_SPECULAR_TEXTURE
layout(binding = kUnitSpecularTexture) uniform sampler2D specularTexture;
#endif
#ifdef HAS_SPECULAR_COLOR_TEXTURE
layout(binding = kUnitSpecularColorTexture) uniform sampler2D specularColorTexture;  // sRGB: decoded by the sampler
#endif

vec4 specularLobeOfMaterial(vec3 normal) {
  const float ior = material.transmissionFactors.z;  // KHR_materials_ior (MaterialBlock keeps it there)
  const float reflectance = (ior - 1.0) / (ior + 1.0);
  vec3 f0 = reflectance * reflectance * material.specularFactors.rgb;
  float weight = material.specularFactors.a;
#ifdef HAS_SPECULAR_TEXTURE
  weight *= texture(specularTexture, textureUv(SPECULAR_SET, material.specularTransformU,
                                               material.specularTransformV)).a;
#endif
#ifdef HAS_SPECULAR_COLOR_TEXTURE
  f0 *= texture(specularColorTexture, textureUv(SPECULAR_COLOR_SET, material.specularColorTransformU,
                                                material.specularColorTransformV)).rgb;
#endif
  return vec4(min(f0, vec3(1.0)), clamp(weight, 0.0, 1.0));
}
