// KHR_materials_iridescence without a GL context: the thin-film Fresnel's
// CPU port (lib/reference/lobe_iridescence.hpp, the port of
// glsl/lobe_iridescence.glsl; tests/iridescence_parity_tests.cpp holds the
// GPU to it) has the properties the specification's model must have, and
// the frame plan gives the lobe its attachment and target only when a
// material has the extension.
#include <doctest/doctest.h>

#include <algorithm>
#include <iterator>
#include <cmath>

#include "frame/frame_plan.hpp"
#include "headlight/scene_builder.hpp"
#include "headlight/targets.hpp"
#include "reference/shading.hpp"
#include "support/colour.hpp"
#include "support/plan_settings.hpp"

using namespace headlight;
using headlight::test::chroma;
using headlight::test::dominantChannel;
using reference::thinFilmFresnel;

namespace {

const glm::vec3 kGreyMetal(0.4f);  // IridescenceSuzanne's base colour

}  // namespace

TEST_CASE("a film of thickness 0 leaves the base's reflectance") {
  // The specification fades the film's IOR to the outside's as the
  // thickness goes to 0: at normal incidence what is left is the base's F0,
  // plus the m > 0 terms' residue through the clamped r123 (sqrt(1e-5)).
  const float dielectricF0 = reference::thinFilmIorToFresnel0(1.5f, 1.0f);
  for (const glm::vec3 base : {glm::vec3(dielectricF0), kGreyMetal, glm::vec3(0.9f, 0.6f, 0.2f)}) {
    const glm::vec3 film = thinFilmFresnel(1.0f, 1.33f, 1.0f, 0.0f, base);
    for (int c = 0; c < 3; ++c) CHECK(std::abs(film[c] - base[c]) < 0.01f);
  }
}

TEST_CASE("a thin film colours the reflection, and the colour turns with the view angle") {
  // 400 nm of IOR 1.33 (IridescenceSuzanne's film) on a grey metal: the
  // reflectance is far from grey, and its dominant hue at normal incidence,
  // at 45 degrees and at grazing angles is not one hue.
  int dominantSeen[3] = {0, 0, 0};
  for (const float cosTheta : {1.0f, 0.7f, 0.3f}) {
    const glm::vec3 film = thinFilmFresnel(1.0f, 1.33f, cosTheta, 400.0f, kGreyMetal);
    CAPTURE(cosTheta);
    CHECK(chroma(film) > 0.4f);
    ++dominantSeen[dominantChannel(film)];
  }
  CHECK(std::count(std::begin(dominantSeen), std::end(dominantSeen), 0) <= 1);
  // And with the thickness, at one angle.
  const glm::vec3 thinner = thinFilmFresnel(1.0f, 1.33f, 1.0f, 250.0f, kGreyMetal);
  const glm::vec3 thicker = thinFilmFresnel(1.0f, 1.33f, 1.0f, 400.0f, kGreyMetal);
  CHECK(dominantChannel(thinner) != dominantChannel(thicker));
}

TEST_CASE("a thick film's interference averages out to grey") {
  // At 5 um the Fourier terms' Gaussian envelopes vanish: what is left is
  // the incoherent sum, the same in every channel for a grey base.
  for (const float cosTheta : {1.0f, 0.5f, 0.1f}) {
    const glm::vec3 film = thinFilmFresnel(1.0f, 1.33f, cosTheta, 5000.0f, kGreyMetal);
    CAPTURE(cosTheta);
    CHECK(chroma(film) < 1e-3f);
  }
  // kMaxFilmThicknessNm: past it the film reflects what it does at it.
  const glm::vec3 atLimit = reference::iridescenceFresnel({1.0f, reference::kMaxFilmThicknessNm, 1.33f, 1.5f},
                                                          glm::vec3(0.5f), 0.0f, 0.8f);
  const glm::vec3 beyond = reference::iridescenceFresnel({1.0f, 1e9f, 1.33f, 1.5f}, glm::vec3(0.5f), 0.0f, 0.8f);
  CHECK(atLimit == beyond);
}

