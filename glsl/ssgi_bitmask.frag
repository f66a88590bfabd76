// SSGI, the `bitmask` method (lib/passes/ssgi_bitmask.hpp; docs/ACCURACY.md
// §3.3 has the formulas). Per pixel, `sliceCount` screen-space directions
// (each with its opposite) are marched out to R's footprint on screen; every
// depth sample is a slab from its visible surface to `thicknessWorld`
// behind it, and the part of that slab within R of the shaded point marks
// the sectors of the slice it covers in a 32-bit mask. The sectors split the
// slice's half of the normal hemisphere into 32 equal angles; each carries
// its exact cosine-weighted solid angle, so the visible sum is the reference's
// ao_R (cosine-weighted fraction of the hemisphere open within R). Sectors a
// sample newly covers gather that sample's direct Lambertian light.
// The sky visibility (the reference's sky_vis, ACCURACY.md §2.4) marks a
// second mask with the same slabs uncut by R, plus `skyStepCount` samples per
// side spaced geometrically from R's footprint out to the screen edge; their
// slabs deepen with distance (skySlabDepth); sectors first covered there (or
// by a slab's part beyond R) gather its light as indirect from beyond R,
// composited beside the within-R indirect. What lies off screen, and what
// the depth buffer hides behind the slabs, is taken as open: a scene seen
// from outside it (the Cornell box's open front) is right there, one framed
// from inside its walls is too light where the walls leave the screen.
// Reads the G-buffer's depth (linearised by the frame's coefficients), not
// the position target. Its pure functions are in ssgi_common.glsl; what reads
// textures is here.
#include "shared_layout.h"
#include "ssgi_common.glsl"

layout(binding = kUnitGbufferDepth) uniform sampler2D gbufferDepth;
layout(binding = kUnitGbufferNormal) uniform sampler2D gbufferNormal;
layout(binding = kUnitGbufferAlbedo) uniform sampler2D gbufferAlbedo;
layout(binding = kUnitGbufferMaterial) uniform sampler2D gbufferMaterial;
layout(binding = kUnitDirectDiffuse) uniform sampler2D directDiffuse;

layout(location = 0) out vec4 outSsgi;
layout(location = 1) out vec4 outSky;

// The surface point on the view ray through `windowPoint` (pixels, not
// necessarily a centre), from the depth and normal of the pixel it falls in:
// that pixel's tangent plane met by the exact ray. The slice's samples then
// lie in the slice's plane; a pixel centre up to half a pixel off it would
// put an open plane's own points above its horizon at grazing angles.
// A grazing floor moves far in depth over half a pixel: the meeting point
// may be many pixels' lateral size away. Where it is more than 32 pixels'
// size from the centre's point (a curved surface seen edge-on), the pixel
// centre's point is kept. Where the plane is within 0.6 degrees of edge-on
// to the ray (|cos| < 0.01), no point is known: `known` is false and the
// sample is skipped (such a surface covers next to nothing on screen).
vec3 surfaceOnRay(vec2 windowPoint, ivec2 pixel, float depth, vec3 pixelNormal, out bool known) {
  const vec3 centre = viewPositionAt(pixel, depth);
  vec3 origin, direction;
  viewRayAt(windowPoint, origin, direction);
  float t;
  known = planeMeetsRay(origin, direction, centre, pixelNormal, 0.01, t);
  if (!known) return centre;
  const vec3 onRay = origin + direction * t;
  const vec2 scale = vec2(frame.projection[0][0], frame.projection[1][1]);
  const float pixelSize = 2.0 * frame.viewport.w / scale.y * (orthographicView() ? 1.0 : -centre.z);
  return distance(onRay, centre) < 32.0 * pixelSize ? onRay : centre;
}

