#include "support/gl.hpp"

#include <thread>

#include "headlight/error.hpp"
#include "headlight/scene_builder.hpp"
#include "headlight/shapes.hpp"

namespace headlight::test {

Scene orthoQuadScene() {
  Scene scene;
  scene.source = "test:quad";
  addInstance(scene, makeSquare({0, 0, 0}, {0, 0, 1}, 1.0f),
              addMaterial(scene, makeMaterial({0.5f, 0.25f, 0.125f}, 0.6f, 0.3f)));
  scene.cameras.push_back(makeOrthographicCamera({0, 0, 2}, {0, 0, 0}, 1.5f));
  return scene;
}

Scene openPlaneScene() {
  Scene scene;
  scene.source = "test:plane";
  addInstance(scene, makeSquare({0, 0, 0}, {0, 1, 0}, 50.0f), addMaterial(scene, makeMaterial(glm::vec3(0.8f), 0.8f)));
  scene.cameras.push_back(makeLookAtCamera({0, 2, 6}, {0, 0, -4}, 0.8f));
  return scene;
}

Frame renderFresh(Scene scene, const RenderSettings& settings) {
  Renderer renderer(sharedContext());
  renderer.setScene(std::move(scene));
  return renderer.render(settings);
}

bool canMakeContext(Backend backend) {
  bool made = false;
  std::thread([&] {
    try {
      Context context(ContextOptions{.backend = backend, .errorPolicy = GlErrorPolicy::Throw, .eglDeviceName = {}});
      made = true;
    } catch (const ContextError&) {
    }
  }).join();
  return made;
}

std::string takeGlErrors(Context& context) {
  try {
    if (!context.isCurrent()) context.makeCurrent();
    context.checkErrors("the end of the test case");
  } catch (const GlError& error) {
    return error.what();
  } catch (const ContextError& error) {
    return std::string("the test context cannot be made current again: ") + error.what();
  }
  return {};
}

double meanWhere(const Frame& frame, const ImageF& image, int channel,
                 const std::function<bool(glm::vec3, glm::vec3)>& select, int& count) {
  double sum = 0;
  count = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      if (frame.position.at(x, y, 3) == 0.0f) continue;
      const glm::vec3 p(frame.position.at(x, y, 0), frame.position.at(x, y, 1), frame.position.at(x, y, 2));
      const glm::vec3 n(frame.normal.at(x, y, 0), frame.normal.at(x, y, 1), frame.normal.at(x, y, 2));
      if (!select(p, n)) continue;
      sum += image.at(x, y, channel);
      ++count;
    }
  return count > 0 ? sum / count : 0.0;
}

}  // namespace headlight::test
