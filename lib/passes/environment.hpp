#pragma once
// The tables image-based ambient light reads, computed on the GPU once:
//  - the split-sum BRDF table (Karis 2013): 64 x 64 RG16F, (N.V, roughness)
//    -> (scale, bias) of F0; once per renderer;
//  - the prefiltered sky: 64 x kSkyRoughnessLevels RGBA16F, (direction.y,
//    roughness) -> GGX-filtered radiance. The sky depends only on the
//    direction's height, so a 2D table holds what a cube map would;
//  - the sky's irradiance: 64 x 1 RGBA16F, normal.y -> E / pi (the radiance a
//    white Lambertian surface reflects).
// Both sky tables are recomputed only when the sky changes.
#include <optional>

#include "gl/objects.hpp"
#include "headlight/scene.hpp"
#include "passes/fullscreen.hpp"

namespace headlight {

struct EnvironmentTables {
  gl::Texture brdfLut;
  gl::Texture skyPrefiltered;
  gl::Texture skyIrradiance;
};

class EnvironmentPass {
 public:
  EnvironmentPass();                 // builds the programs and the BRDF table
  void updateSky(const Sky& sky);    // recomputes the sky tables if the sky's colours changed
  bool holds(const Sky& sky) const;  // the sky tables are this sky's (intensity aside)
  const EnvironmentTables& tables() const { return tables_; }

 private:
  gl::Program brdfProgram_;
  gl::Program prefilterProgram_;
  gl::Program irradianceProgram_;
  gl::Buffer skyBlock_;
  FullscreenDraw draw_;
  EnvironmentTables tables_;
  std::optional<Sky> tabulatedSky_;  // the colours the sky tables hold
};

}  // namespace headlight
