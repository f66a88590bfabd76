#include "passes/light_field.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "gl/readback.hpp"
#include "gl/target_formats.hpp"
#include "passes/virtual_lights.hpp"

namespace headlight {
namespace {

constexpr float kPi = 3.14159265358979323846f;

// Texels per side of a probe's cube faces: 16 resolves a wall's edge to
// 6 degrees, and 64 probes draw 384 faces of 256 texels.
constexpr int kProbeFaceSize = 16;

// The moments' lobe about each octahedral texel's direction, cos^32 (half
// weight at 12 degrees, about the texel's half width): DDGI's depth
// sharpness, for 8 x 8 texels.
float momentWeight(float cosine) {
  if (cosine <= 0.0f) return 0.0f;
  float w = cosine;
  for (int i = 0; i < 5; ++i) w *= w;
  return w;
}

// Distances past which a texel is taken to see nothing (empty texels read as
// infinity).
float seenDistance(float distance, float farDistance) { return std::min(distance, farDistance); }

}  // namespace

glm::vec3 LightFieldGrid::probePosition(int index) const {
  const int x = index % counts.x, y = (index / counts.x) % counts.y, z = index / (counts.x * counts.y);
  return origin + spacing * glm::vec3(x, y, z);
}

LightFieldGrid lightFieldGrid(const Bounds& bounds, int budget) {
  LightFieldGrid grid;
  if (bounds.empty() || budget <= 0) return grid;
  const glm::vec3 size = bounds.size();
  const float diagonal = glm::length(size);
  if (!std::isfinite(diagonal) || diagonal <= 0.0f) return grid;
  // Probes on the cells' corners, the bounds' faces included (a floor's
  // irradiance is read at the floor, not half a cell above it, where a
  // light overhead is nearer); one layer, at the middle, along an axis the
  // scene is less than half a cell deep in.
  const auto countsAlong = [](float extent, float cell) {
    return extent < 0.5f * cell ? 1 : 1 + int(std::ceil(extent / cell));
  };
  const auto countsFor = [&](float cell) {
    return glm::ivec3(countsAlong(size.x, cell), countsAlong(size.y, cell), countsAlong(size.z, cell));
  };
  const auto fits = [&](float cell) {
    const glm::ivec3 c = countsFor(cell);
    return std::int64_t(c.x) * c.y * c.z <= std::int64_t(budget);
  };
  // The smallest cell whose grid fits the budget; the probe count falls as
  // the cell grows.
  float low = diagonal * 1e-4f, high = diagonal;
  if (fits(low)) high = low;
  for (int i = 0; i < 48 && high > low * 1.0001f; ++i) {
    const float middle = 0.5f * (low + high);
    (fits(middle) ? high : low) = middle;
  }
  // The outer probes stand kProbeInset of a cell inside the bounds, off
  // the surfaces that bound them (a probe in a wall sees nothing on its
  // far side). An axis with one layer keeps the cell's size as its
  // spacing: the shaders scale offsets by the smallest spacing, not by how
  // thin the scene is.
  constexpr float kProbeInset = 0.05f;
  grid.counts = countsFor(high);
  for (int axis = 0; axis < 3; ++axis) {
    if (grid.counts[axis] == 1) {
      grid.origin[axis] = bounds.center()[axis];
      grid.spacing[axis] = high;
    } else {
      const float inset = kProbeInset * high;
      grid.origin[axis] = bounds.min[axis] + inset;
      grid.spacing[axis] = (size[axis] - 2.0f * inset) / float(grid.counts[axis] - 1);
    }
  }
  return grid;
}

glm::vec2 octahedralFromDirection(const glm::vec3& direction) {
  glm::vec2 p = glm::vec2(direction) / (std::abs(direction.x) + std::abs(direction.y) + std::abs(direction.z));
  if (direction.z < 0.0f) {
    const glm::vec2 sign(p.x >= 0.0f ? 1.0f : -1.0f, p.y >= 0.0f ? 1.0f : -1.0f);
    p = (1.0f - glm::abs(glm::vec2(p.y, p.x))) * sign;
  }
  return p * 0.5f + 0.5f;
}

glm::vec3 directionFromOctahedral(const glm::vec2& uv) {
  const glm::vec2 p = uv * 2.0f - 1.0f;
  glm::vec3 n(p.x, p.y, 1.0f - std::abs(p.x) - std::abs(p.y));
  if (n.z < 0.0f) {
    const glm::vec2 sign(n.x >= 0.0f ? 1.0f : -1.0f, n.y >= 0.0f ? 1.0f : -1.0f);
    const glm::vec2 folded = (1.0f - glm::abs(glm::vec2(n.y, n.x))) * sign;
    n.x = folded.x;
    n.y = folded.y;
  }
  return glm::normalize(n);
}

float ProbeView::reachToward(const glm::vec3& point) const {
  const glm::vec3 offset = point - position;
  const glm::vec3 magnitude = glm::abs(offset);
  const int axis = magnitude.x >= magnitude.y && magnitude.x >= magnitude.z ? 0 : magnitude.y >= magnitude.z ? 1 : 2;
  const int face = 2 * axis + (offset[axis] < 0.0f ? 1 : 0);
  const glm::vec4 clip = clipFromWorld[std::size_t(face)] * glm::vec4(point, 1.0f);
  if (clip.w <= 0.0f) return 0.0f;
  const glm::vec2 ndc = glm::vec2(clip) / clip.w;
  const int x = std::clamp(int(std::floor((ndc.x * 0.5f + 0.5f) * float(size))), 0, size - 1);
  const int glRow = std::clamp(int(std::floor((ndc.y * 0.5f + 0.5f) * float(size))), 0, size - 1);
  const int y = size - 1 - glRow;  // rows top first
  float reach = 0.0f;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const int tx = std::clamp(x + dx, 0, size - 1), ty = std::clamp(y + dy, 0, size - 1);
      reach = std::max(reach, distances[std::size_t((face * size + ty) * size + tx)]);
    }
  return reach;
}

