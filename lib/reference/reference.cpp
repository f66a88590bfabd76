// Ray-traced ground truth with Embree 3 (docs/ACCURACY.md defines every
// quantity). Top to bottom: check the inputs, flatten the scene into one
// Embree triangle geometry per instance, then trace every geometry pixel of
// the frame on worker threads, each pixel with its own random stream.
#include "headlight/reference.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <exception>
#include <limits>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "headlight/error.hpp"
#include "settings/option_binding.hpp"

#ifndef HEADLIGHT_HAS_EMBREE
#define HEADLIGHT_HAS_EMBREE 0
#endif

#if HEADLIGHT_HAS_EMBREE
#include <embree3/rtcore.h>

#if defined(__x86_64__) || defined(_M_X64)
#include <pmmintrin.h>
#include <xmmintrin.h>
#endif

#include "reference/shading.hpp"
#endif

namespace headlight {

std::span<const Option<ReferenceSettings>> referenceOptions() {
  static const Option<ReferenceSettings> rows[] = {
      bindOption<ReferenceSettings>(
          {"reference-samples", OptionType::Int, "reference rays per pixel (cosine-weighted hemisphere)", 1, 1 << 20},
          [](auto& s) -> auto& { return s.samplesPerPixel; }),
  };
  return rows;
}

#if !HEADLIGHT_HAS_EMBREE

bool referenceAvailable() { return false; }

ReferenceImages traceReference(const Scene&, const Frame&, const ReferenceSettings&) {
  throw Error("headlight was built without Embree (meson -Dembree=enabled)");
}

#else

namespace {

using namespace reference;

// Specular ambient: a quarter as many GGX rays as cosine rays, at least 16
// (below that the split-sum weights kd are too noisy for a 1-spp preview).
constexpr int kMinSpecularSamples = 16;

// ---- Inputs ------------------------------------------------------------------

std::string sizeText(const ImageF& image) {
  return std::to_string(image.width) + "x" + std::to_string(image.height) + "x" + std::to_string(image.channelCount());
}

void checkImage(const ImageF& image, const char* name, int width, int height, int minChannels) {
  const bool ok = image.width == width && image.height == height && image.channelCount() >= minChannels &&
                  image.pixels.size() == std::size_t(width) * std::size_t(height) * image.channels.size();
  if (!ok)
    throw SettingsError("traceReference: frame." + std::string(name) + " is " + sizeText(image) + " with " +
                        std::to_string(image.pixels.size()) + " floats; expected " + std::to_string(width) + "x" +
                        std::to_string(height) + " with at least " + std::to_string(minChannels) + " channels");
}

void validate(const Frame& frame, const ReferenceSettings& settings) {
  for (const Option<ReferenceSettings>& option : referenceOptions())
    checkOptionValue(option.spec, option.get(settings));
  if (!(settings.radius > 0.0f) || !std::isfinite(settings.radius))
    throw SettingsError("traceReference: radius must be a finite number > 0 (world units), got " +
                        std::to_string(settings.radius));
  if (settings.threads < 0)
    throw SettingsError("traceReference: threads must be >= 0 (0 = all hardware threads), got " +
                        std::to_string(settings.threads));
  const int width = frame.position.width, height = frame.position.height;
  if (frame.position.empty() || width <= 0 || height <= 0)
    throw SettingsError("traceReference: frame.position is empty (" + sizeText(frame.position) +
                        "); expected a rendered frame's G-buffer");
  checkImage(frame.position, "position", width, height, 4);
  checkImage(frame.normal, "normal", width, height, 3);
  checkImage(frame.albedo, "albedo", width, height, 3);
  checkImage(frame.material, "material", width, height, 2);
  if (!frame.emissive.empty()) checkImage(frame.emissive, "emissive", width, height, 3);
}

// ---- Embree handles ------------------------------------------------------------

const char* embreeErrorName(RTCError code) {
  switch (code) {
    case RTC_ERROR_NONE:
      return "RTC_ERROR_NONE";
    case RTC_ERROR_UNKNOWN:
      return "RTC_ERROR_UNKNOWN";
    case RTC_ERROR_INVALID_ARGUMENT:
      return "RTC_ERROR_INVALID_ARGUMENT";
    case RTC_ERROR_INVALID_OPERATION:
      return "RTC_ERROR_INVALID_OPERATION";
    case RTC_ERROR_OUT_OF_MEMORY:
      return "RTC_ERROR_OUT_OF_MEMORY";
    case RTC_ERROR_UNSUPPORTED_CPU:
      return "RTC_ERROR_UNSUPPORTED_CPU";
    case RTC_ERROR_CANCELLED:
      return "RTC_ERROR_CANCELLED";
  }
  return "unknown RTCError";
}

// Embree reports errors through a callback (possibly from its build
// threads); the first one is kept for the Error thrown at the next check.
struct ErrorLog {
  std::mutex mutex;
  std::string first;
};

// Owns one RTCDevice. Move-only; the error log lives on the heap so that the
// callback's pointer survives a move.
class EmbreeDevice {
 public:
  explicit EmbreeDevice(const std::string& config) : log_(std::make_unique<ErrorLog>()) {
    device_ = rtcNewDevice(config.empty() ? nullptr : config.c_str());
    if (!device_)
      throw Error("traceReference: rtcNewDevice(\"" + config + "\") failed with " +
                  embreeErrorName(rtcGetDeviceError(nullptr)) + " (does this CPU support SSE2?)");
    rtcSetDeviceErrorFunction(device_, &EmbreeDevice::onError, log_.get());
  }
  ~EmbreeDevice() {
    if (device_) rtcReleaseDevice(device_);
  }
  EmbreeDevice(EmbreeDevice&& other) noexcept
      : device_(std::exchange(other.device_, nullptr)), log_(std::move(other.log_)) {}
  EmbreeDevice& operator=(EmbreeDevice&& other) noexcept {
    std::swap(device_, other.device_);
    std::swap(log_, other.log_);
    return *this;
  }
  EmbreeDevice(const EmbreeDevice&) = delete;
  EmbreeDevice& operator=(const EmbreeDevice&) = delete;

