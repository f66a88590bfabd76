// The per-pixel path of the Embree reference (tracer.hpp): Tracer's
// tracePixel, the lobe reads and the rays it casts (pixel_tracer.hpp holds the
// class), and traceRows, which hands rows to a worker's Tracer.
#include "reference/tracer.hpp"

#if defined(__x86_64__) || defined(_M_X64)
#include <pmmintrin.h>
#include <xmmintrin.h>
#endif

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>

#include "headlight/error.hpp"
#include "reference/frame_lobes.hpp"
#include "reference/lobe_clearcoat.hpp"
#include "reference/lobe_transmission.hpp"
#include "reference/pixel_tracer.hpp"
#include "reference/shading.hpp"
#include "reference/transmission_trace.hpp"

namespace headlight::reference {

void Tracer::tracePixel(int x, int y, const Outputs& out) {
  const Frame& frame = in_.frame;
  const std::size_t pixel = std::size_t(y) * std::size_t(frame.position.width) + std::size_t(x);
  float* ao = &out.images.ao.pixels[pixel * 3];
  float* indirect = &out.images.indirect.pixels[pixel * 6];
  float* lit = &out.images.lit.pixels[pixel * 4];
  if (frame.position.at(x, y, 3) == 0.0f) {
    const glm::vec3 sky = backgroundRadiance(backgroundRay(x, y));
    ao[0] = ao[1] = ao[2] = 1.0f;
    std::fill(indirect, indirect + 6, 0.0f);
    lit[0] = sky.r, lit[1] = sky.g, lit[2] = sky.b, lit[3] = 0.0f;
    if (in_.blendedScene) {
      Pcg32 random = pixelStream(in_.settings.seed, pixel);
      compositeBlended(x, y, nullptr, lit, random);
    }
    return;
  }

  const glm::vec3 position(frame.position.at(x, y, 0), frame.position.at(x, y, 1), frame.position.at(x, y, 2));
  if (!isFinite(position))
    throw SettingsError("traceReference: frame.position at pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                        ") is not finite on a geometry pixel (A = 1)");
  const glm::vec3 albedo(frame.albedo.at(x, y, 0), frame.albedo.at(x, y, 1), frame.albedo.at(x, y, 2));
  const float metallic = frame.material.at(x, y, 0), roughness = frame.material.at(x, y, 1);
  glm::vec3 normal(frame.normal.at(x, y, 0), frame.normal.at(x, y, 1), frame.normal.at(x, y, 2));
  const float normalLength = glm::length(normal);
  // A G-buffer normal is unit length; a hand-made frame might hold zero.
  normal = normalLength > 1e-6f && std::isfinite(normalLength) ? normal / normalLength : glm::vec3(0, 1, 0);
  // Embree asserts on non-finite rays: a camera at the shading point has
  // no view direction, so it looks along the normal.
  glm::vec3 view = viewDirection(position);
  if (!std::isfinite(view.x + view.y + view.z)) view = normal;
  const glm::vec3 origin = position + normal * in_.epsilon;
  const Basis basis = basisAround(normal);
  Pcg32 random = pixelStream(in_.settings.seed, pixel);
  Surface surface = makeSurface(albedo, metallic, roughness, normal, view);
  TransmissiveSurface transmissive = transmissiveSurfaceHere(x, y);
  if (transmissive.share > 0.0f) {  // transmission.glsl: ior's F0, then every lobe as on an opaque surface
    surface.f0 = iorF0(transmissive.ior, albedo, metallic);
    surface.transmission = transmissive.share;
    transmissive.blur = transmissionRoughness(roughness, transmissive.ior);
  }
  const Clearcoat coat = frameLobesAt(frame, x, y, surface);

  // Cosine-weighted rays: AO, indirect, the diffuse sky.
  const int n = in_.settings.samplesPerPixel;
  const float radius = in_.settings.radius;
  const glm::vec3 diffuseWeight = (1.0f - metallic) * albedo;
  int open = 0, escaped = 0;
  glm::dvec3 sum(0.0), sumSquares(0.0), sumWithinRadius(0.0), skySum(0.0);
  for (int i = 0; i < n; ++i) {
    const float xi0 = random.uniform(), xi1 = random.uniform();
    const glm::vec3 direction = basis.toWorld(cosineSampleHemisphere(xi0, xi1));
    RTCRayHit rayHit = traceFromSurface(origin, direction, view);
    if (rayHit.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
      ++open;
      ++escaped;
      if (!in_.environment)
        skySum += glm::dvec3(skyRadiance(in_.scene.sky, direction) * layerScaleToward(surface, direction));
      continue;
    }
    const float t = rayHit.ray.tfar;
    if (in_.settings.screenBound && t < radius && !shownOnScreen(origin + direction * t)) {
      ++open;  // a screen-space method sees nothing there
      continue;
    }
    if (t >= radius) ++open;
    // Glass is geometry to AO (above), but the sky and the surfaces behind
    // it light the pixel through it, tinted as a light is through it (it
    // sends no Lambertian light of its own: its transmitted share's).
    const PassedHit through = pastTransmissive(origin, direction, rayHit);
    if (through.hit.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
      if (!in_.environment)
        skySum += glm::dvec3(through.transmittance * skyRadiance(in_.scene.sky, direction) *
                             layerScaleToward(surface, direction));
      continue;
    }
    const glm::dvec3 contribution =
        glm::dvec3(through.transmittance * diffuseWeight * radianceLeaving(through.hit, direction));
    sum += contribution;
    sumSquares += contribution * contribution;
    if (t < radius) sumWithinRadius += contribution;
  }
  const double count = double(n);
  const double aoValue = double(open) / count;
  const glm::dvec3 indirectMean = sum / count;
  const glm::dvec3 indirectRMean = sumWithinRadius / count;
  ao[0] = float(aoValue);
  ao[1] = float(double(escaped) / count);
  ao[2] = ao[1];  // specular.Y where no specular sample is taken (an unlit pixel); ambientLight's below
  for (int c = 0; c < 3; ++c) {
    indirect[c] = float(indirectRMean[c]);
    indirect[3 + c] = float(indirectMean[c]);
  }
  if (n > 1) {
    out.aoStandardError[pixel] = std::sqrt(aoValue * (1.0 - aoValue) / (count - 1.0));
    // Unbiased sample variance of the per-ray contributions, over n.
    const glm::dvec3 variance = glm::max((sumSquares - count * indirectMean * indirectMean) / (count - 1.0), 0.0);
    const glm::dvec3 standardError = glm::sqrt(variance / count);
    out.indirectStandardError[pixel] = (standardError.x + standardError.y + standardError.z) / 3.0;
  } else {
    // One sample says nothing about its spread.
    out.aoStandardError[pixel] = std::numeric_limits<double>::quiet_NaN();
    out.indirectStandardError[pixel] = std::numeric_limits<double>::quiet_NaN();
  }

  // KHR_materials_unlit (material.exr's material.unlit): lit is the albedo,
  // as the composite writes it.
  if (unlitPixel(x, y)) {
    lit[0] = albedo.r, lit[1] = albedo.g, lit[2] = albedo.b, lit[3] = 1.0f;
    return;
  }
  const glm::vec3 skyMean =
      in_.environment ? environmentIrradianceOverPi(surface, origin, n, random) : glm::vec3(skySum / count);
  glm::vec3 specularAlbedo(0.0f);
  // The material's occlusion (glTF's occlusionTexture x strength) dims the
  // sky's light, the coat's too, as the composite does; not the one bounce
  // (ambient.glsl adds SSGI's indirect light after it).
  const float materialOcclusion = frame.material.channelCount() > 2 ? frame.material.at(x, y, 2) : 1.0f;
  // A transmissive surface's diffuse lobe keeps only the share not transmitted (ambientLight's too).
  glm::vec3 under = materialOcclusion * ambientLight(surface, origin, basis, skyMean, random, &specularAlbedo, &ao[2]) +
                    glm::vec3(indirectMean) * (1.0f - surface.transmission);
  if (!frame.emissive.empty())
    under += glm::vec3(frame.emissive.at(x, y, 0), frame.emissive.at(x, y, 1), frame.emissive.at(x, y, 2));
  // The coat over all the base sends; directLight layers it per light.
  glm::vec3 radiance = directLight(surface, position, origin, coat, transmissive) +
                       clearcoatLayer(coat, under, materialOcclusion * coatAmbient(coat, view, origin, random));
  if (transmissive.share > 0.0f)
    radiance += transmittedLight(surface, position, transmissive, specularAlbedo, coat, random);
  lit[0] = radiance.r, lit[1] = radiance.g, lit[2] = radiance.b, lit[3] = 1.0f;
  // After the opaque surface's samples, so its numbers do not depend on
  // whether the scene blends.
  if (in_.blendedScene) compositeBlended(x, y, &position, lit, random);
}

// The coat's reflection of the sky (or map) with true visibility, times
// the intensity; none, and no random numbers drawn, without a coat.
glm::vec3 Tracer::coatAmbient(const Clearcoat& coat, const glm::vec3& view, const glm::vec3& origin, Pcg32& random) {
  if (coat.weight <= 0.0f) return glm::vec3(0.0f);
  const glm::vec3 sum = clearcoatAmbient(coat, view, in_.specularSamples, random, [&](const glm::vec3& direction) {
    return unoccluded(origin, direction, std::numeric_limits<float>::infinity()) ? ambientRadiance(direction)
                                                                                 : glm::vec3(0.0f);
  });
  return sum * in_.skyIntensity;
}

// The first surface along `direction` from a shading point's offset origin
// `origin` (p + eps n), robust where that origin lies on another surface's
// plane (a pixel centred on a crease: p + eps n is still on the adjacent
// wall, and float rounding decided whether rays into the wall hit it).
// The ray starts eps behind the origin, so a surface through the origin
// is met at t = eps (to rounding) whichever way the ray crosses it.
// Surfaces met before that (behind the origin) are passed, as before;
// those after are hits. One met within 10% of eps of the origin is a hit
// only when the ray enters it from the side that faces the camera
// (`toEye`, the view direction at p): that side is the free one, since the
// camera sees p past it. Met from its hidden side it is a surface the
// origin sits on, and the ray goes on (as a path tracer skips the
// primitive it starts on). `rayHit.ray.tfar` is returned from the origin.
RTCRayHit Tracer::traceFromSurface(const glm::vec3& origin, const glm::vec3& direction, const glm::vec3& toEye) {
  const float epsilon = in_.epsilon;
  const glm::vec3 start = origin - direction * epsilon;
  RTCRayHit rayHit = makeRayHit(start, direction, std::numeric_limits<float>::infinity());
  for (int attempt = 0; attempt < 8; ++attempt) {
    rtcIntersect1(in_.rtcScene, &context_, &rayHit);
    if (rayHit.hit.geomID == RTC_INVALID_GEOMETRY_ID) break;
    const float t = rayHit.ray.tfar;
    if (t > 1.1f * epsilon) break;
    if (t >= 0.9f * epsilon) {
      const glm::vec3 faceNormal(rayHit.hit.Ng_x, rayHit.hit.Ng_y, rayHit.hit.Ng_z);
      const float towardEye = glm::dot(faceNormal, toEye), along = glm::dot(faceNormal, direction);
      if (towardEye * along < 0.0f || towardEye == 0.0f) break;  // entered from the eye's side
    }
    rayHit = makeRayHit(start, direction, std::numeric_limits<float>::infinity());
    rayHit.ray.tnear = std::nextafter(t, std::numeric_limits<float>::infinity());
  }
  if (rayHit.hit.geomID != RTC_INVALID_GEOMETRY_ID) rayHit.ray.tfar = std::max(rayHit.ray.tfar - epsilon, 0.0f);
  return rayHit;
}

PassedHit Tracer::pastTransmissive(const glm::vec3& origin, const glm::vec3& direction, const RTCRayHit& first) {
  if (!in_.transmissiveScene || first.hit.geomID == RTC_INVALID_GEOMETRY_ID ||
      !in_.instances[first.hit.geomID].material->transmissive())
    return {first, glm::vec3(1.0f)};
  return passTransmissive(in_.scene, in_.instances, in_.rtcScene, context_, origin, direction, first);
}

// True when nothing lies between `origin` and `far` along `direction`.
// Embree asserts on non-finite rays, so one (from a light at NaN, say)
// counts as blocked.
bool Tracer::unoccluded(const glm::vec3& origin, const glm::vec3& direction, float far) {
  if (!isFinite(origin) || !isFinite(direction)) return false;
  RTCRay ray = makeRayHit(origin, direction, far).ray;
  rtcOccluded1(in_.rtcScene, &context_, &ray);
  return ray.tfar >= 0.0f;  // Embree sets tfar to -inf on a hit
}

// True when `point` (world, on a surface) is in the frame's view and the
// camera sees it: nothing lies between it and the near plane along its
// camera ray (perspective and orthographic alike).
bool Tracer::shownOnScreen(const glm::vec3& point) {
  const glm::vec4 clip = clipFromWorld_ * glm::vec4(point, 1.0f);
  if (!(clip.w > 0.0f)) return false;
  const glm::vec3 ndc = glm::vec3(clip) / clip.w;
  if (std::abs(ndc.x) > 1.0f || std::abs(ndc.y) > 1.0f || std::abs(ndc.z) > 1.0f) return false;
  const glm::vec4 nearPoint = worldFromClip_ * glm::vec4(ndc.x, ndc.y, -1.0f, 1.0f);
  const glm::vec3 origin = glm::vec3(nearPoint) / nearPoint.w;
  const glm::vec3 toPoint = point - origin;
  const float distance = glm::length(toPoint);
  // Short of the point by a few epsilons: the ray must not meet the surface it lies on.
  const float far = distance - 4.0f * in_.epsilon;
  return far <= 0.0f || unoccluded(origin, toPoint / distance, far);
}

// The transmissive surface the pixel's primary ray meets first, if any.
TransmissiveSurface Tracer::transmissiveSurfaceHere(int x, int y) {
  if (!in_.transmissiveScene) return {};
  const auto [origin, direction] = primaryRay(x, y);
  if (!isFinite(origin) || !isFinite(direction)) return {};
  return transmissiveSurfaceAt(in_.scene, in_.instances, in_.rtcScene, context_, origin, direction);
}

// makeSurface's roughness floor: a surface at it is smooth, and sends one ray.
constexpr float kSmoothTransmissionRoughness = 0.03f;

// What reaches the eye through a transmissive surface (transmission_trace.hpp's model): the first opaque
// surface along the view direction from where the volume's path leaves, shaded in full (as a blended
// layer is), or the background, times the renderer's throughput under the coat.
glm::vec3 Tracer::transmittedLight(const Surface& surface, const glm::vec3& position, const TransmissiveSurface& t,
                                   const glm::vec3& specularAlbedo, const Clearcoat& coat, Pcg32& random) {
  const glm::vec3 path = volumeTransmissionRay(surface.normal, surface.view, t.thickness, t.ior, t.modelScale);
  const glm::vec3 attenuation = volumeAttenuation(glm::length(path), t.attenuationColor, t.attenuationDistance);
  // A rough surface spreads what it lets through: each of the specular
  // samples crosses two uncorrelated rough interfaces, the front's and the
  // back's (parallel to it; a thin wall's two sides), microfacet normals
  // drawn from GGX's D(m) (n.m) at the surface's roughness and refracted by
  // Snell's law at each, so ior 1 bends nothing at any roughness
  // (TransmissionRoughnessTest's model). The samples weigh alike: they give
  // the lobe's shape; its energy is the throughput's. A smooth surface, or
  // ior 1, sends one ray straight on, shading what it meets with the
  // pixel's rays; a rough one shares them among its directions.
  const float eta = std::max(t.ior, 1.0f);
  const bool rough = surface.roughness > kSmoothTransmissionRoughness && eta > 1.0f;
  const int count = rough ? std::max(in_.specularSamples, 1) : 1;
  const int raysEach = rough ? std::max(in_.settings.samplesPerPixel / count, 1) : 0;
  const float alpha = surface.roughness * surface.roughness;
  const Basis basis = basisAround(surface.normal);
  glm::vec3 sum(0.0f);
  int crossed = 0;
  for (int i = 0; i < count; ++i) {
    glm::vec3 direction = -surface.view;
    if (rough) {
      const glm::vec3 front = basis.toWorld(importanceSampleGgx(random.uniform(), random.uniform(), alpha));
      const glm::vec3 back = basis.toWorld(importanceSampleGgx(random.uniform(), random.uniform(), alpha));
      if (glm::dot(surface.view, front) <= 0.0f) continue;  // a facet the eye cannot see
      const glm::vec3 inside = refractGlsl(-surface.view, front, 1.0f / eta);
      if (glm::dot(inside, back) >= 0.0f) continue;  // meets the back facet from behind
      const glm::vec3 out = refractGlsl(glm::normalize(inside), back, eta);
      if (out == glm::vec3(0.0f)) continue;  // reflected inside at the back: not this lobe's light
      direction = glm::normalize(out);
    }
    const RTCRayHit hit =
        firstOpaqueHit(in_.instances, in_.rtcScene, context_, position + path, direction, in_.epsilon);
    glm::vec3 behind(0.0f);
    float alphaBehind = 0.0f;
    if (hit.hit.geomID == RTC_INVALID_GEOMETRY_ID)
      behind = backgroundRadiance(direction);
    else if (!shadeBlendedHit(hit, direction, random, behind, alphaBehind, raysEach))
      behind = glm::vec3(0.0f);  // the back of a single-sided surface: never drawn
    sum += behind;
    ++crossed;
  }
  if (crossed == 0) return glm::vec3(0.0f);
  // What the coat does not reflect goes on through (transmission.glsl).
  return clearcoatLayer(coat, transmissionThroughput(surface, specularAlbedo, attenuation), glm::vec3(0.0f)) *
         (sum / float(crossed));
}

// composite.frag's background ray, for this top-first pixel.
glm::vec3 Tracer::backgroundRay(int x, int y) const {
  const CameraView& view = in_.frame.view;
  const float width = float(in_.frame.position.width), height = float(in_.frame.position.height);
  const glm::vec2 fragCoord(float(x) + 0.5f, height - float(y) - 0.5f);  // GL's rows run bottom up
  const glm::vec4 clip(fragCoord.x / width * 2.0f - 1.0f, fragCoord.y / height * 2.0f - 1.0f, 1.0f, 1.0f);
  const glm::vec4 viewFar = glm::inverse(view.projection) * clip;
  const glm::vec3 rayView = view.orthographic ? glm::vec3(0.0f, 0.0f, -1.0f) : glm::vec3(viewFar) / viewFar.w;
  return glm::normalize(glm::transpose(glm::mat3(view.view)) * rayView);
}

// The primary ray through the centre of top-first pixel (x, y), from the
// near plane (perspective and orthographic alike).
std::pair<glm::vec3, glm::vec3> Tracer::primaryRay(int x, int y) const {
  const float width = float(in_.frame.position.width), height = float(in_.frame.position.height);
  const glm::vec2 ndc((float(x) + 0.5f) / width * 2.0f - 1.0f, (height - float(y) - 0.5f) / height * 2.0f - 1.0f);
  const glm::vec4 nearPoint = worldFromClip_ * glm::vec4(ndc, -1.0f, 1.0f);
  const glm::vec4 farPoint = worldFromClip_ * glm::vec4(ndc, 1.0f, 1.0f);
  const glm::vec3 origin = glm::vec3(nearPoint) / nearPoint.w;
  return {origin, glm::normalize(glm::vec3(farPoint) / farPoint.w - origin)};
}

namespace {

// Embree's advice for speed: denormals flushed to zero on tracing threads.
void setFlushDenormals() {
#if defined(__x86_64__) || defined(_M_X64)
  _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
  _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
#endif
}

}  // namespace

void traceRows(const TraceInputs& inputs, const Outputs& outputs, std::atomic<int>& nextRow) {
  setFlushDenormals();
  Tracer tracer(inputs);
  const int width = inputs.frame.position.width, height = inputs.frame.position.height;
  for (int y = nextRow++; y < height; y = nextRow++)
    for (int x = 0; x < width; ++x) tracer.tracePixel(x, y, outputs);
}

}  // namespace headlight::reference
