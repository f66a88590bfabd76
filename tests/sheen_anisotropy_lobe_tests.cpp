// The CPU ports of the sheen and anisotropy lobes (lib/reference/lobe_*.hpp)
// against what they claim, by numeric integration over the hemisphere: the
// sheen albedo fit E against the lobe it approximates, the stretched GGX
// distribution's normalisation and its reduction to brdf.glsl's isotropic
// lobe at strength 0, and the reference's anisotropic sampler against the
// integral it estimates. No GL: the GLSL is held to these ports by the
// parity tests (sheen_anisotropy_parity_tests.cpp).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include "reference/lobe_anisotropy.hpp"
#include "reference/lobe_sheen.hpp"
#include "reference/shading.hpp"

using namespace headlight::reference;

namespace {

// The integral of f(l) over the hemisphere around +Z, midpoint rule in
// (theta, phi): fine enough for the smooth lobes integrated here.
double integrateHemisphere(const std::function<double(const glm::vec3&)>& f, int thetaSteps = 512, int phiSteps = 256) {
  double sum = 0.0;
  const double dTheta = 0.5 * kPi / thetaSteps, dPhi = 2.0 * kPi / phiSteps;
  for (int i = 0; i < thetaSteps; ++i) {
    const double theta = (i + 0.5) * dTheta;
    for (int j = 0; j < phiSteps; ++j) {
      const double phi = (j + 0.5) * dPhi;
      const glm::vec3 l(float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)),
                        float(std::cos(theta)));
      sum += f(l) * std::sin(theta) * dTheta * dPhi;
    }
  }
  return sum;
}

glm::vec3 viewAt(float nDotV) { return {std::sqrt(1.0f - nDotV * nDotV), 0.0f, nDotV}; }

// The sheen lobe's directional albedo for a white sheen colour.
double integratedSheenAlbedo(float nDotV, float roughness) {
  const glm::vec3 view = viewAt(nDotV);
  return integrateHemisphere([&](const glm::vec3& l) {
    const glm::vec3 h = glm::normalize(l + view);
    return double(sheenReflected(glm::vec3(1.0f), roughness, nDotV, l.z, h.z).r);
  });
}

}  // namespace

TEST_CASE("sheen: the albedo fit E is within its stated error of the integrated Charlie lobe") {
  // 0.1 for sheen roughness 0.5..1 (measured worst 0.078, at N.V = 1 and
  // roughness 0.75); smoother fabrics' grazing peak is fitted worse
  // (docs/ACCURACY.md), and checked only to stay in 0..1.
  double worst = 0.0;
  for (float roughness : {0.5f, 0.75f, 1.0f})
    for (float nDotV : {0.2f, 0.5f, 0.8f, 1.0f}) {
      const double integrated = integratedSheenAlbedo(nDotV, roughness);
      const double fitted = sheenAlbedo(sheenAlpha(roughness), nDotV);
      CAPTURE(roughness);
      CAPTURE(nDotV);
      worst = std::max(worst, std::abs(fitted - integrated));
      CHECK(std::abs(fitted - integrated) < 0.1);
    }
  MESSAGE("sheen albedo fit, roughness 0.5..1: worst error " << worst);
  for (float roughness : {0.0f, 0.07f, 0.25f, 0.5f, 1.0f})
    for (float nDotV : {0.0f, 0.01f, 0.5f, 1.0f}) {
      const float e = sheenAlbedo(sheenAlpha(roughness), nDotV);
      CHECK(e > 0.0f);
      CHECK(e < 1.0f);
    }
}

TEST_CASE("sheen: no colour, no change; the base keeps 0..1 of its light") {
  for (float roughness : {0.0f, 0.3f, 1.0f})
    for (float nDotV : {0.05f, 0.5f, 1.0f})
      for (float nDotL : {0.05f, 0.5f, 1.0f}) {
        CHECK(sheenBaseScale(glm::vec3(0.0f), roughness, nDotV, nDotL) == 1.0f);
        CHECK(sheenReflected(glm::vec3(0.0f), roughness, nDotV, nDotL, 0.7f) == glm::vec3(0.0f));
        const float scale = sheenBaseScale(glm::vec3(1.0f, 0.5f, 0.0f), roughness, nDotV, nDotL);
        CHECK(scale > 0.0f);
        CHECK(scale < 1.0f);
      }
  // Brighter at grazing view than head-on: what sheen is for.
  const glm::vec3 head = viewAt(1.0f), grazing = viewAt(0.1f), toLight(0.0f, 0.0f, 1.0f);
  auto toward = [&](const glm::vec3& view) {
    const glm::vec3 h = glm::normalize(toLight + view);
    return sheenReflected(glm::vec3(1.0f), 0.5f, view.z, toLight.z, h.z).r;
  };
  CHECK(toward(grazing) > 3.0f * toward(head));
}

