// Low-discrepancy sampling and the GGX distribution, shared by the table
// passes and the direct-light and composite passes.
const float kPi = 3.14159265358979;

// The i-th of n points of the Hammersley set in [0,1)^2.
vec2 hammersley(uint i, uint n) {
  uint bits = bitfieldReverse(i);
  return vec2(float(i) / float(n), float(bits) * 2.3283064365386963e-10);
}

// A frame with `normal` as +Z.
mat3 basisAround(vec3 normal) {
  const vec3 up = abs(normal.z) < 0.999 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0);
  const vec3 tangent = normalize(cross(up, normal));
  return mat3(tangent, cross(normal, tangent), normal);
}

// A half vector drawn from the GGX distribution with roughness alpha
// (= perceptual roughness squared) around +Z.
vec3 importanceSampleGgx(vec2 xi, float alpha) {
  const float phi = 2.0 * kPi * xi.x;
  const float cosTheta = sqrt((1.0 - xi.y) / (1.0 + (alpha * alpha - 1.0) * xi.y));
  const float sinTheta = sqrt(1.0 - cosTheta * cosTheta);
  return vec3(sinTheta * cos(phi), sinTheta * sin(phi), cosTheta);
}

// A direction drawn with density cos(theta) / pi around +Z.
vec3 cosineSampleHemisphere(vec2 xi) {
  const float r = sqrt(xi.x), phi = 2.0 * kPi * xi.y;
  return vec3(r * cos(phi), r * sin(phi), sqrt(max(0.0, 1.0 - xi.x)));
}

// Smith-GGX visibility, height-correlated (Heitz 2014): G / (4 N.L N.V).
float smithGgxVisibility(float nDotV, float nDotL, float alpha) {
  const float a2 = alpha * alpha;
  const float ggxV = nDotL * sqrt(nDotV * nDotV * (1.0 - a2) + a2);
  const float ggxL = nDotV * sqrt(nDotL * nDotL * (1.0 - a2) + a2);
  return 0.5 / max(ggxV + ggxL, 1e-7);
}

// Texel centre -> the value it stands for, for a table of `size` texels
// that spans [low, high] from the first texel's centre to the last's.
float tableValue(float fragCoord, float size, float low, float high) {
  return mix(low, high, (fragCoord - 0.5) / max(size - 1.0, 1.0));
}
