// The light field's irradiance at a surface point (lib/passes/light_field.hpp
// makes the probes; docs/ACCURACY.md §3.3 "The light field"). The eight
// probes of the grid cell round the point are mixed by DDGI's weights
// (Majercik et al. 2019, §4.3): trilinear; a probe behind the surface counts
// less (the wrap-shaded direction to it); and a probe that cannot see the
// point, by its distance moments and Chebyshev's inequality, hardly at all.
// Needs shared_layout.h (the probes' storage block).

struct LightFieldGrid {
  vec3 origin;   // probe (0, 0, 0), world
  vec3 spacing;  // between neighbours, per axis
  ivec3 counts;  // probes per axis
};

vec2 octahedralFromDirection(vec3 direction) {
  vec2 p = direction.xy / (abs(direction.x) + abs(direction.y) + abs(direction.z));
  if (direction.z < 0.0) p = (1.0 - abs(p.yx)) * vec2(p.x >= 0.0 ? 1.0 : -1.0, p.y >= 0.0 ? 1.0 : -1.0);
  return p * 0.5 + 0.5;
}

// The four texels round `direction` on a probe's octahedral maps and
// their bilinear weights, clamped at the map's edges (the fold's seams are
// a texel wide).
struct MapTaps {
  ivec4 index;
  vec4 weight;
};
MapTaps mapTaps(vec3 direction) {
  const float last = float(kLightFieldMapSize - 1);
  const vec2 texel = clamp(octahedralFromDirection(direction) * float(kLightFieldMapSize) - 0.5, 0.0, last);
  const ivec2 low = ivec2(floor(texel));
  const ivec2 high = min(low + 1, ivec2(kLightFieldMapSize - 1));
  const vec2 f = texel - vec2(low);
  return MapTaps(ivec4(low.y, low.y, high.y, high.y) * kLightFieldMapSize + ivec4(low.x, high.x, low.x, high.x),
                 vec4((1.0 - f.x) * (1.0 - f.y), f.x * (1.0 - f.y), (1.0 - f.x) * f.y, f.x * f.y));
}

// The mean and mean square of the distance the probe sees along `direction`.
vec2 probeMoments(int probe, vec3 direction) {
  const MapTaps taps = mapTaps(direction);
  vec2 sum = vec2(0.0);
  for (int k = 0; k < 4; ++k) {
    const vec4 pair = lightField.probes[probe].moments[taps.index[k] >> 1];
    sum += taps.weight[k] * ((taps.index[k] & 1) == 0 ? pair.xy : pair.zw);
  }
  return sum;
}

// A probe's irradiance for a surface of normal `normal`.
vec3 probeIrradiance(int probe, vec3 normal) {
  const MapTaps taps = mapTaps(normal);
  vec3 sum = vec3(0.0);
  for (int k = 0; k < 4; ++k) sum += taps.weight[k] * lightField.probes[probe].irradiance[taps.index[k]].rgb;
  return sum;
}

// The irradiance at `position` (world) for a surface facing `normal`, seen
// from `toEye` (unit, world).
vec3 lightFieldIrradiance(LightFieldGrid grid, vec3 position, vec3 normal, vec3 toEye) {
  const vec3 cell = (position - grid.origin) / grid.spacing;
  const ivec3 last = grid.counts - 1;
  const ivec3 base = clamp(ivec3(floor(cell)), ivec3(0), max(last - 1, ivec3(0)));
  const vec3 along = clamp(cell - vec3(base), 0.0, 1.0);
  // The point the probes judge visibility at: moved off the surface, mostly
  // toward the eye (DDGI's self-shadow bias), by 0.3 of 3/4 of the spacing.
  const float spacing = min(grid.spacing.x, min(grid.spacing.y, grid.spacing.z));
  const vec3 judged = position + (0.2 * normal + 0.8 * toEye) * (0.3 * 0.75 * spacing);
  vec3 sum = vec3(0.0);
  float weightSum = 0.0;
  for (int corner = 0; corner < 8; ++corner) {
    const ivec3 offset = ivec3(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
    const ivec3 index3 = min(base + offset, last);
    const int probe = (index3.z * grid.counts.y + index3.y) * grid.counts.x + index3.x;
    const vec3 probePosition = grid.origin + grid.spacing * vec3(index3);
    if (lightField.probes[probe].irradiance[0].w == 0.0) continue;  // inside a closed mesh
    const vec3 trilinear = mix(1.0 - along, along, vec3(offset));
    float weight = 1.0;
    // Behind the surface: less, never none (a probe in a wall still knows the room).
    const vec3 toProbe = normalize(probePosition - position);
    const float wrap = 0.5 * (dot(toProbe, normal) + 1.0);
    weight *= wrap * wrap + 0.2;
    // What the probe sees toward the judged point, against its distance.
    const vec3 fromProbe = judged - probePosition;
    const float distance = length(fromProbe);
    const vec2 moments = probeMoments(probe, fromProbe / max(distance, 1e-30));
    if (distance > moments.x) {
      const float variance = abs(moments.x * moments.x - moments.y);
      const float excess = distance - moments.x;
      const float chebyshev = variance / (variance + excess * excess);
      weight *= max(chebyshev * chebyshev * chebyshev, 0.05);
    }
    // Tiny weights fall faster (DDGI's crush below 0.2).
    weight = max(weight, 1e-6);
    if (weight < 0.2) weight *= weight * weight / (0.2 * 0.2);
    weight *= trilinear.x * trilinear.y * trilinear.z;
    sum += weight * probeIrradiance(probe, normal);
    weightSum += weight;
  }
  return weightSum > 0.0 ? sum / weightSum : vec3(0.0);
}
