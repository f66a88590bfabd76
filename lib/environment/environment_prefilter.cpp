// The environment map's specular and irradiance tables (environment_prefilter.hpp).
#include "environment/environment_prefilter.hpp"

#include <algorithm>
#include <cmath>
#include <thread>

namespace headlight::environment {
namespace {

// Van der Corput radical inverse: the second Hammersley coordinate.
float radicalInverse(unsigned bits) {
  bits = (bits << 16u) | (bits >> 16u);
  bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
  bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
  bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
  bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
  return float(bits) * 2.3283064365386963e-10f;
}

// An orthonormal frame whose third axis is `n` (Frisvad's, branch-free sign).
glm::mat3 frameAround(const glm::vec3& n) {
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z), b = n.x * n.y * a;
  return {glm::vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x), glm::vec3(b, sign + n.y * n.y * a, -n.y),
          n};
}

// The map's mip chain down to 4 x 2, each level area-preserving.
std::vector<EquirectImage> mipChain(const EquirectImage& base) {
  std::vector<EquirectImage> chain{base};
  while (chain.back().height > 2)
    chain.push_back(resampleEquirect(chain.back(), chain.back().width / 2, chain.back().height / 2));
  return chain;
}

glm::vec3 trilinear(const std::vector<EquirectImage>& chain, const glm::vec2& uv, float lod) {
  lod = std::clamp(lod, 0.0f, float(chain.size() - 1));
  const int low = int(lod);
  const int high = std::min(low + 1, int(chain.size()) - 1);
  return glm::mix(chain[std::size_t(low)].bilinear(uv), chain[std::size_t(high)].bilinear(uv), lod - float(low));
}

// One GGX sample of a level, in the frame around R (N = V = R = +Z): the
// light direction, its N.L weight and the mip level it reads. The same for
// every texel of the level, so computed once.
struct LobeSample {
  glm::vec3 light;
  float nDotL;
  float lod;
};

std::vector<LobeSample> lobeSamples(float roughness, float baseTexelSolidAngle) {
  const float alpha = std::max(roughness * roughness, 1e-4f);
  const int sampleCount = kEnvironmentSpecularSamples;
  std::vector<LobeSample> samples;
  for (int i = 0; i < sampleCount; ++i) {
    const float xi0 = (float(i) + 0.5f) / float(sampleCount), xi1 = radicalInverse(unsigned(i));
    const float cosH = std::sqrt((1.0f - xi1) / (1.0f + (alpha * alpha - 1.0f) * xi1));
    const float sinH = std::sqrt(std::max(0.0f, 1.0f - cosH * cosH)), phi = 2.0f * kPi * xi0;
    const glm::vec3 h(sinH * std::cos(phi), sinH * std::sin(phi), cosH);
    const glm::vec3 l = 2.0f * cosH * h - glm::vec3(0.0f, 0.0f, 1.0f);  // reflect(-R, H)
    if (l.z <= 0.0f) continue;
    // pdf(L) = D(H) N.H / (4 V.H) = D / 4 with N = V.
    const float d = alpha * alpha / (kPi * std::pow(cosH * cosH * (alpha * alpha - 1.0f) + 1.0f, 2.0f));
    const float sampleSolidAngle = 1.0f / (float(sampleCount) * d * 0.25f + 1e-8f);
    samples.push_back({glm::normalize(l), l.z, 0.5f * std::log2(sampleSolidAngle / baseTexelSolidAngle) + 1.0f});
  }
  return samples;
}

