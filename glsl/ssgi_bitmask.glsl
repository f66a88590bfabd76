// SSGI, the `bitmask` method (lib/passes/ssgi_bitmask.hpp; docs/ACCURACY.md
// §3.3 has the formulas). Per pixel, `sliceCount` screen-space directions
// (each with its opposite) are marched out to R's footprint on screen; every
// depth sample is a slab from its visible surface to `thicknessWorld`
// behind it (deeper where the sample stands for a wider stretch of screen:
// radiusSlabDepth), and the part of that slab within R of the shaded point marks
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
// textures is here. A fullscreen pass's body: fullscreen_entry.frag or .comp
// runs it per output pixel, writing the members lib/passes/ssgi_bitmask.cpp
// names for the part it draws.
#include "shared_layout.h"
#include "ssgi_common.glsl"
#include "shadows.glsl"  // with virtual lights: HAS_PLANAR_SHADOWS, HAS_CUBE_SHADOWS (SsgiBitmaskVariant)
#include "light_field.glsl"

layout(binding = kUnitGbufferDepth) uniform sampler2D gbufferDepth;
layout(binding = kUnitGbufferNormal) uniform sampler2D gbufferNormal;
layout(binding = kUnitGbufferAlbedo) uniform sampler2D gbufferAlbedo;
layout(binding = kUnitGbufferMaterial) uniform sampler2D gbufferMaterial;
layout(binding = kUnitDirectDiffuse) uniform sampler2D directDiffuse;
layout(binding = kUnitGbufferEmissive) uniform sampler2D gbufferEmissive;
// Depth and view normal in one texel (glsl/ssgi_surface.glsl): a march step's one fetch.
layout(binding = kUnitSsgiSurface) uniform sampler2D ssgiSurface;

struct PassOutputs {
  vec4 nearField;  // AO and indirect light within R (SsgiTextures::occlusion)
  vec4 farField;   // sky visibility and indirect light beyond R (SsgiTextures::sky), with both parts in one pass
  // The far field's own pass (a coarser resolution, lib/passes/ssgi_bitmask.hpp) writes this to the sky
  // instead: its sky visibility as the part of the AO within R it leaves (the sky is open at most where that
  // is), which the blur multiplies by the full-resolution AO, keeping the contact detail a coarse sky would lose.
  vec4 farFieldOverNear;
  vec4 specular;  // specularOutput (SsgiTextures::specular)
};

// The world width of a pixel at view depth `viewZ` (negative in front).
float pixelFootprint(float viewZ) {
  return 2.0 * frame.viewport.w / frame.projection[1][1] * (orthographicView() ? 1.0 : -viewZ);
}

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
  return distance(onRay, centre) < 32.0 * pixelFootprint(centre.z) ? onRay : centre;
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
  const vec4 surface = texelFetch(ssgiSurface, point.pixel, 0);
  const float sampleDepth = surface.r;
  if (sampleDepth >= 1.0) return kMarchSkip;  // background never occludes
  point.normal = surface.gba;
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
// leave the sky open through the gaps. Too deep, and a near object's slab
// covers the sky seen past it (between MetalRoughSpheres' balls; a wall far
// behind a sphere in builtin:depth-step). 0.25 since issue 16, with 16 sky
// steps (docs/BENCHMARKS.md, "Thin occluders"): HDR-FLIP cornell / slats /
// MetalRoughSpheres at 0.5 -> 0.230 / 0.066 / 0.064, 0.35 -> 0.237 / 0.062 /
// 0.052, 0.25 -> 0.243 / 0.062 / 0.046. (Before, with 8 sky steps at
// 128x128: sky RMSE cornell / spheres / slats 0 -> 0.27 / 0.050 / 0.094,
// 0.5 -> 0.17 / 0.051 / 0.090, 1 -> 0.13 / 0.090 / 0.136.)
const float kSkyDepthPerDistance = 0.25;
float skySlabDepth(vec3 offsetFront) {
  return max(bitmask.thicknessWorld, kSkyDepthPerDistance * length(offsetFront));
}