TEST_CASE("the thin-film Fresnel is finite and non-negative over its inputs") {
  // Rec.709 of a saturated spectral reflectance can leave the gamut: a
  // channel may exceed 1 (up to 1.28 on this sweep), but never goes below 0
  // (the specification's final max) or to NaN.
  int values = 0, nonFinite = 0, negative = 0;
  float largest = 0.0f;
  for (float thickness = 0.0f; thickness <= 3000.0f; thickness += 37.0f)
    for (float cosTheta = 1e-4f; cosTheta <= 1.0f; cosTheta += 0.049f)
      for (float filmIor = 1.0f; filmIor <= 2.6f; filmIor += 0.2f)
        for (float f0 = 0.0f; f0 <= 1.0f; f0 += 0.1f) {
          const glm::vec3 film = thinFilmFresnel(1.0f, filmIor, cosTheta, thickness, glm::vec3(f0));
          for (int c = 0; c < 3; ++c) {
            ++values;
            nonFinite += !std::isfinite(film[c]);
            negative += film[c] < 0.0f;
            largest = std::max(largest, film[c]);
          }
        }
  CHECK(values > 100000);
  CHECK(nonFinite == 0);
  CHECK(negative == 0);
  CHECK(largest < 1.5f);
}

TEST_CASE("the metal and dielectric films mix by metallic") {
  const reference::IridescenceInputs inputs{1.0f, 400.0f, 1.33f, 2.0f};
  const glm::vec3 albedo(0.9f, 0.6f, 0.2f);
  const glm::vec3 dielectric = thinFilmFresnel(1.0f, 1.33f, 0.8f, 400.0f, glm::vec3(1.0f / 9.0f));  // ior 2: F0 1/9
  const glm::vec3 metal = thinFilmFresnel(1.0f, 1.33f, 0.8f, 400.0f, albedo);
  const glm::vec3 none = reference::iridescenceFresnel(inputs, albedo, 0.0f, 0.8f);
  const glm::vec3 full = reference::iridescenceFresnel(inputs, albedo, 1.0f, 0.8f);
  const glm::vec3 half = reference::iridescenceFresnel(inputs, albedo, 0.5f, 0.8f);
  for (int c = 0; c < 3; ++c) {
    CHECK(none[c] == doctest::Approx(dielectric[c]).epsilon(1e-5));
    CHECK(full[c] == doctest::Approx(metal[c]).epsilon(1e-5));
    CHECK(half[c] == doctest::Approx(0.5f * (dielectric[c] + metal[c])).epsilon(1e-5));
  }
}

TEST_CASE("strength 0 is no film: Schlick's Fresnel alone, to the bit") {
  const reference::Surface plain =
      reference::makeSurface({0.8f, 0.5f, 0.2f}, 0.3f, 0.4f, {0.0f, 1.0f, 0.0f}, glm::normalize(glm::vec3(0.3f, 1, 0.2f)));
  reference::Surface unfilmed = plain;
  reference::applyLobe(unfilmed, Lobe::Iridescence, {0.0f, 400.0f, 1.33f, 1.5f});
  reference::Surface filmed = plain;
  reference::applyLobe(filmed, Lobe::Iridescence, {1.0f, 400.0f, 1.33f, 1.5f});
  const glm::vec3 toLight = glm::normalize(glm::vec3(-0.2f, 1.0f, 0.1f));
  CHECK(reference::cookTorrance(unfilmed, toLight) == reference::cookTorrance(plain, toLight));
  CHECK(reference::cookTorrance(filmed, toLight) != reference::cookTorrance(plain, toLight));
}

namespace {

bool hasDefine(const std::vector<std::string>& defines, std::string_view name) {
  return std::find(defines.begin(), defines.end(), name) != defines.end();
}

}  // namespace

