// The Embree reference against closed forms. No GL context: scenes are built
// in code and frames synthesised by filling the G-buffer images by hand, so
// each case knows its shading points exactly. Tolerances are a few reported
// standard errors (Monte Carlo noise) plus a stated bound on the systematic
// error (tessellation, the ray-origin offset). Without Embree every case
// checks that traceReference refuses instead.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <glm/gtc/matrix_transform.hpp>
#include <numbers>
#include <string>
#include <vector>

#include "headlight/error.hpp"
#include "headlight/reference.hpp"
#include "headlight/scene_builder.hpp"
#include "headlight/scene_loader.hpp"
#include "headlight/shapes.hpp"
#include "reference/sampler_enums.hpp"
#include "reference/shading.hpp"
#include "reference/texture_sampler.hpp"
#include "support/embree.hpp"
#include "support/images.hpp"

using namespace headlight;

namespace {

// ---- Scenes ------------------------------------------------------------------

Material lambert(glm::vec3 color, glm::vec3 emissive = glm::vec3(0.0f)) {
  Material material = makeMaterial(color, 1.0f);
  material.emissiveFactor = emissive;
  return material;
}

void add(Scene& scene, Primitive primitive, Material material) {
  addInstance(scene, std::move(primitive), addMaterial(scene, std::move(material)));
}

// Light only where a case asks for it: no sky unless set.
Scene emptyScene() {
  Scene scene;
  scene.source = "test";
  scene.sky.intensity = 0.0f;
  return scene;
}

// The floor y = 0 (facing up) meeting the wall z = 0 (facing +Z), 100 each way.
Scene cornerScene(Material wall = lambert(glm::vec3(0.5f))) {
  Scene scene = emptyScene();
  add(scene, makeSquare({0, 0, 0}, {0, 1, 0}, 100.0f), lambert(glm::vec3(0.5f)));
  add(scene, makeSquare({0, 0, 0}, {0, 0, 1}, 100.0f), wall);
  return scene;
}

// ---- Frames ----------------------------------------------------------------------

struct ShadingPoint {
  glm::vec3 position{0.0f};
  glm::vec3 normal{0.0f, 1.0f, 0.0f};
  glm::vec3 albedo{0.5f};
  float metallic = 0.0f;
  float roughness = 1.0f;
  bool geometry = true;
  float occlusion = 1.0f;  // the material's occlusion (texture x strength)
};

// A G-buffer whose pixel (x, y) holds point(x, y); sky intensity 0 unless
// given. The view is the identity (camera at the origin looking down -Z).
Frame syntheticFrame(int width, int height, const std::function<ShadingPoint(int x, int y)>& point,
                     float skyIntensity = 0.0f) {
  Frame frame;
  frame.position = test::makeImage(width, height, {"position.X", "position.Y", "position.Z", "A"});
  frame.normal = test::makeImage(width, height, {"normal.X", "normal.Y", "normal.Z"});
  frame.albedo = test::makeImage(width, height, {"albedo.R", "albedo.G", "albedo.B"});
  frame.material = test::makeImage(width, height, {"material.metallic", "material.roughness", "material.occlusion"});
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const ShadingPoint p = point(x, y);
      const std::size_t i = std::size_t(y * width + x);
      if (!p.geometry) continue;
      for (int c = 0; c < 3; ++c) {
        frame.position.pixels[i * 4 + std::size_t(c)] = p.position[c];
        frame.normal.pixels[i * 3 + std::size_t(c)] = p.normal[c];
        frame.albedo.pixels[i * 3 + std::size_t(c)] = p.albedo[c];
      }
      frame.position.pixels[i * 4 + 3] = 1.0f;
      frame.material.pixels[i * 3 + 0] = p.metallic;
      frame.material.pixels[i * 3 + 1] = p.roughness;
      frame.material.pixels[i * 3 + 2] = p.occlusion;
    }
  frame.view.projection = glm::perspective(0.8f, float(width) / float(height), 0.1f, 100.0f);
  frame.settings.lighting.skyIntensity = skyIntensity;
  return frame;
}

Frame uniformFrame(int width, int height, ShadingPoint point, float skyIntensity = 0.0f) {
  return syntheticFrame(
      width, height, [&](int, int) { return point; }, skyIntensity);
}