  RTCDevice get() const { return device_; }

  // Throws Error naming `operation` if Embree reported an error since the
  // last check.
  void check(const std::string& operation) {
    std::string message;
    {
      std::lock_guard<std::mutex> lock(log_->mutex);
      message = std::exchange(log_->first, std::string());
    }
    const RTCError code = rtcGetDeviceError(device_);
    if (message.empty() && code == RTC_ERROR_NONE) return;
    throw Error("traceReference: " + operation + ": Embree reported " +
                (message.empty() ? std::string(embreeErrorName(code)) : message));
  }

 private:
  static void onError(void* user, RTCError code, const char* text) {
    auto* log = static_cast<ErrorLog*>(user);
    std::lock_guard<std::mutex> lock(log->mutex);
    if (log->first.empty()) log->first = std::string(embreeErrorName(code)) + ": " + (text ? text : "");
  }

  RTCDevice device_ = nullptr;
  std::unique_ptr<ErrorLog> log_;
};

// Owns one RTCScene. Move-only.
class EmbreeScene {
 public:
  EmbreeScene() = default;
  explicit EmbreeScene(RTCDevice device) : scene_(rtcNewScene(device)) {}
  ~EmbreeScene() {
    if (scene_) rtcReleaseScene(scene_);
  }
  EmbreeScene(EmbreeScene&& other) noexcept : scene_(std::exchange(other.scene_, nullptr)) {}
  EmbreeScene& operator=(EmbreeScene&& other) noexcept {
    std::swap(scene_, other.scene_);
    return *this;
  }
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  RTCScene get() const { return scene_; }

