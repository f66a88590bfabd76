// GL tests of materials as the G-buffer reads them: texture variants and UV
// orientation, alphaMode MASK (G-buffer and shadows), COLOR_0, and the
// conformance models that exercise them.
#include <doctest/doctest.h>

#include <glad/gl.h>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include "context/context_access.hpp"
#include "gl/shader_library.hpp"
#include "headlight/error.hpp"
#include "headlight/reference.hpp"
#include "headlight/scene_builder.hpp"
#include "headlight/scene_loader.hpp"
#include "headlight/shapes.hpp"
#include "shared_layout.h"
#include "support/assets.hpp"
#include "support/gl.hpp"
#include "tooling/bench.hpp"

using namespace headlight;
using namespace headlight::test;

TEST_CASE("textured material: every texture variant builds, and UV (0,0) is the image's top-left") {
  Scene scene = orthoQuadScene();
  // A 2x2 image: top row red, green; bottom row blue, white (rows top first,
  // as glTF's UV origin is the top-left corner).
  ImageData image;
  image.name = "quadrants";
  image.width = 2;
  image.height = 2;
  image.rgba = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255};
  scene.images.push_back(image);
  Material& material = scene.materials[0];
  material.baseColorFactor = glm::vec4(1.0f);
  for (TextureRef* texture : {&material.baseColorTexture, &material.metallicRoughnessTexture, &material.normalTexture,
                              &material.occlusionTexture, &material.emissiveTexture}) {
    texture->image = 0;
    texture->minFilter = texture->magFilter = 0x2600;  // GL_NEAREST: one texel per quadrant
  }
  material.emissiveFactor = glm::vec3(1.0f);
  const Frame frame = renderFresh(scene, smallSettings(64, 64));
  // makeSquare puts UV (0,0) at the quad's top-left in world (-1, +1).
  auto albedoAt = [&](float worldX, float worldY) {
    const int x = int((worldX / 1.5f * 0.5f + 0.5f) * 64), y = int((0.5f - worldY / 1.5f * 0.5f) * 64);
    return glm::vec3(frame.albedo.at(x, y, 0), frame.albedo.at(x, y, 1), frame.albedo.at(x, y, 2));
  };
  CHECK(albedoAt(-0.5f, 0.5f).r > 0.9f);   // top-left: red
  CHECK(albedoAt(0.5f, 0.5f).g > 0.9f);    // top-right: green
  CHECK(albedoAt(-0.5f, -0.5f).b > 0.9f);  // bottom-left: blue
  CHECK(albedoAt(0.5f, -0.5f).r > 0.9f);   // bottom-right: white
  CHECK(albedoAt(0.5f, -0.5f).g > 0.9f);
  CHECK(!frame.emissive.empty());
}

namespace {

// A 2x1 image: the left texel fully transparent, the right opaque (white).
ImageData halfTransparentImage() {
  ImageData image;
  image.name = "half-transparent";
  image.width = 2;
  image.height = 1;
  image.rgba = {255, 255, 255, 0, 255, 255, 255, 255};
  return image;
}

// quadScene's quad with alphaMode MASK and halfTransparentImage (nearest):
// the left half (world x < 0) is cut out.
Scene maskedQuadScene() {
  Scene scene = orthoQuadScene();
  scene.images.push_back(halfTransparentImage());
  Material& material = scene.materials[0];
  material.alphaMode = AlphaMode::Mask;
  material.baseColorTexture.image = 0;
  material.baseColorTexture.minFilter = material.baseColorTexture.magFilter = 0x2600;  // GL_NEAREST
  material.baseColorTexture.wrapS = material.baseColorTexture.wrapT = 0x812F;          // GL_CLAMP_TO_EDGE
  return scene;
}

// Pixel of world (x, y) in quadScene's 1.5-half-height orthographic view.
glm::ivec2 quadPixel(float worldX, float worldY, int size) {
  return {int((worldX / 1.5f * 0.5f + 0.5f) * float(size)), int((0.5f - worldY / 1.5f * 0.5f) * float(size))};
}

std::size_t backgroundPixels(const Frame& frame) {
  std::size_t count = 0;
  for (int y = 0; y < frame.position.height; ++y)
    for (int x = 0; x < frame.position.width; ++x) count += frame.position.at(x, y, 3) == 0.0f ? 1 : 0;
  return count;
}

}  // namespace

