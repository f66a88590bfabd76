// KHR_materials_iridescence: a thin dielectric film on the base material
// changes its Fresnel term (lib/reference/lobe_iridescence.hpp is the CPU
// port; every constant and clamp here is there too). The film's reflectance
// is Belcour & Barla's (2017) as the extension's specification states it:
// Schlick's Fresnel at both interfaces, no polarisation, the phase shifts 0
// or pi, and the spectral integral in Fourier space (the m = 0 term and two
// pairs of Diracs) against Gaussian fits of the CIE XYZ sensitivities, then
// XYZ to linear Rec.709, the renderer's working space.
//
// Evaluated once per pixel at cos(theta1) = N.V (as the glTF Sample Viewer
// does): the punctual lights' highlights peak where H = N, so V.H = N.V there,
// and the split-sum ambient term needs one Fresnel value per pixel anyway.
// Schlick's Fresnel still varies with V.H per light: the specular term's F
// is mix(Schlick(V.H), thinFilmFresnel, iridescence) (brdf.glsl).
// Needs kPi (sampling.glsl), shared_layout.h and brdf.glsl's Surface
// (brdf.glsl's #include_lobes expands it where Surface is defined).

float thinFilmIorToFresnel0(float transmittedIor, float incidentIor) {
  const float r = (transmittedIor - incidentIor) / (transmittedIor + incidentIor);
  return r * r;
}

vec3 thinFilmIorToFresnel0(vec3 transmittedIor, float incidentIor) {
  const vec3 r = (transmittedIor - incidentIor) / (transmittedIor + incidentIor);
  return r * r;
}

// The inverse at an interface with air: F0 = ((n - 1) / (n + 1))^2.
vec3 thinFilmFresnel0ToIor(vec3 f0) {
  const vec3 root = sqrt(f0);
  return (1.0 + root) / (1.0 - root);
}

// max(): N.V may round a hair above 1, and pow of a negative base is undefined in GLSL.
vec3 thinFilmSchlick(vec3 f0, float cosTheta) { return f0 + (1.0 - f0) * pow(max(1.0 - cosTheta, 0.0), 5.0); }

// One Fourier term of the film's reflectance spectrum seen through the
// CIE XYZ sensitivities (Gaussian fits: amplitude, mean and variance per
// channel, X with a second lobe), for optical path difference `opdNm` and
// phase shift `shift`, as linear Rec.709.
vec3 thinFilmSensitivity(float opdNm, vec3 shift) {
  const float phase = 2.0 * kPi * opdNm * 1.0e-9;
  const vec3 amplitude = vec3(5.4856e-13, 4.4201e-13, 5.2481e-13);
  const vec3 mean = vec3(1.6810e+06, 1.7953e+06, 2.2084e+06);
  const vec3 variance = vec3(4.3278e+09, 9.3046e+09, 6.6121e+09);
  vec3 xyz = amplitude * sqrt(2.0 * kPi * variance) * cos(mean * phase + shift) * exp(-(phase * phase) * variance);
  xyz.x += 9.7470e-14 * sqrt(2.0 * kPi * 4.5282e+09) * cos(2.2399e+06 * phase + shift.x) *
           exp(-4.5282e+09 * (phase * phase));
  xyz /= 1.0685e-7;
  return vec3(dot(vec3(3.2404542, -1.5371385, -0.4985314), xyz), dot(vec3(-0.9692660, 1.8760108, 0.0415560), xyz),
              dot(vec3(0.0556434, -0.2040259, 1.0572252), xyz));
}

