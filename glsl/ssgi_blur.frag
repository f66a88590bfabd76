// SSGI denoise and upsample (lib/passes/ssgi_blur.hpp): the noise of the
// raw SSGI averaged out, neighbours weighted by how alike their
// G-buffer normal and depth are to this pixel's. The raw SSGI may be at
// 1/2 or 1/4 of the resolution: then raw texel t stands for G-buffer pixel
// t * divisor + divisor / 2, as the SSGI pass shaded it.
#include "shared_layout.h"

layout(binding = kUnitGbufferPosition) uniform sampler2D gbufferPosition;
layout(binding = kUnitGbufferNormal) uniform sampler2D gbufferNormal;
layout(binding = kUnitSsgi) uniform sampler2D rawSsgi;
layout(binding = kUnitSsgiSky) uniform sampler2D rawSky;
// R = specular sky visibility, G = its weight, B = its bend (ssgi_bitmask.frag's specularOutput).
layout(binding = kUnitSsgiSpecular) uniform sampler2D rawSpecular;

layout(location = 0) out vec4 outSsgi;
layout(location = 1) out vec4 outSky;
layout(location = 2) out vec4 outSpecular;

// A 7x7 window with Gaussian weights (sigma 2 pixels): it spans about two
// of the SSGI pass's 4x4 tiles, each offset differently, so it averages
// their noise where the 4x4 box it replaced averaged one tile and showed the
// tile's pattern. Measured on builtin:cornell at 256x256 against the
// 4096-ray reference (docs/BENCHMARKS.md, "Structured artefacts").
const int kTapRadius = 3;
const float kSpatialSigma = 2.0;
const float kSpatialFalloff = 1.0 / (2.0 * kSpatialSigma * kSpatialSigma);

void main() {
  const ivec2 pixel = ivec2(gl_FragCoord.xy);
  const vec4 centerPosition = texelFetch(gbufferPosition, pixel, 0);
  if (centerPosition.a == 0.0) discard;  // background keeps the cleared value
  const vec3 centerNormal = texelFetch(gbufferNormal, pixel, 0).xyz;
  // View-space z of a world point: the view matrix's third row.
  const vec4 viewDepthRow = vec4(frame.view[0][2], frame.view[1][2], frame.view[2][2], frame.view[3][2]);
  const float centerDepth = dot(viewDepthRow, vec4(centerPosition.xyz, 1.0));
  // A quarter of the SSGI radius: neighbours on the same surface differ by
  // far less, across a silhouette by more.
  const float depthScale = 0.25 * blur.ssgiRadiusWorld;
  const ivec2 size = ivec2(frame.viewport.xy);
  const int divisor = blur.ssgiDownsample;
  const ivec2 rawSize = textureSize(rawSsgi, 0);
  const ivec2 rawCenter = min(pixel / divisor, rawSize - 1);
  vec4 sum = vec4(0.0);
  vec4 skySum = vec4(0.0);
  // Visibility and weight weighted by the blur's weight times the pixel's own
  // (its G); the bend by that times the visibility, as the pass weighs it.
  vec3 specularSum = vec3(0.0);
  float weightSum = 0.0;
  for (int dy = -kTapRadius; dy <= kTapRadius; ++dy)
    for (int dx = -kTapRadius; dx <= kTapRadius; ++dx) {
      const ivec2 rawNeighbour = clamp(rawCenter + ivec2(dx, dy), ivec2(0), rawSize - 1);
      const ivec2 neighbour = min(rawNeighbour * divisor + divisor / 2, size - 1);
      const vec4 position = texelFetch(gbufferPosition, neighbour, 0);
      if (position.a == 0.0) continue;
      const float depth = dot(viewDepthRow, vec4(position.xyz, 1.0));
      // cos^8 by three squarings (llvmpipe's pow is an exp and a log).
      float normalWeight = max(dot(centerNormal, texelFetch(gbufferNormal, neighbour, 0).xyz), 0.0);
      normalWeight *= normalWeight;
      normalWeight *= normalWeight;
      normalWeight *= normalWeight;
      // One exp for the depth and the Gaussian's distance together.
      const float weight = normalWeight * exp(-abs(depth - centerDepth) / depthScale -
                                              float(dx * dx + dy * dy) * kSpatialFalloff);
      sum += texelFetch(rawSsgi, rawNeighbour, 0) * weight;
      skySum += texelFetch(rawSky, rawNeighbour, 0) * weight;
      // The specular visibility over the inner 5x5 only (84 % of the
      // Gaussian's weight): a fetch fewer on 24 of the 49 taps.
      if (abs(dx) < kTapRadius && abs(dy) < kTapRadius) {
        const vec3 specular = texelFetch(rawSpecular, rawNeighbour, 0).rgb;
        specularSum += vec3(specular.r, 1.0, specular.r * specular.b) * (specular.g * weight);
      }
      weightSum += weight;
    }
  // At full resolution the centre has weight 1. Below it, a pixel on a
  // surface no raw texel nearby sampled (a thin strut) takes the nearest.
  const bool weighed = weightSum > 1e-4;
  outSsgi = weighed ? sum / weightSum : texelFetch(rawSsgi, rawCenter, 0);
  outSky = weighed ? skySum / weightSum : texelFetch(rawSky, rawCenter, 0);
  // Where no neighbour's slices saw the lobe, the sky visibility stands in.
  outSpecular = specularSum.y > 1e-4 ? vec4(specularSum.x / specularSum.y, specularSum.y / max(weightSum, 1e-4),
                                            specularSum.x > 1e-6 ? specularSum.z / specularSum.x : 0.0, 0.0)
                                     : vec4(outSky.r, 0.0, 0.0, 0.0);
}
