#include "passes/environment.hpp"

#include <algorithm>
#include <cmath>
#include <span>

#include "environment/environment_prefilter.hpp"
#include "shared_layout.h"

namespace headlight {

EnvironmentPass::EnvironmentPass() : skyBlock_(gl::Buffer::create(sizeof(gpu::SkyBlock))) {
  tables_.brdfLut = gl::Texture::create2D(GL_RG16F, gpu::kBrdfLutSize, gpu::kBrdfLutSize);
  tables_.skyPrefiltered = gl::Texture::create2D(GL_RGBA16F, gpu::kSkyTableWidth, gpu::kSkyRoughnessLevels);
  tables_.skyIrradiance = gl::Texture::create2D(GL_RGBA16F, gpu::kSkyTableWidth, 1);
  for (const gl::Texture* table : {&tables_.brdfLut, &tables_.skyPrefiltered, &tables_.skyIrradiance}) {
    glTextureParameteri(table->id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(table->id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(table->id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(table->id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  }
}

void EnvironmentPass::makeBrdfTable(PassForm form) {
  if (brdfMade_) return;
  brdfPass_.run("BRDF table", "scaleBias", tables_.brdfLut, form);
  brdfMade_ = true;
}

bool EnvironmentPass::holds(const Sky& sky) const {
  // Intensity is applied in the composite pass, so a changed intensity
  // needs no new table.
  return tabulatedSky_ && tabulatedSky_->zenith == sky.zenith && tabulatedSky_->horizon == sky.horizon &&
         tabulatedSky_->ground == sky.ground;
}

void EnvironmentPass::updateSky(const Sky& sky, PassForm form) {
  if (holds(sky)) return;
  tabulatedSky_ = sky;
  gpu::SkyBlock block{glm::vec4(sky.zenith, 0.0f), glm::vec4(sky.horizon, 0.0f), glm::vec4(sky.ground, 0.0f)};
  skyBlock_.update(block);
  skyBlock_.bindUniform(gpu::SkyBlock::kBinding);
  prefilterPass_.run("prefiltered sky table", "radiance", tables_.skyPrefiltered, form);
  irradiancePass_.run("sky irradiance table", "irradianceOverPi", tables_.skyIrradiance, form);
}

namespace {

// Equirectangular lookups: bilinear, around in azimuth, clamped at the poles.
void setEquirectSampling(const gl::Texture& texture) {
  glTextureParameteri(texture.id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTextureParameteri(texture.id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(texture.id(), GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTextureParameteri(texture.id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

// Half float where it holds the map, else float: a texel above half's
// largest value (65504; the sun in an unclipped HDRI is brighter) became inf
// in a half texture and NaN in what it lit, whatever radiance-precision
// asked for (issue 32).
GLenum equirectFormat(std::span<const float> values) {
  const bool fitsHalf = std::all_of(values.begin(), values.end(), [](float v) { return std::abs(v) <= 65504.0f; });
  return fitsHalf ? GL_RGBA16F : GL_RGBA32F;
}

gl::Texture uploadEquirect(const environment::EquirectImage& image) {
  gl::Texture texture = gl::Texture::create2D(equirectFormat(image.rgb), image.width, image.height);
  glTextureSubImage2D(texture.id(), 0, 0, 0, image.width, image.height, GL_RGB, GL_FLOAT, image.rgb.data());
  setEquirectSampling(texture);
  return texture;
}

}  // namespace

void EnvironmentPass::updateEnvironment(const EnvironmentMap& map) {
  if (holdsEnvironment(map)) return;
  const environment::EnvironmentTables prefiltered = environment::prefilterEnvironment(map);
  const environment::EquirectImage& level0 = prefiltered.specular.front();
  bool specularFitsHalf = true;
  for (const environment::EquirectImage& level : prefiltered.specular)
    specularFitsHalf = specularFitsHalf && equirectFormat(level.rgb) == GL_RGBA16F;
  tables_.environmentSpecular = gl::Texture::create2DArray(specularFitsHalf ? GL_RGBA16F : GL_RGBA32F, level0.width,
                                                           level0.height, int(prefiltered.specular.size()));
  for (std::size_t layer = 0; layer < prefiltered.specular.size(); ++layer)
    glTextureSubImage3D(tables_.environmentSpecular.id(), 0, 0, 0, GLint(layer), level0.width, level0.height, 1, GL_RGB,
                        GL_FLOAT, prefiltered.specular[layer].rgb.data());
  setEquirectSampling(tables_.environmentSpecular);
  tables_.environmentIrradiance = uploadEquirect(prefiltered.irradianceOverPi);
  tables_.environmentBackground = uploadEquirect(environment::equirectOf(map));
  environmentHash_ = map.sourceHash;
}

void EnvironmentPass::dropEnvironment() {
  tables_.environmentSpecular = gl::Texture();
  tables_.environmentIrradiance = gl::Texture();
  tables_.environmentBackground = gl::Texture();
  environmentHash_.clear();
}

void bindAmbientTables(const EnvironmentTables& tables, bool sky, bool environment) {
  if (environment) {
    tables.environmentSpecular.bind(gpu::kUnitEnvironmentSpecular);
    tables.environmentIrradiance.bind(gpu::kUnitEnvironmentIrradiance);
    tables.environmentBackground.bind(gpu::kUnitEnvironmentBackground);
  }
  if (sky) tables.brdfLut.bind(gpu::kUnitBrdfLut);
  if (sky && !environment) {
    tables.skyPrefiltered.bind(gpu::kUnitSkyPrefiltered);
    tables.skyIrradiance.bind(gpu::kUnitSkyIrradiance);
  }
}

}  // namespace headlight
