// One antialias sample of lit into lit.accumulation (lib/frame/antialias.hpp),
// and where the preview is shown over a colour or transparent its
// foreground, RGB x A and A, into lit.foreground: the fullscreen entry's
// accumulated-frames blend (ACCUMULATE_OUTPUTS, weight 1 / (sample + 1))
// keeps each running mean.
#include "shared_layout.h"

layout(binding = kUnitLit) uniform sampler2D litSample;

struct PassOutputs {
  vec4 lit;
  vec4 foreground;  // premultiplied: no sky where the sample saw none of the geometry
};

PassOutputs shadePixel(ivec2 pixel) {
  PassOutputs outputs;
  outputs.lit = texelFetch(litSample, pixel, 0);
  outputs.foreground = vec4(outputs.lit.rgb * outputs.lit.a, outputs.lit.a);
  return outputs;
}
