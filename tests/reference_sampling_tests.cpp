// The reference's CPU ports of the GPU's sampling and texture lookups, against
// the GL sampler's rules and sampling.glsl: wrap modes, filtering and sRGB
// decoding, the tangent frame, GGX importance sampling. No Embree, no GL.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <glm/gtc/matrix_transform.hpp>
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
#include "support/images.hpp"

using namespace headlight;

TEST_CASE("wrapTexel repeats, clamps and mirrors as the GL sampler does" * doctest::test_suite("reference")) {
  using namespace reference;
  // A 4-texel axis, texel indices -5..8.
  const int repeat[] = {3, 0, 1, 2, 3, 0, 1, 2, 3, 0, 1, 2, 3, 0};
  const int clamp[] = {0, 0, 0, 0, 0, 0, 1, 2, 3, 3, 3, 3, 3, 3};
  const int mirror[] = {3, 3, 2, 1, 0, 0, 1, 2, 3, 3, 2, 1, 0, 0};
  for (int i = -5; i <= 8; ++i) {
    CAPTURE(i);
    CHECK(wrapTexel(i, 4, kGlRepeat) == repeat[i + 5]);
    CHECK(wrapTexel(i, 4, kGlClampToEdge) == clamp[i + 5]);
    CHECK(wrapTexel(i, 4, kGlMirroredRepeat) == mirror[i + 5]);
  }
}

TEST_CASE("sampleTexture filters bilinearly or nearest, and decodes sRGB before filtering" *
          doctest::test_suite("reference")) {
  using namespace reference;
  // A 2x1 image: black, then white (sRGB code 188 on the right: linear 0.5029).
  Scene scene;
  scene.images.push_back(ImageData{"two texels", 2, 1, {0, 0, 0, 255, 188, 188, 188, 255}});
  TextureRef ref;
  ref.image = 0;
  ref.wrapS = ref.wrapT = kGlClampToEdge;
  ref.magFilter = kGlLinear;
  // Texel centres at u = 0.25 and 0.75; halfway between, the mean.
  CHECK(sampleTexture(scene, ref, {0.25f, 0.5f}, false).r == doctest::Approx(0.0f));
  CHECK(sampleTexture(scene, ref, {0.5f, 0.5f}, false).r == doctest::Approx(188.0f / 255.0f / 2.0f));
  CHECK(sampleTexture(scene, ref, {0.5f, 0.5f}, true).r == doctest::Approx(0.5029f / 2.0f).epsilon(1e-3));
  CHECK(sampleTexture(scene, ref, {0.5f, 0.5f}, true).a == doctest::Approx(1.0f));  // alpha is never sRGB
  // Repeat: left of the first centre blends with the last texel.
  ref.wrapS = kGlRepeat;
  CHECK(sampleTexture(scene, ref, {0.0f, 0.5f}, false).r == doctest::Approx(188.0f / 255.0f / 2.0f));
  ref.magFilter = kGlNearest;
  CHECK(sampleTexture(scene, ref, {0.49f, 0.5f}, false).r == 0.0f);
  CHECK(sampleTexture(scene, ref, {0.51f, 0.5f}, false).r == doctest::Approx(188.0f / 255.0f));
}

// ---- CPU ports of the GLSL (reference/shading.hpp) ------------------------------
// Values worked out by hand the way glsl/sampling.glsl computes them, so
// that a port drifting from the shader (another frame, an added clamp)
// fails here and not as a bias in the reference.

TEST_CASE("basisAround builds the frame sampling.glsl builds" * doctest::test_suite("reference")) {
  using reference::basisAround;
  const auto near = [](glm::vec3 a, glm::vec3 b) { return glm::length(a - b) < 1e-6f; };
  // Near +-Z the helper axis is +X: tangent = cross(+X, n), bitangent = cross(n, tangent).
  const reference::Basis up = basisAround({0, 0, 1});
  CHECK(near(up.tangent, {0, -1, 0}));
  CHECK(near(up.bitangent, {1, 0, 0}));
  const reference::Basis down = basisAround({0, 0, -1});
  CHECK(near(down.tangent, {0, 1, 0}));
  CHECK(near(down.bitangent, {1, 0, 0}));
  // Elsewhere the helper is +Z.
  const reference::Basis side = basisAround({1, 0, 0});
  CHECK(near(side.tangent, {0, 1, 0}));
  CHECK(near(side.bitangent, {0, 0, 1}));
  const reference::Basis tilted = basisAround({0, 0.6f, 0.8f});
  CHECK(near(tilted.tangent, {-1, 0, 0}));
  CHECK(near(tilted.bitangent, {0, -0.8f, 0.6f}));
  // Whatever the normal: orthonormal and right-handed.
  for (const glm::vec3 n :
       {glm::vec3(0.3f, -0.5f, 0.81f), glm::vec3(-0.7f, 0.7f, 0.1f), glm::vec3(0.01f, 0.0f, -1.0f)}) {
    const reference::Basis basis = basisAround(glm::normalize(n));
    CHECK(glm::dot(basis.tangent, basis.bitangent) == doctest::Approx(0.0f).epsilon(1e-6));
    CHECK(glm::length(basis.tangent) == doctest::Approx(1.0f));
    CHECK(glm::length(basis.bitangent) == doctest::Approx(1.0f));
    CHECK(near(glm::cross(basis.tangent, basis.bitangent), basis.normal));
  }
}

TEST_CASE("importanceSampleGgx is sampling.glsl's, without a clamp" * doctest::test_suite("reference")) {
  using reference::importanceSampleGgx;
  // xi = (0.25, 0.5), alpha = 0.5: phi = pi/2, cos^2 = 0.5 / (1 - 0.75 * 0.5) = 0.8.
  const glm::vec3 h = importanceSampleGgx(0.25f, 0.5f, 0.5f);
  CHECK(h.x == doctest::Approx(0.0).epsilon(1e-6));
  CHECK(h.y == doctest::Approx(std::sqrt(0.2)).epsilon(1e-6));
  CHECK(h.z == doctest::Approx(std::sqrt(0.8)).epsilon(1e-6));
  // alpha = 1 is the uniform-in-cos^2 case: cos^2 = 1 - xi1.
  const glm::vec3 rough = importanceSampleGgx(0.0f, 0.36f, 1.0f);
  CHECK(rough.z == doctest::Approx(0.8).epsilon(1e-6));
  CHECK(rough.x == doctest::Approx(0.6).epsilon(1e-6));
  // Bit for bit the GLSL's expression, NaN where it is NaN: sqrt(1 - cos^2)
  // with nothing between.
  for (float alpha : {0.0009f, 0.01f, 0.2f, 0.7f, 1.0f})
    for (float xi1 : {0.0f, 1e-7f, 0.1f, 0.5f, 0.9f, 0.9999f})
      for (float xi0 : {0.0f, 0.3f, 0.77f}) {
        CAPTURE(alpha);
        CAPTURE(xi1);
        const float phi = 2.0f * reference::kPi * xi0;
        const float cosTheta = std::sqrt((1.0f - xi1) / (1.0f + (alpha * alpha - 1.0f) * xi1));
        const float sinTheta = std::sqrt(1.0f - cosTheta * cosTheta);
        const glm::vec3 glsl(sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta);
        const glm::vec3 port = importanceSampleGgx(xi0, xi1, alpha);
        for (int c = 0; c < 3; ++c) {
          CHECK(std::isnan(port[c]) == std::isnan(glsl[c]));
          if (!std::isnan(glsl[c])) CHECK(port[c] == glsl[c]);
        }
      }
}