TEST_CASE("alphaMode MASK: the G-buffer leaves background exactly where alpha < cutoff") {
  constexpr int size = 96;
  Scene scene = maskedQuadScene();
  const Frame masked = renderFresh(scene, smallSettings(size, size));
  // The quad spans world -1..1, pixels 16..80; its texel edge is world x = 0
  // (pixel 48). One pixel of margin around each edge for rasterisation.
  for (int y = 18; y < 78; ++y)
    for (int x = 18; x < 78; ++x) {
      if (x == 47 || x == 48) continue;
      CAPTURE(x);
      CAPTURE(y);
      CHECK(masked.position.at(x, y, 3) == (x < 48 ? 0.0f : 1.0f));
    }
  // A factor alpha below the cutoff cuts out the whole quad; at the cutoff it
  // is kept (glTF: rendered when alpha >= alphaCutoff).
  scene.materials[0].baseColorTexture = TextureRef{};
  scene.materials[0].baseColorFactor.a = 0.49f;
  CHECK(backgroundPixels(renderFresh(scene, smallSettings(size, size))) == std::size_t(size * size));
  scene.materials[0].baseColorFactor.a = 0.5f;
  const Frame kept = renderFresh(scene, smallSettings(size, size));
  CHECK(kept.position.at(30, 48, 3) == 1.0f);
  CHECK(kept.position.at(66, 48, 3) == 1.0f);
  // OPAQUE ignores alpha.
  scene.materials[0].alphaMode = AlphaMode::Opaque;
  scene.materials[0].baseColorFactor.a = 0.0f;
  CHECK(renderFresh(scene, smallSettings(size, size)).position.at(30, 48, 3) == 1.0f);
}

TEST_CASE("alphaMode MASK: the cut-out passes light through the shadow map") {
  // The masked quad at z = 0 in front of a wall at z = -1, lit straight down
  // -Z: seen along the light, the wall through the hole is lit as the open
  // wall beside the quad is; with the quad opaque it would be in shadow.
  constexpr int size = 96;
  Scene scene = maskedQuadScene();
  addInstance(scene, makeSquare({0, 0, -1}, {0, 0, 1}, 5.0f), addMaterial(scene, makeMaterial(glm::vec3(0.8f), 1.0f)));
  Light light;
  light.type = Light::Type::Directional;
  light.direction = {0, 0, -1};
  light.intensity = 3.0f;
  scene.lights.push_back(light);
  scene.sky.intensity = 0.0f;
  RenderSettings settings = smallSettings(size, size);
  settings.ssgi.enabled = false;
  const Frame frame = renderFresh(scene, settings);
  const glm::ivec2 hole = quadPixel(-0.5f, 0.0f, size), open = quadPixel(-1.3f, 0.0f, size);
  const glm::ivec2 quad = quadPixel(0.5f, 0.0f, size);
  REQUIRE(frame.position.at(hole.x, hole.y, 2) == doctest::Approx(-1.0f));  // the wall, seen through the hole
  REQUIRE(frame.position.at(quad.x, quad.y, 2) == doctest::Approx(0.0f));   // the quad's opaque half
  const float openLit = frame.lit.at(open.x, open.y, 0);
  CHECK(openLit > 0.1f);
  CHECK(frame.lit.at(hole.x, hole.y, 0) == doctest::Approx(openLit).epsilon(0.01));
  // Lit at 45 degrees from +x, the opaque half's shadow falls on the wall
  // seen through the hole (world x -1..0): kept texels still cast shadows.
  scene.lights[0].direction = glm::normalize(glm::vec3(-1, 0, -1));
  const Frame slanted = renderFresh(scene, settings);
  const float slantedOpen = slanted.lit.at(open.x, open.y, 0);  // its light passes through the hole
  CHECK(slantedOpen > 0.1f);
  CHECK(slanted.lit.at(hole.x, hole.y, 0) < 0.05f * slantedOpen);
}