// How deep a depth sample within R is taken to be: the scene's thickness,
// or kDepthPerFootprint times the world width of the stretch of screen the
// sample stands for (the gap to the next step, at the sample's depth) where
// that is more. An object narrower on screen than the gap between steps
// (builtin:slats' bars, 1-2 pixels wide) is hit by one sample or none; its
// slab, only as deep as the scene's thickness, covered a sliver of the
// angle the object hides, and the wall between the slats was left open (AO
// RMSE 0.127 at R = 0.1 diag). Per sample, so near steps (dense) keep the
// scene's thickness. 1.25: slats' AO RMSE 0.127 -> 0.045 (1: 0.070, 1.5:
// 0.027 at HDR-FLIP +0.0008, 2: 0.044 at +0.007); no other scene changed.
const float kDepthPerFootprint = 1.25;
float radiusSlabDepth(vec3 offsetFront, vec3 position, float stepPixels) {
  return max(bitmask.thicknessWorld, kDepthPerFootprint * stepPixels * pixelFootprint(position.z + offsetFront.z));
}

// The slices' rotations and the steps' jitter: a 4x4 Bayer tile gives the 16
// pixels of a tile 16 stratified values, each tile shifted by its own hashed
// offset. The blur (ssgi_blur.frag) averages about one of each. The tile
// alone repeated every 4 pixels: each of its 16 rotations marched its few
// samples along the same directions across the whole screen, and where
// those hit or missed a bright surface the blur showed 4x4 blocks, diagonal
// streaks and a staircase shadow in the light from beyond R (builtin:cornell;
// docs/BENCHMARKS.md, "Structured artefacts"). Offset per tile, what is left
// is noise without a pattern. Jimenez's interleaved gradient noise per pixel
// instead was unstructured too but, not stratified, lost 0.02 HDR-FLIP.
const int kBayer[16] = int[16](0, 8, 2, 10, 12, 4, 14, 6, 3, 11, 1, 9, 15, 7, 13, 5);

// PCG's output permutation (Jarzynski and Olano 2020): a well-mixed 32-bit
// hash of the tile's index.
uint pcgHash(uint value) {
  const uint state = value * 747796405u + 2891336453u;
  const uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}
float unitFromHash(uint hash) { return float(hash >> 8) * (1.0 / 16777216.0); }

// The light a surface seen beyond R sends: its direct pass's Lambertian
// radiance (emission included), or with virtual lights, which carry the
// direct light from beyond R, its emission alone.
vec3 farLight(ivec2 pixel) {
  if (bitmask.farLightSource == kFarLightDirect) return texelFetch(directDiffuse, pixel, 0).rgb;
  if (bitmask.farLightSource == kFarLightEmission) return texelFetch(gbufferEmissive, pixel, 0).rgb;
  return vec3(0.0);
}

// A slice through the shaded point: the plane through the eye's ray to the
// point and a screen direction, and what its marches have found so far.
struct Slice {
  vec2 direction;         // on screen, unit
  vec3 side;              // in the slice, unit, perpendicular to toEye
  vec3 toEye;             // unit, from the point
  float lowest;           // the normal hemisphere's edge on the -side, as an angle from toEye
  float projectedLength;  // the normal's length projected into the slice: the slice's weight
  uint occupied;          // sectors covered within R
  uint skyOccupied;       // sectors covered at any distance
  uint hiddenOccupied;    // sectors first covered within R by a surface that faces away: what sends light there is hidden
  vec3 indirect;          // light gathered within R (weighted by projectedLength)
  vec3 farIndirect;       // light gathered beyond R (weighted by projectedLength)
};

// Marches one side of the slice out to R's footprint (`radiusPixels`) in
// `stepCount` quadratically spaced steps: each depth sample's slab, cut to
// R, marks the sectors it covers; sectors it newly covers gather its light.
// The same slab uncut marks the sky's mask, and sectors that only it covers
// gather light as light from beyond R.
void marchWithinRadius(inout Slice slice, float edges[kSectors + 1], vec2 stepDirection, ivec2 pixel, vec3 position,
                       float radiusPixels, float jitter) {
  const int stepCount = bitmask.stepCount;
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
    // The slab front..back, cut to the sphere of radius R about the point;
    // the steps are offset(u) apart, d offset / dj = 2 u (R - 1) / stepCount.
    const float stepPixels = 2.0 * u * max(radiusPixels - 1.0, 0.0) / float(stepCount);
    const vec3 span = point.awayFromEye * radiusSlabDepth(offsetFront, position, stepPixels);
    float t0, t1;
    const bool inRange = slabWithinRadius(offsetFront, offsetFront + span, bitmask.radiusWorld, t0, t1);
    const uint mask = inRange ? sectorsBetween(offsetFront + span * t0, offsetFront + span * t1, slice.side,
                                               slice.toEye, slice.lowest)
                              : 0u;
    const uint fresh = mask & ~slice.occupied;
    slice.occupied |= mask;
    if (!facing) slice.hiddenOccupied |= fresh;
    // The same slab uncut, for the sky: sectors no nearer sample took
    // gather its light as light from beyond R.
    const vec3 skySlabBack = offsetFront + point.awayFromEye * skySlabDepth(offsetFront);
    const uint skyMask =
        bitmask.skyStepCount == 0 ? 0u : sectorsBetween(offsetFront, skySlabBack, slice.side, slice.toEye, slice.lowest);
    const uint skyFresh = skyMask & ~(slice.skyOccupied | slice.occupied);
    slice.skyOccupied |= skyMask;
    if (!facing || (fresh | skyFresh) == 0u) continue;
    // One fetch of the sample's light serves both (llvmpipe calls out to fetch a texel).
    const vec3 light = texelFetch(directDiffuse, point.pixel, 0).rgb;
    slice.indirect += (slice.projectedLength * sectorWeight(fresh, edges)) * light;
    if (skyFresh != 0u)
      slice.farIndirect += (slice.projectedLength * sectorWeight(skyFresh, edges)) *
                           (bitmask.farLightSource == kFarLightDirect ? light : farLight(point.pixel));
  }
}

