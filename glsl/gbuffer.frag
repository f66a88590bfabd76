// G-buffer fragment stage: glTF metallic-roughness inputs to the targets
// described in lib/passes/gbuffer.hpp. Feature #defines say which textures
// and vertex attributes this variant reads, which texture set each texture
// samples (<NAME>_TEXCOORD_1) and whether the material transforms its UVs
// (HAS_TEXTURE_TRANSFORM, KHR_texture_transform) or is unlit (UNLIT).
#include "shared_layout.h"
#include "lobes.glsl"
#if defined(BLEND_FORWARD) || defined(TRANSMISSION_FORWARD)
// A forward pass shades the material here (blend.glsl, transmission.glsl):
// its lobes come from the material (surface.glsl forwardLobes), not from
// the G-buffer's lobe targets.
#define FORWARD_SHADING
#endif

layout(location = 0) in vec3 vWorldPosition;
layout(location = 1) in vec3 vWorldNormal;
#ifdef HAS_TEXCOORDS
layout(location = 2) in vec2 vTexcoord;
#endif
#ifdef HAS_TANGENTS
layout(location = 3) in vec4 vWorldTangent;
#endif
#ifdef HAS_VERTEX_COLORS
layout(location = 4) in vec4 vColor;  // COLOR_0
#endif
#ifdef HAS_TEXCOORDS_1
layout(location = 5) in vec2 vTexcoord1;  // TEXCOORD_1
#endif

#ifdef HAS_TEXCOORDS
#include "texture_uv.glsl"
// The UV a texture samples at this fragment (texture_uv.glsl).
vec2 textureUv(bool secondSet, vec4 rowU, vec4 rowV) {
#ifdef HAS_TEXCOORDS_1
  return textureUvOf(vTexcoord, vTexcoord1, secondSet, rowU, rowV);
#else
  return textureUvOf(vTexcoord, vec2(0.0), secondSet, rowU, rowV);
#endif
}
#endif
#ifdef BASE_COLOR_TEXCOORD_1
#define BASE_COLOR_SET true
#else
#define BASE_COLOR_SET false
#endif
#ifdef METALLIC_ROUGHNESS_TEXCOORD_1
#define METALLIC_ROUGHNESS_SET true
#else
#define METALLIC_ROUGHNESS_SET false
#endif
#ifdef NORMAL_TEXCOORD_1
#define NORMAL_SET true
#else
#define NORMAL_SET false
#endif
#ifdef OCCLUSION_TEXCOORD_1
#define OCCLUSION_SET true
#else
#define OCCLUSION_SET false
#endif
#ifdef EMISSIVE_TEXCOORD_1
#define EMISSIVE_SET true
#else
#define EMISSIVE_SET false
#endif

#ifdef HAS_BASE_COLOR_TEXTURE
layout(binding = kUnitBaseColorTexture) uniform sampler2D baseColorTexture;
#endif
#ifdef HAS_METALLIC_ROUGHNESS_TEXTURE
layout(binding = kUnitMetallicRoughnessTexture) uniform sampler2D metallicRoughnessTexture;
#endif
#ifdef HAS_NORMAL_TEXTURE
layout(binding = kUnitNormalTexture) uniform sampler2D normalTexture;
#endif
#ifdef HAS_OCCLUSION_TEXTURE
layout(binding = kUnitOcclusionTexture) uniform sampler2D occlusionTexture;
#endif
#ifdef HAS_EMISSIVE_TEXTURE
layout(binding = kUnitEmissiveTexture) uniform sampler2D emissiveTexture;
#endif

// Outside any #ifdef: the G-buffer's clearcoat lobe (lobe_clearcoat_material.glsl)
// and the blend pass's (blend.glsl) both use it, and a file is expanded once,
// where it is first included.
#include "lobe_clearcoat.glsl"

