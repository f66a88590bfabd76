// G-buffer fragment stage: glTF metallic-roughness inputs to the targets
// described in lib/passes/gbuffer.hpp. Feature #defines say which textures
// and vertex attributes this variant reads.
#include "shared_layout.h"

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

#ifdef BLEND_FORWARD
#include "blend.glsl"  // alphaMode BLEND: the blend pass lights the material instead (lib/passes/blend.hpp)
#else
layout(location = 0) out vec4 outPosition;
layout(location = 1) out vec4 outNormal;
layout(location = 2) out vec4 outAlbedo;
layout(location = 3) out vec4 outMaterial;
#ifdef HAS_EMISSIVE_TARGET
layout(location = 4) out vec4 outEmissive;
#endif
#endif

#ifdef HAS_NORMAL_TEXTURE
// Tangent frame for normal mapping: from the TANGENT attribute when the file
// has one, else from screen-space derivatives of position and UV
// (Schueler's cotangent frame), which needs no precomputed tangents.
mat3 tangentFrame(vec3 normal) {
#ifdef HAS_TANGENTS
  const vec3 tangent = normalize(vWorldTangent.xyz - normal * dot(normal, vWorldTangent.xyz));
  return mat3(tangent, cross(normal, tangent) * vWorldTangent.w, normal);
#else
  const vec3 dp1 = dFdx(vWorldPosition), dp2 = dFdy(vWorldPosition);
  const vec2 duv1 = dFdx(vTexcoord), duv2 = dFdy(vTexcoord);
  const vec3 dp2perp = cross(dp2, normal), dp1perp = cross(normal, dp1);
  const vec3 tangent = dp2perp * duv1.x + dp1perp * duv2.x;
  const vec3 bitangent = dp2perp * duv1.y + dp1perp * duv2.y;
  const float invmax = inversesqrt(max(max(dot(tangent, tangent), dot(bitangent, bitangent)), 1e-30));
  return mat3(tangent * invmax, bitangent * invmax, normal);
#endif
}
#endif

void main() {
  vec4 baseColor = material.baseColorFactor;
  float metallic = material.factors.x;
  float roughness = material.factors.y;
  float occlusion = 1.0;
#ifdef HAS_BASE_COLOR_TEXTURE
  baseColor *= texture(baseColorTexture, vTexcoord);  // sRGB texture: decoded to linear by the sampler
#endif
#ifdef HAS_VERTEX_COLORS
  baseColor *= vColor;
#endif
#ifdef ALPHA_MASK
  // alphaMode MASK: a cut-out fragment leaves the background (position.a = 0).
  if (baseColor.a < material.alphaCutoff) discard;
#endif
#ifdef HAS_METALLIC_ROUGHNESS_TEXTURE
  const vec4 metallicRoughness = texture(metallicRoughnessTexture, vTexcoord);
  roughness *= metallicRoughness.g;
  metallic *= metallicRoughness.b;
#endif
#ifdef HAS_OCCLUSION_TEXTURE
  occlusion = 1.0 + material.factors.w * (texture(occlusionTexture, vTexcoord).r - 1.0);
#endif

  // The back of a double-sided surface faces the other way. Points and
  // lines without a normal (0, gltf_geometry.cpp) face the camera.
  vec3 normal = normalize(vWorldNormal) * (gl_FrontFacing ? 1.0 : -1.0);
  if (dot(vWorldNormal, vWorldNormal) < 1e-24) {
    normal = frame.cameraPosition.w > 0.5 ? vec3(frame.view[0][2], frame.view[1][2], frame.view[2][2])
                                          : normalize(frame.cameraPosition.xyz - vWorldPosition);
  }
#ifdef HAS_NORMAL_TEXTURE
  vec3 tangentNormal = texture(normalTexture, vTexcoord).xyz * 2.0 - 1.0;  // the texture is 0..1 encoded
  tangentNormal.xy *= material.factors.z;
  normal = normalize(tangentFrame(normal) * tangentNormal);
#endif

#if defined(HAS_EMISSIVE_TARGET) || defined(BLEND_FORWARD)
  vec3 emissive = material.emissiveFactor.rgb;
#ifdef HAS_EMISSIVE_TEXTURE
  emissive *= texture(emissiveTexture, vTexcoord).rgb;
#endif
#endif
#ifdef BLEND_FORWARD
  shadeBlended(vWorldPosition, normal, baseColor, metallic, roughness, occlusion, emissive);
#else
  outPosition = vec4(vWorldPosition, 1.0);
  outNormal = vec4(normal, 0.0);
  outAlbedo = vec4(baseColor.rgb, 1.0);
  outMaterial = vec4(clamp(metallic, 0.0, 1.0), clamp(roughness, 0.0, 1.0), clamp(occlusion, 0.0, 1.0), 1.0);
#ifdef HAS_EMISSIVE_TARGET
  outEmissive = vec4(emissive, 1.0);
#endif
#endif
}