gpu::GpuLightProbe makeLightProbe(const ProbeView& view, std::span<const gpu::GpuVirtualLight> lights,
                                  float farDistance) {
  gpu::GpuLightProbe probe{};
  constexpr int kSide = gpu::kLightFieldMapSize;
  std::array<glm::vec3, kSide * kSide> mapDirections;
  for (int v = 0; v < kSide; ++v)
    for (int u = 0; u < kSide; ++u)
      mapDirections[std::size_t(v * kSide + u)] =
          directionFromOctahedral({(float(u) + 0.5f) / kSide, (float(v) + 0.5f) / kSide});

  // Irradiance, per texel's normal d: each virtual light the probe's view
  // reaches is a Lambertian patch of its texel's area A sending flux Phi,
  // arriving from one direction w: Phi cos_sender / (pi r^2 + A) max(d . w, 0).
  // A disc's form factor, A / (pi r^2 + A), keeps a patch next to the probe
  // finite (a point's, A / (pi r^2), is not). The cosine is exact per
  // texel: a probe beside a bright wall gets none of it on the normal
  // facing away (order-2 harmonics rang there: twice the light on the
  // wall behind builtin:slats).
  std::array<glm::vec3, kSide * kSide> irradiance{};
  for (const gpu::GpuVirtualLight& light : lights) {
    const glm::vec3 offset = glm::vec3(light.position) - view.position;
    const float distance = glm::length(offset);
    if (!(distance > 0.0f)) continue;
    const glm::vec3 toLight = offset / distance;
    const float cosSender = -glm::dot(glm::vec3(light.normal), toLight);
    if (cosSender <= 0.0f) continue;
    // Reached: nothing nearer along the way than 2 % short of the light.
    if (view.reachToward(glm::vec3(light.position)) < distance * 0.98f) continue;
    const glm::vec3 arriving = glm::vec3(light.flux) * (cosSender / (kPi * distance * distance + light.normal.w));
    for (std::size_t t = 0; t < mapDirections.size(); ++t)
      irradiance[t] += arriving * std::max(glm::dot(mapDirections[t], toLight), 0.0f);
  }
  for (std::size_t t = 0; t < irradiance.size(); ++t) probe.irradiance[t] = glm::vec4(irradiance[t], 0.0f);
  probe.irradiance[0].w = view.backFaceShare > ProbeView::kInsideShare ? 0.0f : 1.0f;

  // Moments: the distance to what each cube texel sees, weighed about each
  // map texel's direction.
  const int size = view.size;
  const std::size_t texels = view.distances.size();
  std::vector<glm::vec3> directions(texels);
  for (int face = 0; face < 6; ++face) {
    const glm::mat4 worldFromClip = glm::inverse(view.clipFromWorld[std::size_t(face)]);
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        const float u = (float(x) + 0.5f) / float(size) * 2.0f - 1.0f;
        const float v = (float(size - 1 - y) + 0.5f) / float(size) * 2.0f - 1.0f;
        const glm::vec4 point = worldFromClip * glm::vec4(u, v, 0.5f, 1.0f);
        directions[std::size_t((face * size + y) * size + x)] =
            glm::normalize(glm::vec3(point) / point.w - view.position);
      }
  }
  for (std::size_t m = 0; m < mapDirections.size(); ++m) {
    double weightSum = 0.0, mean = 0.0, meanSquare = 0.0;
    for (std::size_t t = 0; t < texels; ++t) {
      const float weight = momentWeight(glm::dot(mapDirections[m], directions[t]));
      if (weight <= 0.0f) continue;
      const double distance = seenDistance(view.distances[t], farDistance);
      weightSum += weight;
      mean += weight * distance;
      meanSquare += weight * distance * distance;
    }
    const glm::vec2 moments = weightSum > 0.0 ? glm::vec2(float(mean / weightSum), float(meanSquare / weightSum))
                                              : glm::vec2(farDistance, farDistance * farDistance);
    glm::vec4& pair = probe.moments[m / 2];
    if (m % 2 == 0) {
      pair.x = moments.x;
      pair.y = moments.y;
    } else {
      pair.z = moments.x;
      pair.w = moments.y;
    }
  }
  return probe;
}