// F_iridescence of the specification: light from a medium of `outsideIor`
// (air: 1) through a film of `filmIor` and `thicknessNm` onto a base of
// normal-incidence reflectance `baseF0`, at cos(theta1) in the outer medium.
vec3 thinFilmFresnel(float outsideIor, float filmIor, float cosTheta1, float thicknessNm, vec3 baseF0) {
  // The specification's fade of the film's IOR to the outside's as the
  // thickness goes to 0 (over 0..0.03, in the thickness's unit, nm), so a
  // film of thickness 0 is no film.
  const float eta2 = mix(outsideIor, filmIor, smoothstep(0.0, 0.03, thicknessNm));
  const float ratio = outsideIor / eta2;
  const float cosTheta2Squared = 1.0 - ratio * ratio * (1.0 - cosTheta1 * cosTheta1);
  if (cosTheta2Squared < 0.0) return vec3(1.0);  // total internal reflection in the film
  const float cosTheta2 = sqrt(cosTheta2Squared);

  // Outside -> film: phase shift pi on reflection off a denser medium.
  const float r12 = thinFilmSchlick(vec3(thinFilmIorToFresnel0(eta2, outsideIor)), cosTheta1).x;
  const float t121 = 1.0 - r12;
  const float phi21 = kPi - (eta2 < outsideIor ? kPi : 0.0);
  // Film -> base; 0.9999 keeps the IOR finite for a white metal.
  const vec3 baseIor = thinFilmFresnel0ToIor(clamp(baseF0, 0.0, 0.9999));
  const vec3 r23 = thinFilmSchlick(thinFilmIorToFresnel0(baseIor, eta2), cosTheta2);
  const vec3 phi23 = mix(vec3(0.0), vec3(kPi), lessThan(baseIor, vec3(eta2)));

  const float opd = 2.0 * eta2 * thicknessNm * cosTheta2;  // optical path difference, nm
  const vec3 phi = phi21 + phi23;
  const vec3 r123Squared = clamp(r12 * r23, 1e-5, 0.9999);
  const vec3 r123 = sqrt(r123Squared);
  const vec3 rs = t121 * t121 * r23 / (1.0 - r123Squared);
  vec3 reflectance = r12 + rs;  // m = 0: the incoherent sum
  vec3 cm = rs - t121;
  for (int m = 1; m <= 2; ++m) {
    cm *= r123;
    reflectance += cm * 2.0 * thinFilmSensitivity(float(m) * opd, float(m) * phi);
  }
  return max(reflectance, vec3(0.0));
}

// The film's Fresnel for a surface of `albedo` and `metallic`: glTF mixes
// a dielectric base (F0 from the base's IOR) and a metal one (F0 = base
// colour) by metallic, and the film lies on each. `film` is the lobe's
// attachment: strength, thickness (nm), the film's IOR, the base's IOR
// (lobe_iridescence_material.glsl writes it).
vec3 iridescenceFresnel(vec4 film, vec3 albedo, float metallic, float nDotV) {
  const float thickness = clamp(film.y, 0.0, kMaxFilmThicknessNm);
  const float filmIor = clamp(film.z, 1.0, kMaxIridescenceIor);
  if (metallic >= 1.0) return thinFilmFresnel(1.0, filmIor, nDotV, thickness, albedo);
  const float baseF0 = thinFilmIorToFresnel0(clamp(film.w, 0.0, kMaxIridescenceIor), 1.0);
  const vec3 dielectric = thinFilmFresnel(1.0, filmIor, nDotV, thickness, vec3(baseF0));
  if (metallic <= 0.0) return dielectric;
  return mix(dielectric, thinFilmFresnel(1.0, filmIor, nDotV, thickness, albedo), metallic);
}

// ---- The lobe's hooks (brdf.glsl, ambient.glsl). The G-buffer holds the
// film (strength, thickness, film IOR, base IOR); Apply turns it into what
// the Surface keeps: the film's Fresnel at N.V (rgb) and the strength (a)
// that mixes it with Schlick's. The Fresnel is one value per pixel, so it
// leaves the split-sum integral whole: F (scale + bias).
#ifndef FORWARD_SHADING
layout(binding = kUnitIridescenceLobe) uniform sampler2D iridescenceLobeTarget;
#endif

vec4 iridescenceLobeApply(inout Surface s, vec4 film) {
  const float strength = clamp(film.x, 0.0, 1.0);
  return vec4(strength > 0.0 ? iridescenceFresnel(film, s.albedo, s.metallic, s.nDotV) : vec3(0.0), strength);
}

vec3 iridescenceLobeFresnel(Surface s, vec4 film, vec3 fresnel) { return mix(fresnel, film.rgb, film.a); }

vec3 iridescenceLobeSpecularAlbedo(Surface s, vec4 film, vec3 albedo, vec2 scaleBias) {
  return mix(albedo, film.rgb * (scaleBias.x + scaleBias.y), film.a);
}