ReferenceSettings referenceSettings(int samples, float radius, unsigned seed = 1) {
  ReferenceSettings settings;
  settings.samplesPerPixel = samples;
  settings.radius = radius;
  settings.seed = seed;
  return settings;
}

// Mean of a channel over all pixels.
double mean(const ImageF& image, int channel) {
  double sum = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) sum += image.at(x, y, channel);
  return sum / double(image.width * image.height);
}

// One channel's values, pixel by pixel.
std::vector<float> channelValues(const ImageF& image, int channel) {
  std::vector<float> values;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) values.push_back(image.at(x, y, channel));
  return values;
}

// The standard error of a mean over `pixels` independent pixels whose own
// standard errors average `pixelStandardError`.
double meanStandardError(double pixelStandardError, int pixels) {
  return pixelStandardError / std::sqrt(double(pixels));
}

using headlight::test::kNeedsEmbree;

}  // namespace

TEST_CASE("referenceAvailable says whether this build has Embree" * doctest::test_suite("reference")) {
  CHECK(referenceAvailable() == bool(HEADLIGHT_HAS_EMBREE));
}

TEST_CASE("without Embree, traceReference refuses and names the build option" * doctest::test_suite("reference") *
          doctest::skip(HEADLIGHT_HAS_EMBREE)) {
  const Frame frame = uniformFrame(2, 2, ShadingPoint{});
  CHECK_THROWS_WITH_AS(traceReference(emptyScene(), frame, referenceSettings(16, 1.0f)),
                       "headlight was built without Embree (meson -Dembree=enabled)", Error);
}

// ---- The CPU texture sampler (reference/texture_sampler.hpp) ---------------------

TEST_CASE("reference: an open plane is unoccluded and receives nothing" * doctest::test_suite("reference") *
          kNeedsEmbree) {
  Scene scene = emptyScene();
  add(scene, makeSquare({0, 0, 0}, {0, 1, 0}, 10.0f), lambert(glm::vec3(1.0f), glm::vec3(1.0f)));
  const Frame frame = uniformFrame(4, 4, ShadingPoint{});
  const ReferenceSettings settings = referenceSettings(256, 1e6f);
  const ReferenceImages result = traceReference(scene, frame, settings);
  REQUIRE(result.ao.channels == std::vector<std::string>{"ao.Y", "sky.Y", "specular.Y"});
  REQUIRE(result.indirect.channels == std::vector<std::string>{"indirectR.R", "indirectR.G", "indirectR.B",
                                                               "indirect.R", "indirect.G", "indirect.B"});
  REQUIRE(result.lit.channels == std::vector<std::string>{"R", "G", "B", "A"});
  CHECK(result.samplesPerPixel == 256);
  for (float value : result.ao.pixels) CHECK(value == 1.0f);  // AO and sky visibility
  for (float value : result.indirect.pixels) CHECK(value == 0.0f);
  CHECK(result.aoMeanStandardError == 0.0);
  CHECK(result.aoMaxStandardError == 0.0);
  CHECK(result.indirectMeanStandardError == 0.0);
  CHECK(result.lit.at(0, 0, 3) == 1.0f);
}

TEST_CASE("reference: a progress callback hears the rows handed out, ending at all of them, and changes nothing" *
          doctest::test_suite("reference") * kNeedsEmbree) {
  Scene scene = emptyScene();
  add(scene, makeSquare({0, 0, 0}, {0, 1, 0}, 10.0f), lambert(glm::vec3(1.0f), glm::vec3(1.0f)));
  const Frame frame = uniformFrame(8, 6, ShadingPoint{});
  ReferenceSettings settings = referenceSettings(64, 1.0f);
  settings.threads = 2;
  std::vector<std::pair<int, int>> calls;
  const ReferenceImages reported =
      traceReference(scene, frame, settings, [&](int started, int rows) { calls.emplace_back(started, rows); });
  REQUIRE(!calls.empty());
  CHECK(calls.back() == std::pair(6, 6));  // the last call: every row
  for (std::size_t i = 1; i < calls.size(); ++i) CHECK(calls[i].first >= calls[i - 1].first);
  for (const auto& [started, rows] : calls) CHECK((rows == 6 && started >= 0 && started <= 6));
  // The same images as without a callback (the random streams are per pixel).
  CHECK(reported.ao.pixels == traceReference(scene, frame, settings).ao.pixels);
}

