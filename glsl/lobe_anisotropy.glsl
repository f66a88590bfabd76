// KHR_materials_anisotropy's lobe: GGX stretched along the surface's
// anisotropy direction T (world, unit, perpendicular to N; B = N x T), with
// the specification's roughnesses alpha_t = mix(alpha, 1, strength^2) along
// T and alpha_b = alpha along B; strength 0 is brdf.glsl's isotropic lobe.
// Pure functions of their inputs; lib/reference/lobe_anisotropy.hpp is the
// CPU port (same names, clamps and constants), held to this file by
// tests/sheen_anisotropy_parity_tests.cpp. Needs sampling.glsl (kPi); the hooks at the end
// need brdf.glsl's Surface (its #include_lobes expands this file).

float anisotropyAlphaT(float alpha, float strength) { return mix(alpha, 1.0, strength * strength); }

// D(h) = 1 / (pi a_t a_b ((T.H / a_t)^2 + (B.H / a_b)^2 + (N.H)^2)^2), written
// as a w^2 / pi with a = a_t a_b and w = a / |(a_b T.H, a_t B.H, a N.H)|^2,
// which stays finite as alpha nears 0.
float anisotropicDistribution(float alphaT, float alphaB, float tDotH, float bDotH, float nDotH) {
  const float a = alphaT * alphaB;
  const vec3 stretched = vec3(alphaB * tDotH, alphaT * bDotH, a * nDotH);
  const float w = a / max(dot(stretched, stretched), 1e-30);
  return a * w * w / kPi;
}

// G2 / (4 N.L N.V), height-correlated Smith with the stretched roughness.
float anisotropicVisibility(float alphaT, float alphaB, vec3 atV, vec3 atL) {
  const float lambdaV = atL.z * length(vec3(alphaT * atV.x, alphaB * atV.y, atV.z));
  const float lambdaL = atV.z * length(vec3(alphaT * atL.x, alphaB * atL.y, atL.z));
  return 0.5 / max(lambdaV + lambdaL, 1e-7);
}

// D Vis toward `toLight` (brdf.glsl's specular term without Fresnel).
// `nDotV` and `nDotL` as cookTorrance clamps them.
float anisotropicSpecular(vec3 tangent, float strength, float alpha, vec3 normal, vec3 view, vec3 toLight,
                          vec3 halfVector, float nDotV, float nDotL) {
  const vec3 bitangent = cross(normal, tangent);
  const float alphaT = anisotropyAlphaT(alpha, strength);
  const float distribution = anisotropicDistribution(alphaT, alpha, dot(tangent, halfVector),
                                                     dot(bitangent, halfVector), max(dot(normal, halfVector), 0.0));
  const vec3 atV = vec3(dot(tangent, view), dot(bitangent, view), nDotV);
  const vec3 atL = vec3(dot(tangent, toLight), dot(bitangent, toLight), nDotL);
  return distribution * anisotropicVisibility(alphaT, alpha, atV, atL);
}

// Image-based light, energy: the perceptual roughness of the isotropic lobe
// whose split-sum albedo (the BRDF table) stands in for the stretched
// lobe's, alpha = (alpha_t + alpha_b) / 2. The stretched lobe reflects less
// than the isotropic one of the material's roughness (0.62 against 0.95 at
// roughness 0.4, strength 0.9, N.V 0.7); the mean alpha's lobe reflects 0.68
// (tests/sheen_anisotropy_lobe_tests.cpp bounds the difference).
float anisotropicAlbedoRoughness(float roughness, float strength) {
  const float alpha = roughness * roughness;
  return sqrt(0.5 * (anisotropyAlphaT(alpha, strength) + alpha));
}

// Image-based light: the direction the prefiltered tables are read in. The
// normal is bent toward the grain's normal facing the eye (perpendicular to
// B, in the plane of B and V), the more the stronger and smoother the
// anisotropy, and the view is mirrored about it: the stretched lobe's
// reflection sweeps along the grain.
vec3 anisotropicReflection(vec3 normal, vec3 view, vec3 tangent, float strength, float roughness) {
  const vec3 bitangent = cross(normal, tangent);
  const vec3 grainNormal = cross(cross(bitangent, view), bitangent);
  const float bend = 1.0 - strength * (1.0 - roughness);
  const vec3 bent = mix(grainNormal, normal, bend * bend * bend * bend);
  // A view along B with bend 0 leaves no normal: keep N.
  return reflect(-view, dot(bent, bent) > 1e-12 ? normalize(bent) : normal);
}

// ---- The lobe's hooks (brdf.glsl, ambient.glsl): its value is the world
// direction T (xyz) and the strength (w; 0: the isotropic lobe),
// lobe_anisotropy_material.glsl's.
#ifndef FORWARD_SHADING
layout(binding = kUnitAnisotropyLobe) uniform sampler2D anisotropyLobeTarget;
#endif

float anisotropyLobeSpecularTerm(Surface s, vec4 anisotropy, float term, float alpha, vec3 toLight, vec3 halfVector,
                                 float nDotL) {
  if (anisotropy.w <= 0.0) return term;
  return anisotropicSpecular(anisotropy.xyz, anisotropy.w, alpha, s.normal, s.view, toLight, halfVector, s.nDotV,
                             nDotL);
}

float anisotropyLobeAlbedoRoughness(Surface s, vec4 anisotropy, float roughness) {
  return anisotropy.w > 0.0 ? anisotropicAlbedoRoughness(s.roughness, anisotropy.w) : roughness;
}

vec3 anisotropyLobeReflection(Surface s, vec4 anisotropy, vec3 reflected) {
  if (anisotropy.w <= 0.0) return reflected;
  return anisotropicReflection(s.normal, s.view, anisotropy.xyz, anisotropy.w, s.roughness);
}