TEST_CASE("frame plan: the iridescence lobe's attachment and target exist only when a material has the extension") {
  Scene scene;
  addMaterial(scene, makeMaterial({0.5f, 0.5f, 0.5f}, 0.5f));
  const FramePlan without = planFrame(summarizeScene(scene), test::resolvedPlanSettings(), {});
  CHECK(!without.allocates(lobeAttachment(Lobe::Iridescence)));
  CHECK(!hasDefine(without.gbuffer.defines, "HAS_IRIDESCENCE_LOBE"));
  CHECK(std::none_of(without.reads.begin(), without.reads.end(),
                     [](const TargetRead& read) { return read.target->name == "iridescence"; }));

  Material filmed = makeMaterial({0.5f, 0.5f, 0.5f}, 0.5f);
  filmed.iridescence = MaterialIridescence{};
  addMaterial(scene, filmed);
  const SceneSummary summary = summarizeScene(scene);
  CHECK(summary.lobes == lobeBit(Lobe::Iridescence));
  const FramePlan with = planFrame(summary, test::resolvedPlanSettings(), {});
  CHECK(with.allocates(lobeAttachment(Lobe::Iridescence)));
  CHECK(with.formatOf(lobeAttachment(Lobe::Iridescence)) == GpuFormat::Rgba16F);
  CHECK(hasDefine(with.gbuffer.defines, "HAS_IRIDESCENCE_LOBE"));
  CHECK(hasDefine(with.gbuffer.defines, "HAS_IRIDESCENCE_TARGET"));
  // After position, normal, albedo and material: location 4 (no emission).
  CHECK(hasDefine(with.gbuffer.defines, "IRIDESCENCE_TARGET_LOCATION 4"));
  REQUIRE(with.direct);
  REQUIRE(with.composite);
  CHECK(with.direct->lobes == lobeBit(Lobe::Iridescence));
  CHECK(with.composite->lobes == lobeBit(Lobe::Iridescence));
  const auto read = std::find_if(with.reads.begin(), with.reads.end(),
                                 [](const TargetRead& r) { return r.target->name == "iridescence"; });
  REQUIRE(read != with.reads.end());
  CHECK(read->sources == std::vector<Attachment>{lobeAttachment(Lobe::Iridescence)});
  CHECK(read->channels ==
        std::vector<std::string>{"iridescence.factor", "iridescence.thickness", "iridescence.ior", "iridescence.baseIor"});
  // An unlit material's film would change nothing: no lobe.
  Scene unlit;
  filmed.unlit = true;
  addMaterial(unlit, filmed);
  CHECK(summarizeScene(unlit).lobes == 0);
}

TEST_CASE("the film stays finite at the loader's extremes") {
  // What loading lets through (gltf/material_extensions.cpp refuses NaN, IORs
  // below 1 and negative thicknesses): a base IOR of 0 (glTF's "F0 = 1",
  // kept as 0), huge film IORs and thicknesses.
  for (const reference::IridescenceInputs film :
       {reference::IridescenceInputs{1.0f, 400.0f, 1.33f, 0.0f}, reference::IridescenceInputs{1.0f, 400.0f, 1e30f, 1.5f},
        reference::IridescenceInputs{1.0f, 1e30f, 1.33f, 1.5f}, reference::IridescenceInputs{1.0f, 0.0f, 1.0f, 1.0f},
        reference::IridescenceInputs{1.0f, 3e38f, 3e38f, 3e38f}})
    for (const float metallic : {0.0f, 0.5f, 1.0f})
      for (const float nDotV : {1e-4f, 0.5f, 1.0f, 1.0001f}) {
        const glm::vec3 fresnel = reference::iridescenceFresnel(film, glm::vec3(1.0f, 0.5f, 0.0f), metallic, nDotV);
        CAPTURE(film.filmIor);
        CAPTURE(film.thicknessNm);
        CAPTURE(film.baseIor);
        CAPTURE(metallic);
        CAPTURE(nDotV);
        for (int c = 0; c < 3; ++c) {
          CHECK(std::isfinite(fresnel[c]));
          CHECK(fresnel[c] >= 0.0f);
        }
      }
}