TEST_CASE("reference: alphaMode MASK cut-outs are holes to the traced rays" * doctest::test_suite("reference") *
          kNeedsEmbree) {
  // A shading point on a floor under a 100-wide masked roof at height 1.
  auto roofed = [](float alpha, bool halfTexture) {
    Scene scene = emptyScene();
    add(scene, makeSquare({0, 0, 0}, {0, 1, 0}, 100.0f), lambert(glm::vec3(0.5f)));
    Material roof = lambert(glm::vec3(0.5f));
    roof.alphaMode = AlphaMode::Mask;
    roof.baseColorFactor.a = alpha;
    roof.doubleSided = true;
    if (halfTexture) {  // 2x1: transparent | opaque, nearest, clamped: half the roof is cut out
      ImageData image;
      image.width = 2;
      image.height = 1;
      image.rgba = {255, 255, 255, 0, 255, 255, 255, 255};
      scene.images.push_back(image);
      roof.baseColorTexture.image = 0;
      roof.baseColorTexture.magFilter = reference::kGlNearest;
      roof.baseColorTexture.wrapS = roof.baseColorTexture.wrapT = reference::kGlClampToEdge;
    }
    add(scene, makeSquare({0, 1, 0}, {0, -1, 0}, 100.0f), roof);
    return scene;
  };
  const Frame frame = uniformFrame(8, 8, ShadingPoint{});
  const ReferenceSettings settings = referenceSettings(1024, 1e6f);
  // Alpha below the cutoff: no roof at all, exactly the open plane.
  for (float value : traceReference(roofed(0.49f, false), frame, settings).ao.pixels) CHECK(value == 1.0f);
  // At the cutoff the roof is kept: nearly everything is blocked (rays
  // escape only below 1/100 rad of the horizon: < 1e-3 of the cosine weight).
  CHECK(mean(traceReference(roofed(0.5f, false), frame, settings).ao, 0) < 1e-3);
  // Half the roof cut out (a half-space of directions by symmetry): AO 1/2.
  const ReferenceImages half = traceReference(roofed(1.0f, true), frame, settings);
  const double ao = mean(half.ao, 0);
  CAPTURE(ao);
  CHECK(std::abs(ao - 0.5) < 4.0 * meanStandardError(half.aoMeanStandardError, 64) + 1e-3);
  // COLOR_0's alpha counts too: a vertex alpha below the cutoff opens the roof.
  Scene colored = roofed(1.0f, false);
  colored.primitives[1].colors.assign(colored.primitives[1].positions.size(), glm::vec4(1.0f, 1.0f, 1.0f, 0.4f));
  for (float value : traceReference(colored, frame, settings).ao.pixels) CHECK(value == 1.0f);
}

TEST_CASE("reference: an inner corner is half occluded" * doctest::test_suite("reference") * kNeedsEmbree) {
  // A point on the floor 1 mm in front of the wall: the wall covers the half
  // of the hemisphere with direction.z < 0, which is half of the cosine
  // weight by symmetry. Systematic error: rays that pass the wall's edge
  // (100 away) need |direction.z| < 1e-5, a 1e-5 fraction.
  const Scene scene = cornerScene();
  ShadingPoint point;
  point.position = {0.0f, 0.0f, 1e-3f};
  const Frame frame = uniformFrame(8, 8, point);
  const ReferenceSettings settings = referenceSettings(4096, 1e6f);
  const ReferenceImages result = traceReference(scene, frame, settings);
  const double ao = mean(result.ao, 0);
  const double standardError = meanStandardError(result.aoMeanStandardError, 64);
  CAPTURE(ao);
  CAPTURE(standardError);
  CHECK(std::abs(ao - 0.5) < 4.0 * standardError + 1e-4);
  // sqrt(0.25 / 4095) per pixel, up to the spread of the estimates.
  CHECK(result.aoMeanStandardError == doctest::Approx(std::sqrt(0.25 / 4095.0)).epsilon(0.01));
  CHECK(result.aoMaxStandardError >= result.aoMeanStandardError);

  // Within a radius shorter than the point's distance to the wall, nothing
  // is in range.
  // The sky visibility is the same rays' escapes: within 1e6 (the walls are
  // 100 long) it is the AO, and it does not depend on R.
  const ReferenceImages near = traceReference(scene, frame, referenceSettings(4096, 5e-4f));
  for (float value : channelValues(near.ao, 0)) CHECK(value == 1.0f);
  CHECK(channelValues(result.ao, 1) == channelValues(result.ao, 0));
  CHECK(channelValues(near.ao, 1) == channelValues(result.ao, 1));
}