// Beyond R, for the sky: from R's footprint (at least a pixel) to the
// screen edge along this side, in geometric steps (a far occluder covers
// less angle, so the samples thin out with distance).
void marchBeyondRadius(inout Slice slice, float edges[kSectors + 1], vec2 stepDirection, ivec2 pixel, vec3 position,
                       float radiusPixels, float jitter) {
  const int skyStepCount = bitmask.skyStepCount;
  if (skyStepCount == 0) return;
  const vec2 origin = vec2(pixel) + 0.5;
  const vec2 edge =
      vec2(stepDirection.x > 0.0 ? frame.viewport.x : 0.0, stepDirection.y > 0.0 ? frame.viewport.y : 0.0);
  const vec2 toEdge = abs(edge - origin) / max(abs(stepDirection), vec2(1e-6));
  const float edgeOffset = min(toEdge.x, toEdge.y);
  const float firstOffset = max(radiusPixels, 1.0);
  if (edgeOffset <= firstOffset) return;
  // offset_k = first (edge / first)^((k + jitter) / K), one factor a step
  // (two pow calls a march, not one a step).
  const float growth = pow(edgeOffset / firstOffset, 1.0 / float(skyStepCount));
  float offset = firstOffset * pow(growth, jitter) / growth;
  for (int k = 0; k < skyStepCount; ++k) {
    offset *= growth;
    MarchPoint point;
    const int found = marchPoint(origin + stepDirection * offset, position, point);
    if (found == kMarchOffScreen) break;
    if (found == kMarchSkip) continue;  // the sky itself, or a surface seen edge-on
    const vec3 offsetFront = point.offsetFront;
    const uint skyMask = sectorsBetween(offsetFront, offsetFront + point.awayFromEye * skySlabDepth(offsetFront),
                                        slice.side, slice.toEye, slice.lowest);
    const uint skyFresh = skyMask & ~(slice.skyOccupied | slice.occupied);
    slice.skyOccupied |= skyMask;
    if (skyFresh != 0u && dot(point.normal, offsetFront) < 0.0 && bitmask.farLightSource != kFarLightNone)
      slice.farIndirect += (slice.projectedLength * sectorWeight(skyFresh, edges)) *
                           farLight(point.pixel);
  }
}

// ---- Virtual lights (lib/passes/virtual_lights.hpp) -------------------------
// The light from beyond R as one bounce off what the punctual lights reach:
// a virtual light of flux F at distance d along w gives the point the
// irradiance F max(n_v . -w, 0) max(n . w, 0) / (pi d^2); returned as E / pi,
// the cosine-weighted mean of the light arriving, as the marches' sums are.
// Those within R are the near field's (its marches see them, with their
// occlusion); the pixel gathers one of kVirtualLightSubsets interleaved
// subsets and scales it up, and the far field's blur averages the subsets.
// What the slices found within R hides a virtual light behind it: w's
// sector in each of the first kOccludingSlices slices, weighted by how near
// w lies to the slice's plane. builtin:cornell's boxes shade the walls and
// floor beside them from the lamp's bright ceiling as they shade them from
// the lamp: without this, light leaked through them (HDR-FLIP 0.179; with
// it 0.156; the nearest surface per group of sectors at any distance
// instead, occluding nearer than 0.5 / 0.7 of the light's distance: 0.161 /
// 0.188, the ceiling itself hiding the lamp's spot at grazing angles).
const int kOccludingSlices = 4;
struct OccludingSlices {
  int count;
  vec3 axis[kOccludingSlices];  // the slice plane's normal
  vec3 side[kOccludingSlices];
  float lowest[kOccludingSlices];
  uint occupied[kOccludingSlices];  // sectors covered within R
};

