// The clear coat's image-based light (composite.frag and blend.glsl, with
// lobe_clearcoat.glsl): the split sum as ambient.glsl computes the base's,
// for the coat's lobe without Fresnel (c Fc carries it, clearcoatLayer), so
// its directional albedo is the BRDF table's scale + bias; the sky (or
// environment map) prefiltered for the coat's roughness around its own
// reflection. Occluded as the base's ambient is. Without HAS_SKY the coat
// has no ambient to reflect.
#include "ambient.glsl"
#include "lobe_clearcoat.glsl"

vec3 clearcoatAmbient(Clearcoat c, vec3 view, float materialOcclusion, float skyVisibility) {
#ifdef HAS_SKY
  const float size = float(kBrdfLutSize);
  const vec2 scaleBias = texture(brdfLut, vec2(tableCoordinate(c.nDotV, 0.0, 1.0, size),
                                               tableCoordinate(c.roughness, 0.0, 1.0, size))).rg;
  const vec3 reflected = reflect(-view, c.normal);
  return (scaleBias.x + scaleBias.y) * prefilteredSky(reflected, c.roughness) * lighting.skyIntensity *
         materialOcclusion * skyVisibility;
#else
  return vec3(0.0);
#endif
}
