// The surface the bitmask SSGI's marches sample, packed so that a step is one
// fetch: the depth buffer's value and the view-space normal, which each march
// step otherwise fetched from two textures and turned into view space itself
// (ssgi_bitmask.glsl, marchPoint). float32: the depth must stay the depth
// buffer's exact value (the marches linearise it), and the normal the
// product the marches computed. A fullscreen pass's body with no GL code of
// its own (its row: lib/frame/frame_plan.cpp).
#include "shared_layout.h"

layout(binding = kUnitGbufferDepth) uniform sampler2D gbufferDepth;
layout(binding = kUnitGbufferNormal) uniform sampler2D gbufferNormal;

struct PassOutputs {
  vec4 surface;  // R = the depth buffer's value (1 on background), GBA = the view-space normal as stored
};

PassOutputs shadePixel(ivec2 pixel) {
  PassOutputs outputs;
  outputs.surface =
      vec4(texelFetch(gbufferDepth, pixel, 0).r, mat3(frame.view) * texelFetch(gbufferNormal, pixel, 0).xyz);
  return outputs;
}