 private:
  RTCScene scene_ = nullptr;
};

// ---- Textures ----------------------------------------------------------------------

// The sRGB decode curve for each 8-bit code, as GL_SRGB8_ALPHA8 applies it
// before filtering.
const float* srgbToLinearTable() {
  static const auto table = [] {
    std::array<float, 256> values{};
    for (int i = 0; i < 256; ++i) {
      const float c = float(i) / 255.0f;
      values[std::size_t(i)] = c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
    }
    return values;
  }();
  return table.data();
}

// A texel index wrapped as glTF's sampler says (the GL enum values).
int wrapTexel(int i, int size, int mode) {
  if (mode == 0x812F) return std::clamp(i, 0, size - 1);  // CLAMP_TO_EDGE
  if (mode == 0x8370) {                                   // MIRRORED_REPEAT
    const int m = ((i % (2 * size)) + 2 * size) % (2 * size);
    return m < size ? m : 2 * size - 1 - m;
  }
  return ((i % size) + size) % size;  // REPEAT
}

// Keeps a texture coordinate in a range where the integer texel arithmetic
// cannot overflow, without changing what it samples.
float tameCoordinate(float u, int mode) {
  if (!std::isfinite(u)) return 0.0f;
  if (mode == 0x812F) return std::clamp(u, -1.0f, 2.0f);
  if (mode == 0x8370) return u - 2.0f * std::floor(u * 0.5f);
  return u - std::floor(u);
}

// Samples level 0 of `ref`'s image at `uv` (bilinear, or nearest when the
// magnification filter says so); RGB decoded from sRGB when `srgb`. Mip maps
// are not used: one hit per ray has no footprint to choose a level from,
// and the mean over many rays is the filtered value anyway.
glm::vec4 sampleTexture(const Scene& scene, const TextureRef& ref, glm::vec2 uv, bool srgb) {
  const ImageData& image = scene.images[std::size_t(ref.image)];
  if (image.width <= 0 || image.height <= 0) return glm::vec4(1.0f);
  const float* decode = srgbToLinearTable();
  auto texel = [&](int x, int y) {
    const std::uint8_t* p = &image.rgba[(std::size_t(wrapTexel(y, image.height, ref.wrapT)) * std::size_t(image.width) +
                                         std::size_t(wrapTexel(x, image.width, ref.wrapS))) *
                                        4];
    if (srgb) return glm::vec4(decode[p[0]], decode[p[1]], decode[p[2]], float(p[3]) / 255.0f);
    return glm::vec4(p[0], p[1], p[2], p[3]) / 255.0f;
  };
  const float u = tameCoordinate(uv.x, ref.wrapS) * float(image.width);
  const float v = tameCoordinate(uv.y, ref.wrapT) * float(image.height);
  if (ref.magFilter == 0x2600)  // NEAREST
    return texel(int(std::floor(u)), int(std::floor(v)));
  const float x = u - 0.5f, y = v - 0.5f;
  const float x0 = std::floor(x), y0 = std::floor(y);
  const float fx = x - x0, fy = y - y0;
  const int ix = int(x0), iy = int(y0);
  return glm::mix(glm::mix(texel(ix, iy), texel(ix + 1, iy), fx),
                  glm::mix(texel(ix, iy + 1), texel(ix + 1, iy + 1), fx), fy);
}

// ---- The scene as Embree sees it ----------------------------------------------------

// glTF's default material: white, fully metallic, fully rough.
const Material& defaultMaterial() {
  static const Material material;
  return material;
}

// What a hit needs to shade itself: geometry id = instance index.
struct InstanceShading {
  const Primitive* primitive = nullptr;
  const Material* material = nullptr;
  glm::mat3 normalFromLocal{1.0f};        // headlight::normalMatrix, as gpu_scene.cpp uses
  const float* worldPositions = nullptr;  // Embree's vertex buffer, xyz per vertex
  float frontSign = 1.0f;                 // glTF: a transform with negative determinant flips the winding
};

struct TracedScene {
  EmbreeDevice device;
  EmbreeScene scene;
  std::vector<InstanceShading> instances;  // indexed by geometry id
};

TracedScene buildScene(const Scene& scene, int threads) {
  // "threads=N" also bounds Embree's own BVH-building threads.
  TracedScene traced{
      EmbreeDevice(threads > 0 ? "threads=" + std::to_string(threads) : std::string()), EmbreeScene(), {}};
  traced.device.check("rtcNewDevice");
  traced.scene = EmbreeScene(traced.device.get());
  traced.device.check("rtcNewScene");
  traced.instances.resize(scene.instances.size());
  for (std::size_t id = 0; id < scene.instances.size(); ++id) {
    const Instance& instance = scene.instances[id];
    const std::string what = scene.source + ": instance " + std::to_string(id);
    if (instance.primitive < 0 || std::size_t(instance.primitive) >= scene.primitives.size())
      throw Error("traceReference: " + what + " names primitive " + std::to_string(instance.primitive) +
                  "; the scene has " + std::to_string(scene.primitives.size()));
    if (instance.material < -1 || (instance.material >= 0 && std::size_t(instance.material) >= scene.materials.size()))
      throw Error("traceReference: " + what + " names material " + std::to_string(instance.material) +
                  "; the scene has " + std::to_string(scene.materials.size()));
    const Primitive& primitive = scene.primitives[std::size_t(instance.primitive)];
    const Material& material =
        instance.material >= 0 ? scene.materials[std::size_t(instance.material)] : defaultMaterial();
    const std::size_t triangleCount = primitive.indices.size() / 3;
    const std::size_t vertexCount = primitive.positions.size();
    if (triangleCount == 0 || vertexCount == 0) continue;
    if (primitive.normals.size() != vertexCount ||
        (!primitive.texcoords.empty() && primitive.texcoords.size() != vertexCount))
      throw Error("traceReference: " + what + ": primitive " + std::to_string(instance.primitive) + " has " +
                  std::to_string(vertexCount) + " positions but " + std::to_string(primitive.normals.size()) +
                  " normals and " + std::to_string(primitive.texcoords.size()) + " texcoords");
    const std::uint32_t largest =
        *std::max_element(primitive.indices.begin(), primitive.indices.begin() + 3 * triangleCount);
    if (largest >= vertexCount)
      throw Error("traceReference: " + what + ": primitive " + std::to_string(instance.primitive) + " has index " +
                  std::to_string(largest) + " but " + std::to_string(vertexCount) + " vertices");
    for (const TextureRef* ref :
         {&material.baseColorTexture, &material.emissiveTexture, &material.metallicRoughnessTexture})
      if (ref->present() && std::size_t(ref->image) >= scene.images.size())
        throw Error("traceReference: " + what + ": material \"" + material.name + "\" names image " +
                    std::to_string(ref->image) + "; the scene has " + std::to_string(scene.images.size()));

    RTCGeometry geometry = rtcNewGeometry(traced.device.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* positions = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0,
                                                                  RTC_FORMAT_FLOAT3, 3 * sizeof(float), vertexCount));
    if (positions) {
      for (std::size_t v = 0; v < vertexCount; ++v) {
        const glm::vec3 world = glm::vec3(instance.worldFromLocal * glm::vec4(primitive.positions[v], 1.0f));
        positions[3 * v + 0] = world.x;
        positions[3 * v + 1] = world.y;
        positions[3 * v + 2] = world.z;
      }
      // The scene outlives the Embree scene (both live for this call), so
      // its indices are shared rather than copied.
      rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, primitive.indices.data(), 0,
                                 3 * sizeof(std::uint32_t), triangleCount);
      rtcCommitGeometry(geometry);
      rtcAttachGeometryByID(traced.scene.get(), geometry, unsigned(id));
    }
    rtcReleaseGeometry(geometry);  // the scene holds its own reference
    traced.device.check(what + " (" + std::to_string(triangleCount) + " triangles)");

