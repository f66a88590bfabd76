// KHR_materials_iridescence through the whole frame (the parity test covers
// direct light pixel by pixel): a film of strength 0 changes no pixel of lit
// (sky, SSGI and the composite included), the blend pass puts the film on
// an alphaMode BLEND surface, and the Embree reference reads the film from
// iridescence.exr.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "headlight/reference.hpp"
#include "headlight/scene_builder.hpp"
#include "headlight/shapes.hpp"
#include "support/colour.hpp"
#include "support/gl.hpp"

using namespace headlight;
using headlight::test::chroma;
using headlight::test::rgbAt;

namespace {

Material withFilm(Material material, float strength, float thicknessNm = 400.0f, float filmIor = 1.33f) {
  MaterialIridescence film;
  film.iridescenceFactor = strength;
  film.iridescenceThicknessMaximum = thicknessNm;
  film.iridescenceIor = filmIor;
  material.iridescence = film;
  return material;
}

// A grey metal sphere (the film's colour shows best on grey metal) on a
// floor, one sun, the default sky. `sphere` is the sphere's material.
Scene sphereScene(const Material& sphere) {
  Scene scene;
  scene.source = "test:iridescence";
  addInstance(scene, makeFloor(4.0f), addMaterial(scene, makeMaterial({0.8f, 0.8f, 0.8f}, 0.8f)));
  addInstance(scene, makeUvSphere(0.7f, 48, 24), addMaterial(scene, sphere), moved({0.0f, 0.7f, 0.0f}));
  scene.cameras.push_back(makeLookAtCamera({0.0f, 1.6f, 3.5f}, {0.0f, 0.6f, 0.0f}, 0.7f));
  Light sun;
  sun.type = Light::Type::Directional;
  sun.direction = {-0.4f, -1.0f, -0.6f};
  sun.intensity = 3.0f;
  scene.lights.push_back(sun);
  return scene;
}

const Material kGreyMetal = makeMaterial({0.5f, 0.5f, 0.5f}, 0.3f, 1.0f);

}  // namespace

TEST_CASE("iridescence: a film of strength 0 leaves every pixel of lit as without the extension") {
  const RenderSettings settings = test::smallSettings(64, 48);
  const Frame plain = test::renderFresh(sphereScene(kGreyMetal), settings);
  const Frame unfilmed = test::renderFresh(sphereScene(withFilm(kGreyMetal, 0.0f)), settings);
  REQUIRE(plain.iridescence.empty());
  REQUIRE(!unfilmed.iridescence.empty());  // the lobe is drawn: the material has the extension
  REQUIRE(plain.lit.pixels.size() == unfilmed.lit.pixels.size());
  // mix(Schlick, film, 0) is Schlick exactly, in the direct light and the
  // ambient term alike; the other passes do not read the lobe.
  int differ = 0;
  for (std::size_t i = 0; i < plain.lit.pixels.size(); ++i) differ += plain.lit.pixels[i] != unfilmed.lit.pixels[i];
  CHECK(differ == 0);
}

TEST_CASE("iridescence: the blend pass puts the film on an alphaMode BLEND surface") {
  Material glass = kGreyMetal;
  glass.alphaMode = AlphaMode::Blend;
  glass.baseColorFactor.a = 0.9f;
  const RenderSettings settings = test::smallSettings(64, 48);
  const Frame plain = test::renderFresh(sphereScene(glass), settings);
  const Frame filmed = test::renderFresh(sphereScene(withFilm(glass, 1.0f)), settings);
  REQUIRE(!plain.coverage.empty());
  // The blended sphere is in no G-buffer target: its film is the blend
  // pass's own (lobe_iridescence_material.glsl), and lit shows it.
  int blended = 0, coloured = 0;
  for (int y = 0; y < plain.lit.height; ++y)
    for (int x = 0; x < plain.lit.width; ++x) {
      if (plain.coverage.at(x, y, 0) < 0.5f) continue;
      const glm::vec3 off = rgbAt(plain.lit, x, y), on = rgbAt(filmed.lit, x, y);
      if (std::min({off.r, off.g, off.b}) < 1e-3f) continue;
      ++blended;
      coloured += chroma(on / off) > 0.15f;  // as the conformance test's metal
    }
  MESSAGE("blend pass: " << blended << " blended pixels, " << coloured << " coloured by the film");
  CHECK(blended > 100);
  CHECK(coloured > blended / 2);
}

