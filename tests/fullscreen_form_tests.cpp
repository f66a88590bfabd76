// The two forms of every fullscreen pass (lib/passes/fullscreen.hpp): the
// same body under a fragment entry and a compute entry must give the same
// pixels. Each case renders one configuration in both forms (on llvmpipe in
// CI: compute shaders run there) and compares every target the pass feeds, and
// checks that each fullscreen pass ran in the form asked for and says so.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "frame/frame_plan.hpp"
#include "headlight/frame.hpp"
#include "headlight/scene_loader.hpp"
#include "headlight/settings.hpp"
#include "support/gl.hpp"

namespace headlight {
namespace {

// The largest difference between two images of one layout, relative to the
// larger magnitude where that is above 1.
double largestDifference(const ImageF& a, const ImageF& b) {
  REQUIRE(a.width == b.width);
  REQUIRE(a.height == b.height);
  REQUIRE(a.channels == b.channels);
  double largest = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) {
    const double scale = std::max({1.0, std::abs(double(a.pixels[i])), std::abs(double(b.pixels[i]))});
    largest = std::max(largest, std::abs(double(a.pixels[i]) - double(b.pixels[i])) / scale);
  }
  return largest;
}

// Every fullscreen pass of `frame` says it ran as `form`; returns how many did.
int checkForms(const Frame& frame, PassForm form) {
  int fullscreen = 0;
  for (const PassTime& time : frame.timings) {
    const bool isFullscreen = std::any_of(fullscreenPassRows().begin(), fullscreenPassRows().end(),
                                          [&](const FullscreenPassRow& row) { return row.name == time.pass; }) ||
                              time.pass == "brdf-table";
    CAPTURE(time.pass);
    if (isFullscreen) {
      CHECK(time.form == passFormName(form));
      // Timed by a GL_TIME_ELAPSED query too: known, and within the wall time around it.
      CHECK(time.gpuMilliseconds >= 0.0);
      ++fullscreen;
    } else {
      CHECK(time.form.empty());
    }
    CHECK(time.gpuMilliseconds <= time.milliseconds * 1.5 + 1.0);
  }
  return fullscreen;
}

// 1e-3: both forms store the same shader arithmetic into the same formats;
// llvmpipe may contract a multiply-add differently in the two stages (a half
// float's step is 1e-3 relative), nothing more.
constexpr double kTolerance = 1e-3;

void compareForms(const std::string& sceneName, RenderSettings settings, int expectedFullscreenPasses) {
  const Scene scene = makeBuiltinScene(sceneName);
  settings.fullscreenForm = FullscreenForm::Fragment;
  const Frame fragment = test::renderFresh(scene, settings);
  settings.fullscreenForm = FullscreenForm::Compute;
  const Frame compute = test::renderFresh(scene, settings);
  CHECK(checkForms(fragment, PassForm::Fragment) == expectedFullscreenPasses);
  CHECK(checkForms(compute, PassForm::Compute) == expectedFullscreenPasses);
  double largest = 0;
  for (const FrameTarget& target : frameTargets()) {
    if (target.image == nullptr) continue;
    const ImageF& a = fragment.*target.image;
    const ImageF& b = compute.*target.image;
    if (a.empty() && b.empty()) continue;
    CAPTURE(target.name);
    const double difference = largestDifference(a, b);
    CHECK(difference <= kTolerance);
    largest = std::max(largest, difference);
  }
  MESSAGE(sceneName << ": largest fragment/compute difference over every target " << largest);
}

}  // namespace

TEST_CASE("forms: direct light, composite and the sky tables give the same pixels as fragment and compute") {
  RenderSettings settings = test::smallSettings(80, 64);
  settings.ssgi.enabled = false;
  // brdf-table, direct, sky, composite
  compareForms("cornell", settings, 4);
  compareForms("spheres", settings, 4);
}

TEST_CASE("forms: each SSGI method's own pass gives the same pixels in both forms") {
  for (SsgiMethod method : {SsgiMethod::Hemisphere, SsgiMethod::Radiance, SsgiMethod::Bitmask}) {
    CAPTURE(ssgiMethodName(method));
    RenderSettings settings = test::smallSettings(80, 64);
    settings.ssgi.method = method;
    settings.ssgi.blur = false;  // the pass writes ssgi.exr itself
    // brdf-table, direct, sky, ssgi, composite; the bitmask's packed surface too (ssgi-surface)
    compareForms("cornell", settings, method == SsgiMethod::Bitmask ? 6 : 5);
  }
}

TEST_CASE("forms: the blur, its far-field lines and the upsample give the same pixels in both forms") {
  RenderSettings settings = test::smallSettings(96, 72);
  settings.ssgi.resolution = SsgiResolution::Half;
  settings.ssgi.farResolution = SsgiResolution::Quarter;  // the far field's own pass and its row/column lines
  compareForms("spheres", settings, 7);  // brdf-table, direct, sky, ssgi-surface, ssgi, ssgi-blur, composite
}

TEST_CASE("forms: accumulated SSGI frames blend in the entry alike in both forms") {
  RenderSettings settings = test::smallSettings(64, 48);
  settings.ssgi.frames = 4;
  compareForms("cornell", settings, 7);
  // And the accumulation is a mean: four frames differ from one.
  const Scene scene = makeBuiltinScene("cornell");
  settings.fullscreenForm = FullscreenForm::Compute;
  const Frame four = test::renderFresh(scene, settings);
  settings.ssgi.frames = 1;
  const Frame one = test::renderFresh(scene, settings);
  CHECK(largestDifference(four.ssgi, one.ssgi) > 1e-3);
}

TEST_CASE("forms: auto runs each pass in its row's form on llvmpipe, and names the form") {
  const Scene scene = makeBuiltinScene("cornell");
  const Frame frame = test::renderFresh(scene, test::smallSettings(64, 48));
  // Whatever this machine is: on llvmpipe (CI) each row's measured form, on a GPU compute.
  const bool software = isSoftwareRasterizer(frame.glRenderer);
  const PassForms forms = choosePassForms(std::nullopt, software);
  int checked = 0;
  for (const PassTime& time : frame.timings)
    for (std::size_t index = 0; index < fullscreenPassRows().size(); ++index)
      if (const FullscreenPassRow& row = fullscreenPassRows()[index]; row.name == time.pass) {
        CAPTURE(time.pass);
        CHECK(time.form == passFormName(forms[index]));
        CHECK(forms[index] == (software ? row.softwareForm : PassForm::Compute));
        ++checked;
      }
  CHECK(checked >= 4);  // direct, ssgi, ssgi-blur, composite (and sky on a first frame)
  // On a hardware GPU auto is compute for every pass; asked for, a form is that form.
  for (PassForm form : choosePassForms(std::nullopt, false)) CHECK(form == PassForm::Compute);
  for (PassForm form : choosePassForms(FullscreenForm::Fragment, false)) CHECK(form == PassForm::Fragment);
  CHECK(isSoftwareRasterizer("llvmpipe (LLVM 15.0.6, 256 bits)"));
  CHECK(!isSoftwareRasterizer("NVIDIA H200/PCIe/SSE2"));
}

}  // namespace headlight