// The share of the slices whose sector along `direction` is open within R.
float openWithinRadius(OccludingSlices slices, vec3 toEye, vec3 direction) {
  const float sectorAngle = kPi / float(kSectors);
  float open = 0.0, total = 0.0;
  for (int s = 0; s < slices.count; ++s) {
    const float outOfPlane = dot(direction, slices.axis[s]);
    float weight = max(1.0 - outOfPlane * outOfPlane, 0.0);
    weight *= weight;
    weight *= weight;
    const float theta = fastAtan2(dot(direction, slices.side[s]), dot(direction, toEye));
    const int sector = int(floor((theta - slices.lowest[s]) / sectorAngle));
    const bool covered = sector >= 0 && sector < kSectors && (slices.occupied[s] & (1u << uint(sector))) != 0u;
    total += weight;
    if (!covered) open += weight;
  }
  return total > 1e-4 ? open / total : 1.0;
}

// A virtual light near its light is hidden where the light is: seen from
// the point, the two lie within an angle of about (their distance apart) /
// (the distance to the point), and what shades the point from the light
// shades it from them too, on screen or off it (builtin:cornell's boxes
// from the ceiling's bright spot round the lamp; the corner behind the tall
// box in the stability suite's near-wall view, where no occluder is on
// screen). The light's shadow counts in full at angle 0 and fades out at
// kShadowAngle radians. Per pixel: the first kShadowedLights lights' shadow
// visibility (-1: unknown; directional lights, which are not near anything,
// lights without a map, and lights behind the surface).
const int kShadowedLights = 8;
const float kShadowAngle = 2.0;
struct LightShadows {
  int count;
  vec4 positionVisible[kShadowedLights];  // the light's position, its shadow visibility at the point
};

LightShadows lightShadowsAt(vec3 worldPosition, vec3 worldNormal) {
  LightShadows shadows;
  shadows.count = min(lighting.lightCount, kShadowedLights);
  for (int i = 0; i < shadows.count; ++i) {
    const GpuLight light = lights.lightList[i];
    shadows.positionVisible[i] = vec4(light.position, -1.0);
    if (light.type == kLightDirectional || light.castsShadows == 0 || light.shadowLayer < 0) continue;
    const vec3 toLight = normalize(light.position - worldPosition);
    if (dot(worldNormal, toLight) <= 0.0) continue;
    // Behind transmissive casters: the mean of the channels' tint.
    shadows.positionVisible[i].w = dot(shadowVisibility(light, worldPosition, worldNormal, toLight), vec3(1.0 / 3.0));
  }
  return shadows;
}

// What of a virtual light's light the point's shadow hides.
float shadowedShare(LightShadows shadows, GpuVirtualLight light, float distance) {
  const int index = int(light.position.w);
  if (index >= shadows.count || shadows.positionVisible[index].w < 0.0) return 1.0;
  const vec4 lightShadow = shadows.positionVisible[index];
  const float spread = length(light.position.xyz - lightShadow.xyz) / (kShadowAngle * distance);
  return mix(lightShadow.w, 1.0, clamp(spread, 0.0, 1.0));
}

vec3 virtualLightGather(vec3 worldPosition, vec3 worldNormal, int subset, OccludingSlices slices, vec3 toEye) {
  const LightShadows shadows = lightShadowsAt(worldPosition, worldNormal);
  const float radius2 = bitmask.radiusWorld * bitmask.radiusWorld;
  const mat3 viewFromWorld = mat3(frame.view);
  vec3 sum = vec3(0.0);
  for (int i = subset; i < bitmask.virtualLightCount; i += kVirtualLightSubsets) {
    const GpuVirtualLight light = virtualLights.virtualLightList[i];
    const vec3 offset = light.position.xyz - worldPosition;
    const float distance2 = dot(offset, offset);
    if (distance2 <= radius2) continue;
    const vec3 toLight = offset * inversesqrt(distance2);
    const float cosReceiver = dot(worldNormal, toLight), cosSender = -dot(light.normal.xyz, toLight);
    if (cosReceiver <= 0.0 || cosSender <= 0.0) continue;
    const float open = openWithinRadius(slices, toEye, viewFromWorld * toLight) *
                       shadowedShare(shadows, light, sqrt(distance2));
    sum += light.flux.rgb * (open * cosReceiver * cosSender / distance2);
  }
  return sum * (float(kVirtualLightSubsets) / (kPi * kPi));
}