TEST_CASE("iridescence: the Embree reference reads the film from iridescence.exr" *
          doctest::skip(!referenceAvailable())) {
  const Scene scene = sphereScene(withFilm(kGreyMetal, 1.0f));
  RenderSettings renderSettings = test::smallSettings(48, 36);
  renderSettings.ssgi.enabled = false;
  const Frame frame = test::renderFresh(scene, renderSettings);
  REQUIRE(!frame.iridescence.empty());
  Frame withoutFilm = frame;
  withoutFilm.iridescence = ImageF{};
  ReferenceSettings settings;
  settings.samplesPerPixel = 64;
  settings.radius = 0.5f;
  const ReferenceImages filmed = traceReference(scene, frame, settings);
  const ReferenceImages plain = traceReference(scene, withoutFilm, settings);
  // The same seeds: the floor's pixels trace the same rays either way, and
  // the sphere's light gains the film's colour (its base is grey).
  int sphere = 0, coloured = 0, floorDiffers = 0;
  double referenceSum = 0.0, renderSum = 0.0;
  for (int y = 0; y < frame.lit.height; ++y)
    for (int x = 0; x < frame.lit.width; ++x) {
      if (frame.position.at(x, y, 3) == 0.0f) continue;
      const glm::vec3 on = rgbAt(filmed.lit, x, y), off = rgbAt(plain.lit, x, y);
      if (frame.iridescence.at(x, y, 0) == 0.0f) {
        floorDiffers += on != off;
        continue;
      }
      ++sphere;
      if (std::min({off.r, off.g, off.b}) > 1e-3f && chroma(on / off) > 0.15f) ++coloured;
      referenceSum += double(on.r + on.g + on.b);
      const glm::vec3 rendered = rgbAt(frame.lit, x, y);
      renderSum += double(rendered.r + rendered.g + rendered.b);
    }
  MESSAGE("reference on the filmed sphere: " << sphere << " pixels, " << coloured
                                             << " coloured by the film; reference / render light "
                                             << referenceSum / renderSum);
  CHECK(sphere > 100);
  CHECK(floorDiffers == 0);
  CHECK(coloured > sphere / 2);
  // And the renderer's filmed sphere carries about the light the reference's
  // does: they share the direct term; the ambient term differs by the
  // split-sum tables against GGX sampling with true visibility.
  CHECK(referenceSum / renderSum == doctest::Approx(1.0).epsilon(0.2));
}

TEST_CASE("iridescence: the strength and thickness textures reach iridescence.exr, through their transforms") {
  Scene scene = test::orthoQuadScene();
  // A 2x2 image: R 255 / 0 on the top row / bottom row's left texel and G
  // 0 / 255 likewise (rows top first: UV (0, 0) is the top-left texel).
  ImageData image;
  image.name = "film";
  image.width = 2;
  image.height = 2;
  image.rgba = {255, 0, 0, 255, 0, 255, 0, 255, 0, 255, 0, 255, 255, 0, 0, 255};
  scene.images.push_back(image);
  MaterialIridescence film;
  film.iridescenceFactor = 0.5f;
  film.iridescenceIor = 1.8f;
  film.iridescenceThicknessMinimum = 200.0f;
  film.iridescenceThicknessMaximum = 600.0f;
  for (TextureRef* texture : {&film.iridescenceTexture, &film.iridescenceThicknessTexture}) {
    texture->image = 0;
    texture->minFilter = texture->magFilter = 0x2600;  // GL_NEAREST: one texel per quadrant
  }
  // The thickness texture is turned half a turn: its top-left texel lands
  // on the quad's bottom-right.
  film.iridescenceThicknessTexture.transform.rotation = 3.14159265f;
  film.iridescenceThicknessTexture.transform.offset = {1.0f, 1.0f};
  scene.materials[0].ior = 1.7f;
  scene.materials[0].iridescence = film;
  const Frame frame = test::renderFresh(scene, test::smallSettings(64, 64));
  REQUIRE(!frame.iridescence.empty());
  // The quad spans world -1..1 of the ortho camera's -1.5..1.5.
  auto at = [&](float worldX, float worldY, int channel) {
    const int x = int((worldX / 1.5f * 0.5f + 0.5f) * 64), y = int((0.5f - worldY / 1.5f * 0.5f) * 64);
    return frame.iridescence.at(x, y, channel);
  };
  CHECK(at(-0.5f, 0.5f, 0) == doctest::Approx(0.5f).epsilon(1e-3));  // top-left: R 1 x factor 0.5
  CHECK(at(0.5f, 0.5f, 0) == doctest::Approx(0.0f));                 // top-right: R 0
  CHECK(at(0.5f, -0.5f, 0) == doctest::Approx(0.5f).epsilon(1e-3));  // bottom-right: R 1
  // Rotated by pi about UV (0, 0) and moved back by (1, 1): UV (u, v) reads
  // (1 - u, 1 - v), so the bottom-right shows the top-left texel (G 0: the minimum).
  CHECK(at(0.5f, -0.5f, 1) == doctest::Approx(200.0f).epsilon(1e-3));
  CHECK(at(-0.5f, -0.5f, 1) == doctest::Approx(600.0f).epsilon(1e-3));  // reads the top-right texel, G 1
  CHECK(at(-0.5f, 0.5f, 2) == doctest::Approx(1.8f).epsilon(1e-3));
  CHECK(at(-0.5f, 0.5f, 3) == doctest::Approx(1.7f).epsilon(1e-3));
}

TEST_CASE("iridescence: the largest values a file may give draw finite pixels") {
  // Loading accepts any finite IOR >= 1 and thickness >= 0: the lobe bounds
  // them (kMaxIridescenceIor, kMaxFilmThicknessNm) before half storage and
  // (n - 1) / (n + 1) would overflow.
  Material extreme = withFilm(kGreyMetal, 1.0f, 3e38f, 3e38f);
  extreme.metallicFactor = 0.5f;
  extreme.ior = 3e38f;
  const Frame frame = test::renderFresh(sphereScene(extreme), test::smallSettings(48, 36));
  REQUIRE(!frame.iridescence.empty());
  int nonFinite = 0, filmed = 0;
  for (const float value : frame.lit.pixels) nonFinite += !std::isfinite(value);
  for (const float value : frame.iridescence.pixels) nonFinite += !std::isfinite(value);
  for (int y = 0; y < frame.iridescence.height; ++y)
    for (int x = 0; x < frame.iridescence.width; ++x) filmed += frame.iridescence.at(x, y, 0) > 0.0f;
  CHECK(nonFinite == 0);
  CHECK(filmed > 100);
}