// Tangent frame for normal mapping: from the TANGENT attribute when the file
// has one, else from screen-space derivatives of position and UV
// (Schueler's cotangent frame), which needs no precomputed tangents.
mat3 tangentFrame(vec3 normal, vec2 normalUv) {
#ifdef HAS_TANGENTS
  const vec3 tangent = normalize(vWorldTangent.xyz - normal * dot(normal, vWorldTangent.xyz));
  return mat3(tangent, cross(normal, tangent) * vWorldTangent.w, normal);
#else
  const vec3 dp1 = dFdx(vWorldPosition), dp2 = dFdy(vWorldPosition);
  const vec2 duv1 = dFdx(normalUv), duv2 = dFdy(normalUv);
  const vec3 dp2perp = cross(dp2, normal), dp1perp = cross(normal, dp1);
  const vec3 tangent = dp2perp * duv1.x + dp1perp * duv2.x;
  const vec3 bitangent = dp2perp * duv1.y + dp1perp * duv2.y;
  const float invmax = inversesqrt(max(max(dot(tangent, tangent), dot(bitangent, bitangent)), 1e-30));
  return mat3(tangent * invmax, bitangent * invmax, normal);
#endif
}

// A normal texture's tangent-space normal taken to world space by `frame`,
// unit; `unmapped` where it has no direction. A texel at the encoding's
// middle (0.5, 0.5, 0.5: unused atlas space, or a mip level averaging
// opposite normals) is the zero vector, and normalize(0) is NaN: one such
// pixel made ToyCar's lit.exr unwritable at 320x240 (issue 34).
vec3 mappedNormal(mat3 frame, vec3 tangentNormal, vec3 unmapped) {
  const vec3 mapped = frame * tangentNormal;
  return dot(mapped, mapped) > 1e-24 ? normalize(mapped) : unmapped;
}

// Each lobe's value from the material, `<name>LobeOfMaterial` (the lobes of
// LOBE_NAMES; clearcoat's is clearcoatLobeOfMaterial, from the normal
// before the base's normal map).
#include_lobes "_material"
#ifdef HAS_CLEARCOAT_LOBE
#include "lobe_clearcoat_material.glsl"
#endif

#ifdef FORWARD_SHADING
// The forward passes' lighting, for blend.glsl and transmission.glsl alike:
// the loader expands each file once, wherever it is first named, so both
// must meet these outside their own #ifdef.
#include "sampling.glsl"
#include "brdf.glsl"
#include "shadows.glsl"
#include "surface.glsl"
#include "ambient.glsl"
#endif

#if defined(BLEND_FORWARD)
#include "blend.glsl"  // alphaMode BLEND: the blend pass lights the material instead (lib/passes/blend.hpp)
#elif defined(TRANSMISSION_FORWARD)
#include "transmission.glsl"  // KHR_materials_transmission: the transmission pass shades it (lib/passes/transmission.hpp)
#else
layout(location = 0) out vec4 outPosition;
layout(location = 1) out vec4 outNormal;
layout(location = 2) out vec4 outAlbedo;
layout(location = 3) out vec4 outMaterial;
#ifdef HAS_EMISSIVE_TARGET
layout(location = EMISSIVE_TARGET_LOCATION) out vec4 outEmissive;
#endif
#ifdef HAS_CLEARCOAT_TARGET
layout(location = CLEARCOAT_TARGET_LOCATION) out vec4 outClearcoatLobe;
#endif
LOBE_TARGET_OUTPUTS  // `<name>LobeOut` for each lobe of LOBE_NAMES
#ifdef HAS_IDS_TARGET
layout(location = 7) flat in uint vObjectIndex;
layout(location = IDS_TARGET_LOCATION) out uvec4 outIds;
#endif
#endif

