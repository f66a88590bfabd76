// Pure functions of the SSGI pass: every input is a parameter, apart from the
// frame block for projection.

// A frame with the normal as +Z and the tangent from `rotation` made
// orthogonal to it (Gram-Schmidt). If rotation is parallel to the normal
// (a surface seen edge-on along the noise direction), another axis is used.
mat3 tangentFrame(vec3 normal, vec3 rotation) {
  vec3 tangent = rotation - normal * dot(rotation, normal);
  if (dot(tangent, tangent) < 1e-6) {
    const vec3 axis = abs(normal.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0);
    tangent = axis - normal * dot(axis, normal);
  }
  tangent = normalize(tangent);
  return mat3(tangent, cross(normal, tangent), normal);
}

// Projects a view-space point to an integer pixel; false when it falls
// outside the image or behind the camera.
bool projectToPixel(vec3 viewPosition, out ivec2 pixel) {
  const vec4 clip = frame.projection * vec4(viewPosition, 1.0);
  if (clip.w <= 0.0) return false;
  const vec2 window = (clip.xy / clip.w * 0.5 + 0.5) * frame.viewport.xy;
  pixel = ivec2(floor(window));
  return all(greaterThanEqual(window, vec2(0.0))) && all(lessThan(window, frame.viewport.xy));
}

// The seed's range check: 1 while the occluder is within `radius` of the
// shaded point in depth, falling off smoothly beyond, so a distant
// foreground object does not darken the background.
float rangeCheck(float radius, float shadedDepth, float occluderDepth) {
  return smoothstep(0.0, 1.0, radius / max(abs(shadedDepth - occluderDepth), 1e-30));
}

// The view depth of the G-buffer surface at a sample's pixel, taken along
// the sample's own view ray rather than the pixel centre's: the surface's
// tangent plane there (position and normal) is intersected with the ray.
// The seed compared with the pixel centre's depth, which differs by up to
// half a pixel's depth gradient: on a floor seen at a grazing angle that is
// more than the bias, and a flat plane occluded itself (AO 0.80 measured).
// On a curved surface seen edge-on the plane is a poor guess far from the
// pixel, so the correction is held within `limit` (the SSGI radius: past it
// the range check fades the sample out anyway).
float surfaceDepthAlongRay(vec3 sampleView, vec3 surfaceView, vec3 surfaceNormalView, bool orthographic,
                           float limit) {
  if (orthographic) {
    // The view ray is the line through the sample along z: solve the plane
    // for z at the sample's x and y (an orthographic near plane may lie
    // behind the camera, so there is no "behind the eye" here).
    if (abs(surfaceNormalView.z) < 1e-4) return surfaceView.z;
    const vec2 offset = sampleView.xy - surfaceView.xy;
    const float z = surfaceView.z - dot(surfaceNormalView.xy, offset) / surfaceNormalView.z;
    return clamp(z, surfaceView.z - limit, surfaceView.z + limit);
  }
  const vec3 rayDirection = normalize(sampleView);
  const float facing = dot(surfaceNormalView, rayDirection);
  if (abs(facing) < 1e-4) return surfaceView.z;
  const float t = dot(surfaceNormalView, surfaceView) / facing;
  // The ray meets the plane only behind the eye (a sample above the horizon
  // of a grazing floor): the surface is not in front of the sample.
  if (t <= 0.0) return surfaceView.z - limit;
  return clamp(t * rayDirection.z, surfaceView.z - limit, surfaceView.z + limit);
}