TEST_CASE("conformance: AlphaBlendModeTest's masked planes show background through their cut-outs" *
          doctest::skip(!test::exists(test::sharedFolder() / "gltf-conformance" / "AlphaBlendModeTest"))) {
  const std::string path =
      (test::sharedFolder() / "gltf-conformance" / "AlphaBlendModeTest" / "glTF" / "AlphaBlendModeTest.gltf").string();
  Scene scene = loadScene(path);
  const bool maskNamed = std::any_of(scene.ignored.begin(), scene.ignored.end(),
                                     [](const IgnoredFeature& f) { return f.feature == "alphaMode MASK"; });
  const bool blendNamed = std::any_of(scene.ignored.begin(), scene.ignored.end(),
                                      [](const IgnoredFeature& f) { return f.feature == "alphaMode BLEND"; });
  CHECK(!maskNamed);
  CHECK(!blendNamed);  // rendered by the blend pass (gltf_blend_tests.cpp)
  int masked = 0;
  for (const Material& material : scene.materials) masked += material.masked() ? 1 : 0;
  CHECK(masked == 3);  // MatCutoff25, MatCutoff75, MatCutoffDefault
  Scene opaque = scene;
  for (Material& material : opaque.materials) material.alphaMode = AlphaMode::Opaque;
  for (int size : {64, 128}) {
    CAPTURE(size);
    const Frame withMask = renderFresh(scene, smallSettings(size, size));
    const Frame withoutMask = renderFresh(opaque, smallSettings(size, size));
    // Where the cut-outs let the eye through, it sees what is behind the
    // planes (the bed, or background): never anything nearer.
    int throughCutOut = 0, nearer = 0;
    const glm::vec3 eye = withMask.view.position;
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        auto distance = [&](const Frame& frame) {
          if (frame.position.at(x, y, 3) == 0.0f) return std::numeric_limits<float>::infinity();
          return glm::length(glm::vec3(frame.position.at(x, y, 0), frame.position.at(x, y, 1),
                                       frame.position.at(x, y, 2)) - eye);
        };
        const float masked = distance(withMask), kept = distance(withoutMask);
        if (masked > kept * 1.001f) ++throughCutOut;
        if (masked < kept * 0.999f) ++nearer;
      }
    CAPTURE(throughCutOut);
    CHECK(throughCutOut > size * size / 100);  // at least 1% of the image
    CHECK(nearer == 0);
  }
}

TEST_CASE("COLOR_0 multiplies base colour, and its alpha counts for MASK") {
  constexpr int size = 64;
  Scene scene = orthoQuadScene();  // base colour (0.5, 0.25, 0.125)
  scene.primitives[0].colors.assign(scene.primitives[0].positions.size(), glm::vec4(0.2f, 0.4f, 0.8f, 1.0f));
  const Frame frame = renderFresh(scene, smallSettings(size, size));
  // albedo is 8-bit sRGB: 1/255 of the encoded value is < 0.002 linear here.
  CHECK(frame.albedo.at(32, 32, 0) == doctest::Approx(0.1f).epsilon(0.03));
  CHECK(frame.albedo.at(32, 32, 1) == doctest::Approx(0.1f).epsilon(0.03));
  CHECK(frame.albedo.at(32, 32, 2) == doctest::Approx(0.1f).epsilon(0.03));
  // A vertex alpha below the cutoff cuts the masked quad out; opaque, it stays.
  for (glm::vec4& color : scene.primitives[0].colors) color.a = 0.4f;
  CHECK(renderFresh(scene, smallSettings(size, size)).position.at(32, 32, 3) == 1.0f);
  scene.materials[0].alphaMode = AlphaMode::Mask;
  CHECK(backgroundPixels(renderFresh(scene, smallSettings(size, size))) == std::size_t(size * size));
}