// One depth sample of either march: the surface it shows, as an offset from
// the shaded point.
struct MarchPoint {
  ivec2 pixel;
  vec3 normal;       // view space, as stored (unit)
  vec3 offsetFront;  // the visible surface minus the shaded point, view space
  vec3 awayFromEye;  // unit: the way the slab behind the surface extends
};
const int kMarchSurface = 0;    // a surface to test
const int kMarchSkip = 1;       // background, or a surface seen edge-on: nothing here
const int kMarchOffScreen = 2;  // the screen edge ends the march: off screen is taken as open
int marchPoint(vec2 samplePoint, vec3 position, out MarchPoint point) {
  if (any(lessThan(samplePoint, vec2(0.0))) || any(greaterThanEqual(samplePoint, frame.viewport.xy)))
    return kMarchOffScreen;
  point.pixel = ivec2(samplePoint);
  const float sampleDepth = texelFetch(gbufferDepth, point.pixel, 0).r;
  if (sampleDepth >= 1.0) return kMarchSkip;  // background never occludes
  point.normal = mat3(frame.view) * texelFetch(gbufferNormal, point.pixel, 0).xyz;
  bool known;
  const vec3 front = surfaceOnRay(samplePoint, point.pixel, sampleDepth, point.normal, known);
  if (!known) return kMarchSkip;
  point.awayFromEye = orthographicView() ? vec3(0.0, 0.0, -1.0) : normalize(front);
  point.offsetFront = front - position;
  return kMarchSurface;
}

// How deep a surface is taken to be behind what the depth buffer shows, for
// the sky visibility: the scene's thickness, or kSkyDepthPerDistance times
// its distance from the shaded point where that is more. Beyond R a few
// samples span the whole screen, and a slab only `thickness` deep would cover
// a sliver of angle between them: a wall or ceiling seen at a distance would
// leave the sky open through the gaps. 0.5: measured at 128x128 against the
// reference (256 rays), 8 sky steps, sky RMSE cornell / spheres / slats:
// 0 -> 0.27 / 0.050 / 0.094, 0.5 -> 0.17 / 0.051 / 0.090, 1 -> 0.13 / 0.090 /
// 0.136 (spheres far away then shade the floor), 2 -> 0.12 / 0.116 / 0.136.
const float kSkyDepthPerDistance = 0.5;
float skySlabDepth(vec3 offsetFront) {
  return max(bitmask.thicknessWorld, kSkyDepthPerDistance * length(offsetFront));
}

// A 4x4 Bayer matrix: the 16 pixels of a tile (what the blur averages) get
// 16 stratified rotations.
const int kBayer[16] = int[16](0, 8, 2, 10, 12, 4, 14, 6, 3, 11, 1, 9, 15, 7, 13, 5);

