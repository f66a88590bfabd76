// KHR_materials_anisotropy in the G-buffer pass (gbuffer.frag, and its blend
// variant): the anisotropy direction resolved to world space, where the
// tangent frame is. The specification's direction is the texture's RG
// (-1..1; (1, 0) without a texture) turned counter-clockwise by
// anisotropyRotation in the tangent plane; strength is anisotropyStrength
// times the texture's B. Needs gbuffer.frag's tangentFrame, textureUv and
// the material block.
#ifdef ANISOTROPY_TEXCOORD_1
#define ANISOTROPY_SET true
#else
#define ANISOTROPY_SET false
#endif
#ifdef HAS_ANISOTROPY_TEXTURE
layout(binding = kUnitAnisotropyTexture) uniform sampler2D anisotropyTexture;
#endif

// The direction T (world, unit, perpendicular to `shadingNormal`) and the
// strength; 0 where the strength is 0 (the isotropic lobe).
vec4 anisotropyLobeOfMaterial(vec3 shadingNormal) {
  vec2 uv = vec2(0.0);
#ifdef HAS_TEXCOORDS
  uv = textureUv(ANISOTROPY_SET, material.anisotropyTransformU, material.anisotropyTransformV);
#endif
  // The frame first: its derivatives need every fragment of the quad.
  // (Points and lines without a normal have none: the shading normal stands in.)
  const vec3 geometricNormal = dot(vWorldNormal, vWorldNormal) > 1e-24
                                   ? normalize(vWorldNormal) * (gl_FrontFacing ? 1.0 : -1.0)
                                   : shadingNormal;
  const mat3 tangentToWorld = tangentFrame(geometricNormal, uv);
  vec3 texel = vec3(1.0, 0.5, 1.0);  // direction (1, 0), full strength
#ifdef HAS_ANISOTROPY_TEXTURE
  texel = texture(anisotropyTexture, uv).rgb;
#endif
  const float strength = clamp(material.anisotropyFactors.x * texel.b, 0.0, 1.0);
  const vec2 encoded = texel.rg * 2.0 - 1.0;
  const float c = material.anisotropyFactors.y, s = material.anisotropyFactors.z;
  vec3 tangent = tangentToWorld * vec3(c * encoded.x - s * encoded.y, s * encoded.x + c * encoded.y, 0.0);
  tangent -= shadingNormal * dot(shadingNormal, tangent);
  // No tangent frame (no TANGENT and no UVs to derive one): any direction
  // in the surface, as good as none.
  if (dot(tangent, tangent) < 1e-12)
    tangent = cross(shadingNormal, abs(shadingNormal.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0));
  if (strength <= 0.0 || dot(tangent, tangent) < 1e-12) return vec4(0.0);
  return vec4(normalize(tangent), strength);
}