// ---- Specular sky visibility (issue 16; docs/ACCURACY.md §3.3) -------------
// The split-sum specular reflects the sky about R = reflect(-V, N) within a
// GGX lobe; the reference counts the sky only where the lobe's rays escape.
// The diffuse sky visibility is cosine-weighted over the hemisphere: for a
// reflection aimed at the floor it is far too open. Each slice's mask of
// sectors covered at any distance is read under the lobe instead, about R's
// angle projected into the slice, and the slices are weighted by how near R
// lies to their planes.

// The lobe's width in angle: GGX's alpha = roughness^2 (the roughness
// clamped as brdf.glsl's makeSurface does), but no narrower than two
// sectors: a lobe a sector wide or less is read as one sector open or
// covered, and where a reflected occluder's edge falls in it the steps'
// jitter flips it from pixel to pixel (black grain on polished metal, issue
// 33). The mirror row of tests/gl_ssgi_specular_tests.cpp, grain against 32
// frames at a floor of 1/4, 1, 2 sectors: 0.082, 0.058, 0.041; the
// visibility's RMSE against the reference on builtin:spheres 0.094, 0.095,
// 0.096 (0.099 before the slices turned toward R).
const float kLobeFloorSectors = 2.0;
float specularLobeAlpha(float roughness) {
  const float clamped = max(roughness, 0.03);
  return max(clamped * clamped, kLobeFloorSectors * kPi / float(kSectors));
}

// sin(x) on [0, pi] by Bhaskara's rational approximation (error < 0.002):
// a sector's N.L in the slice without a sine call per sector.
float sinHalfTurn(float x) {
  const float p = x * (kPi - x);
  return 16.0 * p / (5.0 * kPi * kPi - 4.0 * p);
}

// One slice's reading of the lobe: x = the open share of the lobe's weight
// over the slice's 32 sectors (sectors in `covered` are blocked), y = the
// slice's weight, cos^8 of R's angle to the slice's plane (0 where the lobe
// misses the hemisphere), z = x times the bend: how far the open part's
// mean direction lies from the whole lobe's, in radians toward the normal.
// The open part sees another stretch of sky than the lobe about R (under a
// ball, the rays that escape go up, where the sky is brighter), so the
// composite looks the sky up along R turned by the bend. In the plane of incidence a direction delta from
// R has its half vector delta / 2 from N, so the lobe's profile is GGX's D
// there, 1 / (alpha^2 + tan^2(delta / 2))^2 ~ 1 / (1 + (delta / 2 alpha)^2)^2,
// with its long tails; times Smith's G1 for L (Schlick's form, k = alpha / 2),
// which fades the lobe at the horizon. (The split sum's N.L cancels in
// BRDF cos.)
// The bend has two parts: the horizon's (the whole hemisphere's lobe mean,
// nonzero on an open plane at a grazing angle) and the occluders' (the open
// part's mean from there). The horizon's part counts at kHorizonBendShare.
// In full it made every open floor worse (the stability suite's NaN-vertex
// floor worse than no SSGI: HDR-FLIP 0.00966 against 0.00954); left out,
// balls lost the turn of their grazing reflections (spheres 0.0419 ->
// 0.0437, MetalRoughSpheres 0.0403 -> 0.0415). At 3/4: NaN-vertex 0.00942,
// flat plane 0.00674 -> 0.00622, grazing floor 0.00627 -> 0.00573, spheres
// 0.0422, MetalRoughSpheres 0.0409 (docs/BENCHMARKS.md, "Session 10").
const float kHorizonBendShare = 0.75;
vec3 sliceSpecularVisibility(Slice slice, uint covered, vec3 reflected, float alpha) {
  const vec3 axis = cross(slice.side, slice.toEye);
  const float outOfPlane = dot(reflected, axis);
  float weight = max(1.0 - outOfPlane * outOfPlane, 0.0);
  weight *= weight;
  weight *= weight;
  const float thetaR = atan(dot(reflected, slice.side), dot(reflected, slice.toEye));
  const float sectorAngle = kPi / float(kSectors);
  const float k = 0.5 * alpha;
  float open = 0.0, total = 0.0, openAngle = 0.0, totalAngle = 0.0;  // angles from R, lobe-weighted
  for (int s = 0; s < kSectors; ++s) {
    const float fromHorizon = (float(s) + 0.5) * sectorAngle;
    const float fromR = slice.lowest + fromHorizon - thetaR;
    const float offset = fromR / (2.0 * alpha);
    const float profile = 1.0 / (1.0 + offset * offset);
    const float nDotL = sinHalfTurn(fromHorizon);
    const float lobe = profile * profile * nDotL / (nDotL * (1.0 - k) + k);
    total += lobe;
    totalAngle += lobe * fromR;
    if ((covered & (1u << uint(s))) == 0u) {
      open += lobe;
      openAngle += lobe * fromR;
    }
  }
  if (total <= 1e-12) return vec3(0.0);
  // The normal's angle in the slice is lowest + pi/2: positive bends toward it.
  const float towardNormal = slice.lowest + 0.5 * kPi >= thetaR ? 1.0 : -1.0;
  // The lobe's mean over the hemisphere, then the open part's mean from it.
  const float horizonBend = totalAngle / total;
  const float occluderBend = open > 1e-12 ? openAngle / open - horizonBend : 0.0;
  const float bend = open > 1e-12 ? towardNormal * (occluderBend + kHorizonBendShare * horizonBend) : 0.0;
  const float visible = weight * open / total;
  return vec3(visible, weight, visible * bend);
}

