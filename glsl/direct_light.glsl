// Direct light (lib/passes/direct_light.hpp): every punctual light with its
// shadow, plus emission. `towardEye` is the radiance toward the eye
// (Cook-Torrance); `diffuse` (written with WRITE_DIFFUSE_RADIANCE) is the
// Lambertian radiance the surface sends in every direction, which the SSGI
// methods gather as one-bounce light (docs/ACCURACY.md). A fullscreen pass's
// body: fullscreen_entry.frag or .comp runs it per pixel.
#include "shared_layout.h"
#include "sampling.glsl"
#include "brdf.glsl"
#include "shadows.glsl"
#include "surface.glsl"
#ifdef HAS_CLEARCOAT_LOBE
#include "lobe_clearcoat.glsl"
#endif

#ifdef HAS_EMISSIVE
layout(binding = kUnitGbufferEmissive) uniform sampler2D gbufferEmissive;
#endif

struct PassOutputs {
  vec4 towardEye;
  vec4 diffuse;
};

PassOutputs shadePixel(ivec2 pixel) {
  PassOutputs o;
  const vec4 worldPosition = texelFetch(gbufferPosition, pixel, 0);
  if (worldPosition.a == 0.0) {  // background: no light
    o.towardEye = o.diffuse = vec4(0.0);
    return o;
  }
  const Surface surface = surfaceAt(pixel, worldPosition.xyz);
#ifdef HAS_CLEARCOAT_LOBE
  const Clearcoat coat = clearcoatAt(pixel, surface.view);
#endif
  vec3 towardEye = vec3(0.0);
  vec3 irradiance = vec3(0.0);  // sum of light radiance * attenuation * visibility * N.L
  const int lightCount = lighting.lightCount;
  for (int i = 0; i < lightCount; ++i) {
    const GpuLight light = lights.lightList[i];
    vec3 toLight;
    const float attenuation = lightAttenuation(light, worldPosition.xyz, toLight);
    if (attenuation <= 0.0) continue;
    const vec3 visibility = shadowVisibility(light, worldPosition.xyz, surface.normal, toLight);
    const vec3 incoming = light.radiance * (attenuation * visibility);
    vec3 brdf = cookTorrance(surface, toLight);
#ifdef HAS_CLEARCOAT_LOBE
    brdf = clearcoatLayer(coat, brdf, vec3(clearcoatSpecular(coat, surface.view, toLight)));
#endif
    towardEye += brdf * incoming;
    irradiance += incoming * max(dot(surface.normal, toLight), 0.0);
  }
#ifdef HAS_EMISSIVE
  const vec3 emission = texelFetch(gbufferEmissive, pixel, 0).rgb;
#else
  const vec3 emission = vec3(0.0);
#endif
#ifdef HAS_CLEARCOAT_LOBE
  o.towardEye = vec4(towardEye + clearcoatLayer(coat, emission, vec3(0.0)), 1.0);  // the coat darkens emission too
#else
  o.towardEye = vec4(towardEye + emission, 1.0);
#endif
  o.diffuse = vec4((1.0 - surface.metallic) * surface.albedo / kPi * irradiance + emission, 1.0);
  return o;
}
