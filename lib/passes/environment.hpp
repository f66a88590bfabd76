#pragma once
// The tables image-based ambient light reads, computed on the GPU once:
//  - the split-sum BRDF table (Karis 2013): 64 x 64 RG16F, (N.V, roughness)
//    -> (scale, bias) of F0; once per renderer, with the first tables made;
//  - the prefiltered sky: 64 x kSkyRoughnessLevels RGBA16F, (direction.y,
//    roughness) -> GGX-filtered radiance. The sky depends only on the
//    direction's height, so a 2D table holds what a cube map would;
//  - the sky's irradiance: 64 x 1 RGBA16F, normal.y -> E / pi (the radiance a
//    white Lambertian surface reflects).
// Both sky tables are recomputed only when the sky changes.
// With an environment map (Scene::environment) the sky's tables are not
// made; instead the map's: its GGX-prefiltered levels (a 2D array, one layer
// a roughness level), its irradiance over pi and the map itself (the
// background), prefiltered on the CPU (environment/environment_prefilter.hpp)
// once per map content: a batch of scenes with the same map reuses them.
// The GPU tables are fullscreen passes (glsl/brdf_lut.glsl,
// sky_prefilter.glsl, sky_irradiance.glsl), in either form.
#include <optional>
#include <string>
#include <variant>

#include "gl/objects.hpp"
#include "headlight/scene.hpp"
#include "passes/fullscreen.hpp"

namespace headlight {

struct EnvironmentTables {
  gl::Texture brdfLut;
  gl::Texture skyPrefiltered;
  gl::Texture skyIrradiance;
  // Only while an environment map is held (updateEnvironment):
  gl::Texture environmentSpecular;    // 128 x 64 x 8 layers RGBA16F, equirectangular, layer = roughness level
  gl::Texture environmentIrradiance;  // 64 x 32 RGBA16F, equirectangular, E / pi
  gl::Texture environmentBackground;  // the map as given, RGBA16F
};

// Binds what ambient.glsl reads for a variant with the sky term (`sky`) and
// with an environment map (`environment`, whose tables then stand in for
// the sky's): the composite's and the blend pass's.
void bindAmbientTables(const EnvironmentTables& tables, bool sky, bool environment);

class EnvironmentPass {
 public:
  EnvironmentPass();  // allocates the tables; programs are built on first use
  // The BRDF table, made once (every pass that reads the split sum needs it:
  // the composite's sky term, transmission's throughput, the blend pass).
  bool hasBrdfTable() const { return brdfMade_; }
  void makeBrdfTable(PassForm form);
  // Recomputes the sky tables if the sky's colours changed.
  void updateSky(const Sky& sky, PassForm form);
  bool holds(const Sky& sky) const;  // the sky tables are this sky's (intensity aside)
  const EnvironmentTables& tables() const { return tables_; }
  // Prefilters and uploads the map's tables unless they are this map's
  // (same content hash) already.
  void updateEnvironment(const EnvironmentMap& map);
  bool holdsEnvironment(const EnvironmentMap& map) const { return environmentHash_ == map.sourceHash; }
  void dropEnvironment();  // a scene without a map: its textures are released

 private:
  // One table's fullscreen pass: the body's one output, no variants.
  class TablePass : FullscreenPass<std::monostate> {
   public:
    explicit TablePass(std::string_view body)
        : FullscreenPass(body, [](const std::monostate&) { return std::vector<std::string>{}; }) {}
    void run(std::string_view what, std::string_view member, const gl::Texture& table, PassForm form) {
      const PassOutput outputs[] = {{member, &table}};
      FullscreenPass::run(what, {}, form, outputs);
    }
  };

  TablePass brdfPass_{"brdf_lut.glsl"};
  TablePass prefilterPass_{"sky_prefilter.glsl"};
  TablePass irradiancePass_{"sky_irradiance.glsl"};
  bool brdfMade_ = false;
  gl::Buffer skyBlock_;
  EnvironmentTables tables_;
  std::optional<Sky> tabulatedSky_;  // the colours the sky tables hold
  std::string environmentHash_;      // the map the environment tables hold; empty: none
};

}  // namespace headlight
