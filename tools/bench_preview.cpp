// A one-off measurement for docs/BENCHMARKS.md ("Preview PNG"): the preview
// as it was written before the one-pass tonemap (per-pixel push_back, an
// ImageBuf, OpenImageIO's colorconvert, ImageBuf::write), copied here, against
// writePreview. Not part of the build; from build/, after ninja:
//   g++ -O2 -std=c++20 -I../lib/include -I../lib ../tools/bench_preview.cpp -o bench_preview \
//     -Wl,--start-group libheadlight.a subprojects/glad/libglad.a -lOpenImageIO -lOpenImageIO_Util -lEGL \
//     -lOSMesa -ltinygltf /usr/lib/x86_64-linux-gnu/libembree3.so.3 -Wl,--end-group && ./bench_preview
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <vector>
#include "headlight/output.hpp"
#include "output/tonemap.hpp"
using namespace headlight;
static double ms(std::chrono::steady_clock::time_point a) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - a).count();
}
int main() {
  Frame frame;
  frame.lit.width = 1024;
  frame.lit.height = 1024;
  frame.lit.channels = {"R", "G", "B", "A"};
  frame.lit.pixels.resize(1024 * 1024 * 4);
  for (std::size_t i = 0; i < frame.lit.pixels.size(); ++i)
    frame.lit.pixels[i] = float((i * 2654435761u) % 1000) / 300.0f;
  std::vector<double> oldT, newT, oldEnc, newEnc;
  for (int r = 0; r < 7; ++r) {
    auto t = std::chrono::steady_clock::now();
    // the old writePreview's body, up to and including the write
    const ImageF& lit = frame.lit;
    const float scale = 1.0f;
    ImageF display;
    display.width = lit.width;
    display.height = lit.height;
    display.channels = {"R", "G", "B"};
    display.pixels.reserve(std::size_t(lit.width) * lit.height * 3);
    for (std::size_t p = 0; p < lit.pixels.size(); p += 4)
      for (int c = 0; c < 3; ++c) display.pixels.push_back(tonemapAces(std::max(0.0f, lit.pixels[p + c] * scale)));
    OIIO::ImageSpec spec(display.width, display.height, 3, OIIO::TypeDesc::FLOAT);
    spec.channelnames = display.channels;
    OIIO::ImageBuf linear(spec);
    linear.set_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, display.pixels.data());
    OIIO::ImageBuf encoded = OIIO::ImageBufAlgo::colorconvert(linear, "linear", "sRGB");
    oldEnc.push_back(ms(t));
    OIIO::ImageSpec out = encoded.spec();
    out.set_format(OIIO::TypeDesc::UINT8);
    encoded.write("/tmp/headlight_bench_preview_old.png", OIIO::TypeDesc::UINT8);
    oldT.push_back(ms(t));
    t = std::chrono::steady_clock::now();
    writePreview(frame, "/tmp/headlight_bench_preview_new.png");
    newT.push_back(ms(t));
  }
  std::sort(oldT.begin(), oldT.end());
  std::sort(newT.begin(), newT.end());
  std::sort(oldEnc.begin(), oldEnc.end());
  std::printf(
      "1024x1024 preview, median of 7: old %.1f ms (tonemap+colorconvert %.1f ms), new %.1f ms (incl. PNG write)\n",
      oldT[3], oldEnc[3], newT[3]);
  OIIO::ImageBuf a("/tmp/headlight_bench_preview_old.png"), b("/tmp/headlight_bench_preview_new.png");
  auto cmp = OIIO::ImageBufAlgo::compare(a, b, 1.5f / 255, 1.5f / 255);
  std::printf("old vs new PNG: max difference %.0f/255, %lld pixels over 1/255\n", cmp.maxerror * 255,
              (long long)cmp.nfail);
}