void main() {
  const int divisor = bitmask.downsample;
  const ivec2 outputPixel = ivec2(gl_FragCoord.xy);
  const ivec2 size = ivec2(frame.viewport.xy);
  const ivec2 pixel = min(outputPixel * divisor + divisor / 2, size - 1);
  const float depth = texelFetch(gbufferDepth, pixel, 0).r;
  if (depth >= 1.0) discard;  // background: keeps the cleared (1, 0, 0, 0)

  const vec3 position = viewPositionAt(pixel, depth);
  const vec3 normal = normalize(mat3(frame.view) * texelFetch(gbufferNormal, pixel, 0).xyz);
  const vec3 toEye = orthographicView() ? vec3(0.0, 0.0, 1.0) : normalize(-position);
  const float radius = bitmask.radiusWorld;
  // R's footprint on screen, in pixels, at the shaded point's depth.
  const float pixelsPerUnit =
      0.5 * frame.viewport.y * frame.projection[1][1] / (orthographicView() ? 1.0 : max(-position.z, 1e-30));
  const float radiusPixels = radius * pixelsPerUnit;

  const int bayer = kBayer[(outputPixel.y & 3) * 4 + (outputPixel.x & 3)];
  // The seed and accumulated frames turn both by irrational steps (R2 sequence).
  const float rotationIndex = float(bitmask.rotationIndex);
  const float rotation = fract((float(bayer) + 0.5) / 16.0 + 0.7548777 * rotationIndex);
  const float jitter = fract((float((bayer * 7 + 5) & 15) + 0.5) / 16.0 + 0.5698403 * rotationIndex);

  const int sliceCount = bitmask.sliceCount, stepCount = bitmask.stepCount;
  const int skyStepCount = bitmask.skyStepCount;
  float visibleSum = 0.0, skyVisibleSum = 0.0, totalSum = 0.0;
  vec3 indirect = vec3(0.0), farIndirect = vec3(0.0);  // gathered within R, and beyond it
  for (int s = 0; s < sliceCount; ++s) {
    const float phi = (float(s) + rotation) * kPi / float(sliceCount);
    const vec2 direction = vec2(cos(phi), sin(phi));  // on screen
    // The slice: the plane through the eye's ray to the point and the
    // screen direction; `side` is its unit vector perpendicular to toEye.
    const vec3 side = normalize(vec3(direction, 0.0) - toEye * dot(vec3(direction, 0.0), toEye));
    const vec3 axis = cross(side, toEye);
    const vec3 projectedNormal = normal - axis * dot(normal, axis);
    const float projectedLength = length(projectedNormal);
    if (projectedLength < 1e-4) continue;  // the normal is the slice's axis: it holds no solid angle
    const float n = clamp(atan(dot(projectedNormal, side), dot(projectedNormal, toEye)), -0.5 * kPi, 0.5 * kPi);
    const float sinN = sin(n), cosN = cos(n);
    const float lowest = n - 0.5 * kPi;  // the hemisphere's edge on the -side
    const float sectorAngle = kPi / float(kSectors);
    // sliceMeasure at each sector's edge theta = lowest + k sectorAngle,
    // where cos(2 theta - n) = -cos(n + 2 k sectorAngle): the angle sum with
    // cos and sin of 2 k sectorAngle, turned on by a rotation per sector, so
    // the table costs no cosine per pixel (llvmpipe's cos is dear).
    const float turnCos = cos(2.0 * sectorAngle), turnSin = sin(2.0 * sectorAngle);
    float edges[kSectors + 1];
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
    const float total = edges[kSectors] - edges[0];  // = cos(n) + n sin(n)

    uint occupied = 0u;     // within R
    uint skyOccupied = 0u;  // at any distance
    for (int sign = -1; sign <= 1; sign += 2) {
      const vec2 stepDirection = direction * float(sign);
      for (int j = 0; j < stepCount; ++j) {
        const float u = (float(j) + jitter) / float(stepCount);
        // Quadratic spacing crowds steps near the point; the first is at
        // least a pixel away, the last reaches R's footprint.
        const float offset = 1.0 + u * u * max(radiusPixels - 1.0, 0.0);
        MarchPoint point;
        const int found = marchPoint(vec2(pixel) + 0.5 + stepDirection * offset, position, point);
        if (found == kMarchOffScreen) break;
        if (found == kMarchSkip) continue;
        const vec3 offsetFront = point.offsetFront;
        // Only a surface facing the point sends it light.
        const bool facing = dot(point.normal, offsetFront) < 0.0;
        // The slab front..back, cut to the sphere of radius R about the point.
        const vec3 span = point.awayFromEye * bitmask.thicknessWorld;
        float t0, t1;
        const bool inRange = slabWithinRadius(offsetFront, offsetFront + span, radius, t0, t1);
        const uint mask =
            inRange ? sectorsBetween(offsetFront + span * t0, offsetFront + span * t1, side, toEye, lowest) : 0u;
        const uint fresh = mask & ~occupied;
        occupied |= mask;
        // The same slab uncut, for the sky: sectors no nearer sample took
        // gather its light as light from beyond R.
        const vec3 skySlabBack = offsetFront + point.awayFromEye * skySlabDepth(offsetFront);
        const uint skyMask = skyStepCount == 0 ? 0u : sectorsBetween(offsetFront, skySlabBack, side, toEye, lowest);
        const uint skyFresh = skyMask & ~(skyOccupied | occupied);
        skyOccupied |= skyMask;
        if (!facing || (fresh | skyFresh) == 0u) continue;
        // One fetch of the sample's light serves both (llvmpipe calls out to fetch a texel).
        const vec3 light = projectedLength * texelFetch(directDiffuse, point.pixel, 0).rgb;
        indirect += sectorWeight(fresh, edges) * light;
        farIndirect += sectorWeight(skyFresh, edges) * light;
      }
      // Beyond R, for the sky: from R's footprint (at least a pixel) to the
      // screen edge along this side, in geometric steps (a far occluder
      // covers less angle, so the samples thin out with distance).
      if (skyStepCount == 0) continue;
      const vec2 origin = vec2(pixel) + 0.5;
      const vec2 edge =
          vec2(stepDirection.x > 0.0 ? frame.viewport.x : 0.0, stepDirection.y > 0.0 ? frame.viewport.y : 0.0);
      const vec2 toEdge = abs(edge - origin) / max(abs(stepDirection), vec2(1e-6));
      const float edgeOffset = min(toEdge.x, toEdge.y);
      const float firstOffset = max(radiusPixels, 1.0);
      if (edgeOffset <= firstOffset) continue;
      for (int k = 0; k < skyStepCount; ++k) {
        const float offset = firstOffset * pow(edgeOffset / firstOffset, (float(k) + jitter) / float(skyStepCount));
        MarchPoint point;
        const int found = marchPoint(origin + stepDirection * offset, position, point);
        if (found == kMarchOffScreen) break;
        if (found == kMarchSkip) continue;  // the sky itself, or a surface seen edge-on
        const vec3 offsetFront = point.offsetFront;
        const uint skyMask = sectorsBetween(offsetFront, offsetFront + point.awayFromEye * skySlabDepth(offsetFront),
                                            side, toEye, lowest);
        const uint skyFresh = skyMask & ~(skyOccupied | occupied);
        skyOccupied |= skyMask;
        if (skyFresh != 0u && dot(point.normal, offsetFront) < 0.0)
          farIndirect +=
              (projectedLength * sectorWeight(skyFresh, edges)) * texelFetch(directDiffuse, point.pixel, 0).rgb;
      }
    }
    visibleSum += projectedLength * max(total - sectorWeight(occupied, edges), 0.0);
    // What is occluded within R is occluded from the sky too.
    const float skyOccludedWeight = sectorWeight(skyOccupied | occupied, edges);
    skyVisibleSum += projectedLength * max(total - skyOccludedWeight, 0.0);
    totalSum += projectedLength * total;
  }
  // The ratio of the slices' visible to total cosine-weighted measure: an
  // open plane is exactly 1 at any slice count.
  const float visibility = totalSum > 0.0 ? clamp(visibleSum / totalSum, 0.0, 1.0) : 1.0;
  const float ambientOcclusion = clamp(1.0 - bitmask.intensity * (1.0 - visibility), 0.0, 1.0);
  const float skyVisibility = totalSum > 0.0 ? clamp(skyVisibleSum / totalSum, 0.0, 1.0) : 1.0;
  // A Lambertian receiver: (1 - metallic) albedo / pi * integral(L cos) over
  // the occluded directions; the sums above are that integral over pi.
  const vec3 receiver = (1.0 - texelFetch(gbufferMaterial, pixel, 0).x) * texelFetch(gbufferAlbedo, pixel, 0).rgb;
  const vec3 gathered = totalSum > 0.0 ? indirect / totalSum : vec3(0.0);
  outSsgi = vec4(ambientOcclusion, gathered * receiver * bitmask.indirectStrength);
  // With no sky steps the mask above is the within-R one: sky = AO.
  const vec3 farGathered = totalSum > 0.0 ? farIndirect / totalSum : vec3(0.0);
  outSky = vec4(clamp(1.0 - bitmask.intensity * (1.0 - skyVisibility), 0.0, 1.0),
                farGathered * receiver * bitmask.indirectStrength);
}