void main() {
  vec4 baseColor = material.baseColorFactor;
  float metallic = material.factors.x;
  float roughness = material.factors.y;
  float occlusion = 1.0;
#ifdef HAS_BASE_COLOR_TEXTURE
  // sRGB texture: decoded to linear by the sampler.
  baseColor *= texture(baseColorTexture,
                       textureUv(BASE_COLOR_SET, material.baseColorTransformU, material.baseColorTransformV));
#endif
#ifdef HAS_VERTEX_COLORS
  baseColor *= vColor;
#endif
#ifdef ALPHA_MASK
  // alphaMode MASK: a cut-out fragment leaves the background (position.a = 0).
  if (baseColor.a < material.alphaCutoff) discard;
#endif
#ifdef HAS_METALLIC_ROUGHNESS_TEXTURE
  const vec4 metallicRoughness =
      texture(metallicRoughnessTexture, textureUv(METALLIC_ROUGHNESS_SET, material.metallicRoughnessTransformU,
                                                  material.metallicRoughnessTransformV));
#ifdef ROUGHNESS_FROM_GLOSSINESS
  // KHR_materials_pbrSpecularGlossiness: the texture is its
  // specularGlossinessTexture and the factor its glossinessFactor.
  roughness = 1.0 - roughness * metallicRoughness.a;
#else
  roughness *= metallicRoughness.g;
  metallic *= metallicRoughness.b;
#endif
#endif
#ifdef HAS_OCCLUSION_TEXTURE
  const vec2 occlusionUv = textureUv(OCCLUSION_SET, material.occlusionTransformU, material.occlusionTransformV);
  occlusion = 1.0 + material.factors.w * (texture(occlusionTexture, occlusionUv).r - 1.0);
#endif

  // The back of a double-sided surface faces the other way. Points and
  // lines without a normal (0, gltf/geometry.cpp) face the camera.
  vec3 normal = normalize(vWorldNormal) * (gl_FrontFacing ? 1.0 : -1.0);
  if (dot(vWorldNormal, vWorldNormal) < 1e-24) {
    normal = frame.cameraPosition.w > 0.5 ? vec3(frame.view[0][2], frame.view[1][2], frame.view[2][2])
                                          : normalize(frame.cameraPosition.xyz - vWorldPosition);
  }
#ifdef HAS_CLEARCOAT_LOBE
  const vec4 clearcoatLobe = clearcoatLobeOfMaterial(normal);  // before the base's normal map
#endif
#ifdef HAS_NORMAL_TEXTURE
  const vec2 normalUv = textureUv(NORMAL_SET, material.normalTransformU, material.normalTransformV);
  vec3 tangentNormal = texture(normalTexture, normalUv).xyz * 2.0 - 1.0;  // the texture is 0..1 encoded
  tangentNormal.xy *= material.factors.z;
  normal = mappedNormal(tangentFrame(normal, normalUv), tangentNormal, normal);
#endif

#if defined(HAS_EMISSIVE_TARGET) || defined(FORWARD_SHADING)
  vec3 emissive = material.emissiveFactor.rgb;
#ifdef HAS_EMISSIVE_TEXTURE
  emissive *= texture(emissiveTexture, textureUv(EMISSIVE_SET, material.emissiveTransformU,
                                                material.emissiveTransformV)).rgb;
#endif
#endif
#if defined(FORWARD_SHADING) && defined(HAS_CLEARCOAT_LOBE)
  forwardClearcoatLobe = clearcoatLobe;
#endif
#if defined(BLEND_FORWARD)
  shadeBlended(vWorldPosition, normal, baseColor, metallic, roughness, occlusion, emissive);
#elif defined(TRANSMISSION_FORWARD)
  shadeTransmissive(vWorldPosition, normal, baseColor.rgb, metallic, roughness, occlusion, emissive, transmissionAt(),
                    thicknessAt());
#else
  outPosition = vec4(vWorldPosition, 1.0);
  outNormal = vec4(normal, 0.0);
  outAlbedo = vec4(baseColor.rgb, 1.0);
  // A = the unlit flag (KHR_materials_unlit): the composite then writes the
  // base colour as the pixel's radiance.
#ifdef UNLIT
  const float unlit = 1.0;
#else
  const float unlit = 0.0;
#endif
  outMaterial = vec4(clamp(metallic, 0.0, 1.0), clamp(roughness, 0.0, 1.0), clamp(occlusion, 0.0, 1.0), unlit);
#ifdef HAS_EMISSIVE_TARGET
  outEmissive = vec4(emissive, 1.0);
#endif
#ifdef HAS_CLEARCOAT_TARGET
  outClearcoatLobe = clearcoatLobe;
#endif
  LOBES_WRITE_TARGETS(normal);
#ifdef HAS_IDS_TARGET
  outIds = objects.objectList[vObjectIndex].ids;
#endif
#endif
}