TEST_CASE("anisotropy: strength 0 is brdf's isotropic GGX, and the stretched D is normalised") {
  const glm::vec3 normal(0.0f, 0.0f, 1.0f), tangent(1.0f, 0.0f, 0.0f);
  for (float alpha : {0.01f, 0.1f, 0.36f, 1.0f})
    for (float nDotV : {0.1f, 0.6f, 1.0f})
      for (const glm::vec3& toLight : {glm::vec3(0.0f, 0.0f, 1.0f), glm::normalize(glm::vec3(-0.5f, 0.3f, 0.8f)),
                                       glm::normalize(glm::vec3(0.2f, -0.9f, 0.3f))}) {
        const glm::vec3 view = glm::normalize(glm::vec3(std::sqrt(1.0f - nDotV * nDotV), 0.2f, nDotV));
        const glm::vec3 h = glm::normalize(view + toLight);
        const float a2 = alpha * alpha, d = h.z * h.z * (a2 - 1.0f) + 1.0f;
        const float isotropic = a2 / (kPi * d * d) * smithGgxVisibility(view.z, toLight.z, alpha);
        const float stretched = anisotropicSpecular(tangent, 0.0f, alpha, normal, view, toLight, h, view.z, toLight.z);
        CAPTURE(alpha);
        CAPTURE(nDotV);
        CHECK(stretched == doctest::Approx(isotropic).epsilon(1e-4));
      }
  // The integral of D(h) N.H over the hemisphere of h is 1.
  for (float strength : {0.0f, 0.5f, 1.0f}) {
    const float alpha = 0.25f, alphaT = anisotropyAlphaT(alpha, strength);
    const double total = integrateHemisphere(
        [&](const glm::vec3& h) { return double(anisotropicDistribution(alphaT, alpha, h.x, h.y, h.z) * h.z); }, 2048,
        512);
    CAPTURE(strength);
    CHECK(total == doctest::Approx(1.0).epsilon(0.01));
  }
}

TEST_CASE("anisotropy: the reference's stretched sampler estimates the lobe's albedo") {
  // With F = 1 the lobe's albedo is the integral of D Vis N.L; the
  // reference's estimator draws h with density D N.H and weighs each
  // reflected direction by 4 Vis V.H N.L / N.H (tracer.cpp).
  const float alpha = 0.2f, nDotV = 0.7f;
  const glm::vec3 view = viewAt(nDotV), normal(0.0f, 0.0f, 1.0f), tangent(1.0f, 0.0f, 0.0f);
  for (float strength : {0.3f, 0.9f}) {
    const float alphaT = anisotropyAlphaT(alpha, strength);
    const double integrated = integrateHemisphere(
        [&](const glm::vec3& l) {
          const glm::vec3 h = glm::normalize(l + view);
          return double(anisotropicSpecular(tangent, strength, alpha, normal, view, l, h, nDotV, l.z) * l.z);
        },
        2048, 512);
    Pcg32 random(1234u, 5u);
    const int count = 200000;
    double sum = 0.0;
    for (int i = 0; i < count; ++i) {
      const glm::vec3 h = importanceSampleAnisotropicGgx(random.uniform(), random.uniform(), alphaT, alpha);
      const glm::vec3 l = 2.0f * glm::dot(view, h) * h - view;
      if (l.z <= 0.0f) continue;
      const float visibility = anisotropicVisibility(alphaT, alpha, view, l);
      sum += 4.0 * visibility * glm::dot(view, h) * l.z / h.z;
    }
    CAPTURE(strength);
    CHECK(sum / count == doctest::Approx(integrated).epsilon(0.02));
  }
}

TEST_CASE("anisotropy: the ambient's stand-in roughness reflects about what the stretched lobe reflects") {
  // The renderer's split-sum table is isotropic: it is read at
  // anisotropicAlbedoRoughness. Against the integrated stretched lobe
  // (F = 1) that stand-in is within 0.15 (measured worst 0.13, roughness
  // 0.2, strength 0.9, N.V 1) and nearer than the material's own roughness.
  const glm::vec3 normal(0.0f, 0.0f, 1.0f), tangent(1.0f, 0.0f, 0.0f);
  auto isotropicAlbedo = [&](float roughness, const glm::vec3& view) {
    const float alpha = roughness * roughness;
    return integrateHemisphere([&](const glm::vec3& l) {
      const glm::vec3 h = glm::normalize(l + view);
      const float a2 = alpha * alpha, d = h.z * h.z * (a2 - 1.0f) + 1.0f;
      return double(a2 / (kPi * d * d) * smithGgxVisibility(view.z, l.z, alpha) * l.z);
    });
  };
  for (float roughness : {0.2f, 0.4f, 0.6f})
    for (float strength : {0.5f, 0.9f})
      for (float nDotV : {0.3f, 0.7f, 1.0f}) {
        const float across = std::sqrt(1.0f - nDotV * nDotV);
        const glm::vec3 view(0.6f * across, 0.8f * across, nDotV);
        const double stretched = integrateHemisphere([&](const glm::vec3& l) {
          const glm::vec3 h = glm::normalize(l + view);
          return double(anisotropicSpecular(tangent, strength, roughness * roughness, normal, view, l, h, nDotV, l.z) *
                        l.z);
        });
        const double standIn = isotropicAlbedo(anisotropicAlbedoRoughness(roughness, strength), view);
        const double material = isotropicAlbedo(roughness, view);
        CAPTURE(roughness);
        CAPTURE(strength);
        CAPTURE(nDotV);
        CHECK(std::abs(standIn - stretched) < 0.15);
        CHECK(std::abs(standIn - stretched) < std::abs(material - stretched));
      }
}
