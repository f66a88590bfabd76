// The fragment form of a fullscreen pass (lib/passes/fullscreen.hpp): one
// triangle (fullscreen.vert) covers the outputs, and each fragment writes
// what the pass's body, `PassOutputs shadePixel(ivec2 pixel)`, returns for
// its pixel. The program is the body followed by this file; the loader
// defines PASS_OUTPUT_COUNT (1..4), PASS_OUTPUTk (the PassOutputs member
// written to colour attachment k) and, for accumulated frames,
// ACCUMULATE_OUTPUTS: each output then blends into what the previous frame
// left, read from its own texture (glTextureBarrier between the draws makes
// that read defined: every fragment reads only its own texel).
#ifdef ACCUMULATE_OUTPUTS
layout(location = kLocationAccumulateWeight) uniform float accumulateWeight;
// Weight 0 overwrites (the first frame); w blends as (1 - w) previous + w value.
#define PASS_RESULT(previous, value) (accumulateWeight > 0.0 ? mix(previous, value, accumulateWeight) : (value))
#else
#define PASS_RESULT(previous, value) (value)
#endif

#if PASS_OUTPUT_COUNT > 0
layout(location = 0) out vec4 passOutput0;
#ifdef ACCUMULATE_OUTPUTS
layout(binding = kUnitPassAccumulated0) uniform sampler2D passAccumulated0;
#endif
#endif
#if PASS_OUTPUT_COUNT > 1
layout(location = 1) out vec4 passOutput1;
#ifdef ACCUMULATE_OUTPUTS
layout(binding = kUnitPassAccumulated1) uniform sampler2D passAccumulated1;
#endif
#endif
#if PASS_OUTPUT_COUNT > 2
layout(location = 2) out vec4 passOutput2;
#ifdef ACCUMULATE_OUTPUTS
layout(binding = kUnitPassAccumulated2) uniform sampler2D passAccumulated2;
#endif
#endif
#if PASS_OUTPUT_COUNT > 3
layout(location = 3) out vec4 passOutput3;
#ifdef ACCUMULATE_OUTPUTS
layout(binding = kUnitPassAccumulated3) uniform sampler2D passAccumulated3;
#endif
#endif

void main() {
  const ivec2 pixel = ivec2(gl_FragCoord.xy);
  const PassOutputs shaded = shadePixel(pixel);
#if PASS_OUTPUT_COUNT > 0
  passOutput0 = PASS_RESULT(texelFetch(passAccumulated0, pixel, 0), vec4(shaded.PASS_OUTPUT0));
#endif
#if PASS_OUTPUT_COUNT > 1
  passOutput1 = PASS_RESULT(texelFetch(passAccumulated1, pixel, 0), vec4(shaded.PASS_OUTPUT1));
#endif
#if PASS_OUTPUT_COUNT > 2
  passOutput2 = PASS_RESULT(texelFetch(passAccumulated2, pixel, 0), vec4(shaded.PASS_OUTPUT2));
#endif
#if PASS_OUTPUT_COUNT > 3
  passOutput3 = PASS_RESULT(texelFetch(passAccumulated3, pixel, 0), vec4(shaded.PASS_OUTPUT3));
#endif
}
