// What transmissive casters (KHR_materials_transmission, _volume) let
// through to what they shadow: pure functions, every input a parameter.
// shadow_transmittance.frag sums them into a light's transmittance map,
// shadows.glsl reads it back; lib/reference/lobe_transmission.hpp ports them
// with the same names and constants for the Embree reference's shadow rays.
//
// The model: light goes straight through (no caustic, no refraction offset).
// Each crossing keeps the specular transmission's share of what the Fresnel
// layer lets in, transmission x (1 - metallic) x (1 - F) (the weights of
// transmissiveCookTorrance), F Schlick's for the dielectric F0 of the ior
// at the crossing's angle. The base colour tints where light crosses a thin
// wall and where it enters a volume, not again where it leaves one (a glass
// ball tints once, a window pane once per pane). Inside a volume light fades
// by Beer-Lambert over the straight path between its surfaces.
//
// A map sums optical depths, -ln(transmittance), so that layers add in any
// order: each crossing's own, and for a volume, its extinction times the
// distance from the light, taken away where light enters and added where it
// leaves (for a closed surface the sum is the extinction times the length
// inside).

// An optical depth this large lets nothing through (e^-30 ~ 1e-13); a
// crossing that transmits nothing counts as this much.
const float kOpaqueOpticalDepth = 30.0;

// The share of light one crossing lets through, per channel. `cosine` is the
// cosine between the surface normal and the direction to the light (its sign
// does not matter here); `tints` says whether the base colour applies.
vec3 shadowCrossing(vec3 baseColor, float metallic, float transmission, float ior, float cosine, bool tints) {
  const float relative = (max(ior, 1.0) - 1.0) / (max(ior, 1.0) + 1.0);
  const float f0 = relative * relative;
  const float fresnel = f0 + (1.0 - f0) * pow(1.0 - clamp(abs(cosine), 0.0, 1.0), 5.0);
  const float share = clamp(transmission, 0.0, 1.0) * (1.0 - clamp(metallic, 0.0, 1.0)) * (1.0 - fresnel);
  return share * (tints ? clamp(baseColor, 0.0, 1.0) : vec3(1.0));
}

// -ln(transmittance), at most kOpaqueOpticalDepth per channel.
vec3 crossingOpticalDepth(vec3 crossing) {
  return min(-log(max(crossing, vec3(exp(-kOpaqueOpticalDepth)))), vec3(kOpaqueOpticalDepth));
}

// KHR_materials_volume's extinction per world unit: what is left of white
// light after attenuationDistance is attenuationColor. Distance 0 stands
// for the specification's infinity: nothing is absorbed.
vec3 volumeExtinction(vec3 attenuationColor, float attenuationDistance) {
  if (attenuationDistance <= 0.0) return vec3(0.0);
  return min(-log(max(attenuationColor, vec3(exp(-kOpaqueOpticalDepth)))), vec3(kOpaqueOpticalDepth)) /
         attenuationDistance;
}

// What a layer adds to the map's sum where light crosses a surface at
// `distanceFromLight` (world units, along the light's path): its own
// optical depth, and for a volume (thickness > 0) its extinction times the
// distance, negative where light enters (the normal faces the light,
// cosine > 0), positive where it leaves.
vec3 shadowLayerOpticalDepth(vec3 baseColor, float metallic, float transmission, float ior, float cosine,
                             bool volume, vec3 extinction, float distanceFromLight) {
  const bool enters = cosine > 0.0;
  const vec3 crossing = shadowCrossing(baseColor, metallic, transmission, ior, cosine, !volume || enters);
  vec3 depth = crossingOpticalDepth(crossing);
  if (volume) depth += (enters ? -1.0 : 1.0) * extinction * distanceFromLight;
  return depth;
}

// The transmittance a map's sum stands for.
vec3 shadowTransmittance(vec3 opticalDepth) { return exp(-max(opticalDepth, vec3(0.0))); }
