// Antialiasing on the GPU (lib/frame/antialias.hpp): what it does to lit,
// what it leaves alone, and how close it comes to a supersampled render.
#include <doctest/doctest.h>

#include <algorithm>
#include <string_view>

#include "diff/flip.hpp"
#include "headlight/renderer.hpp"
#include "headlight/scene_loader.hpp"
#include "support/gl.hpp"

namespace headlight {
using namespace headlight::test;

namespace {

// The mean of each factor x factor block: a render at factor times the size
// turned into a box-filtered one at the size (supersampling).
ImageF boxDown(const ImageF& image, int factor) {
  ImageF out;
  out.width = image.width / factor;
  out.height = image.height / factor;
  out.channels = image.channels;
  const int channels = image.channelCount();
  out.pixels.assign(std::size_t(out.width) * std::size_t(out.height) * std::size_t(channels), 0.0f);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x)
      for (int c = 0; c < channels; ++c) {
        double sum = 0;
        for (int j = 0; j < factor; ++j)
          for (int i = 0; i < factor; ++i) sum += image.at(x * factor + i, y * factor + j, c);
        out.pixels[(std::size_t(y) * std::size_t(out.width) + std::size_t(x)) * std::size_t(channels) +
                   std::size_t(c)] = float(sum / (factor * factor));
      }
  return out;
}

// HDR-FLIP's mean of lit against a reference lit (RGBA).
double litFlip(const ImageF& reference, const ImageF& test) {
  return flip::hdrFlip({reference.pixels.data(), reference.width, reference.height, 4},
                       {test.pixels.data(), test.width, test.height, 4})
      .mean;
}

RenderSettings sized(int width, int height, int samples) {
  RenderSettings settings;
  settings.width = width;
  settings.height = height;
  settings.antialiasSamples = samples;
  return settings;
}

bool hasPass(const Frame& frame, std::string_view name) {
  return std::any_of(frame.timings.begin(), frame.timings.end(),
                     [&](const PassTime& time) { return time.pass == name; });
}

}  // namespace

TEST_CASE("antialias: the default's lit is within half the pixel centre's FLIP of a 16-sample render") {
  // cornell at 160x120, its SSGI on (each sample reads the centre's, as in
  // the reference); FLIP at the papers' 67 pixels per degree.
  Renderer renderer(sharedContext());
  renderer.setScene(loadScene("builtin:cornell"));
  const Frame reference = renderer.render(sized(160, 120, 16));
  const Frame centre = renderer.render(sized(160, 120, 1));
  const Frame antialiased = renderer.render(sized(160, 120, RenderSettings{}.antialiasSamples));
  const double centreFlip = litFlip(reference.lit, centre.lit);
  const double antialiasedFlip = litFlip(reference.lit, antialiased.lit);
  MESSAGE("cornell 160x120 lit HDR-FLIP against 16 samples: centre " << centreFlip << ", default " << antialiasedFlip);
  CHECK(centreFlip > 0.002);  // the edges alias: there is something to remove
  CHECK(antialiasedFlip <= 0.5 * centreFlip);
  // What it costs is one entry of its own; the centre's passes keep theirs.
  CHECK(hasPass(antialiased, "antialias"));
  CHECK(!hasPass(centre, "antialias"));
  CHECK(hasPass(antialiased, "composite"));
}

TEST_CASE("antialias: the jittered samples come closer to a 4x4 supersampled render than the pixel centres") {
  // A render at 4x the size, box-filtered down: supersampling by other
  // means, so a jitter of the wrong size or sign shows. SSGI off: its
  // screen-space estimate changes with the resolution by itself.
  Renderer renderer(sharedContext());
  renderer.setScene(loadScene("builtin:cornell"));
  RenderSettings large = sized(384, 288, 1);
  large.ssgi.enabled = false;
  const ImageF reference = boxDown(renderer.render(large).lit, 4);
  RenderSettings small = sized(96, 72, 1);
  small.ssgi.enabled = false;
  const double centreFlip = litFlip(reference, renderer.render(small).lit);
  small.antialiasSamples = RenderSettings{}.antialiasSamples;
  const double antialiasedFlip = litFlip(reference, renderer.render(small).lit);
  MESSAGE("cornell 96x72, no SSGI, lit HDR-FLIP against 384x288 box-filtered: centre " << centreFlip << ", default "
                                                                                       << antialiasedFlip);
  CHECK(antialiasedFlip <= 0.5 * centreFlip);
}

