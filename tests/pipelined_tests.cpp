// Pipelined rendering (Renderer::submit / collect): frame N+1's passes are
// queued before frame N's pixels are read, and every frame must still be
// exactly the frame render() gives, whatever is queued behind it.
#include <doctest/doctest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "headlight/camera.hpp"
#include "headlight/error.hpp"
#include "headlight/frame.hpp"
#include "headlight/renderer.hpp"
#include "headlight/scene_loader.hpp"
#include "headlight/targets.hpp"
#include "support/gl.hpp"

namespace headlight {
namespace {

// Every target of `a` equals `b`'s, pixel for pixel.
void checkSameTargets(const Frame& a, const Frame& b) {
  int compared = 0;
  for (const FrameTarget& target : frameTargets()) {
    if (target.image == nullptr) continue;
    CAPTURE(target.name);
    const ImageF& x = a.*target.image;
    const ImageF& y = b.*target.image;
    CHECK(x.width == y.width);
    CHECK(x.height == y.height);
    CHECK(x.channels == y.channels);
    CHECK(x.pixels == y.pixels);
    compared += !x.empty();
  }
  CHECK(compared >= 7);  // position, normal, albedo, material, depth, ssgi, lit
}

std::vector<Camera> orbit(const Scene& scene, int count) {
  std::vector<Camera> cameras;
  for (int i = 0; i < count; ++i)
    cameras.push_back(fitCamera(scene.worldBounds(), 1.0f, 0.8f, 6.2831853f * float(i) / float(count)));
  return cameras;
}

}  // namespace

TEST_CASE("pipelined: frames submitted ahead come back in order, each the frame render() gives") {
  const Scene scene = makeBuiltinScene("cornell");
  const RenderSettings settings = test::smallSettings(64, 64);
  const std::vector<Camera> cameras = orbit(scene, 3);
  Renderer renderer(test::sharedContext());
  renderer.setScene(scene);
  std::vector<Frame> expected;
  for (const Camera& camera : cameras) expected.push_back(renderer.render(settings, &camera));

  // Two in flight: N+1 is queued before N is collected.
  renderer.submit(settings, &cameras[0]);
  renderer.submit(settings, &cameras[1]);
  CHECK(renderer.submitted() == 2);
  CHECK_THROWS_WITH_AS(renderer.submit(settings, &cameras[2]),
                       "Renderer::submit: 2 frames are submitted and not collected (at most 2): collect() first",
                       SettingsError);
  const Frame first = renderer.collect();
  renderer.submit(settings, &cameras[2]);
  const Frame second = renderer.collect();
  const Frame third = renderer.collect();
  CHECK(renderer.submitted() == 0);
  CHECK_THROWS_WITH_AS(renderer.collect(), "Renderer::collect: no frame submitted", SettingsError);
  checkSameTargets(first, expected[0]);
  checkSameTargets(second, expected[1]);
  checkSameTargets(third, expected[2]);
  // The passes are named as render()'s (the once-per-scene ones ran in
  // render() already), and the readback is timed last.
  std::vector<std::string> names;
  for (const PassTime& time : second.timings) names.push_back(time.pass);
  CHECK(names ==
        std::vector<std::string>{"gbuffer", "direct", "ssgi-surface", "ssgi", "ssgi-blur", "composite", "readback"});
  for (const PassTime& time : expected[1].timings)
    if (time.pass != "shadows") CHECK(std::find(names.begin(), names.end(), time.pass) != names.end());
}

TEST_CASE("pipelined: a frame submitted before setScene is the old scene's, with the old scene's name") {
  const Scene cornell = makeBuiltinScene("cornell");
  const Scene spheres = makeBuiltinScene("spheres");
  const RenderSettings settings = test::smallSettings(48, 48);
  Renderer renderer(test::sharedContext());
  renderer.setScene(cornell);
  const Frame expected = renderer.render(settings);
  renderer.submit(settings);
  renderer.setScene(spheres);  // its upload and the next frame queue behind the pending copies
  renderer.submit(settings);
  const Frame old = renderer.collect();
  const Frame fresh = renderer.collect();
  CHECK(old.sceneSource == cornell.source);
  CHECK(fresh.sceneSource == spheres.source);
  checkSameTargets(old, expected);
  CHECK(fresh.lit.pixels != old.lit.pixels);
}

}  // namespace headlight
