// SSGI denoise and upsample (lib/passes/ssgi_blur.hpp): the noise of the
// raw SSGI averaged out, neighbours weighted by how alike their
// G-buffer normal and depth are to this pixel's. The raw SSGI may be at
// 1/2 or 1/4 of the resolution: then raw texel t stands for G-buffer pixel
// t * divisor + divisor / 2, as the SSGI pass shaded it. The raw sky may have
// its own divisor (the bitmask method's far-field pass): it is blurred at
// its own resolution first (skyOnly, the output at that divisor: a line of
// texels along rows, then one along columns), then upsampled here from a
// 3x3 window. A fullscreen pass's body: fullscreen_entry.frag or .comp runs
// it per output pixel (lib/passes/ssgi_blur.cpp names the members it writes).
#include "shared_layout.h"

layout(binding = kUnitGbufferPosition) uniform sampler2D gbufferPosition;
layout(binding = kUnitGbufferNormal) uniform sampler2D gbufferNormal;
layout(binding = kUnitSsgi) uniform sampler2D rawSsgi;
layout(binding = kUnitSsgiSky) uniform sampler2D rawSky;
// R = specular sky visibility, G = its weight, B = its bend (ssgi_bitmask.frag's specularOutput),
// on the raw sky's grid (the far field's pass writes it).
layout(binding = kUnitSsgiSpecular) uniform sampler2D rawSpecular;

struct PassOutputs {
  vec4 nearField;  // the AO and light within R (SsgiTextures::occlusion)
  vec4 sky;
  vec4 specular;
  vec4 skyLine;       // skyOnly: the raw sky blurred along one axis at its own resolution
  vec4 specularLine;  // skyOnly: the raw specular so blurred, its three channels as the raw ones
};

// A 7x7 window with Gaussian weights (sigma 2 pixels): it spans about two
// of the SSGI pass's 4x4 tiles, each offset differently, so it averages
// their noise where the 4x4 box it replaced averaged one tile and showed the
// tile's pattern. Measured on builtin:cornell at 256x256 against the
// 4096-ray reference (docs/BENCHMARKS.md, "Structured artefacts").
// A window of radius r has sigma 2r/3 texels: 2 for the 7x7, 2/3 for the
// 3x3 upsample of a sky already blurred at its own resolution. The radii
// are lib/passes/ssgi_blur.cpp's.
const int kTapRadius = 3;
// The far field's line blur takes the specular visibility over 3 of its
// texels, not the sky's 15: a wider window smeared a mirror's reflected
// occluders across it (the reference's specular.Y on builtin:spheres, RMSE
// 0.095 / 0.100 / 0.107 at radius 1 / 2 / 3) for less grain (0.041 / 0.043
// / 0.055 on the mirror row, with the lobe no narrower than two sectors).
const int kSpecularLineRadius = 1;

// View-space z of a world point: the view matrix's third row.
float viewDepth(vec3 world) {
  return dot(vec4(frame.view[0][2], frame.view[1][2], frame.view[2][2], frame.view[3][2]), vec4(world, 1.0));
}

// The specular visibility, weight and bend (specularOutput's channels) of a
// window's sum from filterWindow with `weightSum` the window's weights, or
// `fallback` where no tap's slices saw the lobe.
vec4 specularMean(vec4 specularSum, float weightSum, vec4 fallback) {
  return specularSum.y > 1e-4 ? vec4(specularSum.x / specularSum.y, specularSum.y / max(weightSum, 1e-4),
                                     specularSum.x > 1e-6 ? specularSum.z / specularSum.x : 0.0, 0.0)
                              : fallback;
}

// The pixel the weights are judged against.
struct Centre {
  ivec2 pixel;
  vec3 normal;
  float depth;
};

// A window of raw texels (`radius` either side of `rawCentre` along x and y, raw texel u
// standing for G-buffer pixel u * divisor + divisor / 2), weighted by the
// Gaussian of its offset from `centreOnRaw` (raw texels) and by how alike
// its normal and depth are to the centre's; `second` is summed with the same
// weights when `withSecond`, and the specular visibility (on `first`'s grid)
// of the taps within `specularRadius` (-1: none) into `specularSum`:
// visibility and weight weighted by the blur's weight times the texel's own
// (its G), the bend by that times the visibility, as the pass weighs them,
// and in w the blur's weights of those taps.
void filterWindow(sampler2D first, sampler2D second, bool withSecond, int specularRadius, int divisor, ivec2 radius,
                  ivec2 rawCentre, vec2 centreOnRaw, Centre centre, inout vec4 sum, inout vec4 secondSum,
                  inout vec4 specularSum, inout float weightSum) {
  // A quarter of the SSGI radius: neighbours on the same surface differ by
  // far less, across a silhouette by more.
  const float depthScale = 0.25 * blur.ssgiRadiusWorld;
  const float sigma = 2.0 * float(max(radius.x, radius.y)) / 3.0;
  const float spatialFalloff = 1.0 / (2.0 * sigma * sigma);
  const ivec2 size = ivec2(frame.viewport.xy);
  const ivec2 rawSize = textureSize(first, 0);
  for (int dy = -radius.y; dy <= radius.y; ++dy)
    for (int dx = -radius.x; dx <= radius.x; ++dx) {
      const ivec2 rawNeighbour = clamp(rawCentre + ivec2(dx, dy), ivec2(0), rawSize - 1);
      const ivec2 neighbour = min(rawNeighbour * divisor + divisor / 2, size - 1);
      const vec4 position = texelFetch(gbufferPosition, neighbour, 0);
      if (position.a == 0.0) continue;
      // cos^8 by three squarings (llvmpipe's pow is an exp and a log).
      float normalWeight = max(dot(centre.normal, texelFetch(gbufferNormal, neighbour, 0).xyz), 0.0);
      normalWeight *= normalWeight;
      normalWeight *= normalWeight;
      normalWeight *= normalWeight;
      // One exp for the depth and the Gaussian's distance together.
      const vec2 offset = vec2(rawCentre + ivec2(dx, dy)) - centreOnRaw;
      const float weight = normalWeight * exp(-abs(viewDepth(position.xyz) - centre.depth) / depthScale -
                                              dot(offset, offset) * spatialFalloff);
      sum += texelFetch(first, rawNeighbour, 0) * weight;
      if (withSecond) secondSum += texelFetch(second, rawNeighbour, 0) * weight;
      if (abs(dx) <= specularRadius && abs(dy) <= specularRadius) {
        const vec3 specular = texelFetch(rawSpecular, rawNeighbour, 0).rgb;
        specularSum += vec4(vec3(specular.r, 1.0, specular.r * specular.b) * (specular.g * weight), weight);
      }
      weightSum += weight;
    }
}

