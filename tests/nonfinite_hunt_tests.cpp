// The hunt for NaN and infinity (issue 34, item 3): every conformance model
// (../shared/gltf-conformance, or $HEADLIGHT_SHARED_DIR) rendered from its
// own cameras, one framed as --orbit frames it and orbit views at grazing and steep angles, at
// two small sizes (one odd), and every target of every frame checked for a
// non-finite value before anything writes it (the writers' finite-output
// check refuses such a target: a user gets no image at all). A missing
// folder is a visible skip.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "headlight/scene_builder.hpp"
#include "headlight/scene_loader.hpp"
#include "support/assets.hpp"
#include "support/gl.hpp"

namespace fs = std::filesystem;
using namespace headlight;
using namespace headlight::test;

namespace {

fs::path conformanceFolder() { return sharedFolder() / "gltf-conformance"; }

std::vector<std::string> conformanceModels() {
  std::vector<std::string> models;
  for (const auto& entry : fs::directory_iterator(conformanceFolder()))
    if (entry.is_directory() && fs::exists(entry.path() / "glTF" / (entry.path().filename().string() + ".gltf")))
      models.push_back(entry.path().filename().string());
  std::sort(models.begin(), models.end());
  return models;
}

// A camera on the sphere that frames `bounds` whole, `azimuth` and
// `elevation` degrees about its centre (elevation 0: level with it).
Camera orbitCamera(const Bounds& bounds, float azimuth, float elevation) {
  constexpr float kFov = 0.7f;
  const float radius = std::max(bounds.radius(), 1e-3f);
  const float distance = radius / std::sin(0.5f * kFov);
  const float a = glm::radians(azimuth), e = glm::radians(elevation);
  const glm::vec3 direction(std::cos(e) * std::sin(a), std::sin(e), std::cos(e) * std::cos(a));
  return makeLookAtCamera(bounds.center() + direction * distance, bounds.center(), kFov);
}

// Where a target first holds a non-finite value, and how many it holds.
struct NonFinite {
  std::size_t count = 0;
  int x = -1, y = -1, channel = -1;
};

NonFinite findNonFinite(const ImageF& image) {
  NonFinite found;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      for (int c = 0; c < int(image.channels.size()); ++c)
        if (!std::isfinite(image.at(x, y, c)) && found.count++ == 0) found.x = x, found.y = y, found.channel = c;
  return found;
}

}  // namespace

TEST_CASE(
    "no conformance model renders a NaN or infinity, from its own camera, a fitted one and orbit views at "
    "grazing and steep angles, at two sizes" *
    doctest::skip(!test::exists(conformanceFolder() / "README.md") || backendUnderTest() == Backend::OSMesa)) {
  // (Once, on EGL: OSMesa's llvmpipe shades the same programs alike, and the
  // hunt takes ~20 s.)
  // As --orbit frames a model (14 degrees above), level, a few degrees above
  // and below (surfaces seen edge-on), steep from above and below: views
  // where N.V and the lobes' denominators reach 0.
  const glm::vec2 kOrbits[] = {{0.0f, 14.0f},   {30.0f, 0.0f},   {135.0f, 3.0f},
                               {225.0f, -4.0f}, {300.0f, 80.0f}, {60.0f, -85.0f}};
  const glm::ivec2 kSizes[] = {{64, 48}, {97, 61}};
  const std::vector<std::string> models = conformanceModels();
  REQUIRE(models.size() >= 20);
  int frames = 0;
  for (const std::string& model : models) {
    CAPTURE(model);
    Scene scene = loadScene((conformanceFolder() / model / "glTF" / (model + ".gltf")).string());
    const Bounds bounds = scene.worldBounds();
    // The file's own cameras, then the orbits.
    for (const glm::vec2& orbit : kOrbits) scene.cameras.push_back(orbitCamera(bounds, orbit.x, orbit.y));
    Renderer renderer(sharedContext());
    renderer.setScene(std::move(scene));
    const int cameraCount = int(renderer.scene().cameras.size());
    for (int camera = 0; camera < cameraCount; ++camera)
      for (const glm::ivec2& size : kSizes) {
        RenderSettings settings = smallSettings(size.x, size.y);
        settings.camera = camera;
        const Frame frame = renderer.render(settings);
        ++frames;
        for (const auto& [name, image] : frame.targets()) {
          const NonFinite found = findNonFinite(*image);
          CAPTURE(camera);
          CAPTURE(size.x);
          CAPTURE(name);
          CAPTURE(found.x);
          CAPTURE(found.y);
          CAPTURE(found.channel);
          CHECK(found.count == 0);
        }
      }
  }
  MESSAGE(frames, " frames of ", models.size(), " models checked");
}