// The specular visibility the pass writes: R = the slices' weighted mean
// (the diffuse sky visibility where no slice saw the lobe), G = the mean
// slice weight, by which the blur weighs the pixel against its neighbours,
// B = the bend (radians toward the normal), the slices' mean weighted by
// their open shares.
vec4 specularOutput(vec3 specularSum, float skyVisibility, int sliceCount) {
  const bool seen = specularSum.y > 1e-4;
  const float visibility = seen ? clamp(specularSum.x / specularSum.y, 0.0, 1.0) : skyVisibility;
  // The intensity fades the occlusion, and the bend with it (0: none).
  const float bend = specularSum.x > 1e-6 ? clamp(bitmask.intensity, 0.0, 1.0) * specularSum.z / specularSum.x : 0.0;
  return vec4(clamp(1.0 - bitmask.intensity * (1.0 - visibility), 0.0, 1.0),
              specularSum.y / float(max(sliceCount, 1)), bend, 0.0);
}

// The light the screen hides within R, from the light field (issue 33; docs/ACCURACY.md §3.3, "The light
// field"). A sector first covered within R by a surface that faces away from the point (the lit side of
// builtin:slats' bars, which faces away from the camera) gathered nothing: what lights the point from there
// is hidden. The field's irradiance, at the probes' resolution, stands in for it over those sectors'
// cosine-weighted share, `hiddenShare`. Light from beyond R stays the virtual lights' (their gather is
// sharper than the probes: builtin:cornell's HDR-FLIP 0.144 with them, 0.196 with the field's light
// through the open directions instead, at 64 probes); the field over every covered sector less what the
// near field gathered there lit the floor round cornell's blocks with the open room's light (0.166).
vec3 hiddenWithinRadius(LightFieldGrid grid, vec3 worldPosition, vec3 worldNormal, vec3 worldToEye, float hiddenShare) {
  return lightFieldIrradiance(grid, worldPosition, worldNormal, worldToEye) / kPi * hiddenShare;
}

// The slices' rotation (in units of pi / sliceCount: slice s lies at angle
// (s + rotation) pi / sliceCount on screen) turned so that slice 0 holds the
// reflection R, by `share` of the way from `random`. A polished metal is lit
// by its specular alone, and a lobe narrower than the angle between slices
// was read by whichever slice the pixel's random rotation brought near R:
// black grain on mirrors that the blur, weighing by normals that turn fast
// across a ball, could not average (issue 33). Where the diffuse albedo
// ((1 - metallic) x the base colour's largest channel) is 0 the AO and
// indirect light shade nothing, so the turn costs them nothing: metals,
// and black dielectrics such as specular-glossiness chrome. Rough surfaces
// and those with a diffuse colour keep the random rotation, whose variety
// the blur averages.
float turnedTowardReflection(float random, vec3 reflected, vec3 toEye, float diffuseAlbedo, float roughness,
                             int sliceCount) {
  const float share = (1.0 - smoothstep(0.0, 0.25, diffuseAlbedo)) * (1.0 - smoothstep(0.3, 0.6, roughness));
  // The slice plane holds toEye and the screen direction (d, 0): R lies in
  // it for d along R's component off toEye, with z removed.
  const vec2 d = reflected.xy * toEye.z - toEye.xy * reflected.z;
  if (share <= 0.0 || dot(d, d) < 1e-12) return random;
  const float aligned = fract(atan(d.y, d.x) * float(sliceCount) / kPi);
  // The slices repeat with period 1 in rotation: turn the short way round.
  const float turn = fract(aligned - random + 0.5) - 0.5;
  return fract(random + share * turn);
}

