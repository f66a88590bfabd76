// The procedural sky: radiance as a function of the direction's height
// alone, continuous at the horizon. Reads the SkyBlock.
vec3 skyRadiance(vec3 direction) {
  const float height = clamp(direction.y, -1.0, 1.0);
  if (height >= 0.0) return mix(sky.horizon.rgb, sky.zenith.rgb, sqrt(height));
  return mix(sky.horizon.rgb, sky.ground.rgb, min(1.0, -height * 4.0));
}

// The unit direction at height y in the table's plane (the sky is
// symmetric about +Y, so any azimuth would do).
vec3 directionAtHeight(float y) { return vec3(sqrt(max(0.0, 1.0 - y * y)), y, 0.0); }