TEST_CASE("reference: a point exactly on a crease is half occluded" * doctest::test_suite("reference") * kNeedsEmbree) {
  // Pixels centred on the Cornell box's floor-back wall edge (z = -1, y = 0)
  // and on the corner scene's edge: p + eps n still lies in the wall's
  // plane, where float rounding used to decide whether rays into the wall
  // hit it (AO 1.0 or 0.38 measured). The limit from the floor's side is
  // 0.5 for any radius (the wall fills the half with direction.z < 0); the
  // edges' far ends are 100 away (corner) and 1 away (Cornell: the side
  // walls, which lie beyond R = 0.05 and the R = 1e6 case is not run there).
  const Scene corner = cornerScene();
  const Scene cornell = makeBuiltinScene("cornell");
  struct Case {
    const Scene* scene;
    glm::vec3 position;
    float radius;
  };
  const Case cases[] = {{&corner, {0.3f, 0.0f, 0.0f}, 1e6f},
                        {&corner, {-7.25f, 0.0f, 0.0f}, 0.5f},
                        {&cornell, {0.1f, 0.0f, -1.0f}, 0.05f},
                        {&cornell, {-0.4f, 0.0f, -1.0f}, 0.05f}};
  for (const Case& c : cases) {
    ShadingPoint point;
    point.position = c.position;
    Frame frame = uniformFrame(4, 4, point);
    // A camera in front of the edge, above the floor, as a render has it.
    frame.view.position = c.position + glm::vec3(0.0f, 1.0f, 3.0f);
    frame.view.view = glm::lookAt(frame.view.position, c.position, glm::vec3(0, 1, 0));
    const ReferenceSettings settings = referenceSettings(4096, c.radius);
    const ReferenceImages result = traceReference(*c.scene, frame, settings);
    const double standardError = meanStandardError(result.aoMeanStandardError, 16);
    CAPTURE(c.position.x);
    CAPTURE(standardError);
    for (float value : channelValues(result.ao, 0))
      CHECK(std::abs(value - 0.5) < 0.05);  // 4096 rays: SE 0.0078 per pixel
    CHECK(std::abs(mean(result.ao, 0) - 0.5) < 4.0 * standardError + 1e-3);
  }
}

TEST_CASE("reference: a sphere above a plane blocks its cosine-weighted cap" * doctest::test_suite("reference") *
          kNeedsEmbree) {
  // A sphere of radius r centred h above the point subtends a cone of
  // half-angle asin(r / h) around the normal, whose cosine-weighted
  // fraction of the hemisphere is sin^2 = (r / h)^2. The 128 x 64 UV sphere
  // lies inside the true one, down to r cos^2(pi / 128) (the centre of its
  // largest facets), which shrinks (r/h)^2 by at most 1.5e-4 here; the ray
  // origin's offset (4e-4 up: 2e-5 x (diagonal 14.2 + coordinate 5)) grows
  // it by 2e-4. Tolerance: 4 standard errors + 5e-4.
  constexpr float kRadius = 0.5f, kHeight = 1.0f;
  Scene scene = emptyScene();
  add(scene, makeSquare({0, 0, 0}, {0, 1, 0}, 5.0f), lambert(glm::vec3(0.5f)));
  add(scene, makeUvSphere(kRadius, 128, 64, {0, kHeight, 0}), lambert(glm::vec3(0.5f)));
  const Frame frame = uniformFrame(8, 8, ShadingPoint{});
  const ReferenceSettings settings = referenceSettings(4096, 1e6f);
  const ReferenceImages result = traceReference(scene, frame, settings);
  const double expected = 1.0 - double(kRadius * kRadius) / double(kHeight * kHeight);
  const double ao = mean(result.ao, 0);
  const double standardError = meanStandardError(result.aoMeanStandardError, 64);
  CAPTURE(ao);
  CAPTURE(standardError);
  CHECK(std::abs(ao - expected) < 4.0 * standardError + 5e-4);

  // R shorter than the gap to the sphere (h - r = 0.5): nothing in range.
  // The sky visibility sees the sphere at any R.
  const ReferenceImages outOfRange = traceReference(scene, frame, referenceSettings(1024, 0.4f));
  for (float value : channelValues(outOfRange.ao, 0)) CHECK(value == 1.0f);
  CHECK(std::abs(mean(outOfRange.ao, 1) - expected) < 4.0 * 2.0 * standardError + 5e-4);  // 1024 rays: twice the SE
}