PassOutputs shadePixel(ivec2 outputPixel) {
  const int divisor = bitmask.downsample;
  const ivec2 size = ivec2(frame.viewport.xy);
  const ivec2 pixel = min(outputPixel * divisor + divisor / 2, size - 1);
  const float depth = texelFetch(gbufferDepth, pixel, 0).r;
  if (depth >= 1.0) {  // background: open, no light
    const vec4 open = vec4(1.0, 0.0, 0.0, 0.0);
    return PassOutputs(open, open, open, open);
  }

  const vec3 position = viewPositionAt(pixel, depth);
  const vec3 normal = normalize(mat3(frame.view) * texelFetch(gbufferNormal, pixel, 0).xyz);
  const vec3 toEye = orthographicView() ? vec3(0.0, 0.0, 1.0) : normalize(-position);
  // R's footprint on screen, in pixels, at the shaded point's depth.
  const float pixelsPerUnit =
      0.5 * frame.viewport.y * frame.projection[1][1] / (orthographicView() ? 1.0 : max(-position.z, 1e-30));
  const float radiusPixels = bitmask.radiusWorld * pixelsPerUnit;

  // The seed and accumulated frames turn both by irrational steps (R2 sequence).
  const float rotationIndex = float(bitmask.rotationIndex);
  const int sliceCount = bitmask.sliceCount;
  const int bayer = kBayer[(outputPixel.y & 3) * 4 + (outputPixel.x & 3)];
  const uint tileHash = pcgHash(uint(outputPixel.x >> 2) + 4099u * uint(outputPixel.y >> 2));
  const float randomRotation =
      fract((float(bayer) + 0.5) / 16.0 + unitFromHash(tileHash) + 0.7548777 * rotationIndex);
  const float jitter = fract((float((bayer * 7 + 5) & 15) + 0.5) / 16.0 + unitFromHash(pcgHash(tileHash)) +
                             0.5698403 * rotationIndex);

  const vec3 reflected = reflect(-toEye, normal);
  const vec2 metallicRoughness = texelFetch(gbufferMaterial, pixel, 0).xy;
  const vec3 baseColor = texelFetch(gbufferAlbedo, pixel, 0).rgb;
  const float lobeAlpha = specularLobeAlpha(metallicRoughness.y);
  const float diffuseAlbedo = (1.0 - metallicRoughness.x) * max(baseColor.r, max(baseColor.g, baseColor.b));
  const float rotation =
      turnedTowardReflection(randomRotation, reflected, toEye, diffuseAlbedo, metallicRoughness.y, sliceCount);
  vec3 specularSum = vec3(0.0);  // the slices' weighted open shares of the lobe, their weights, bends

  float visibleSum = 0.0, skyVisibleSum = 0.0, hiddenSum = 0.0, totalSum = 0.0;
  vec3 indirect = vec3(0.0), farIndirect = vec3(0.0);  // gathered within R, and beyond it
  OccludingSlices occluding;
  occluding.count = 0;
  for (int s = 0; s < sliceCount; ++s) {
    const float phi = (float(s) + rotation) * kPi / float(sliceCount);
    Slice slice;
    slice.direction = vec2(cos(phi), sin(phi));
    slice.toEye = toEye;
    slice.side = normalize(vec3(slice.direction, 0.0) - toEye * dot(vec3(slice.direction, 0.0), toEye));
    const vec3 axis = cross(slice.side, toEye);
    const vec3 projectedNormal = normal - axis * dot(normal, axis);
    slice.projectedLength = length(projectedNormal);
    if (slice.projectedLength < 1e-4) continue;  // the normal is the slice's axis: it holds no solid angle
    const float n = clamp(atan(dot(projectedNormal, slice.side), dot(projectedNormal, toEye)), -0.5 * kPi, 0.5 * kPi);
    slice.lowest = n - 0.5 * kPi;
    float edges[kSectors + 1];
    sliceEdges(n, edges);
    const float total = edges[kSectors] - edges[0];  // = cos(n) + n sin(n)
    slice.occupied = 0u;
    slice.skyOccupied = 0u;
    slice.hiddenOccupied = 0u;
    slice.indirect = vec3(0.0);
    slice.farIndirect = vec3(0.0);
    for (int sign = -1; sign <= 1; sign += 2) {
      const vec2 stepDirection = slice.direction * float(sign);
      // Each march its own jitter (golden-ratio steps): with one shared
      // jitter every march of a pixel put its samples at the same distances.
      const float march = float(4 * s + sign + 1);
      marchWithinRadius(slice, edges, stepDirection, pixel, position, radiusPixels, fract(jitter + 0.618034 * march));
      marchBeyondRadius(slice, edges, stepDirection, pixel, position, radiusPixels,
                        fract(jitter + 0.618034 * (march + 1.0)));
    }
    if (occluding.count < kOccludingSlices) {
      occluding.axis[occluding.count] = axis;
      occluding.side[occluding.count] = slice.side;
      occluding.lowest[occluding.count] = slice.lowest;
      occluding.occupied[occluding.count] = slice.occupied;
      ++occluding.count;
    }
    indirect += slice.indirect;
    farIndirect += slice.farIndirect;
    visibleSum += slice.projectedLength * max(total - sectorWeight(slice.occupied, edges), 0.0);
    hiddenSum += slice.projectedLength * sectorWeight(slice.hiddenOccupied, edges);
    // What is occluded within R is occluded from the sky too.
    const float skyOccludedWeight = sectorWeight(slice.skyOccupied | slice.occupied, edges);
    // The near field's own pass writes no specular (the far field's does).
    if (bitmask.part != kBitmaskNearField)
      specularSum += sliceSpecularVisibility(slice, slice.skyOccupied | slice.occupied, reflected, lobeAlpha);
    skyVisibleSum += slice.projectedLength * max(total - skyOccludedWeight, 0.0);
    totalSum += slice.projectedLength * total;
  }
  // The ratio of the slices' visible to total cosine-weighted measure: an
  // open plane is exactly 1 at any slice count.
  const float visibility = totalSum > 0.0 ? clamp(visibleSum / totalSum, 0.0, 1.0) : 1.0;
  const float ambientOcclusion = clamp(1.0 - bitmask.intensity * (1.0 - visibility), 0.0, 1.0);
  const float skyVisibility = totalSum > 0.0 ? clamp(skyVisibleSum / totalSum, 0.0, 1.0) : 1.0;
  // A Lambertian receiver: (1 - metallic) albedo / pi * integral(L cos) over
  // the occluded directions; the sums above are that integral over pi.
  const vec3 receiver = (1.0 - metallicRoughness.x) * baseColor;
  const vec3 gathered = totalSum > 0.0 ? indirect / totalSum : vec3(0.0);
  const vec4 nearField = vec4(ambientOcclusion, gathered * receiver * bitmask.indirectStrength);
  // With no sky steps the mask above is the within-R one: sky = AO.
  vec3 farGathered = totalSum > 0.0 ? farIndirect / totalSum : vec3(0.0);
  if (bitmask.virtualLightCount > 0 && bitmask.part != kBitmaskNearField) {
    const vec3 worldPosition = transpose(mat3(frame.view)) * (position - frame.view[3].xyz);
    const vec3 worldNormal = texelFetch(gbufferNormal, pixel, 0).xyz;
    const int subset = (bayer + int(tileHash & 15u)) & (kVirtualLightSubsets - 1);
    farGathered += virtualLightGather(worldPosition, worldNormal, subset, occluding, toEye);
    if (bitmask.lightFieldCounts.x > 0) {
      const LightFieldGrid grid = LightFieldGrid(bitmask.lightFieldOrigin.xyz, bitmask.lightFieldSpacing.xyz,
                                                 bitmask.lightFieldCounts.xyz);
      const float hiddenShare = totalSum > 0.0 ? clamp(hiddenSum / totalSum, 0.0, 1.0) : 0.0;
      farGathered +=
          hiddenWithinRadius(grid, worldPosition, worldNormal, transpose(mat3(frame.view)) * toEye, hiddenShare);
    }
  }
  const vec4 farField = vec4(clamp(1.0 - bitmask.intensity * (1.0 - skyVisibility), 0.0, 1.0),
                             farGathered * receiver * bitmask.indirectStrength);
  const float skyOfOpen = nearField.x > 1e-3 ? min(farField.x / nearField.x, 1.0) : 1.0;
  return PassOutputs(nearField, farField, vec4(skyOfOpen, farField.yzw),
                     specularOutput(specularSum, skyVisibility, sliceCount));
}
