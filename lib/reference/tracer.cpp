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
#include <vector>

#include "headlight/error.hpp"
#include "reference/lobe_transmission.hpp"
#include "reference/lobe_clearcoat.hpp"
#include "reference/lobe_specular.hpp"
#include "reference/shading.hpp"
#include "reference/texture_sampler.hpp"
#include "reference/transmission_trace.hpp"

namespace headlight::reference {

namespace {

bool isFinite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Blended layers composited along one primary ray, nearest first; more are
// ignored (32 layers of alpha 0.1 leave 3 % of what is behind).
constexpr int kMaxBlendLayers = 32;

// One worker's tracer: its own Embree intersect context over the shared
// inputs.
class Tracer {
 public:
  explicit Tracer(const TraceInputs& in) : in_(in) { rtcInitIntersectContext(&context_); }

  void tracePixel(int x, int y, const Outputs& out) {
    const Frame& frame = in_.frame;
    const std::size_t pixel = std::size_t(y) * std::size_t(frame.position.width) + std::size_t(x);
    float* ao = &out.images.ao.pixels[pixel * 2];
    float* indirect = &out.images.indirect.pixels[pixel * 6];
    float* lit = &out.images.lit.pixels[pixel * 4];
    if (frame.position.at(x, y, 3) == 0.0f) {
      const glm::vec3 sky = backgroundRadiance(backgroundRay(x, y));
      ao[0] = ao[1] = 1.0f;
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
    // The transmission pass applies ior's F0 and no lobe (transmission.glsl).
    if (transmissive.share <= 0.0f) readLobes(x, y, surface);

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
          skySum += glm::dvec3(skyRadiance(in_.scene.sky, direction) * sheenBaseScale(surface, direction));
        continue;
      }
      const float t = rayHit.ray.tfar;
      if (t >= radius) ++open;
      const glm::dvec3 contribution = glm::dvec3(diffuseWeight * radianceLeaving(rayHit, direction));
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
    Clearcoat coat;  // none: a weight of 0 changes nothing
    if (transmissive.share > 0.0f) {
      surface.f0 = iorF0(transmissive.ior, albedo, metallic);
      transmissive.blur = transmissionRoughness(roughness, transmissive.ior);
    } else {
      coat = lobesAt(x, y, surface);
      applyIridescence(surface, iridescenceInputsAt(frame, x, y));  // no film without iridescence.exr
    }
    const glm::vec3 skyMean =
        in_.environment ? environmentIrradianceOverPi(surface, origin, n, random) : glm::vec3(skySum / count);
    // A transmissive surface's diffuse lobe keeps only the share not transmitted.
    const float diffuseShare = 1.0f - transmissive.share;
    glm::vec3 specularAlbedo(0.0f);
    glm::vec3 under = ambientLight(surface, origin, basis, skyMean * diffuseShare, random, &specularAlbedo) +
                      glm::vec3(indirectMean) * diffuseShare;
    if (!frame.emissive.empty())
      under += glm::vec3(frame.emissive.at(x, y, 0), frame.emissive.at(x, y, 1), frame.emissive.at(x, y, 2));
    // The coat over all the base sends; directLight layers it per light.
    glm::vec3 radiance = directLight(surface, position, origin, coat, transmissive) +
                         clearcoatLayer(coat, under, coatAmbient(coat, view, origin, random));
    if (transmissive.share > 0.0f)
      radiance += transmittedLight(surface, position, transmissive, specularAlbedo, random);
    lit[0] = radiance.r, lit[1] = radiance.g, lit[2] = radiance.b, lit[3] = 1.0f;
    // After the opaque surface's samples, so its numbers do not depend on
    // whether the scene blends.
    if (in_.blendedScene) compositeBlended(x, y, &position, lit, random);
  }

 private:
  // The lobe targets at a pixel (lobe_specular.hpp, lobe_clearcoat.hpp):
  // the specular lobe changes `surface`; the coat is returned (factor 0,
  // changing nothing, where the frame has no clearcoat target).
  Clearcoat lobesAt(int x, int y, Surface& surface) const {
    auto at = [&](const ImageF& image) {
      return glm::vec4(image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2), image.at(x, y, 3));
    };
    if (!in_.frame.specular.empty()) applySpecularLobe(surface, at(in_.frame.specular));
    return in_.frame.clearcoat.empty() ? Clearcoat{} : makeClearcoat(at(in_.frame.clearcoat), surface.view);
  }

