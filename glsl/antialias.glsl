// One antialias sample of lit into lit.accumulation (lib/frame/antialias.hpp):
// the fullscreen entry's accumulated-frames blend (ACCUMULATE_OUTPUTS, weight
// 1 / (sample + 1)) keeps the running mean.
#include "shared_layout.h"

layout(binding = kUnitLit) uniform sampler2D litSample;

struct PassOutputs {
  vec4 lit;
};

PassOutputs shadePixel(ivec2 pixel) {
  PassOutputs outputs;
  outputs.lit = texelFetch(litSample, pixel, 0);
  return outputs;
}