TEST_CASE("reference: error falls as one over the square root of the samples" * doctest::test_suite("reference") *
          kNeedsEmbree) {
  // RMS of AO - 0.5 over 64 pixels x 2 seeds in the corner: 16 times the
  // rays should divide it by sqrt(16) = 4. With 128 pixels the RMS itself is
  // known to about 6%, so the ratio lands within 4 +- 1 nearly always.
  const Scene scene = cornerScene();
  ShadingPoint point;
  point.position = {0.0f, 0.0f, 1e-3f};
  const Frame frame = uniformFrame(8, 8, point);
  auto rmsError = [&](int samples) {
    double sum = 0;
    int count = 0;
    for (unsigned seed : {7u, 8u}) {
      const ReferenceImages result = traceReference(scene, frame, referenceSettings(samples, 1e6f, seed));
      for (float value : channelValues(result.ao, 0)) {
        sum += (value - 0.5) * (value - 0.5);
        ++count;
      }
    }
    return std::sqrt(sum / count);
  };
  const double coarse = rmsError(256), fine = rmsError(4096);
  CAPTURE(coarse);
  CAPTURE(fine);
  CHECK(coarse / fine > 2.5);
  CHECK(coarse / fine < 6.0);
  // And the reported standard error predicts it: sqrt(0.25 / 255) = 0.0313.
  CHECK(coarse == doctest::Approx(std::sqrt(0.25 / 255.0)).epsilon(0.25));
}

TEST_CASE("reference: one bounce from an emissive wall" * doctest::test_suite("reference") * kNeedsEmbree) {
  // The corner's wall (black, emission 1) fills half of the cosine-weighted
  // hemisphere, so the floor point receives irradiance / pi = 0.5 and
  // reflects albedo x 0.5 (metallic 0). No lights, no sky.
  const Scene scene = cornerScene(lambert(glm::vec3(0.0f), glm::vec3(1.0f)));
  ShadingPoint point;
  point.position = {0.0f, 0.0f, 1e-3f};
  point.albedo = {0.5f, 0.25f, 1.0f};
  const Frame frame = uniformFrame(8, 8, point);
  const ReferenceSettings settings = referenceSettings(4096, 1e6f);
  const ReferenceImages result = traceReference(scene, frame, settings);
  // The per-channel standard error scales with the albedo; the reported one
  // is the mean over channels, so scale it by albedo / mean albedo.
  const double meanAlbedo = (0.5 + 0.25 + 1.0) / 3.0;
  for (int c = 0; c < 3; ++c) {
    const double expected = 0.5 * point.albedo[c];
    const double standardError = meanStandardError(result.indirectMeanStandardError, 64) * point.albedo[c] / meanAlbedo;
    CAPTURE(c);
    CHECK(std::abs(mean(result.indirect, 3 + c) - expected) < 4.0 * standardError + 1e-4);  // unlimited
    CHECK(std::abs(mean(result.indirect, c) - expected) < 4.0 * standardError + 1e-4);      // within R = 1e6
    // lit = direct (none) + sky (none) + indirect: the same numbers.
    CHECK(mean(result.lit, c) == doctest::Approx(mean(result.indirect, 3 + c)).epsilon(1e-5));
  }
  // Bernoulli(0.5) x albedo: per-ray spread 0.5 x albedo, over sqrt(4096).
  CHECK(result.indirectMeanStandardError == doctest::Approx(0.5 * meanAlbedo / 64.0).epsilon(0.02));

  // Within R shorter than the 1 mm to the wall: indirectR is 0, the
  // unlimited indirect is not.
  const ReferenceImages near = traceReference(scene, frame, referenceSettings(256, 5e-4f));
  CHECK(mean(near.indirect, 0) == 0.0);
  CHECK(mean(near.indirect, 3) > 0.2);
}