  // The coat's reflection of the sky (or map) with true visibility, times
  // the intensity; none, and no random numbers drawn, without a coat.
  glm::vec3 coatAmbient(const Clearcoat& coat, const glm::vec3& view, const glm::vec3& origin, Pcg32& random) {
    if (coat.weight <= 0.0f) return glm::vec3(0.0f);
    const glm::vec3 sum = clearcoatAmbient(coat, view, in_.specularSamples, random, [&](const glm::vec3& direction) {
      return unoccluded(origin, direction, std::numeric_limits<float>::infinity()) ? ambientRadiance(direction)
                                                                                   : glm::vec3(0.0f);
    });
    return sum * in_.skyIntensity;
  }

  // The G-buffer's lobe targets at the pixel (KHR_materials_sheen and
  // _anisotropy), where the frame has them; the surface keeps its no-effect
  // values elsewhere.
  void readLobes(int x, int y, Surface& surface) const {
    const Frame& frame = in_.frame;
    if (!frame.sheen.empty()) {
      surface.sheenColor = glm::vec3(frame.sheen.at(x, y, 0), frame.sheen.at(x, y, 1), frame.sheen.at(x, y, 2));
      surface.sheenRoughness = frame.sheen.at(x, y, 3);
    }
    if (!frame.anisotropy.empty()) {
      surface.anisotropyTangent =
          glm::vec3(frame.anisotropy.at(x, y, 0), frame.anisotropy.at(x, y, 1), frame.anisotropy.at(x, y, 2));
      surface.anisotropyStrength = frame.anisotropy.at(x, y, 3);
    }
  }

  // What the base layer keeps of light from `direction` under the sheen (1 without).
  static float sheenBaseScale(const Surface& s, const glm::vec3& direction) {
    return reference::sheenBaseScale(s.sheenColor, s.sheenRoughness, s.nDotV, glm::dot(s.normal, direction));
  }

  bool unlitPixel(int x, int y) const {
    const ImageF& material = in_.frame.material;
    return material.channelCount() > 3 && material.channels[3] == "material.unlit" && material.at(x, y, 3) > 0.5f;
  }

