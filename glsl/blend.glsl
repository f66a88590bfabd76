// The blend pass's lighting (lib/passes/blend.hpp). gbuffer.frag built with
// BLEND_FORWARD evaluates an alphaMode BLEND material exactly as for the
// G-buffer, then calls shadeBlended() instead of writing the G-buffer: the
// direct-light pass's functions (lights, shadow maps) and the composite's
// ambient (ambient.glsl), one colour blended over lit. The surface is in
// no screen-space buffer, so it gets no SSGI: sky visibility 1, no
// indirect light (docs/PIPELINE.md, the blend pass).
#ifdef BLEND_FORWARD
#include "sampling.glsl"
#include "brdf.glsl"
#include "shadows.glsl"
#include "surface.glsl"
#include "ambient.glsl"
#ifdef HAS_CLEARCOAT_LOBE
#include "lobe_clearcoat_ambient.glsl"
#endif

// Blended by BlendPass: lit with (src alpha, 1 - src alpha) on colour and
// (1, 1 - src alpha) on alpha; coverage with (1, 1 - src alpha), so each
// holds 1 - prod(1 - a) of the layers drawn over it.
layout(location = 0) out vec4 outLit;
layout(location = 1) out vec4 outCoverage;

void shadeBlended(vec3 position, vec3 normal, vec4 baseColor, float metallic, float roughness, float occlusion,
                  vec3 emission) {
  Surface surface = makeSurface(baseColor.rgb, clamp(metallic, 0.0, 1.0), clamp(roughness, 0.0, 1.0), normal,
                                viewDirection(position));
  applyMaterialLobes(surface, normal);
#ifdef HAS_CLEARCOAT_LOBE
  const Clearcoat coat = makeClearcoat(forwardClearcoatLobe, surface.view);
  vec3 radiance = clearcoatLayer(coat, emission, vec3(0.0));
#else
  vec3 radiance = emission;
#endif
  const int lightCount = lighting.lightCount;
  for (int i = 0; i < lightCount; ++i) {
    const GpuLight light = lights.lightList[i];
    vec3 toLight;
    const float attenuation = lightAttenuation(light, position, toLight);
    if (attenuation <= 0.0) continue;
    const vec3 visibility = shadowVisibility(light, position, surface.normal, toLight);
    vec3 brdf = cookTorrance(surface, toLight);
#ifdef HAS_CLEARCOAT_LOBE
    brdf = clearcoatLayer(coat, brdf, vec3(clearcoatSpecular(coat, surface.view, toLight)));
#endif
    radiance += brdf * light.radiance * (attenuation * visibility);
  }
#if defined(HAS_SKY) && defined(HAS_CLEARCOAT_LOBE)
  radiance += clearcoatLayer(coat, ambientLight(surface, clamp(occlusion, 0.0, 1.0), 1.0, vec3(0.0)),
                             clearcoatAmbient(coat, surface.view, clamp(occlusion, 0.0, 1.0), 1.0));
#elif defined(HAS_SKY)
  radiance += ambientLight(surface, clamp(occlusion, 0.0, 1.0), 1.0, vec3(0.0));
#endif
  // NaN alpha (a NaN COLOR_0 is refused at load, a NaN factor too) would
  // poison every later layer: clamp keeps 0..1.
  const float alpha = clamp(baseColor.a, 0.0, 1.0);
  outLit = vec4(radiance, alpha);
  outCoverage = vec4(alpha);
}
#endif
