// The Embree reference under an environment map (unit suite): against the
// closed form on a uniform map (the furnace test: a white surface reflects
// exactly the radiance around it), within the estimate's own noise, and
// the background through each pixel.
#include <doctest/doctest.h>

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "headlight/reference.hpp"
#include "headlight/scene_builder.hpp"
#include "headlight/scene_loader.hpp"
#include "headlight/shapes.hpp"
#include "support/embree.hpp"
#include "support/environment_maps.hpp"
#include "support/images.hpp"
#include "support/temp_folder.hpp"

using namespace headlight;
using namespace headlight::test;

namespace {

// A width x height G-buffer of one shading point (a white rough dielectric
// at the origin facing +Y) seen from above, or of background only. The
// view is the identity's: camera at (0, 1, 2) for the view direction.
Frame pointFrame(int width, int height, bool geometry, float environmentIntensity) {
  Frame frame;
  frame.position = makeImage(width, height, {"position.X", "position.Y", "position.Z", "A"});
  frame.normal = makeImage(width, height, {"normal.X", "normal.Y", "normal.Z"});
  frame.albedo = makeImage(width, height, {"albedo.R", "albedo.G", "albedo.B"});
  frame.material = makeImage(width, height, {"material.metallic", "material.roughness", "material.occlusion"});
  for (std::size_t i = 0; geometry && i < std::size_t(width * height); ++i) {
    frame.position.pixels[i * 4 + 3] = 1.0f;
    frame.normal.pixels[i * 3 + 1] = 1.0f;
    for (int c = 0; c < 3; ++c) frame.albedo.pixels[i * 3 + std::size_t(c)] = 1.0f;
    frame.material.pixels[i * 3 + 1] = 0.5f;
    frame.material.pixels[i * 3 + 2] = 1.0f;
  }
  frame.view.projection = glm::perspective(0.8f, float(width) / float(height), 0.1f, 100.0f);
  frame.view.position = {0.0f, 1.0f, 2.0f};
  frame.settings.lighting.skyIntensity = 1.0f;  // not used: the map replaces the sky
  frame.settings.lighting.environmentIntensity = environmentIntensity;
  return frame;
}

}  // namespace

TEST_CASE("reference: a white surface under a uniform environment map reflects its radiance, within the noise" *
          doctest::test_suite("reference") * kNeedsEmbree) {
  const TempFolder folder("environment-reference");
  Scene scene;
  scene.source = "test";
  addInstance(scene, makeSquare({0, 0, 0}, {0, 1, 0}, 10.0f), addMaterial(scene, makeMaterial(glm::vec3(1.0f), 1.0f)));
  scene.environment = loadEnvironmentMap(writeEnvironmentMap(folder.path() / "uniform.exr", 64, 32, uniformRadiance));
  const int width = 8, height = 8;
  const float intensity = 2.0f;  // L = 0.5 x 2 = 1
  ReferenceSettings settings;
  settings.samplesPerPixel = 1024;
  settings.radius = 1.0f;
  const ReferenceImages result = traceReference(scene, pointFrame(width, height, true, intensity), settings);
  // Each pixel is an independent estimate: their spread gives the mean's
  // standard error.
  double sum = 0.0, sumSquares = 0.0;
  const int count = width * height;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const double value = result.lit.at(x, y, 1);
      sum += value;
      sumSquares += value * value;
    }
  const double mean = sum / count;
  const double standardError = std::sqrt(std::max(0.0, sumSquares / count - mean * mean) / (count - 1));
  CAPTURE(mean);
  CAPTURE(standardError);
  CHECK(standardError > 0.0);  // importance-sampled: noisy, not exact by construction
  CHECK(std::abs(mean - 1.0) <= 4.0 * standardError);
  CHECK(std::abs(mean - 1.0) <= 0.01);

  // The background: the map times its intensity, alpha 0; off, black.
  const ReferenceImages background = traceReference(scene, pointFrame(2, 2, false, intensity), settings);
  CHECK(background.lit.at(1, 1, 0) == doctest::Approx(1.0).epsilon(1e-5));
  CHECK(background.lit.at(1, 1, 3) == 0.0f);
  Frame dark = pointFrame(2, 2, false, intensity);
  dark.settings.lighting.environmentBackground = false;
  CHECK(traceReference(scene, dark, settings).lit.at(0, 0, 0) == 0.0f);
}
