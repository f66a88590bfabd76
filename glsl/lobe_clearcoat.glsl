// KHR_materials_clearcoat in the lighting passes (direct_light.frag,
// composite.frag, blend.glsl; docs/PIPELINE.md, "Material lobes"). The
// clearcoat lobe's attachment holds the coat's factor (r), its perceptual
// roughness (g) and its normal, octahedral-encoded (ba)
// (lobe_clearcoat_material.glsl). Following the specification's layering,
// a coat of factor c with Fresnel Fc = Schlick(0.04, N_coat . V) (IOR 1.5)
// turns whatever the surface sends (direct, ambient, SSGI and emission) into
//   coated = base * (1 - c Fc) + c Fc * coat
// where coat is a GGX lobe (D * Vis * N_coat . L, no Fresnel: Fc carries it)
// around the coat's normal. Pure functions; the sampler is read by
// clearcoatAt. Needs sampling.glsl.
#include "sampling.glsl"

// Octahedral encoding of a unit vector into [-1, 1]^2 (Cigolle et al. 2014,
// "A Survey of Efficient Representations for Independent Unit Vectors"):
// two half floats keep a direction to ~0.05 degrees, and the normal fits
// one RGBA attachment beside the factor and the roughness.
vec2 signNotZero(vec2 v) { return vec2(v.x >= 0.0 ? 1.0 : -1.0, v.y >= 0.0 ? 1.0 : -1.0); }

vec2 octahedralEncode(vec3 n) {
  const vec2 p = n.xy / (abs(n.x) + abs(n.y) + abs(n.z));
  return n.z >= 0.0 ? p : (1.0 - abs(p.yx)) * signNotZero(p);
}

vec3 octahedralDecode(vec2 e) {
  vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
  if (n.z < 0.0) n.xy = (1.0 - abs(n.yx)) * signNotZero(n.xy);
  return normalize(n);
}

struct Clearcoat {
  float factor;     // c, 0..1
  float roughness;  // perceptual; clamped as makeSurface clamps the base's
  vec3 normal;      // world, unit
  float nDotV;
  float weight;     // c Fc: the share of the light the coat reflects; the base keeps 1 - weight
};

Clearcoat makeClearcoat(vec4 lobe, vec3 view) {
  Clearcoat c;
  c.factor = lobe.r;
  c.roughness = max(lobe.g, 0.03);  // brdf.glsl: below 0.03 GGX's peak outgrows half floats
  c.normal = octahedralDecode(lobe.ba);
  c.nDotV = max(dot(c.normal, view), 1e-4);
  const float fresnel = 0.04 + 0.96 * pow(1.0 - c.nDotV, 5.0);  // 0.04: F0 of IOR 1.5, the coat's
  c.weight = c.factor * fresnel;
  return c;
}

// The coat's GGX lobe toward a unit `toLight`, times N_coat . L.
float clearcoatSpecular(Clearcoat c, vec3 view, vec3 toLight) {
  const float nDotL = dot(c.normal, toLight);
  if (nDotL <= 0.0) return 0.0;
  const vec3 halfVector = normalize(toLight + view);
  const float nDotH = max(dot(c.normal, halfVector), 0.0);
  const float alpha = c.roughness * c.roughness;
  const float a2 = alpha * alpha;
  const float d = (nDotH * nDotH) * (a2 - 1.0) + 1.0;
  return a2 / (kPi * d * d) * smithGgxVisibility(c.nDotV, nDotL, alpha) * nDotL;
}

// What the coated surface sends, from what the base sends and the coat's lobe.
vec3 clearcoatLayer(Clearcoat c, vec3 base, vec3 coat) { return base * (1.0 - c.weight) + coat * c.weight; }

#if defined(HAS_CLEARCOAT_LOBE) && !defined(FORWARD_SHADING)
layout(binding = kUnitClearcoatLobe) uniform sampler2D clearcoatLobeTarget;

Clearcoat clearcoatAt(ivec2 pixel, vec3 view) { return makeClearcoat(texelFetch(clearcoatLobeTarget, pixel, 0), view); }
#endif