TEST_CASE("reference: direct light matches the BRDF in closed form" * doctest::test_suite("reference") * kNeedsEmbree) {
  // A sun straight down on a plane seen from straight above: N = V = L = H.
  // With roughness 1 (alpha 1): D = 1 / pi, Vis = 0.5 / (1 + 1) = 0.25,
  // F = f0 = 0.04, so L = ((1 - 0.04) albedo / pi + 0.25 x 0.04 / pi) E.
  Scene scene = emptyScene();
  add(scene, makeSquare({0, 0, 0}, {0, 1, 0}, 10.0f), lambert(glm::vec3(0.5f)));
  Light sun;
  sun.type = Light::Type::Directional;
  sun.direction = {0.0f, -1.0f, 0.0f};
  sun.intensity = 3.0f;
  scene.lights.push_back(sun);
  Frame frame = uniformFrame(2, 2, ShadingPoint{});
  frame.view.view = glm::lookAt(glm::vec3(0, 5, 0), glm::vec3(0, 0, 0), glm::vec3(0, 0, -1));
  frame.view.position = {0.0f, 5.0f, 0.0f};
  const ReferenceSettings settings = referenceSettings(64, 1.0f);
  const float expected = (0.96f * 0.5f + 0.25f * 0.04f) / std::numbers::pi_v<float> * 3.0f;
  const ReferenceImages lit = traceReference(scene, frame, settings);
  for (int c = 0; c < 3; ++c) CHECK(lit.lit.at(1, 1, c) == doctest::Approx(expected).epsilon(1e-5));

  // A square above the point shadows it; the square's lit top faces away,
  // so nothing bounces either.
  Scene shadowed = scene;
  add(shadowed, makeSquare({0, 1, 0}, {0, -1, 0}, 0.5f), lambert(glm::vec3(0.5f)));
  const ReferenceImages dark = traceReference(shadowed, frame, settings);
  for (int c = 0; c < 3; ++c) CHECK(dark.lit.at(1, 1, c) == 0.0f);
  // ... unless the light casts no shadow, as in the renderer.
  shadowed.lights[0].castsShadows = false;
  const ReferenceImages unshadowed = traceReference(shadowed, frame, settings);
  for (int c = 0; c < 3; ++c) CHECK(unshadowed.lit.at(1, 1, c) == doctest::Approx(expected).epsilon(1e-5));
}

TEST_CASE("reference: a white surface under a uniform open sky reflects the sky" * doctest::test_suite("reference") *
          kNeedsEmbree) {
  // The furnace test: albedo 1, metallic 0, nothing blocking, constant sky
  // radiance c x intensity. Diffuse (1 - specular albedo) c plus specular
  // (specular albedo) c is c, whatever the samples' estimate of the
  // specular albedo, because both come from the same samples.
  Scene scene = emptyScene();
  add(scene, makeSquare({0, 0, 0}, {0, 1, 0}, 10.0f), lambert(glm::vec3(1.0f)));
  scene.sky.zenith = scene.sky.horizon = scene.sky.ground = glm::vec3(0.25f, 0.5f, 1.0f);
  ShadingPoint point;
  point.albedo = glm::vec3(1.0f);
  point.roughness = 0.5f;
  Frame frame = uniformFrame(2, 2, point, 2.0f);
  frame.view.position = {0.0f, 1.0f, 2.0f};  // 27 degrees above the horizon
  const ReferenceSettings settings = referenceSettings(256, 1.0f);
  const ReferenceImages result = traceReference(scene, frame, settings);
  for (int c = 0; c < 3; ++c)
    CHECK(result.lit.at(0, 0, c) == doctest::Approx(2.0f * scene.sky.zenith[c]).epsilon(1e-4));
}

