// KHR_materials_transmission and KHR_materials_volume: the pure functions of
// the transmission pass (lib/passes/transmission.hpp), every input a
// parameter. lib/reference/lobe_transmission.hpp ports them to C++ with the
// same names and constants (tests/transmission_parity_tests.cpp holds them
// together). Needs sampling.glsl and brdf.glsl.

// The roughness that blurs transmitted light. Microfacets bend light by
// refraction, which grows with ior - 1 and vanishes at ior 1 (then a rough
// surface transmits sharply: TransmissionRoughnessTest's bottom row); from
// ior 1.5 up it is the surface's roughness, as the glTF Sample Viewer takes
// it.
float transmissionRoughness(float roughness, float ior) { return roughness * clamp(ior * 2.0 - 2.0, 0.0, 1.0); }

// The path light takes through the volume to the eye, from the surface point
// to where it leaves: the view ray refracted into the surface (ior; 1 for
// anything below, including KHR_materials_ior's 0), as long as the thickness
// (KHR_materials_volume's thicknessFactor x texture G, in the mesh's units),
// scaled per axis by the instance's transform. Zero for thin walls
// (thickness 0): the light goes straight through.
vec3 volumeTransmissionRay(vec3 normal, vec3 view, float thickness, float ior, vec3 modelScale) {
  const vec3 refracted = refract(-view, normal, 1.0 / max(ior, 1.0));
  // refract gives 0 only for total internal reflection, impossible entering a
  // denser medium; a normal facing away from the eye could still get there.
  const vec3 direction = dot(refracted, refracted) > 0.0 ? normalize(refracted) : -view;
  return direction * thickness * modelScale;
}

// Beer-Lambert: attenuationColor is what is left of white light after
// attenuationDistance inside the medium; distance 0 stands for the
// specification's infinity (nothing absorbed), and so does a zero path.
vec3 volumeAttenuation(float pathLength, vec3 attenuationColor, float attenuationDistance) {
  if (attenuationDistance <= 0.0 || pathLength <= 0.0) return vec3(1.0);
  return pow(attenuationColor, vec3(pathLength / attenuationDistance));
}

// The thin-walled microfacet BTDF toward the eye for light from behind the
// surface (N.L < 0), times |N.L| as cookTorrance's BRDF is times N.L: GGX
// over the specification's transmission half vector H_T = normalize(V + L
// mirrored through the surface plane), alpha = transmissionRoughness^2,
// clamped as makeSurface clamps roughness. 0 for light from the front.
float specularBtdf(vec3 normal, vec3 view, float nDotV, vec3 toLight, float roughness) {
  const float nDotL = dot(normal, toLight);
  if (nDotL >= 0.0) return 0.0;
  const vec3 mirrored = toLight - 2.0 * nDotL * normal;
  const vec3 halfVector = normalize(mirrored + view);
  const float nDotH = max(dot(normal, halfVector), 0.0);
  const float alpha = max(roughness, 0.03) * max(roughness, 0.03);
  const float a2 = alpha * alpha;
  const float d = (nDotH * nDotH) * (a2 - 1.0) + 1.0;
  return a2 / (kPi * d * d) * smithGgxVisibility(nDotV, -nDotL, alpha) * -nDotL;
}

// cookTorrance for a transmissive surface (s.transmission > 0): the
// specification's mix(diffuse, btdf * baseColor, transmission) under the
// Fresnel layer. From the front it is cookTorrance, whose diffuse lobe keeps
// the share not transmitted (the BTDF sends nothing back toward a light on
// the eye's side); from behind, only the tinted BTDF, weighted like the
// diffuse lobe by (1 - F) (1 - metallic), F the surface's (iridescent where
// it has a film), under the layers over the base (sheen). The BTDF is
// isotropic: anisotropy shapes the reflection only.
// `transmissionRoughnessValue` is transmissionRoughness(roughness, ior).
vec3 transmissiveCookTorrance(Surface s, vec3 toLight, float transmissionRoughnessValue) {
  const float nDotL = dot(s.normal, toLight);
  if (nDotL > 0.0) return cookTorrance(s, toLight);
  const vec3 mirrored = toLight - 2.0 * nDotL * s.normal;
  const vec3 fresnel = surfaceFresnel(s, max(dot(s.view, normalize(mirrored + s.view)), 0.0));
  return s.transmission * (1.0 - fresnel) * (1.0 - s.metallic) * s.albedo *
         (specularBtdf(s.normal, s.view, s.nDotV, toLight, transmissionRoughnessValue) * baseLayerScale(s, -nDotL));
}

// How much of the background arriving through the surface reaches the eye,
// per channel: the transmitted share of what the Fresnel layer lets in
// (`specularAlbedo`: ambient.glsl specularAlbedoOf), tinted by the base
// colour, through the volume (Beer-Lambert over the path's length), under
// the layers over the base (sheen, along the view: light goes straight on).
vec3 transmissionThroughput(Surface s, vec3 specularAlbedo, vec3 attenuation) {
  return s.transmission * (1.0 - specularAlbedo) * (1.0 - s.metallic) * s.albedo * attenuation *
         baseLayerScale(s, s.nDotV);
}

// How far the transmitted lobe spreads: the tangent of its half-width
// angle, kTransmissionSpread x transmissionRoughness^1.5, at most 60
// degrees. Both are fitted to the Embree reference's sampled lobe (two rough
// interfaces refracting each ray, lib/reference/tracer.cpp): a wall's edge
// behind glass of ior 1.5 spreads over about as many pixels in both at
// roughness 0.4 and 0.6 (GGX's alpha, roughness^2, grew too fast: 7 pixels
// against 12 at 0.4; tests/transmission_parity_tests.cpp).
const float kTransmissionSpread = 1.1;
float transmissionSpread(float transmissionRoughnessValue) {
  return min(kTransmissionSpread * pow(transmissionRoughnessValue, 1.5), 1.732);
}

// The mip level of the background copy that the transmission roughness
// reads: texels as wide as the lobe's footprint on what lies behind, which
// grows with the distance from where light leaves the surface to what it
// meets (`distanceBehind`, world units) and is seen there at
// `pixelsPerUnit` (pixels a world unit). 0 for a smooth surface, and for a
// background touching the glass. (The glTF Sample Viewer's log2(size) x
// roughness ignores the distance: TransmissionRoughnessTest's wall, just
// behind its tiles, came out blurred past recognition.)
float transmissionLod(float transmissionRoughnessValue, float distanceBehind, float pixelsPerUnit) {
  const float radius = transmissionSpread(transmissionRoughnessValue) * distanceBehind * pixelsPerUnit;
  return log2(max(2.0 * radius, 1.0));
}
