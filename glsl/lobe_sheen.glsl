// KHR_materials_sheen's lobe: the "Charlie" sheen of Conty and Kulla (2017,
// "Production Friendly Microfacet Sheen BRDF"), layered over the base as the
// extension's specification does it (albedo scaling):
//   f = f_sheen + f_base * min(1 - max3(sheenColor) E(N.V), 1 - max3(sheenColor) E(N.L))
// with f_sheen = sheenColor D V (no Fresnel). Pure functions of their
// inputs; lib/reference/lobe_sheen.hpp is the CPU port (same names, clamps
// and constants), held to this file by tests/sheen_anisotropy_parity_tests.cpp.
// Needs sampling.glsl (kPi); the hooks at the end
// need brdf.glsl's Surface (its #include_lobes expands this file).

// Below 0.07 the distribution's exponent 1 / alpha passes 200: its grazing
// peak then outgrows half floats, and no fabric is that smooth.
const float kSheenMinRoughness = 0.07;

// The distribution's alpha: the perceptual sheen roughness squared, as for
// GGX (the specification's sheenRoughness is perceptual).
float sheenAlpha(float roughness) {
  const float r = clamp(roughness, kSheenMinRoughness, 1.0);
  return r * r;
}

float sheenStrength(vec3 sheenColor) { return max(max(sheenColor.r, sheenColor.g), sheenColor.b); }

// D: fibres around the normal, (2 + 1/alpha) sin(theta_h)^(1/alpha) / (2 pi).
float sheenDistribution(float alpha, float nDotH) {
  const float inverseAlpha = 1.0 / alpha;
  const float sinSquared = max(1.0 - nDotH * nDotH, 1e-7);  // 1e-7: pow(0, x) is undefined in GLSL for x <= 0
  return (2.0 + inverseAlpha) * pow(sinSquared, 0.5 * inverseAlpha) / (2.0 * kPi);
}

// Conty and Kulla's fit of the distribution's Smith Lambda: five
// coefficients, each interpolated between alpha = 1 and alpha = 0 by
// (1 - alpha)^2; mirrored about cos = 0.5, where the fit was made.
float sheenLambdaFit(float x, float alpha) {
  const float t = (1.0 - alpha) * (1.0 - alpha);
  const float a = mix(21.5473, 25.3245, t), b = mix(3.82987, 3.32435, t), c = mix(0.19823, 0.16801, t);
  const float d = mix(-1.97760, -1.27393, t), e = mix(-4.32054, -4.85967, t);
  return a / (1.0 + b * pow(x, c)) + d * x + e;
}
float sheenLambda(float cosTheta, float alpha) {
  return cosTheta < 0.5 ? exp(sheenLambdaFit(cosTheta, alpha))
                        : exp(2.0 * sheenLambdaFit(0.5, alpha) - sheenLambdaFit(1.0 - cosTheta, alpha));
}

// V = G / (4 N.L N.V) with the height-correlated G = 1 / (1 + Lambda(V) + Lambda(L)).
float sheenVisibility(float alpha, float nDotV, float nDotL) {
  return 1.0 / ((1.0 + sheenLambda(nDotV, alpha) + sheenLambda(nDotL, alpha)) * (4.0 * nDotV * nDotL));
}

// E(cos theta): the share of light the sheen lobe reflects (its directional
// albedo for a white sheenColor). An analytic fit in (1 - cos)^3 and
// sqrt(alpha) instead of a table; tests/sheen_anisotropy_lobe_tests.cpp integrates the
// lobe and bounds the fit's error (docs/ACCURACY.md has the numbers).
float sheenAlbedo(float alpha, float cosTheta) {
  const float c = 1.0 - clamp(cosTheta, 0.0, 1.0);
  return 0.65584461 * c * c * c + 1.0 / (4.16526551 + exp(-7.97291361 * sqrt(alpha) + 6.33516894));
}

// The sheen lobe's radiance factor toward `toLight`: f_sheen * N.L (nDotL > 0).
vec3 sheenReflected(vec3 sheenColor, float roughness, float nDotV, float nDotL, float nDotH) {
  const float alpha = sheenAlpha(roughness);
  return sheenColor * (sheenDistribution(alpha, nDotH) * sheenVisibility(alpha, nDotV, nDotL) * nDotL);
}

// What the base layer keeps under the sheen for light arriving along L.
float sheenBaseScale(vec3 sheenColor, float roughness, float nDotV, float nDotL) {
  const float alpha = sheenAlpha(roughness), strength = sheenStrength(sheenColor);
  return min(1.0 - strength * sheenAlbedo(alpha, nDotV), 1.0 - strength * sheenAlbedo(alpha, nDotL));
}

// Image-based light: the base keeps 1 - max3(sheenColor) E(N.V) (the
// specification's single-lookup form), and the lobe reflects
// sheenColor E(N.V) of the ambient prefiltered at the sheen roughness
// (`prefiltered`: the GGX tables stand in for a Charlie-filtered one).
float sheenAmbientBaseScale(vec3 sheenColor, float roughness, float nDotV) {
  return 1.0 - sheenStrength(sheenColor) * sheenAlbedo(sheenAlpha(roughness), nDotV);
}
vec3 sheenAmbient(vec3 sheenColor, float roughness, float nDotV, vec3 prefiltered) {
  return sheenColor * sheenAlbedo(sheenAlpha(roughness), nDotV) * prefiltered;
}

// ---- The lobe's hooks (brdf.glsl): its value is the sheen colour (rgb,
// linear; black: no layer) and roughness (a), lobe_sheen_material.glsl's.
#ifndef FORWARD_SHADING
layout(binding = kUnitSheenLobe) uniform sampler2D sheenLobeTarget;  // colour (sRGB8), roughness
#endif

float sheenLobeLayerScale(Surface s, vec4 sheen, float nDotL) {
  return sheen.rgb != vec3(0.0) ? sheenBaseScale(sheen.rgb, sheen.a, s.nDotV, nDotL) : 1.0;
}

vec3 sheenLobeLayerLight(Surface s, vec4 sheen, float nDotL, float nDotH) {
  return sheen.rgb != vec3(0.0) ? sheenReflected(sheen.rgb, sheen.a, s.nDotV, nDotL, nDotH) : vec3(0.0);
}
