// Pure functions of the SSGI passes (ssgi.frag's kernel methods and
// ssgi_bitmask.frag): every input is a parameter, apart from the frame block
// for projection.
#include "sampling.glsl"  // kPi

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

bool orthographicView() { return frame.cameraPosition.w > 0.5; }

// Where the plane through `planePoint` with unit normal `planeNormal` meets
// the ray origin + t * direction: false where the ray is within `minFacing`
// (|cos| of its angle to the normal) of running along the plane, where the
// meeting point is too far off to trust. The one "tangent plane meets the
// view ray" of both SSGI methods; each names its threshold.
bool planeMeetsRay(vec3 origin, vec3 direction, vec3 planePoint, vec3 planeNormal, float minFacing, out float t) {
  const float facing = dot(planeNormal, direction);
  if (abs(facing) < minFacing * length(direction)) return false;
  t = dot(planeNormal, planePoint - origin) / facing;
  return true;
}

// The view ray through a window point (pixels, not necessarily a centre):
// from the eye (perspective; `direction` reaches z = -1, not unit length)
// or along -z through the point (orthographic).
void viewRayAt(vec2 windowPoint, out vec3 origin, out vec3 direction) {
  const vec2 ndc = windowPoint * frame.viewport.zw * 2.0 - 1.0;
  const vec2 scale = vec2(frame.projection[0][0], frame.projection[1][1]);
  if (orthographicView()) {
    origin = vec3((ndc - vec2(frame.projection[3][0], frame.projection[3][1])) / scale, 0.0);
    direction = vec3(0.0, 0.0, -1.0);
  } else {
    // clip.xy = scale * xy + projection[2].xy * z, clip.w = -z: at z = -1.
    origin = vec3(0.0);
    direction = vec3((ndc + vec2(frame.projection[2][0], frame.projection[2][1])) / scale, -1.0);
  }
}

// The view-space point at `pixel`'s centre whose depth-buffer value is
// `depth` (HL_VIEW_Z_FROM_NDC_DEPTH with the frame's coefficients, computed
// once on the CPU and shared with the depth target's readback): the inverse
// of glm::perspective / glm::ortho.
vec3 viewPositionAt(ivec2 pixel, float depth) {
  const float z = HL_VIEW_Z_FROM_NDC_DEPTH(2.0 * depth - 1.0, frame.depthToViewZ);
  const vec2 ndc = (vec2(pixel) + 0.5) * frame.viewport.zw * 2.0 - 1.0;
  const vec2 scale = vec2(frame.projection[0][0], frame.projection[1][1]);
  if (orthographicView()) return vec3((ndc - vec2(frame.projection[3][0], frame.projection[3][1])) / scale, z);
  // clip.xy = scale * xy + projection[2].xy * z, clip.w = -z.
  return vec3((ndc * -z - vec2(frame.projection[2][0], frame.projection[2][1]) * z) / scale, z);
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
  // Orthographic: the line through the sample along z (an orthographic near
  // plane may lie behind the camera, so there is no "behind the eye" there).
  const vec3 origin = orthographic ? vec3(sampleView.xy, 0.0) : vec3(0.0);
  const vec3 direction = orthographic ? vec3(0.0, 0.0, -1.0) : normalize(sampleView);
  float t;
  if (!planeMeetsRay(origin, direction, surfaceView, surfaceNormalView, 1e-4, t)) return surfaceView.z;
  // The ray meets the plane only behind the eye (a sample above the horizon
  // of a grazing floor): the surface is not in front of the sample.
  if (!orthographic && t <= 0.0) return surfaceView.z - limit;
  return clamp(origin.z + t * direction.z, surfaceView.z - limit, surfaceView.z + limit);
}

// ---- The bitmask method's slices (docs/ACCURACY.md §3.3) -----------------------

const int kSectors = 32;

// The cosine-weighted measure of the slice's angles between 0 (the view
// direction) and theta, signed like theta: integral from 0 to theta of
// cos(t - n) |sin t| dt, where n is the normal's angle in the slice and
// |sin t| the polar Jacobian (Jimenez et al. 2016, eq. 10's antiderivative).
float sliceMeasure(float theta, float n, float sinN, float cosN) {
  const float magnitude = 0.25 * (cosN - cos(2.0 * theta - n)) + 0.5 * theta * sinN;
  return theta >= 0.0 ? magnitude : -magnitude;
}

