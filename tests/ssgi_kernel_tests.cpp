// The SSGI kernel and noise: no context needed, but they live in the SSGI
// pass's file (GL), so these run in the gl executable.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "passes/ssgi.hpp"

using namespace headlight;

TEST_CASE("SSGI kernel: 64 samples in the upper unit hemisphere, deterministic, denser near the centre") {
  const auto kernel = makeSsgiKernel(64, 1);
  REQUIRE(kernel.size() == 64);
  int inner = 0;
  for (const glm::vec3& k : kernel) {
    CHECK(k.z >= 0.0f);
    CHECK(glm::length(k) <= 1.0f);
    if (glm::length(k) < 0.5f) ++inner;
  }
  // Lengths are uniform times lerp(0.1, 1, t^2): a uniform ball would put
  // 1/8 of its volume inside radius 0.5; this kernel puts most samples there.
  CHECK(inner > 40);
  // The scale grows with the index: the first quarter is shorter than the last.
  auto meanLength = [&](int begin, int end) {
    float sum = 0;
    for (int i = begin; i < end; ++i) sum += glm::length(kernel[std::size_t(i)]);
    return sum / float(end - begin);
  };
  CHECK(meanLength(0, 16) < 0.5f * meanLength(48, 64));
  CHECK(makeSsgiKernel(64, 1) == kernel);
  CHECK(makeSsgiKernel(64, 2) != kernel);
  // Cosine weighting: mean cos(theta) of the directions is 2/3 (uniform: 1/2).
  float meanCos = 0;
  for (const glm::vec3& k : makeSsgiKernel(4096, 7)) meanCos += k.z / std::max(glm::length(k), 1e-12f);
  CHECK(meanCos / 4096.0f == doctest::Approx(2.0 / 3.0).epsilon(0.03));
}

TEST_CASE("SSGI noise: 16 unit vectors in the xy plane, deterministic") {
  const auto noise = makeSsgiNoise(1);
  for (const glm::vec2& v : noise) CHECK(glm::length(v) == doctest::Approx(1.0f).epsilon(1e-6));
  CHECK(makeSsgiNoise(1) == noise);
  // Not all the same direction: the rotations must actually vary.
  float spread = 0;
  for (const glm::vec2& v : noise) spread = std::max(spread, glm::length(v - noise[0]));
  CHECK(spread > 1.0f);
}