PassOutputs shadePixel(ivec2 outputPixel) {
  // The G-buffer pixel this output texel stands for.
  const int outputDivisor = blur.outputDownsample;
  const ivec2 size = ivec2(frame.viewport.xy);
  const ivec2 pixel = min(outputPixel * outputDivisor + outputDivisor / 2, size - 1);
  const vec4 centrePosition = texelFetch(gbufferPosition, pixel, 0);
  PassOutputs o;
  if (centrePosition.a == 0.0) {  // background: open, no light, as the SSGI pass leaves it
    o.nearField = o.sky = o.specular = o.skyLine = o.specularLine = vec4(1.0, 0.0, 0.0, 0.0);
    return o;
  }
  const Centre centre = Centre(pixel, texelFetch(gbufferNormal, pixel, 0).xyz, viewDepth(centrePosition.xyz));
  const int skyDivisor = blur.skyDownsample;
  const ivec2 rawSkyCentre = min(pixel / skyDivisor, textureSize(rawSky, 0) - 1);
  vec4 skySum = vec4(0.0), unused = vec4(0.0);
  vec4 specularSum = vec4(0.0), noSpecular = vec4(0.0);  // noSpecular: a window's specular not wanted
  float skyWeightSum = 0.0;
  if (blur.skyOnly != 0) {
    const ivec2 axis = ivec2(blur.skyAxisX, blur.skyAxisY);
    const ivec2 radius = blur.skyTapRadius * (axis == ivec2(0) ? ivec2(1) : axis);
    vec4 specularLineSum = vec4(0.0);
    filterWindow(rawSky, rawSky, false, kSpecularLineRadius, skyDivisor, radius, rawSkyCentre, vec2(rawSkyCentre),
                 centre, skySum, unused, specularLineSum, skyWeightSum);
    o.skyLine = skyWeightSum > 1e-4 ? skySum / skyWeightSum : texelFetch(rawSky, rawSkyCentre, 0);
    o.specularLine = specularMean(specularLineSum, specularLineSum.w, texelFetch(rawSpecular, rawSkyCentre, 0));
    return o;
  }
  const int divisor = blur.ssgiDownsample;
  const ivec2 rawCentre = min(pixel / divisor, textureSize(rawSsgi, 0) - 1);
  vec4 sum = vec4(0.0);
  float weightSum = 0.0;
  if (skyDivisor == divisor) {
    // One grid: the sky takes the same weights, and the specular over the
    // inner 5x5 of the 7x7 (84 % of the Gaussian's weight, a fetch fewer on
    // 24 of the 49 taps).
    filterWindow(rawSsgi, rawSky, true, kTapRadius - 1, divisor, ivec2(kTapRadius), rawCentre, vec2(rawCentre),
                 centre, sum, skySum, specularSum, weightSum);
    skyWeightSum = weightSum;
  } else {
    filterWindow(rawSsgi, rawSsgi, false, -1, divisor, ivec2(kTapRadius), rawCentre, vec2(rawCentre), centre, sum,
                 unused, noSpecular, weightSum);
    // The pixel's own place on the sky's grid (texel u stands for pixel
    // u * d + d / 2), so that the upsample is not shifted toward one texel.
    const vec2 centreOnSky = vec2(pixel - skyDivisor / 2) / float(skyDivisor);
    // The specular on the sky's grid, over the whole upsample window.
    filterWindow(rawSky, rawSky, false, blur.skyTapRadius, skyDivisor, ivec2(blur.skyTapRadius), rawSkyCentre,
                 centreOnSky, centre, skySum, unused, specularSum, skyWeightSum);
  }
  // At full resolution the centre has weight 1. Below it, a pixel on a
  // surface no raw texel nearby sampled (a thin strut) takes the nearest.
  o.nearField = weightSum > 1e-4 ? sum / weightSum : texelFetch(rawSsgi, rawCentre, 0);
  o.sky = skyWeightSum > 1e-4 ? skySum / skyWeightSum : texelFetch(rawSky, rawSkyCentre, 0);
  // A coarser sky holds the sky visibility over the AO within R (ssgi_bitmask.glsl): times this pixel's AO.
  if (skyDivisor != divisor) o.sky.x *= o.nearField.x;
  // Where no neighbour's slices saw the lobe, the sky visibility stands in.
  const float specularWeights = skyDivisor == divisor ? weightSum : skyWeightSum;
  o.specular = specularMean(specularSum, specularWeights, vec4(o.sky.r, 0.0, 0.0, 0.0));
  o.skyLine = o.sky;
  return o;
}