TEST_CASE("reference: the material's occlusion dims the sky's light as the composite's does" *
          doctest::test_suite("reference") * kNeedsEmbree) {
  // glTF's occlusionTexture: less ambient light where it is below 1. The
  // composite scales the sky's ambient by it (ambient.glsl); a reference
  // that left it out read every model with a baked occlusion map brighter
  // than any render could be (NormalTangentMirrorTest: the default SSGI
  // "worse than none", docs/BENCHMARKS.md "Session 23"). The furnace
  // above, at occlusion 0.25, and a metal at 0.5.
  Scene scene = emptyScene();
  add(scene, makeSquare({0, 0, 0}, {0, 1, 0}, 10.0f), lambert(glm::vec3(1.0f)));
  scene.sky.zenith = scene.sky.horizon = scene.sky.ground = glm::vec3(0.25f, 0.5f, 1.0f);
  for (const auto& [metallic, occlusion] : {std::pair{0.0f, 0.25f}, std::pair{1.0f, 0.5f}}) {
    CAPTURE(metallic);
    ShadingPoint point;
    point.albedo = glm::vec3(1.0f);
    point.roughness = 0.5f;
    point.metallic = metallic;
    Frame frame = uniformFrame(2, 2, point, 2.0f);
    frame.view.position = {0.0f, 1.0f, 2.0f};
    const ReferenceSettings settings = referenceSettings(256, 1.0f);
    const ReferenceImages open = traceReference(scene, frame, settings);
    for (std::size_t i = 0; i < 4; ++i) frame.material.pixels[i * 3 + 2] = occlusion;
    const ReferenceImages occluded = traceReference(scene, frame, settings);
    for (int c = 0; c < 3; ++c)
      CHECK(occluded.lit.at(0, 0, c) == doctest::Approx(occlusion * open.lit.at(0, 0, c)).epsilon(1e-4));
    CHECK(occluded.ao.at(0, 0, 1) == open.ao.at(0, 0, 1));  // sky.Y stays the geometry's
  }
}

TEST_CASE("reference: background pixels show the sky through the pixel" * doctest::test_suite("reference") *
          kNeedsEmbree) {
  // Two rows, camera looking down -Z: the top row looks up, the bottom one
  // down, by half the vertical half-angle (rows are top first, as in Frame).
  Scene scene = emptyScene();
  add(scene, makeSquare({0, -10, 0}, {0, 1, 0}, 1.0f), lambert(glm::vec3(0.5f)));
  const Frame frame = syntheticFrame(
      1, 2, [](int, int) { return ShadingPoint{{}, {}, {}, 0, 1, false}; }, 1.5f);
  const ReferenceSettings settings = referenceSettings(16, 1.0f);
  const ReferenceImages result = traceReference(scene, frame, settings);
  const float tangent = std::tan(0.4f) * 0.5f;  // yfov 0.8, pixel centres at +-half the half-height
  for (int y = 0; y < 2; ++y) {
    const glm::vec3 direction = glm::normalize(glm::vec3(0.0f, y == 0 ? tangent : -tangent, -1.0f));
    const glm::vec3 expected = reference::skyRadiance(scene.sky, direction) * 1.5f;
    CAPTURE(y);
    for (int c = 0; c < 3; ++c) CHECK(result.lit.at(0, y, c) == doctest::Approx(expected[c]).epsilon(1e-5));
    CHECK(result.lit.at(0, y, 3) == 0.0f);
    CHECK(result.ao.at(0, y, 0) == 1.0f);
    for (int c = 0; c < 6; ++c) CHECK(result.indirect.at(0, y, c) == 0.0f);
  }
  CHECK(result.lit.at(0, 0, 2) != result.lit.at(0, 1, 2));
}

