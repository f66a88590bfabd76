// Composite (lib/passes/composite.hpp): direct light + image-based ambient,
// occluded by the material's AO and the SSGI's sky visibility (at any
// distance: the sky is infinitely far, so AO within R would let a closed
// room see it), + SSGI's indirect term:
//   ambient = (diffuse_ibl * ssgi_sky + specular_ibl * ssgi_specular) * material_ao + ssgi_indirect
//             + ssgi_indirect_far
// (ssgi_specular: the share of the specular lobe about the reflection open
// to the sky, ssgi_bitmask.frag; the kernel methods write their AO there.)
// Background pixels show the sky, alpha 0. Without HAS_SKY (sky intensity
// 0) the sky term is left out: what it would add is exactly 0. With
// HAS_ENVIRONMENT the environment map's tables stand in for the sky's
// (environment.glsl), and the background is the map (or 0 with
// --no-environment-background). An unlit pixel (KHR_materials_unlit:
// material A = 1) shows its base colour alone, untouched by lights,
// shadows, sky, SSGI and emission. A fullscreen pass's body:
// fullscreen_entry.frag or .comp runs it per pixel.
#include "shared_layout.h"
#include "sampling.glsl"
#include "brdf.glsl"
#include "surface.glsl"
#include "ambient.glsl"
#ifdef HAS_CLEARCOAT_LOBE
#include "lobe_clearcoat_ambient.glsl"
#endif

layout(binding = kUnitDirect) uniform sampler2D directTexture;
#ifdef HAS_SSGI
layout(binding = kUnitSsgi) uniform sampler2D ssgiTexture;
layout(binding = kUnitSsgiSky) uniform sampler2D ssgiSkyTexture;
layout(binding = kUnitSsgiSpecular) uniform sampler2D ssgiSpecularTexture;
#endif

struct PassOutputs {
  vec4 radiance;
};

vec4 shadeRadiance(ivec2 pixel) {
  const vec4 worldPosition = texelFetch(gbufferPosition, pixel, 0);
  if (worldPosition.a == 0.0) {
    // Background: the sky seen through this pixel's centre (roughness-0 row
    // = the sky itself), coverage 0.
    const vec4 clip = vec4(((vec2(pixel) + 0.5) * frame.viewport.zw) * 2.0 - 1.0, 1.0, 1.0);
    const vec4 viewFar = inverse(frame.projection) * clip;
    const vec3 rayView = frame.cameraPosition.w > 0.5 ? vec3(0.0, 0.0, -1.0) : viewFar.xyz / viewFar.w;
    const vec3 rayWorld = normalize(transpose(mat3(frame.view)) * rayView);
#if defined(HAS_ENVIRONMENT)
    // The map at full resolution, not its 128 x 64 roughness-0 layer.
    return vec4(lighting.environmentBackground != 0 ? environmentRadiance(rayWorld) * lighting.skyIntensity
                                                    : vec3(0.0), 0.0);
#elif defined(HAS_SKY)
    return vec4(prefilteredSky(rayWorld, 0.0) * lighting.skyIntensity, 0.0);
#else
    return vec4(0.0);
#endif
  }
  const vec4 material = texelFetch(gbufferMaterial, pixel, 0);
  if (material.a > 0.5) return vec4(texelFetch(gbufferAlbedo, pixel, 0).rgb, 1.0);
  const Surface surface = surfaceAt(pixel, worldPosition.xyz);
#ifdef HAS_SSGI
  const vec4 sky = texelFetch(ssgiSkyTexture, pixel, 0);
  // Light gathered within R and beyond it (the kernel methods: none beyond).
  const vec3 indirect = texelFetch(ssgiTexture, pixel, 0).gba + sky.gba;
  const float skyVisibility = sky.r;
  const vec2 specular = texelFetch(ssgiSpecularTexture, pixel, 0).rb;  // visibility, bend
  const float specularVisibility = specular.x, specularBend = specular.y;
#else
  const vec3 indirect = vec3(0.0);
  const float skyVisibility = 1.0;
  const float specularVisibility = 1.0, specularBend = 0.0;
#endif
  const float materialOcclusion = material.z;
#ifdef HAS_SKY
  vec3 ambient = ambientLight(surface, materialOcclusion, skyVisibility, specularVisibility, specularBend, indirect);
#else
  vec3 ambient = indirect;
#endif
#ifdef HAS_CLEARCOAT_LOBE
  // The coat over the base's ambient and SSGI light, with its own reflection
  // (the direct pass layered the lights and emission). Occluded by the
  // diffuse sky visibility, not the specular one: the SSGI estimates the
  // base's lobe (its roughness, its normal), and a glossy coat over a rough
  // base reflects elsewhere (ClearCoatTest's coated column lost its
  // highlight under the base's lobe, specular_clearcoat_conformance_tests.cpp).
  const Clearcoat coat = clearcoatAt(pixel, surface.view);
  ambient = clearcoatLayer(coat, ambient, clearcoatAmbient(coat, surface.view, materialOcclusion, skyVisibility));
#endif
  return vec4(texelFetch(directTexture, pixel, 0).rgb + ambient, 1.0);
}

PassOutputs shadePixel(ivec2 pixel) { return PassOutputs(shadeRadiance(pixel)); }
