#pragma once
// The environment map's lighting tables, computed once per map on the CPU
// (docs/PIPELINE.md §2.6 says why the CPU): the same two quantities the
// procedural sky's 2D tables hold, now direction-dependent, so each is an
// equirectangular image (environment/equirect.hpp's layout):
//  - specular: kEnvironmentRoughnessLevels images of kEnvironmentSpecularWidth
//    x kEnvironmentSpecularHeight, the map filtered by GGX lobes (N = V = R,
//    weighted by N.L, as sky_prefilter.frag), level k at roughness k / (levels - 1);
//  - irradiance over pi: kEnvironmentIrradianceWidth x Height, the
//    cosine-weighted mean radiance around each normal (sky_irradiance.frag),
//    its first and last rows at the poles (EquirectImage::poleRows).
// Both are in map space; the renderer turns lookups by the rotation.
#include <vector>

#include "environment/equirect.hpp"
#include "headlight/scene.hpp"

namespace headlight::environment {

inline constexpr int kEnvironmentRoughnessLevels = 8;  // as the sky's kSkyRoughnessLevels: roughness 0, 1/7, ..., 1
inline constexpr int kEnvironmentSpecularWidth = 128;  // 2.8 degrees a texel: below roughness ~0.1's lobe
inline constexpr int kEnvironmentSpecularHeight = 64;
inline constexpr int kEnvironmentIrradianceWidth = 64;  // a cosine lobe is smooth; 64 x 32 keeps bilinear error < 0.5%
inline constexpr int kEnvironmentIrradianceHeight = 32;
// Per texel and level, each read from a mip chain (filtered importance sampling).
inline constexpr int kEnvironmentSpecularSamples = 64;

struct EnvironmentTables {
  std::vector<EquirectImage> specular;  // kEnvironmentRoughnessLevels images
  EquirectImage irradianceOverPi;
};

// `map` must be a valid EnvironmentMap (width = 2 x height, finite, >= 0).
EnvironmentTables prefilterEnvironment(const EnvironmentMap& map);

// The map as an EquirectImage (a copy of its texels).
EquirectImage equirectOf(const EnvironmentMap& map);

// E / pi at `normal` (map space) from the table, bilinear as the GPU reads it.
inline glm::vec3 irradianceOverPiAt(const EnvironmentTables& tables, const glm::vec3& normal) {
  return tables.irradianceOverPi.lookup(normal);
}

}  // namespace headlight::environment
