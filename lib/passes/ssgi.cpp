#include "passes/ssgi.hpp"

#include <cmath>
#include <random>

#include "gl/shader_library.hpp"
#include "headlight/error.hpp"
#include "shared_layout.h"

namespace headlight {
namespace {

// Uniform in [0, 1) from the top 24 bits: std::uniform_real_distribution's
// output is not specified across standard libraries, this is.
float uniform01(std::mt19937& rng) { return float(rng() >> 8) * (1.0f / 16777216.0f); }

}  // namespace

std::vector<glm::vec3> makeSsgiKernel(int sampleCount, unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<glm::vec3> kernel;
  kernel.reserve(std::size_t(sampleCount));
  for (int i = 0; i < sampleCount; ++i) {
    // Malley's method: a uniform point on the unit disc lifted to the
    // hemisphere gives directions with density cos(theta) / pi.
    const float u1 = uniform01(rng), u2 = uniform01(rng), u3 = uniform01(rng);
    const float discRadius = std::sqrt(u1), phi = 6.2831853f * u2;
    const glm::vec3 direction(discRadius * std::cos(phi), discRadius * std::sin(phi), std::sqrt(1.0f - u1));
    const float t = float(i) / float(sampleCount);
    const float scale = 0.1f + 0.9f * t * t;  // lerp(0.1, 1.0, t^2)
    kernel.push_back(direction * (u3 * scale));
  }
  return kernel;
}

std::array<glm::vec2, 16> makeSsgiNoise(unsigned seed) {
  std::mt19937 rng(seed ^ 0x9e3779b9u);  // not the kernel's stream
  std::array<glm::vec2, 16> noise;
  for (auto& rotation : noise) {
    const float angle = 6.2831853f * uniform01(rng);
    rotation = glm::vec2(std::cos(angle), std::sin(angle));
  }
  return noise;
}

SsgiPass::SsgiPass()
    : block_(sizeof(gpu::SsgiBlock), nullptr), noise_(GL_TEXTURE_2D, GL_RG16F, 4, 4) {
  const GLenum drawBuffers[] = {GL_COLOR_ATTACHMENT0};
  framebuffer_.setDrawBuffers(drawBuffers);
}

const gl::Program& SsgiPass::programFor(SsgiMethod method) {
  auto found = programs_.find(method);
  if (found != programs_.end()) return found->second;
  std::vector<std::string> defines;
  if (method == SsgiMethod::Radiance) defines.emplace_back("METHOD_RADIANCE");
  const std::string_view files[] = {"fullscreen.vert", "ssgi.frag"};
  return programs_.emplace(method, detail::buildProgram(files, defines)).first->second;
}

void SsgiPass::updateKernel(const SsgiSettings& settings) {
  if (settings.sampleCount == kernelSampleCount_ && settings.seed == kernelSeed_) return;
  gpu::SsgiBlock block{};
  const auto kernel = makeSsgiKernel(settings.sampleCount, settings.seed);
  for (std::size_t i = 0; i < kernel.size(); ++i) block.kernel[i] = glm::vec4(kernel[i], 0.0f);
  block_.update(&block, sizeof(block.kernel));
  const auto noise = makeSsgiNoise(settings.seed);
  glTextureSubImage2D(noise_.id(), 0, 0, 0, 4, 4, GL_RG, GL_FLOAT, noise.data());
  kernelSampleCount_ = settings.sampleCount;
  kernelSeed_ = settings.seed;
}

void SsgiPass::run(const GBuffer& gbuffer, const gl::Texture* directDiffuse, const gl::Texture& output,
                   const SsgiSettings& settings) {
  updateKernel(settings);
  const glm::vec4 params(*settings.radius, *settings.bias, settings.intensity, *settings.indirectStrength);
  const glm::ivec4 counts(settings.sampleCount, ssgiDivisor(settings.resolution), 0, 0);
  block_.update(&params, sizeof(params), offsetof(gpu::SsgiBlock, params));
  block_.update(&counts, sizeof(counts), offsetof(gpu::SsgiBlock, counts));

  framebuffer_.attach(GL_COLOR_ATTACHMENT0, output);
  framebuffer_.checkComplete("SSGI");
  framebuffer_.bind();
  glViewport(0, 0, output.width(), output.height());
  // Background pixels are discarded by the shader and keep this: open, no
  // indirect light.
  const float clear[] = {1.0f, 0.0f, 0.0f, 0.0f};
  glClearNamedFramebufferfv(framebuffer_.id(), GL_COLOR, 0, clear);
  glDisable(GL_DEPTH_TEST);

  gbuffer.position.bind(gpu::kUnitGbufferPosition);
  gbuffer.normal.bind(gpu::kUnitGbufferNormal);
  gbuffer.albedo.bind(gpu::kUnitGbufferAlbedo);
  noise_.bind(gpu::kUnitSsgiNoise);
  if (settings.method == SsgiMethod::Radiance) {
    if (directDiffuse == nullptr) throw GlError("SSGI radiance method: no direct-light diffuse target");
    gbuffer.material.bind(gpu::kUnitGbufferMaterial);
    directDiffuse->bind(gpu::kUnitDirectDiffuse);
  }
  block_.bindUniform(gpu::SsgiBlock::kBinding);
  programFor(settings.method).use();
  emptyVertexArray_.bind();
  glDrawArrays(GL_TRIANGLES, 0, 3);
  framebuffer_.detach(GL_COLOR_ATTACHMENT0);
}

}  // namespace headlight
