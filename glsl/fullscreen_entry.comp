// The compute form of a fullscreen pass (lib/passes/fullscreen.hpp): one
// invocation per output pixel in kPassGroupSize-square groups, the pixels
// past the outputs' size skipped, and each writes what the pass's body,
// `PassOutputs shadePixel(ivec2 pixel)`, returns with imageStore. The
// program is the body followed by this file; the loader defines
// PASS_OUTPUT_COUNT (1..4), PASS_OUTPUTk (the PassOutputs member written to
// image unit kImagePassOutputk), PASS_OUTPUTk_FORMAT (the image's format
// qualifier: the output texture's, so half and float radiance both store
// exactly) and, for accumulated frames, ACCUMULATE_OUTPUTS: each output then
// blends into what the previous dispatch left in its image.
layout(local_size_x = kPassGroupSize, local_size_y = kPassGroupSize) in;

#ifdef ACCUMULATE_OUTPUTS
layout(location = kLocationAccumulateWeight) uniform float accumulateWeight;
// Weight 0 overwrites (the first frame); w blends as (1 - w) previous + w value.
#define PASS_RESULT(previous, value) (accumulateWeight > 0.0 ? mix(previous, value, accumulateWeight) : (value))
#define PASS_IMAGE_ACCESS
#else
#define PASS_RESULT(previous, value) (value)
#define PASS_IMAGE_ACCESS writeonly
#endif

#if PASS_OUTPUT_COUNT > 0
layout(binding = kImagePassOutput0, PASS_OUTPUT0_FORMAT) uniform PASS_IMAGE_ACCESS image2D passOutput0;
#endif
#if PASS_OUTPUT_COUNT > 1
layout(binding = kImagePassOutput1, PASS_OUTPUT1_FORMAT) uniform PASS_IMAGE_ACCESS image2D passOutput1;
#endif
#if PASS_OUTPUT_COUNT > 2
layout(binding = kImagePassOutput2, PASS_OUTPUT2_FORMAT) uniform PASS_IMAGE_ACCESS image2D passOutput2;
#endif
#if PASS_OUTPUT_COUNT > 3
layout(binding = kImagePassOutput3, PASS_OUTPUT3_FORMAT) uniform PASS_IMAGE_ACCESS image2D passOutput3;
#endif

void main() {
  const ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  // Every output has the first one's size (FullscreenDraw checks).
  if (any(greaterThanEqual(pixel, imageSize(passOutput0)))) return;
  const PassOutputs shaded = shadePixel(pixel);
#if PASS_OUTPUT_COUNT > 0
  imageStore(passOutput0, pixel, PASS_RESULT(imageLoad(passOutput0, pixel), vec4(shaded.PASS_OUTPUT0)));
#endif
#if PASS_OUTPUT_COUNT > 1
  imageStore(passOutput1, pixel, PASS_RESULT(imageLoad(passOutput1, pixel), vec4(shaded.PASS_OUTPUT1)));
#endif
#if PASS_OUTPUT_COUNT > 2
  imageStore(passOutput2, pixel, PASS_RESULT(imageLoad(passOutput2, pixel), vec4(shaded.PASS_OUTPUT2)));
#endif
#if PASS_OUTPUT_COUNT > 3
  imageStore(passOutput3, pixel, PASS_RESULT(imageLoad(passOutput3, pixel), vec4(shaded.PASS_OUTPUT3)));
#endif
}