  static RTCRayHit makeRayHit(const glm::vec3& origin, const glm::vec3& direction, float far) {
    RTCRayHit rayHit;
    rayHit.ray.org_x = origin.x, rayHit.ray.org_y = origin.y, rayHit.ray.org_z = origin.z;
    rayHit.ray.dir_x = direction.x, rayHit.ray.dir_y = direction.y, rayHit.ray.dir_z = direction.z;
    rayHit.ray.tnear = 0.0f;
    rayHit.ray.tfar = far;
    rayHit.ray.time = 0.0f;
    rayHit.ray.mask = 0xFFFFFFFFu;
    rayHit.ray.id = 0;
    rayHit.ray.flags = 0;
    rayHit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rayHit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    return rayHit;
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
  RTCRayHit traceFromSurface(const glm::vec3& origin, const glm::vec3& direction, const glm::vec3& toEye) {
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

  // True when nothing lies between `origin` and `far` along `direction`.
  // Embree asserts on non-finite rays, so one (from a light at NaN, say)
  // counts as blocked.
  bool unoccluded(const glm::vec3& origin, const glm::vec3& direction, float far) {
    if (!isFinite(origin) || !isFinite(direction)) return false;
    RTCRay ray = makeRayHit(origin, direction, far).ray;
    rtcOccluded1(in_.rtcScene, &context_, &ray);
    return ray.tfar >= 0.0f;  // Embree sets tfar to -inf on a hit
  }

  // surface.glsl viewDirection.
  glm::vec3 viewDirection(const glm::vec3& worldPosition) const {
    const CameraView& view = in_.frame.view;
    if (view.orthographic) return glm::normalize(glm::vec3(view.view[0][2], view.view[1][2], view.view[2][2]));
    return glm::normalize(view.position - worldPosition);
  }

  // composite.frag's background: the sky or the environment map along `ray`.
  glm::vec3 backgroundRadiance(const glm::vec3& ray) const {
    return (!in_.environment ? skyRadiance(in_.scene.sky, ray)
                             : in_.environment->background ? in_.environment->radiance(ray) : glm::vec3(0.0f)) *
           in_.skyIntensity;
  }

  // The transmissive surface the pixel's primary ray meets first, if any.
  TransmissiveSurface transmissiveSurfaceHere(int x, int y) {
    if (!in_.transmissiveScene) return {};
    const auto [origin, direction] = primaryRay(x, y);
    if (!isFinite(origin) || !isFinite(direction)) return {};
    return transmissiveSurfaceAt(in_.scene, in_.instances, in_.rtcScene, context_, origin, direction);
  }

  // What reaches the eye through a transmissive surface (transmission_trace.hpp's model): the first opaque
  // surface along the view direction from where the volume's path leaves, shaded in full (as a blended
  // layer is), or the background, times the renderer's throughput.
  glm::vec3 transmittedLight(const Surface& surface, const glm::vec3& position, const TransmissiveSurface& t,
                             const glm::vec3& specularAlbedo, Pcg32& random) {
    const glm::vec3 path = volumeTransmissionRay(surface.normal, surface.view, t.thickness, t.ior, t.modelScale);
    const glm::vec3 attenuation = volumeAttenuation(glm::length(path), t.attenuationColor, t.attenuationDistance);
    const glm::vec3 direction = -surface.view;
    const RTCRayHit hit =
        firstOpaqueHit(in_.instances, in_.rtcScene, context_, position + path, direction, in_.epsilon);
    glm::vec3 behind(0.0f);
    float alpha = 0.0f;
    if (hit.hit.geomID == RTC_INVALID_GEOMETRY_ID)
      behind = backgroundRadiance(direction);
    else if (!shadeBlendedHit(hit, direction, random, behind, alpha))
      behind = glm::vec3(0.0f);  // the back of a single-sided surface: never drawn
    return transmissionThroughput(surface, specularAlbedo, t.share, attenuation) * behind;
  }

  // composite.frag's background ray, for this top-first pixel.
  glm::vec3 backgroundRay(int x, int y) const {
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
  std::pair<glm::vec3, glm::vec3> primaryRay(int x, int y) const {
    const CameraView& view = in_.frame.view;
    const float width = float(in_.frame.position.width), height = float(in_.frame.position.height);
    const glm::vec2 ndc((float(x) + 0.5f) / width * 2.0f - 1.0f, (height - float(y) - 0.5f) / height * 2.0f - 1.0f);
    const glm::mat4 worldFromClip = glm::inverse(view.projection * view.view);
    const glm::vec4 nearPoint = worldFromClip * glm::vec4(ndc, -1.0f, 1.0f);
    const glm::vec4 farPoint = worldFromClip * glm::vec4(ndc, 1.0f, 1.0f);
    const glm::vec3 origin = glm::vec3(nearPoint) / nearPoint.w;
    return {origin, glm::normalize(glm::vec3(farPoint) / farPoint.w - origin)};
  }

  // alphaMode BLEND along the primary ray: every blended layer in front of
  // the G-buffer's surface (`opaque`; null on background) is shaded and
  // composited over `lit` back to front, colour a L + (1 - a) behind and
  // alpha a + (1 - a) behind, as the blend pass does, but in the exact
  // order of the hits (no per-instance sort).
  void compositeBlended(int x, int y, const glm::vec3* opaque, float* lit, Pcg32& random) {
    const auto [origin, direction] = primaryRay(x, y);
    if (!isFinite(origin) || !isFinite(direction)) return;
    const float limit = opaque ? glm::dot(*opaque - origin, direction) - in_.epsilon
                               : std::numeric_limits<float>::infinity();
    if (!(limit > 0.0f)) return;
    struct Layer {
      glm::vec3 radiance;
      float alpha;
    };
    std::vector<Layer> layers;
    float tnear = 0.0f;
    for (int i = 0; i < kMaxBlendLayers; ++i) {
      RTCRayHit rayHit = makeRayHit(origin, direction, limit);
      rayHit.ray.tnear = tnear;
      rtcIntersect1(in_.blendedScene, &context_, &rayHit);
      if (rayHit.hit.geomID == RTC_INVALID_GEOMETRY_ID) break;
      tnear = std::nextafter(rayHit.ray.tfar, std::numeric_limits<float>::infinity());
      Layer layer;
      if (shadeBlendedHit(rayHit, direction, random, layer.radiance, layer.alpha)) layers.push_back(layer);
    }
    glm::vec3 color(lit[0], lit[1], lit[2]);
    float coverage = lit[3];
    for (auto layer = layers.rbegin(); layer != layers.rend(); ++layer) {
      color = layer->alpha * layer->radiance + (1.0f - layer->alpha) * color;
      coverage = layer->alpha + (1.0f - layer->alpha) * coverage;
    }
    lit[0] = color.r, lit[1] = color.g, lit[2] = color.b, lit[3] = coverage;
  }

  // One blended layer: its alpha and the radiance it sends along the ray
  // (emission, direct light with shadow rays, sky ambient with true
  // visibility and one-bounce indirect, from the same cosine rays as a
  // G-buffer pixel). False for the back of a single-sided surface, which
  // the rasteriser culls. Normal maps are not read (as radianceLeaving).
  bool shadeBlendedHit(const RTCRayHit& rayHit, const glm::vec3& rayDirection, Pcg32& random, glm::vec3& radiance,
                       float& alpha) {
    const InstanceShading& instance = in_.instances[rayHit.hit.geomID];
    const Primitive& primitive = *instance.primitive;
    const Material& material = *instance.material;
    const std::uint32_t* corner = &primitive.indices[std::size_t(rayHit.hit.primID) * 3];
    const float u = rayHit.hit.u, v = rayHit.hit.v, w = 1.0f - u - v;
    auto world = [&](std::uint32_t index) {
      const float* p = &instance.worldPositions[std::size_t(index) * 3];
      return glm::vec3(p[0], p[1], p[2]);
    };
    const glm::vec3 p0 = world(corner[0]), p1 = world(corner[1]), p2 = world(corner[2]);
    const glm::vec3 faceNormal = glm::cross(p1 - p0, p2 - p0) * instance.frontSign;
    const bool front = glm::dot(faceNormal, rayDirection) <= 0.0f;
    if (!front && !material.doubleSided) return false;
    glm::vec3 normal = instance.normalFromLocal * (w * primitive.normals[corner[0]] + u * primitive.normals[corner[1]] +
                                                   v * primitive.normals[corner[2]]);
    const float normalLength = glm::length(normal);
    normal = normalLength > 0.0f ? normal / normalLength : -rayDirection;
    if (!front) normal = -normal;

    glm::vec4 baseColor = material.baseColorFactor;
    float metallic = material.metallicFactor, roughness = material.roughnessFactor;
    glm::vec3 emission = material.emissiveFactor;
    const bool textured = !primitive.texcoords.empty();
    glm::vec2 uv(0.0f);
    if (textured)
      uv = w * primitive.texcoords[corner[0]] + u * primitive.texcoords[corner[1]] + v * primitive.texcoords[corner[2]];
    if (textured && material.baseColorTexture.present())
      baseColor *= sampleTexture(in_.scene, material.baseColorTexture, uv, true);
    if (!primitive.colors.empty())
      baseColor *= w * primitive.colors[corner[0]] + u * primitive.colors[corner[1]] + v * primitive.colors[corner[2]];
    if (textured && material.metallicRoughnessTexture.present()) {
      const glm::vec4 texel = sampleTexture(in_.scene, material.metallicRoughnessTexture, uv, false);
      roughness *= texel.g;
      metallic *= texel.b;
    }
    if (textured && material.emissiveTexture.present() && material.emissive())
      emission *= glm::vec3(sampleTexture(in_.scene, material.emissiveTexture, uv, true));
    alpha = std::clamp(baseColor.a, 0.0f, 1.0f);  // as blend.glsl
    metallic = std::clamp(metallic, 0.0f, 1.0f);
    roughness = std::clamp(roughness, 0.0f, 1.0f);

    const glm::vec3 position = w * p0 + u * p1 + v * p2;
    const glm::vec3 view = -rayDirection;
    const glm::vec3 origin = position + normal * in_.epsilon;
    const Basis basis = basisAround(normal);
    const glm::vec3 diffuseWeight = (1.0f - metallic) * glm::vec3(baseColor);
    const int n = in_.settings.samplesPerPixel;
    glm::dvec3 skySum(0.0), indirectSum(0.0);
    for (int i = 0; i < n; ++i) {
      const float xi0 = random.uniform(), xi1 = random.uniform();
      const glm::vec3 direction = basis.toWorld(cosineSampleHemisphere(xi0, xi1));
      const RTCRayHit bounce = traceFromSurface(origin, direction, view);
      if (bounce.hit.geomID == RTC_INVALID_GEOMETRY_ID)
        skySum += glm::dvec3(skyRadiance(in_.scene.sky, direction));
      else
        indirectSum += glm::dvec3(diffuseWeight * radianceLeaving(bounce, direction));
    }
    Surface surface = makeSurface(glm::vec3(baseColor), metallic, roughness, normal, view);
    if (material.iridescence)
      applyIridescence(surface, materialIridescence(material, textured ? &primitive : nullptr, corner, u, v));
    // The lobes from the material, as blend.glsl has them (no normal map: the coat's normal is the surface's).
    auto texel = [&](const TextureRef& ref, bool srgb) {
      return textured && ref.present() ? sampleTexture(in_.scene, ref, uv, srgb) : glm::vec4(1.0f);
    };
    if (material.specular || material.ior != 1.5f) {
      const MaterialSpecular specular = material.specular.value_or(MaterialSpecular{});
      applySpecularLobe(surface, specularLobeOfMaterial(material, texel(specular.specularTexture, false),
                                                        texel(specular.specularColorTexture, true)));
    }
    Clearcoat coat;
    if (const std::optional<MaterialClearcoat>& clearcoat = material.clearcoat)
      coat = makeClearcoat(clearcoatLobeOfMaterial(*clearcoat, texel(clearcoat->clearcoatTexture, false),
                                                   texel(clearcoat->clearcoatRoughnessTexture, false), normal),
                           view);
    const glm::vec3 under = emission + ambientLight(surface, origin, basis, glm::vec3(skySum / double(n)), random) +
                            glm::vec3(indirectSum / double(n));
    radiance = directLight(surface, position, origin, coat) +
               clearcoatLayer(coat, under, coatAmbient(coat, view, origin, random));
    return true;
  }

  // lobe_iridescence_material.glsl: a blended material's film at
  // barycentrics (u, v) of the triangle at `corner` (the material has
  // KHR_materials_iridescence); `textured` null: the primitive has no UVs.
  IridescenceInputs materialIridescence(const Material& material, const Primitive* textured,
                                        const std::uint32_t* corner, float u, float v) const {
    const MaterialIridescence& film = *material.iridescence;
    auto sample = [&](const TextureRef& ref) {
      return sampleTexture(in_.scene, ref, textureUv(*textured, ref, corner, u, v), false);
    };
    float strength = film.iridescenceFactor, thickness = film.iridescenceThicknessMaximum;
    if (textured && film.iridescenceTexture.present()) strength *= sample(film.iridescenceTexture).r;
    if (textured && film.iridescenceThicknessTexture.present())
      thickness = glm::mix(film.iridescenceThicknessMinimum, film.iridescenceThicknessMaximum,
                           sample(film.iridescenceThicknessTexture).g);
    return {std::clamp(strength, 0.0f, 1.0f), std::clamp(thickness, 0.0f, kMaxFilmThicknessNm),
            std::min(film.iridescenceIor, kMaxIridescenceIor), std::min(material.ior, kMaxIridescenceIor)};
  }

  // Fraction of a light's radiance that arrives: 1, or 0 behind an occluder.
  // Lights that cast no shadow in the renderer cast none here either.
  float lightVisibility(const Light& light, const glm::vec3& origin, const glm::vec3& toLight, float distance) {
    if (!light.castsShadows) return 1.0f;
    // Stop short of a point or spot light by epsilon: geometry at the light's
    // position (a bulb's own mesh) must not shadow it.
    const float far = std::isfinite(distance) ? std::max(distance - in_.epsilon, 0.0f) : distance;
    return unoccluded(origin, toLight, far) ? 1.0f : 0.0f;
  }

  // direct_light.frag with shadow rays from `origin` for the maps, the coat
  // layered per light; a transmissive surface's as transmission.glsl's (no
  // coat), a light behind it seen through it with its shadow ray from the back.
  glm::vec3 directLight(const Surface& surface, const glm::vec3& position, const glm::vec3& origin,
                        const Clearcoat& coat, const TransmissiveSurface& transmissive = {}) {
    glm::vec3 sum(0.0f);
    for (const Light& light : in_.scene.lights) {
      glm::vec3 toLight;
      float distance;
      const float attenuation = lightAttenuation(light, position, toLight, distance);
      if (attenuation <= 0.0f) continue;
      const glm::vec3 brdf =
          transmissive.share > 0.0f
              ? transmissiveCookTorrance(surface, toLight, transmissive.share, transmissive.blur)
              : clearcoatLayer(coat, cookTorrance(surface, toLight),
                               glm::vec3(clearcoatSpecular(coat, surface.view, toLight)));
      if (brdf == glm::vec3(0.0f)) continue;
      const bool behind = glm::dot(surface.normal, toLight) < 0.0f;
      const glm::vec3 from = behind ? position - surface.normal * in_.epsilon : origin;
      const float visibility = lightVisibility(light, from, toLight, distance);
      sum += brdf * light.color * light.intensity * (attenuation * visibility);
    }
    return sum;
  }

  // Sky ambient with true visibility. Diffuse: the cosine rays' mean sky
  // radiance over escaped rays (`skyMean`, 0 for blocked ones) is E / pi.
  // Specular: GGX-importance-sampled reflections, each weighted by
  // BRDF * N.L / pdf = F * 4 Vis V.H N.L / N.H (as brdf_lut.frag), times the
  // sky when the ray escapes. The same samples' Fresnel-free weights give
  // the split-sum scale and bias, hence the renderer's diffuse weight
  // kd = (1 - (f0 scale + bias)) (1 - metallic) without its 64x64 table.
  // Anisotropy: the half vectors come from the stretched lobe, in its frame
  // (T, B, N), with its visibility. Sheen: each direction's base term is
  // scaled by the layer (sheenBaseScale), and the lobe itself is estimated
  // by sheenAmbient.
  glm::vec3 ambientLight(const Surface& surface, const glm::vec3& origin, const Basis& basis, const glm::vec3& skyMean,
                         Pcg32& random, glm::vec3* specularAlbedoOut = nullptr) {
    const int m = in_.specularSamples;
    const float alpha = surface.roughness * surface.roughness;
    const bool stretched = surface.anisotropyStrength > 0.0f;
    const Basis frame = stretched ? Basis{surface.anisotropyTangent,
                                          glm::cross(surface.normal, surface.anisotropyTangent), surface.normal}
                                  : basis;
    const float alphaT = stretched ? anisotropyAlphaT(alpha, surface.anisotropyStrength) : alpha;
    auto inFrame = [&](const glm::vec3& v, float nDot) {
      return glm::vec3(glm::dot(frame.tangent, v), glm::dot(frame.bitangent, v), nDot);
    };
    double scale = 0.0, bias = 0.0;
    glm::dvec3 specular(0.0);
    for (int j = 0; j < m; ++j) {
      const float xi0 = random.uniform(), xi1 = random.uniform();
      const glm::vec3 halfVector = frame.toWorld(stretched ? importanceSampleAnisotropicGgx(xi0, xi1, alphaT, alpha)
                                                           : importanceSampleGgx(xi0, xi1, alpha));
      const float vDotHRaw = glm::dot(surface.view, halfVector);
      const glm::vec3 toLight = 2.0f * vDotHRaw * halfVector - surface.view;  // reflect(-V, H)
      const float nDotL = glm::dot(surface.normal, toLight);
      if (nDotL <= 0.0f) continue;
      const float nDotH = std::max(glm::dot(surface.normal, halfVector), 0.0f);
      const float vDotH = std::max(vDotHRaw, 0.0f);
      const float visibility = stretched ? anisotropicVisibility(alphaT, alpha, inFrame(surface.view, surface.nDotV),
                                                                 inFrame(toLight, nDotL))
                                         : smithGgxVisibility(surface.nDotV, nDotL, alpha);
      const float weight = 4.0f * visibility * vDotH * nDotL / std::max(nDotH, 1e-7f);
      const float fresnel = std::pow(1.0f - vDotH, 5.0f);
      scale += (1.0f - fresnel) * weight;
      bias += fresnel * weight;
      const glm::vec3 direction = glm::normalize(toLight);
      // KHR_materials_iridescence: the film's Fresnel (one value per pixel) mixed in, as cookTorrance.
      const glm::vec3 sampleFresnel = glm::mix(surface.f0 * (1.0f - fresnel) + surface.f90 * fresnel,
                                               surface.iridescenceFresnel, surface.iridescence);
      if (unoccluded(origin, direction, std::numeric_limits<float>::infinity()))
        specular += glm::dvec3(sampleFresnel * weight * ambientRadiance(direction) * sheenBaseScale(surface, direction));
    }
    const glm::vec3 specularAlbedo =
        glm::mix(surface.f0 * float(scale / m) + surface.f90 * float(bias / m),
                 surface.iridescenceFresnel * float((scale + bias) / m), surface.iridescence);
    if (specularAlbedoOut) *specularAlbedoOut = specularAlbedo;
    const glm::vec3 diffuseWeight = (1.0f - specularAlbedo) * (1.0f - surface.metallic);
    glm::vec3 ambient = diffuseWeight * surface.albedo * skyMean + glm::vec3(specular / double(m));
    if (surface.sheenColor != glm::vec3(0.0f)) ambient += sheenAmbient(surface, origin, basis, random);
    return ambient * in_.skyIntensity;
  }

  // The sheen lobe under the ambient with true visibility: `m` directions
  // uniform over the hemisphere (density 1 / 2 pi), each adding
  // f_sheen N.L L 2 pi where it escapes.
  glm::vec3 sheenAmbient(const Surface& surface, const glm::vec3& origin, const Basis& basis, Pcg32& random) {
    const int m = in_.specularSamples;
    glm::dvec3 sum(0.0);
    for (int j = 0; j < m; ++j) {
      const float cosTheta = random.uniform(), phi = 2.0f * kPi * random.uniform();
      const float sinTheta = std::sqrt(std::max(0.0f, 1.0f - cosTheta * cosTheta));
      const glm::vec3 direction = basis.toWorld({sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta});
      if (cosTheta <= 0.0f || !unoccluded(origin, direction, std::numeric_limits<float>::infinity())) continue;
      const float nDotH = std::max(glm::dot(surface.normal, glm::normalize(direction + surface.view)), 0.0f);
      sum += glm::dvec3(sheenReflected(surface.sheenColor, surface.sheenRoughness, surface.nDotV, cosTheta, nDotH) *
                        ambientRadiance(direction));
    }
    return glm::vec3(sum * double(2.0f * kPi) / double(m));
  }

  // The ambient light arriving from `direction` (unit), before intensity.
  glm::vec3 ambientRadiance(const glm::vec3& direction) const {
    return in_.environment ? in_.environment->radiance(direction) : skyRadiance(in_.scene.sky, direction);
  }

  // E / pi from the environment map with true visibility, by importance
  // sampling the map (environment_sampler.hpp): each of `count` directions
  // drawn in proportion to the map's luminance adds L V cos / (pi pdf).
  // Cosine-weighted rays would rarely find a small bright source.
  // Each direction's light is scaled by the sheen layer above the base (1 without).
  glm::vec3 environmentIrradianceOverPi(const Surface& surface, const glm::vec3& origin, int count, Pcg32& random) {
    const glm::vec3& normal = surface.normal;
    const EnvironmentLight& light = *in_.environment;
    glm::dvec3 sum(0.0);
    for (int i = 0; i < count; ++i) {
      const float xi0 = random.uniform(), xi1 = random.uniform();
      float pdf = 0.0f;
      const glm::vec3 mapDirection = light.sampler.sample(xi0, xi1, pdf);
      const glm::vec3 direction = environment::mapToWorld(mapDirection, light.cosRotation, light.sinRotation);
      const float cosine = glm::dot(normal, direction);
      if (cosine <= 0.0f || pdf <= 0.0f) continue;
      if (!unoccluded(origin, direction, std::numeric_limits<float>::infinity())) continue;
      sum += glm::dvec3(light.map.lookup(mapDirection)) *
             double(cosine * sheenBaseScale(surface, direction) / (kPi * pdf));
    }
    return glm::vec3(sum / double(count));
  }

  // Ld(h): the Lambertian radiance that the hit surface sends back along the
  // ray (direct punctual light with shadow rays, plus its emission). The
  // back of a single-sided surface is black: the renderer never draws it,
  // but it still blocks rays as its shadow maps do.
  glm::vec3 radianceLeaving(const RTCRayHit& rayHit, const glm::vec3& rayDirection) {
    const InstanceShading& instance = in_.instances[rayHit.hit.geomID];
    const Primitive& primitive = *instance.primitive;
    const Material& material = *instance.material;
    const std::uint32_t* corner = &primitive.indices[std::size_t(rayHit.hit.primID) * 3];
    const float u = rayHit.hit.u, v = rayHit.hit.v, w = 1.0f - u - v;
    auto world = [&](std::uint32_t index) {
      const float* p = &instance.worldPositions[std::size_t(index) * 3];
      return glm::vec3(p[0], p[1], p[2]);
    };
    const glm::vec3 p0 = world(corner[0]), p1 = world(corner[1]), p2 = world(corner[2]);
    glm::vec3 faceNormal = glm::cross(p1 - p0, p2 - p0) * instance.frontSign;  // glTF front face: counter-clockwise
    const bool front = glm::dot(faceNormal, rayDirection) <= 0.0f;
    if (!front && !material.doubleSided) return glm::vec3(0.0f);
    if (!front) faceNormal = -faceNormal;
    const float faceLength = glm::length(faceNormal);
    // Degenerate triangles have no face normal; the ray's own direction
    // gives the side it came from.
    const glm::vec3 towardOrigin = faceLength > 0.0f ? faceNormal / faceLength : -rayDirection;

    const glm::vec3 localNormal =
        w * primitive.normals[corner[0]] + u * primitive.normals[corner[1]] + v * primitive.normals[corner[2]];
    glm::vec3 normal = instance.normalFromLocal * localNormal;
    const float normalLength = glm::length(normal);
    normal = normalLength > 0.0f ? normal / normalLength : towardOrigin;
    if (!front) normal = -normal;  // gbuffer.frag: the back of a double-sided surface faces the other way

    glm::vec3 baseColor(material.baseColorFactor);
    float metallic = material.metallicFactor;
    glm::vec3 emissive = material.emissiveFactor;
    // gbuffer.frag samples textures only where the primitive has texcoords.
    const bool textured = !primitive.texcoords.empty();
    auto sample = [&](const TextureRef& ref, bool srgb) {
      return sampleTexture(in_.scene, ref, textureUv(primitive, ref, corner, u, v), srgb);
    };
    if (textured && material.baseColorTexture.present())
      baseColor *= glm::vec3(sample(material.baseColorTexture, true));
    if (!primitive.colors.empty())  // COLOR_0, as gbuffer.frag multiplies it
      baseColor *= glm::vec3(w * primitive.colors[corner[0]] + u * primitive.colors[corner[1]] +
                             v * primitive.colors[corner[2]]);
    // KHR_materials_unlit: the surface shows its base colour, as the
    // composite writes it, whatever lights it.
    if (material.unlit) return baseColor;
    if (textured && material.metallicRoughnessTexture.present())
      metallic *= sample(material.metallicRoughnessTexture, false).b;
    if (textured && material.emissiveTexture.present() && material.emissive())
      emissive *= glm::vec3(sample(material.emissiveTexture, true));
    metallic = std::clamp(metallic, 0.0f, 1.0f);

    const glm::vec3 diffuse = (1.0f - metallic) * baseColor / kPi;
    glm::vec3 radiance = emissive;
    if (diffuse == glm::vec3(0.0f)) return radiance;
    const glm::vec3 hitPosition = w * p0 + u * p1 + v * p2;
    const glm::vec3 shadowOrigin = hitPosition + towardOrigin * in_.epsilon;
    glm::vec3 irradiance(0.0f);
    for (const Light& light : in_.scene.lights) {
      glm::vec3 toLight;
      float distance;
      const float attenuation = lightAttenuation(light, hitPosition, toLight, distance);
      const float nDotL = glm::dot(normal, toLight);
      if (attenuation <= 0.0f || nDotL <= 0.0f) continue;
      const float visibility = lightVisibility(light, shadowOrigin, toLight, distance);
      irradiance += light.color * light.intensity * (attenuation * nDotL * visibility);
    }
    return radiance + diffuse * irradiance;
  }

  const TraceInputs& in_;
  RTCIntersectContext context_;
};

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