// sliceMeasure at each sector's edge theta = lowest + k sectorAngle (lowest
// = n - pi/2, the hemisphere's edge), where cos(2 theta - n) =
// -cos(n + 2 k sectorAngle): the angle sum with cos and sin of
// 2 k sectorAngle, turned on by a rotation per sector, so the table costs no
// cosine per sector (llvmpipe's cos is dear).
void sliceEdges(float n, out float edges[kSectors + 1]) {
  const float sinN = sin(n), cosN = cos(n);
  const float lowest = n - 0.5 * kPi;
  const float sectorAngle = kPi / float(kSectors);
  const float turnCos = cos(2.0 * sectorAngle), turnSin = sin(2.0 * sectorAngle);
  edges[0] = sliceMeasure(lowest, n, sinN, cosN);
  float edgeCos = 1.0, edgeSin = 0.0;  // of 2 k sectorAngle
  for (int k = 0; k < kSectors; ++k) {
    const float turnedCos = edgeCos * turnCos - edgeSin * turnSin;
    edgeSin = edgeSin * turnCos + edgeCos * turnSin;
    edgeCos = turnedCos;
    const float theta = lowest + float(k + 1) * sectorAngle;
    const float magnitude = 0.25 * (cosN + (cosN * edgeCos - sinN * edgeSin)) + 0.5 * theta * sinN;
    edges[k + 1] = theta >= 0.0 ? magnitude : -magnitude;
  }
}

// atan(y, x) to within 1e-5 rad (Abramowitz and Stegun 4.4.49's polynomial
// on [0, 1], folded into the octants), where a sector is
// 0.098 rad wide. llvmpipe's atan costs more: the near field calls this
// twice a step, and its time (pass + blur, builtin:cornell 256x256) went
// 82 -> 76 ms with the same images to 4 decimals of HDR-FLIP and RMSE
// (docs/BENCHMARKS.md, "Fewer atan calls").
float fastAtan2(float y, float x) {
  const float ax = abs(x), ay = abs(y);
  const float a = min(ax, ay) / max(max(ax, ay), 1e-30);
  const float s = a * a;
  float r = a * (0.9998660 + s * (-0.3302995 + s * (0.1801410 + s * (-0.0851330 + s * 0.0208351))));
  r = ay > ax ? 1.57079637 - r : r;
  r = x < 0.0 ? 3.14159274 - r : r;
  return y < 0.0 ? -r : r;
}
// The sectors more than half covered by the angles, in the slice, of the
// offsets `a` and `b` from the shaded point (both on one side of the eye's
// ray through it, so the angles do not wrap round).
uint sectorsBetween(vec3 a, vec3 b, vec3 side, vec3 toEye, float lowest) {
  const float sectorAngle = kPi / float(kSectors);
  const float thetaA = fastAtan2(dot(a, side), dot(a, toEye));
  const float thetaB = fastAtan2(dot(b, side), dot(b, toEye));
  const int firstSector = clamp(int(floor((min(thetaA, thetaB) - lowest) / sectorAngle + 0.5)), 0, kSectors);
  const int endSector = clamp(int(floor((max(thetaA, thetaB) - lowest) / sectorAngle + 0.5)), 0, kSectors);
  if (endSector <= firstSector) return 0u;
  const int count = endSector - firstSector;
  return count >= 32 ? 0xffffffffu : ((1u << uint(count)) - 1u) << uint(firstSector);
}

// The summed weights of the sectors in `bits`, from `edges` (sliceMeasure
// at each sector's start, and the hemisphere's end last). sliceMeasure grows
// monotonically over the hemisphere, so a run of set bits [start, end) weighs
// exactly edges[end] - edges[start]: a mask from sectorsBetween, one run,
// costs two reads instead of one a sector.
float sectorWeight(uint bits, float edges[kSectors + 1]) {
  float sum = 0.0;
  while (bits != 0u) {
    const int start = findLSB(bits);
    const uint pastRun = bits + (1u << uint(start));  // the lowest run carried out
    const int end = pastRun == 0u ? kSectors : findLSB(pastRun);
    sum += max(edges[end] - edges[start], 0.0);
    bits &= pastRun;
  }
  return sum;
}

// The slab from `front` to `back` (offsets from the shaded point) cut to the
// sphere of radius `radius` about the point: false where no part is inside,
// else its ends as fractions t0 <= t1 of the way from front to back.
bool slabWithinRadius(vec3 front, vec3 back, float radius, out float t0, out float t1) {
  const vec3 span = back - front;
  const float a = dot(span, span), b = dot(front, span), c = dot(front, front) - radius * radius;
  t0 = 0.0;
  t1 = 1.0;
  if (a < 1e-30) return c <= 0.0;
  const float discriminant = b * b - a * c;
  if (discriminant < 0.0) return false;
  const float root = sqrt(discriminant);
  t0 = max((-b - root) / a, 0.0);
  t1 = min((-b + root) / a, 1.0);
  return t0 <= t1;
}