TEST_CASE("reference: results do not depend on the thread count" * doctest::test_suite("reference") * kNeedsEmbree) {
  Scene scene = cornerScene(lambert(glm::vec3(0.7f, 0.2f, 0.1f), glm::vec3(0.3f)));
  Light lamp;
  lamp.position = {0.3f, 0.8f, 0.5f};
  lamp.intensity = 2.0f;
  scene.lights.push_back(lamp);
  scene.sky.intensity = 1.0f;
  // A mix of floor points at varying distances from the wall, wall points,
  // and background.
  const Frame frame = syntheticFrame(
      12, 7,
      [](int x, int y) {
        ShadingPoint p;
        if ((x + y) % 5 == 0) p.geometry = false;
        if (x % 2 == 0) {
          p.position = {0.1f * float(x) - 0.6f, 0.0f, 0.02f * float(y) + 0.001f};
        } else {
          p.position = {0.1f * float(x) - 0.6f, 0.05f * float(y), 0.0f};
          p.normal = {0.0f, 0.0f, 1.0f};
          p.roughness = 0.3f;
          p.metallic = 0.5f;
        }
        return p;
      },
      1.0f);
  ReferenceSettings one = referenceSettings(128, 0.3f, 5);
  one.threads = 1;
  ReferenceSettings two = one;
  two.threads = 2;
  ReferenceSettings three = one;
  three.threads = 3;
  const ReferenceImages a = traceReference(scene, frame, one);
  for (const ReferenceSettings& settings : {two, three}) {
    const ReferenceImages b = traceReference(scene, frame, settings);
    CAPTURE(settings.threads);
    CHECK(a.ao.pixels == b.ao.pixels);
    CHECK(a.indirect.pixels == b.indirect.pixels);
    CHECK(a.lit.pixels == b.lit.pixels);
    CHECK(a.aoMeanStandardError == b.aoMeanStandardError);
    CHECK(a.aoMaxStandardError == b.aoMaxStandardError);
    CHECK(a.indirectMeanStandardError == b.indirectMeanStandardError);
  }
  // Another seed gives other numbers.
  ReferenceSettings otherSeed = one;
  otherSeed.seed = 6;
  CHECK(traceReference(scene, frame, otherSeed).ao.pixels != a.ao.pixels);
}

TEST_CASE("reference: bad settings and frames are refused" * doctest::test_suite("reference") * kNeedsEmbree) {
  const Scene scene = cornerScene();
  const Frame frame = uniformFrame(2, 2, ShadingPoint{});
  CHECK_THROWS_WITH_AS(traceReference(scene, frame, referenceSettings(0, 1.0f)),
                       "reference-samples: must be in 1..1048576, got 0", SettingsError);
  CHECK_THROWS_AS(traceReference(scene, frame, referenceSettings(1048577, 1.0f)), SettingsError);
  CHECK_THROWS_WITH_AS(traceReference(scene, frame, referenceSettings(16, 0.0f)),
                       doctest::Contains("radius must be a finite number > 0"), SettingsError);
  CHECK_THROWS_AS(traceReference(scene, frame, referenceSettings(16, -1.0f)), SettingsError);
  CHECK_THROWS_AS(traceReference(scene, frame, referenceSettings(16, NAN)), SettingsError);
  ReferenceSettings negativeThreads = referenceSettings(16, 1.0f);
  negativeThreads.threads = -1;
  CHECK_THROWS_AS(traceReference(scene, frame, negativeThreads), SettingsError);

  CHECK_THROWS_WITH_AS(traceReference(scene, Frame{}, referenceSettings(16, 1.0f)),
                       doctest::Contains("frame.position is empty"), SettingsError);
  Frame mismatched = frame;
  mismatched.normal = test::makeImage(3, 2, {"normal.X", "normal.Y", "normal.Z"});
  CHECK_THROWS_WITH_AS(traceReference(scene, mismatched, referenceSettings(16, 1.0f)),
                       "traceReference: frame.normal is 3x2x3 with 18 floats; expected 2x2 with at least 3 channels",
                       SettingsError);
  Frame noAlbedo = frame;
  noAlbedo.albedo = ImageF{};
  CHECK_THROWS_AS(traceReference(scene, noAlbedo, referenceSettings(16, 1.0f)), SettingsError);
  // A lobe's target the pixels read is checked as the core ones are (every
  // target of frameTargets() the frame holds): a clearcoat of another size
  // is named, not read past its end.
  Frame smallCoat = frame;
  smallCoat.clearcoat =
      test::makeImage(1, 1, {"clearcoat", "clearcoatRoughness", "clearcoatNormal.U", "clearcoatNormal.V"});
  CHECK_THROWS_WITH_AS(traceReference(scene, smallCoat, referenceSettings(16, 1.0f)),
                       "traceReference: frame.clearcoat is 1x1x4 with 4 floats; expected 2x2 with at least 4 channels",
                       SettingsError);

  // One sample is allowed; its spread is unknown.
  const ReferenceImages single = traceReference(scene, frame, referenceSettings(1, 1.0f));
  CHECK(std::isnan(single.aoMeanStandardError));
}