TEST_CASE("antialias: every target but lit is the pixel centre's; lit's alpha becomes the coverage") {
  Renderer renderer(sharedContext());
  renderer.setScene(loadScene("builtin:spheres"));
  const Frame centre = renderer.render(sized(96, 72, 1));
  const Frame antialiased = renderer.render(sized(96, 72, 8));
  for (ImageF Frame::*member :
       {&Frame::position, &Frame::normal, &Frame::albedo, &Frame::material, &Frame::depth, &Frame::ssgi}) {
    REQUIRE(!(antialiased.*member).empty());
    CHECK((antialiased.*member).pixels == (centre.*member).pixels);
  }
  CHECK(antialiased.lit.pixels != centre.lit.pixels);
  // The centre's alpha is 0 or 1; the samples' mean is fractional on the
  // silhouettes, and exact inside and outside them.
  int fractional = 0, centreFractional = 0;
  for (int y = 0; y < 72; ++y)
    for (int x = 0; x < 96; ++x) {
      const float a = antialiased.lit.at(x, y, 3), c = centre.lit.at(x, y, 3);
      centreFractional += c > 0.0f && c < 1.0f;
      fractional += a > 0.0f && a < 1.0f;
      CHECK((a == c || (a > 0.0f && a < 1.0f)));
    }
  CHECK(centreFractional == 0);
  CHECK(fractional > 50);
}

TEST_CASE("antialias: over a transparent preview the foreground is kept apart from the sky behind the edges") {
  Renderer renderer(sharedContext());
  renderer.setScene(loadScene("builtin:spheres"));
  RenderSettings settings = sized(96, 72, 8);
  CHECK(renderer.render(settings).litForeground.empty());  // a preview over the sky needs none
  settings.previewBackground = "transparent";
  const Frame frame = renderer.render(settings);
  REQUIRE(frame.litForeground.width == 96);
  REQUIRE(frame.litForeground.channels.size() == 4);
  int edges = 0;
  for (int y = 0; y < 72; ++y)
    for (int x = 0; x < 96; ++x) {
      CAPTURE(x);
      CAPTURE(y);
      const float a = frame.lit.at(x, y, 3);
      // The same coverage (lit's A is half float, the foreground's float).
      CHECK(frame.litForeground.at(x, y, 3) == doctest::Approx(a).epsilon(1e-3).scale(1.0));
      if (a == 0.0f)
        for (int c = 0; c < 3; ++c) CHECK(frame.litForeground.at(x, y, c) == 0.0f);  // no sky at all
      if (a == 1.0f)
        for (int c = 0; c < 3; ++c)
          CHECK(frame.litForeground.at(x, y, c) == doctest::Approx(frame.lit.at(x, y, c)).epsilon(2e-3).scale(1e-3));
      if (a > 0.05f && a < 0.95f) {
        ++edges;
        // lit = foreground + (1 - a) x the sky behind: the sky's share is what the foreground leaves out.
        for (int c = 0; c < 3; ++c) CHECK(frame.lit.at(x, y, c) > frame.litForeground.at(x, y, c));
      }
    }
  CHECK(edges > 20);
}

TEST_CASE("antialias: the accumulation gives the same pixels as fragment and compute") {
  Renderer renderer(sharedContext());
  renderer.setScene(loadScene("builtin:spheres"));
  RenderSettings settings = sized(64, 48, 4);
  settings.previewBackground = "transparent";  // the foreground output too
  settings.fullscreenForm = FullscreenForm::Fragment;
  const Frame fragment = renderer.render(settings);
  settings.fullscreenForm = FullscreenForm::Compute;
  const Frame compute = renderer.render(settings);
  CHECK(fragment.lit.pixels == compute.lit.pixels);
  CHECK(fragment.litForeground.pixels == compute.litForeground.pixels);
  CHECK(!compute.litForeground.empty());
}

TEST_CASE("antialias-ssgi: each sample runs the SSGI with its own noise; ssgi.exr stays the centre's") {
  Renderer renderer(sharedContext());
  renderer.setScene(loadScene("builtin:cornell"));
  RenderSettings settings = sized(96, 72, 4);
  const Frame reused = renderer.render(settings);
  settings.antialiasSsgi = true;
  const Frame own = renderer.render(settings);
  CHECK(own.ssgi.pixels == reused.ssgi.pixels);
  CHECK(own.depth.pixels == reused.depth.pixels);
  // Interior pixels differ too: each sample's SSGI noise, not only the edges.
  int differing = 0;
  for (std::size_t i = 0; i < own.lit.pixels.size(); ++i) differing += own.lit.pixels[i] != reused.lit.pixels[i];
  CHECK(differing > int(own.lit.pixels.size() / 4));
}

}  // namespace headlight