int lightFieldProbeBudget(int requested, std::uint64_t instances, std::uint64_t triangles,
                          const ResourceLimits& limits) {
  std::int64_t budget = std::max(requested, 0);
  const auto within = [&](std::int64_t limit, std::uint64_t perView) {
    if (perView > 0) budget = std::min<std::int64_t>(budget, limit / std::int64_t(perView * kLightFieldViewsPerProbe));
  };
  within(limits.maxDraws, instances);
  within(limits.maxDrawnTriangles, triangles);
  return int(budget);
}

std::string describeLightField(const LightField& field) {
  const LightFieldGrid& grid = field.grid;
  if (grid.probeCount() == 0)
    return field.requested > 0 ? "no probes (no virtual lights to fill them, or none within the frame's draw budgets)"
                               : "no probes";
  std::string text = std::to_string(grid.probeCount()) + " probes (" + std::to_string(grid.counts.x) + " x " +
                     std::to_string(grid.counts.y) + " x " + std::to_string(grid.counts.z) + ", " +
                     std::to_string(field.insideProbes) + " inside a closed mesh), " +
                     std::to_string(kLightFieldViewsPerProbe * grid.probeCount()) + " views of " +
                     std::to_string(kProbeFaceSize) + " x " + std::to_string(kProbeFaceSize);
  if (grid.probeCount() < field.requested)
    text += "; " + std::to_string(field.requested) +
            " asked for: fewer fill a grid, or fit the frame's --max-draws and --max-drawn-triangles";
  return text;
}

LightField LightFieldPass::run(const GpuScene& scene, GBufferPass& gbuffer, const GBufferVariant& variant,
                               std::span<const gpu::GpuVirtualLight> lights, int budget, const BindView& bindView) {
  LightField out;
  out.requested = budget;
  const LightFieldGrid grid = lightFieldGrid(scene.bounds, lights.empty() ? 0 : budget);
  if (grid.probeCount() == 0) return out;

  const int size = kProbeFaceSize;
  const gl::Texture position = gl::Texture::create2D(gl::internalFormat(GpuFormat::Rgba32F), size, size),
                    depth = gl::Texture::create2D(gl::internalFormat(GpuFormat::Depth32F), size, size);
  GBufferTargets targets{std::vector<const gl::Texture*>(variant.colorAttachments.size(), nullptr), &depth, size, size};
  for (std::size_t location = 0; location < variant.colorAttachments.size(); ++location)
    if (variant.colorAttachments[location] == Attachment::GbufferPosition) targets.colors[location] = &position;

  const float farDistance = 2.0f * scene.bounds.radius();
  std::vector<gpu::GpuLightProbe> probes;
  probes.reserve(std::size_t(grid.probeCount()));
  for (int index = 0; index < grid.probeCount(); ++index) {
    ProbeView view;
    view.position = grid.probePosition(index);
    view.size = size;
    view.distances.reserve(std::size_t(6 * size * size));
    for (const glm::vec3& face : kCubeFaceDirections) {
      const CameraView camera = perspectiveCamera(view.position, face, 0.5f * kPi, scene.bounds);
      view.clipFromWorld.push_back(camera.projection * camera.view);
      bindView(camera, size);
      const auto distancesSeen = [&](GBufferPass::Faces faces) {
        gbuffer.run(scene, targets, variant, faces);
        const ImageF positions = readColor(position, {"x", "y", "z", "a"});
        std::vector<float> seen;
        for (int y = 0; y < size; ++y)
          for (int x = 0; x < size; ++x)
            seen.push_back(
                positions.at(x, y, 3) == 0.0f
                    ? std::numeric_limits<float>::infinity()
                    : glm::length(glm::vec3(positions.at(x, y, 0), positions.at(x, y, 1), positions.at(x, y, 2)) -
                                  view.position));
        return seen;
      };
      const std::vector<float> front = distancesSeen(GBufferPass::Faces::Front),
                               back = distancesSeen(GBufferPass::Faces::Back);
      for (std::size_t t = 0; t < front.size(); ++t) {
        view.distances.push_back(front[t]);
        if (back[t] < front[t]) view.backFaceShare += 1.0f;
      }
    }
    view.backFaceShare /= float(view.distances.size());
    probes.push_back(makeLightProbe(view, lights, farDistance));
    if (view.backFaceShare > ProbeView::kInsideShare) ++out.insideProbes;
  }
  out.grid = grid;
  out.buffer = gl::Buffer::create(probes.size() * sizeof(gpu::GpuLightProbe));
  out.buffer.update(probes.data(), probes.size() * sizeof(gpu::GpuLightProbe));
  return out;
}

}  // namespace headlight