    InstanceShading& shading = traced.instances[id];
    shading.primitive = &primitive;
    shading.material = &material;
    shading.normalFromLocal = normalMatrix(instance.worldFromLocal);
    shading.worldPositions = positions;
    shading.frontSign = mirrors(instance.worldFromLocal) ? -1.0f : 1.0f;
  }
  rtcCommitScene(traced.scene.get());
  traced.device.check("building the BVH of " + scene.source);
  return traced;
}

bool isFinite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// ---- Tracing ---------------------------------------------------------------------------

// Everything a worker reads; nothing here changes while tracing.
struct TraceInputs {
  const Scene& scene;
  const Frame& frame;
  const ReferenceSettings& settings;
  RTCScene rtcScene;
  const std::vector<InstanceShading>& instances;
  float epsilon;       // world units: how far ray origins leave their surface
  float skyIntensity;  // the frame's, resolved
  int specularSamples;
};

struct Outputs {
  ReferenceImages& images;
  std::vector<double>& aoStandardError;        // per pixel; NaN on background
  std::vector<double>& indirectStandardError;  // per pixel, mean of the three channels
};

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
      const glm::vec3 sky = skyRadiance(in_.scene.sky, backgroundRay(x, y)) * in_.skyIntensity;
      ao[0] = ao[1] = 1.0f;
      std::fill(indirect, indirect + 6, 0.0f);
      lit[0] = sky.r, lit[1] = sky.g, lit[2] = sky.b, lit[3] = 0.0f;
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
        skySum += glm::dvec3(skyRadiance(in_.scene.sky, direction));
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

    const Surface surface = makeSurface(albedo, metallic, roughness, normal, view);
    glm::vec3 radiance = directLight(surface, position, origin) +
                         ambientLight(surface, origin, basis, glm::vec3(skySum / count), random) +
                         glm::vec3(indirectMean);
    if (!frame.emissive.empty())
      radiance += glm::vec3(frame.emissive.at(x, y, 0), frame.emissive.at(x, y, 1), frame.emissive.at(x, y, 2));
    lit[0] = radiance.r, lit[1] = radiance.g, lit[2] = radiance.b, lit[3] = 1.0f;
  }

 private:
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

  // Fraction of a light's radiance that arrives: 1, or 0 behind an occluder.
  // Lights that cast no shadow in the renderer cast none here either.
  float lightVisibility(const Light& light, const glm::vec3& origin, const glm::vec3& toLight, float distance) {
    if (!light.castsShadows) return 1.0f;
    // Stop short of a point or spot light by epsilon: geometry at the light's
    // position (a bulb's own mesh) must not shadow it.
    const float far = std::isfinite(distance) ? std::max(distance - in_.epsilon, 0.0f) : distance;
    return unoccluded(origin, toLight, far) ? 1.0f : 0.0f;
  }

  // direct_light.frag with shadow rays from `origin` for the maps.
  glm::vec3 directLight(const Surface& surface, const glm::vec3& position, const glm::vec3& origin) {
    glm::vec3 sum(0.0f);
    for (const Light& light : in_.scene.lights) {
      glm::vec3 toLight;
      float distance;
      const float attenuation = lightAttenuation(light, position, toLight, distance);
      if (attenuation <= 0.0f) continue;
      const glm::vec3 brdf = cookTorrance(surface, toLight);
      if (brdf == glm::vec3(0.0f)) continue;
      const float visibility = lightVisibility(light, origin, toLight, distance);
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
  glm::vec3 ambientLight(const Surface& surface, const glm::vec3& origin, const Basis& basis, const glm::vec3& skyMean,
                         Pcg32& random) {
    const int m = in_.specularSamples;
    const float alpha = surface.roughness * surface.roughness;
    double scale = 0.0, bias = 0.0;
    glm::dvec3 specular(0.0);
    for (int j = 0; j < m; ++j) {
      const float xi0 = random.uniform(), xi1 = random.uniform();
      const glm::vec3 halfVector = basis.toWorld(importanceSampleGgx(xi0, xi1, alpha));
      const float vDotHRaw = glm::dot(surface.view, halfVector);
      const glm::vec3 toLight = 2.0f * vDotHRaw * halfVector - surface.view;  // reflect(-V, H)
      const float nDotL = glm::dot(surface.normal, toLight);
      if (nDotL <= 0.0f) continue;
      const float nDotH = std::max(glm::dot(surface.normal, halfVector), 0.0f);
      const float vDotH = std::max(vDotHRaw, 0.0f);
      const float weight =
          4.0f * smithGgxVisibility(surface.nDotV, nDotL, alpha) * vDotH * nDotL / std::max(nDotH, 1e-7f);
      const float fresnel = std::pow(1.0f - vDotH, 5.0f);
      scale += (1.0f - fresnel) * weight;
      bias += fresnel * weight;
      const glm::vec3 direction = glm::normalize(toLight);
      if (unoccluded(origin, direction, std::numeric_limits<float>::infinity()))
        specular +=
            glm::dvec3((surface.f0 * (1.0f - fresnel) + fresnel) * weight * skyRadiance(in_.scene.sky, direction));
    }
    const glm::vec3 specularAlbedo = surface.f0 * float(scale / m) + float(bias / m);
    const glm::vec3 diffuseWeight = (1.0f - specularAlbedo) * (1.0f - surface.metallic);
    return (diffuseWeight * surface.albedo * skyMean + glm::vec3(specular / double(m))) * in_.skyIntensity;
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
    const bool textured = !primitive.texcoords.empty();
    glm::vec2 uv(0.0f);
    if (textured)
      uv = w * primitive.texcoords[corner[0]] + u * primitive.texcoords[corner[1]] + v * primitive.texcoords[corner[2]];
    if (textured && material.baseColorTexture.present())
      baseColor *= glm::vec3(sampleTexture(in_.scene, material.baseColorTexture, uv, true));
    if (textured && material.metallicRoughnessTexture.present())
      metallic *= sampleTexture(in_.scene, material.metallicRoughnessTexture, uv, false).b;
    if (textured && material.emissiveTexture.present() && material.emissive())
      emissive *= glm::vec3(sampleTexture(in_.scene, material.emissiveTexture, uv, true));
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

ImageF makeImage(int width, int height, std::vector<std::string> channels) {
  ImageF image;
  image.width = width;
  image.height = height;
  image.pixels.assign(std::size_t(width) * std::size_t(height) * channels.size(), 0.0f);
  image.channels = std::move(channels);
  return image;
}

// How far ray origins leave their surface, along the G-buffer normal (and a
// hit's face normal for its shadow rays): 2e-5 of the scene's diagonal plus
// its largest coordinate. Both the G-buffer's interpolated positions and
// Embree's hit points are off their triangle's plane by a few float ulps of
// the triangle's coordinates (1.2e-7 relative each), bounded by the scene's
// largest coordinate; 2e-5 is some 170 such ulps, and still a ninth of the
// Cornell lamp's 1 mm gap under the ceiling (0.11 mm there). A larger
// offset would bias AO in creases: the origin would leave the corner.
float rayEpsilon(const Scene& scene) {
  const Bounds bounds = scene.worldBounds();
  if (bounds.empty()) return 1e-6f;
  const glm::vec3 largest = glm::max(glm::abs(bounds.min), glm::abs(bounds.max));
  const float epsilon = 2e-5f * (2.0f * bounds.radius() + std::max({largest.x, largest.y, largest.z}));
  return std::max(epsilon, std::numeric_limits<float>::min());
}

}  // namespace

bool referenceAvailable() { return true; }

ReferenceImages traceReference(const Scene& scene, const Frame& frame, const ReferenceSettings& settings) {
  validate(frame, settings);
  const auto start = std::chrono::steady_clock::now();
  const int width = frame.position.width, height = frame.position.height;
  const int hardware = int(std::max(1u, std::thread::hardware_concurrency()));
  const int threads = std::clamp(settings.threads > 0 ? settings.threads : hardware, 1, height);

  const TracedScene traced = buildScene(scene, settings.threads);

  ReferenceImages images;
  images.samplesPerPixel = settings.samplesPerPixel;
  images.ao = makeImage(width, height, {"ao.Y", "sky.Y"});
  images.indirect =
      makeImage(width, height, {"indirectR.R", "indirectR.G", "indirectR.B", "indirect.R", "indirect.G", "indirect.B"});
  images.lit = makeImage(width, height, {"R", "G", "B", "A"});
  const std::size_t pixelCount = std::size_t(width) * std::size_t(height);
  std::vector<double> aoStandardError(pixelCount, std::numeric_limits<double>::quiet_NaN());
  std::vector<double> indirectStandardError(pixelCount, std::numeric_limits<double>::quiet_NaN());

  const TraceInputs inputs{scene,
                           frame,
                           settings,
                           traced.scene.get(),
                           traced.instances,
                           rayEpsilon(scene),
                           frame.settings.lighting.skyIntensity.value_or(scene.sky.intensity),
                           std::max(kMinSpecularSamples, settings.samplesPerPixel / 4)};
  const Outputs outputs{images, aoStandardError, indirectStandardError};

  // Rows handed out one at a time: a row's cost varies with what it sees.
  // Each pixel's result depends only on its own random stream, so which
  // thread traces it does not matter.
  std::atomic<int> nextRow{0};
  std::exception_ptr failure;
  std::mutex failureMutex;
  auto work = [&] {
    try {
      setFlushDenormals();
      Tracer tracer(inputs);
      for (int y = nextRow++; y < height; y = nextRow++)
        for (int x = 0; x < width; ++x) tracer.tracePixel(x, y, outputs);
    } catch (...) {
      std::lock_guard<std::mutex> lock(failureMutex);
      if (!failure) failure = std::current_exception();
      nextRow = height;
    }
  };
  std::vector<std::thread> workers;
  for (int i = 1; i < threads; ++i) workers.emplace_back(work);
  work();
  for (std::thread& worker : workers) worker.join();
  if (failure) std::rethrow_exception(failure);

  // Reduced in pixel order, so the means are the same for any thread count.
  double aoSum = 0.0, aoMax = 0.0, indirectSum = 0.0;
  std::size_t geometryPixels = 0;
  for (std::size_t i = 0; i < pixelCount; ++i) {
    if (frame.position.pixels[i * frame.position.channels.size() + 3] == 0.0f) continue;
    ++geometryPixels;
    aoSum += aoStandardError[i];
    aoMax = std::max(aoMax, aoStandardError[i]);
    indirectSum += indirectStandardError[i];
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const bool spread = settings.samplesPerPixel > 1 && geometryPixels > 0;
  images.aoMeanStandardError = spread ? aoSum / double(geometryPixels) : (geometryPixels ? nan : 0.0);
  images.aoMaxStandardError = spread ? aoMax : (geometryPixels ? nan : 0.0);
  images.indirectMeanStandardError = spread ? indirectSum / double(geometryPixels) : (geometryPixels ? nan : 0.0);
  images.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return images;
}

#endif  // HEADLIGHT_HAS_EMBREE

}  // namespace headlight