// One roughness level: each texel's direction R filtered by the GGX lobe
// around it (N = V = R), samples drawn from the mip level whose texels
// match the sample's share of the lobe (Karis 2013, filtered importance
// sampling), so 64 samples do not alias a bright texel.
void filterLevel(const std::vector<EquirectImage>& chain, std::span<const LobeSample> samples, EquirectImage& out,
                 int firstRow, int rowStep) {
  for (int y = firstRow; y < out.height; y += rowStep)
    for (int x = 0; x < out.width; ++x) {
      const glm::mat3 frame = frameAround(out.texelDirection(x, y));
      glm::vec3 sum(0.0f);
      float weight = 0.0f;
      for (const LobeSample& sample : samples) {
        sum += trilinear(chain, directionToUv(frame * sample.light), sample.lod) * sample.nDotL;
        weight += sample.nDotL;
      }
      const glm::vec3 value = sum / std::max(weight, 1e-7f);
      float* p = &out.rgb[(std::size_t(y) * std::size_t(out.width) + std::size_t(x)) * 3];
      p[0] = value.r, p[1] = value.g, p[2] = value.b;
    }
}

// E / pi around each texel's normal: sum over every source texel of L
// times its solid angle times the clamped cosine, divided by the same sum
// without L (which is pi up to quadrature error), so a uniform map gives
// exactly its radiance.
EquirectImage irradianceOverPi(const EquirectImage& source) {
  const EquirectImage coarse =
      resampleEquirect(source, kEnvironmentIrradianceWidth, kEnvironmentIrradianceHeight);
  std::vector<glm::vec3> directions;
  std::vector<float> solidAngles;
  for (int y = 0; y < coarse.height; ++y)
    for (int x = 0; x < coarse.width; ++x) {
      directions.push_back(
          uvToDirection((float(x) + 0.5f) / float(coarse.width), (float(y) + 0.5f) / float(coarse.height)));
      solidAngles.push_back(float(texelSolidAngle(y, coarse.width, coarse.height)));
    }
  // Rows at the poles (EquirectImage::poleRows): the irradiance there is
  // one value, which bilinear lookups near the pole then reach.
  EquirectImage out{coarse.width, coarse.height, std::vector<float>(coarse.rgb.size()), true};
  for (std::size_t o = 0; o < directions.size(); ++o) {
    const glm::vec3 normal = out.texelDirection(int(o % std::size_t(out.width)), int(o / std::size_t(out.width)));
    glm::dvec3 sum(0.0);
    double weight = 0.0;
    for (std::size_t i = 0; i < directions.size(); ++i) {
      const float w = solidAngles[i] * glm::dot(normal, directions[i]);
      if (w <= 0.0f) continue;
      const int x = int(i % std::size_t(coarse.width)), y = int(i / std::size_t(coarse.width));
      sum += glm::dvec3(coarse.texel(x, y)) * double(w);
      weight += w;
    }
    const glm::dvec3 value = sum / weight;
    for (int c = 0; c < 3; ++c) out.rgb[o * 3 + std::size_t(c)] = float(value[c]);
  }
  return out;
}

}  // namespace

EquirectImage equirectOf(const EnvironmentMap& map) { return {map.width, map.height, map.rgb}; }

EnvironmentTables prefilterEnvironment(const EnvironmentMap& map) {
  const EquirectImage source = equirectOf(map);
  EnvironmentTables tables;
  const std::vector<EquirectImage> chain =
      mipChain(resampleEquirect(source, kEnvironmentSpecularWidth, kEnvironmentSpecularHeight));
  tables.specular.push_back(chain.front());  // roughness 0: the map itself, at the table's size
  for (int level = 1; level < kEnvironmentRoughnessLevels; ++level) {
    EquirectImage out{kEnvironmentSpecularWidth, kEnvironmentSpecularHeight,
                      std::vector<float>(chain.front().rgb.size())};
    // Rows split over two threads (the reference machine's cores); each
    // writes its own rows.
    const float roughness = float(level) / float(kEnvironmentRoughnessLevels - 1);
    const std::vector<LobeSample> samples =
        lobeSamples(roughness, 4.0f * kPi / float(chain.front().width * chain.front().height));
    std::thread second([&] { filterLevel(chain, samples, out, 1, 2); });
    filterLevel(chain, samples, out, 0, 2);
    second.join();
    tables.specular.push_back(std::move(out));
  }
  tables.irradianceOverPi = irradianceOverPi(source);
  return tables;
}

}  // namespace headlight::environment