TEST_CASE("conformance: BoxVertexColors' albedo spans its vertex colours" *
          doctest::skip(!test::exists(test::sharedFolder() / "gltf-conformance" / "BoxVertexColors"))) {
  const Scene scene = loadScene(
      (test::sharedFolder() / "gltf-conformance" / "BoxVertexColors" / "glTF" / "BoxVertexColors.gltf").string());
  CHECK(std::none_of(scene.ignored.begin(), scene.ignored.end(),
                     [](const IgnoredFeature& f) { return f.feature == "COLOR_0"; }));
  REQUIRE(!scene.primitives.empty());
  REQUIRE(scene.primitives[0].colors.size() == scene.primitives[0].positions.size());
  const Frame frame = renderFresh(scene, smallSettings(96, 96));
  // The file's colours run 0..1 per channel and its material is the default
  // (white): each albedo channel stays in 0..1 and spans most of it, where an
  // ignored COLOR_0 would leave it 1 everywhere.
  glm::vec3 low(1e9f), high(-1e9f);
  int geometry = 0;
  for (int y = 0; y < 96; ++y)
    for (int x = 0; x < 96; ++x) {
      if (frame.position.at(x, y, 3) == 0.0f) continue;
      ++geometry;
      const glm::vec3 albedo(frame.albedo.at(x, y, 0), frame.albedo.at(x, y, 1), frame.albedo.at(x, y, 2));
      low = glm::min(low, albedo);
      high = glm::max(high, albedo);
    }
  REQUIRE(geometry > 96 * 96 / 10);
  for (int c = 0; c < 3; ++c) {
    CAPTURE(c);
    CAPTURE(low[c]);
    CAPTURE(high[c]);
    CHECK(low[c] >= 0.0f);
    CHECK(high[c] <= 1.0f);
    CHECK(high[c] - low[c] > 0.5f);
  }
}

namespace {

// A sphere of `material`, fitted camera, the default sky and key light.
Frame renderSphereOf(const Material& material, const std::vector<ImageData>& images = {}) {
  Scene scene;
  scene.source = "test:spec-gloss";
  scene.images = images;
  addInstance(scene, makeUvSphere(1.0f, 64, 32), addMaterial(scene, material));
  return renderFresh(scene, smallSettings(64, 64));
}

// The largest difference of lit's RGB between two frames of one camera,
// over geometry, relative to the larger value (at least 0.1): lit is half
// float, a step of 1/1024 of the value.
float largestLitDifference(const Frame& a, const Frame& b) {
  float largest = 0.0f;
  for (int y = 0; y < a.lit.height; ++y)
    for (int x = 0; x < a.lit.width; ++x)
      if (a.position.at(x, y, 3) != 0.0f)
        for (int c = 0; c < 3; ++c) {
          const float p = a.lit.at(x, y, c), q = b.lit.at(x, y, c);
          largest = std::max(largest, std::abs(p - q) / std::max({std::abs(p), std::abs(q), 0.1f}));
        }
  return largest;
}

}  // namespace

TEST_CASE(
    "KHR_materials_pbrSpecularGlossiness: black diffuse with a gold specular renders as gold metal, with the "
    "glossiness from its texture's A as from its factor") {
  // Issue 34 item 2: the loader's mapping (gltf_feature_tests.cpp checks the
  // fields) drawn. A metal's F0 is its base colour and its diffuse 0; a
  // spec-gloss surface with diffuse 0 and specular F0 = that colour is the
  // same surface.
  const glm::vec3 gold(1.0f, 0.766f, 0.336f);
  Material metal = makeMaterial(gold, 0.2f, 1.0f);
  Material specGloss = makeMaterial(glm::vec3(0.0f), 0.2f, 0.0f);  // roughness = 1 - glossiness 0.8
  specGloss.ior = 0.0f;
  specGloss.specular = MaterialSpecular{};
  specGloss.specular->specularColorFactor = gold;
  const Frame metalFrame = renderSphereOf(metal), factorFrame = renderSphereOf(specGloss);
  const float factorDifference = largestLitDifference(metalFrame, factorFrame);
  CAPTURE(factorDifference);
  CHECK(factorDifference < 0.01f);  // measured 0.005: half float's step
  // The texture: white RGB (the specular colour x 1), glossiness 0.8 in A
  // (204 / 255), glossinessFactor 1 in the roughness factor.
  ImageData image;
  image.name = "specular-glossiness";
  image.width = image.height = 1;
  image.rgba = {255, 255, 255, 204};
  Material textured = specGloss;
  textured.roughnessFactor = 1.0f;
  textured.roughnessFromGlossiness = true;
  textured.metallicRoughnessTexture.image = 0;
  textured.specular->specularColorTexture.image = 0;
  const Frame textureFrame = renderSphereOf(textured, {image});
  const float textureDifference = largestLitDifference(metalFrame, textureFrame);
  CAPTURE(textureDifference);
  CHECK(textureDifference < 0.01f);
  // Without the flag the same texture would be read as G = roughness 1.
  textured.roughnessFromGlossiness = false;
  CHECK(largestLitDifference(metalFrame, renderSphereOf(textured, {image})) > 0.05f);
}
