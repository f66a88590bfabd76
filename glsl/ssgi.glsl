// SSGI (lib/passes/ssgi.hpp): the seed's hemisphere method, or with
// METHOD_RADIANCE the same occlusion test gathering direct light. Every buffer is
// read with texelFetch at integer pixels: the position target is RGBA32F,
// which is not filterable, and pixel-exact reads keep the method repeatable.
// Both the G-buffer and this target are in GL's bottom-up pixel order, so no
// y flip is needed anywhere here (the seed's uv.y = 1 - uv.y came from wgpu).
// A fullscreen pass's body: fullscreen_entry.frag or .comp runs it per
// output pixel.
#include "shared_layout.h"
#include "ssgi_common.glsl"

layout(binding = kUnitGbufferPosition) uniform sampler2D gbufferPosition;
layout(binding = kUnitGbufferNormal) uniform sampler2D gbufferNormal;
layout(binding = kUnitGbufferAlbedo) uniform sampler2D gbufferAlbedo;
layout(binding = kUnitSsgiNoise) uniform sampler2D ssgiNoise;
#ifdef METHOD_RADIANCE
// The `radiance` method gathers the light occluders send, not their albedo.
layout(binding = kUnitDirectDiffuse) uniform sampler2D directDiffuse;
layout(binding = kUnitGbufferMaterial) uniform sampler2D gbufferMaterial;
#endif

// SsgiTextures' three, as every SSGI method writes them.
struct PassOutputs {
  vec4 nearField;  // AO, indirect light within R
  // This kernel sees no farther than R: its AO within R is its sky visibility.
  vec4 sky;
  // And its specular sky visibility (no lobe: the AO again), weight 1.
  vec4 specular;
};

PassOutputs shadePixel(ivec2 outputPixel) {
  // Below full resolution each output pixel shades the G-buffer pixel at
  // the centre of the block it stands for.
  const int divisor = ssgi.downsample;
  const ivec2 pixel = min(outputPixel * divisor + divisor / 2, ivec2(frame.viewport.xy) - 1);
  const vec4 worldPosition = texelFetch(gbufferPosition, pixel, 0);
  // Background: open, no indirect light.
  if (worldPosition.a == 0.0) return PassOutputs(vec4(1.0, 0.0, 0.0, 0.0), vec4(1.0, 0.0, 0.0, 0.0), vec4(1.0, 0.0, 0.0, 0.0));

  const vec3 viewPosition = (frame.view * vec4(worldPosition.xyz, 1.0)).xyz;
  // Normals are stored as unit vectors (not remapped to 0..1): no * 2 - 1.
  const vec3 viewNormal = normalize(mat3(frame.view) * texelFetch(gbufferNormal, pixel, 0).xyz);
  const vec2 rotation = texelFetch(ssgiNoise, outputPixel & 3, 0).xy;
  const mat3 tangentToView = tangentFrame(viewNormal, vec3(rotation, 0.0));

  const float radius = ssgi.radiusWorld;
  const float bias = ssgi.biasWorld;
  const int sampleCount = ssgi.sampleCount;
  float occlusion = 0.0;
  vec3 indirect = vec3(0.0);
  for (int i = 0; i < sampleCount; ++i) {
    const vec3 samplePosition = viewPosition + tangentToView * ssgi.kernel[i].xyz * radius;
    ivec2 samplePixel;
    // Off screen there is nothing to compare with: the sample counts as open.
    if (!projectToPixel(samplePosition, samplePixel)) continue;
    const vec4 occluderWorld = texelFetch(gbufferPosition, samplePixel, 0);
    if (occluderWorld.a == 0.0) continue;  // background never occludes
    const vec3 occluderView = (frame.view * vec4(occluderWorld.xyz, 1.0)).xyz;
    const vec3 occluderNormal = mat3(frame.view) * texelFetch(gbufferNormal, samplePixel, 0).xyz;
    const float sceneDepth =
        surfaceDepthAlongRay(samplePosition, occluderView, occluderNormal, frame.cameraPosition.w > 0.5, radius);
    const float rangeWeight = rangeCheck(radius, viewPosition.z, sceneDepth);
    // View space looks down -Z: a surface in front of the sample has larger z.
    if (sceneDepth >= samplePosition.z + bias) {
      occlusion += rangeWeight;
#ifdef METHOD_RADIANCE
      indirect += texelFetch(directDiffuse, samplePixel, 0).rgb * rangeWeight;
#else
      indirect += texelFetch(gbufferAlbedo, samplePixel, 0).rgb * rangeWeight;
#endif
    }
  }
  const float ambientOcclusion = clamp(1.0 - ssgi.intensity * occlusion / float(sampleCount), 0.0, 1.0);
#ifdef METHOD_RADIANCE
  // A Lambertian receiver reflects albedo / pi * integral(L cos); with
  // cosine-distributed kernel directions that is albedo * mean(L).
  indirect *= (1.0 - texelFetch(gbufferMaterial, pixel, 0).x) * texelFetch(gbufferAlbedo, pixel, 0).rgb;
#endif
  return PassOutputs(vec4(ambientOcclusion, indirect * (ssgi.indirectStrength / float(sampleCount))),
                     vec4(ambientOcclusion, 0.0, 0.0, 0.0), vec4(ambientOcclusion, 1.0, 0.0, 0.0));
}
