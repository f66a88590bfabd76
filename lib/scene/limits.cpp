#include "headlight/limits.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>

#include <cmath>
#include <cstdio>
#include <string>

#include "headlight/error.hpp"
#include "scene/address_space.hpp"
#include "scene/material_textures.hpp"
#include "settings/option_binding.hpp"

namespace headlight {

std::span<const Option<ResourceLimits>> limitOptions() {
  using T = OptionType;
  using L = ResourceLimits;
  static const Option<L> rows[] = {
      bindOption<L>(
          {.name = "max-memory",
           .type = T::Int,
           .help = "MiB a render may use (scene, frame and textures); larger requests are refused up front",
           .minimum = 64,
           .maximum = double(std::int64_t(1) << 30),
           .autoMeaning = "half of physical memory or of the address-space limit (ulimit -v), the smaller"},
          [](auto& l) -> auto& { return l.maxMemoryMiB; }),
      bindOption<L>(
          {.name = "max-instances",
           .type = T::Int,
           .help = "most mesh primitives drawn (each node's use of each primitive counts)",
           .minimum = 1,
           .maximum = double(std::int64_t(1) << 31)},
          [](auto& l) -> auto& { return l.maxInstances; }),
      bindOption<L>(
          {.name = "max-triangles",
           .type = T::Int,
           .help = "most triangles decoded from the scene file, all primitives together",
           .minimum = 1,
           .maximum = double(std::int64_t(1) << 31)},
          [](auto& l) -> auto& { return l.maxTriangles; }),
      bindOption<L>(
          {.name = "max-texels",
           .type = T::Int,
           .help = "most texels decoded from the scene's images, all images together",
           .minimum = 1,
           .maximum = double(std::int64_t(1) << 34)},
          [](auto& l) -> auto& { return l.maxTexels; }),
      bindOption<L>(
          {.name = "max-draws",
           .type = T::Int,
           .help = "most instance draws a frame (instances x passes: each shadow view, and the G-buffer once a view: "
                   "the pixel centre and each antialias sample)",
           .minimum = 1,
           .maximum = double(std::int64_t(1) << 40)},
          [](auto& l) -> auto& { return l.maxDraws; }),
      bindOption<L>(
          {.name = "max-drawn-triangles",
           .type = T::Int,
           .help = "most triangles drawn a frame (the scene's triangles x passes)",
           .minimum = 1,
           .maximum = double(std::int64_t(1) << 40)},
          [](auto& l) -> auto& { return l.maxDrawnTriangles; }),
      bindOption<L>(
          {.name = "max-blended-fragments",
           .type = T::Int,
           .help = "most pixels the blend pass shades a frame (each alphaMode BLEND instance's screen rectangle x "
                   "views), estimated from the camera before drawing",
           .minimum = 1,
           .maximum = double(std::int64_t(1) << 50)},
          [](auto& l) -> auto& { return l.maxBlendedFragments; }),
      bindOption<L>(
          {.name = "max-lights",
           .type = T::Int,
           .help = "most punctual lights a scene places (each is evaluated at every pixel of every view)",
           .minimum = 1,
           .maximum = double(std::int64_t(1) << 24)},
          [](auto& l) -> auto& { return l.maxLights; }),
  };
  return rows;
}

std::uint64_t physicalMemoryBytes() {
  const long pages = sysconf(_SC_PHYS_PAGES);
  const long pageSize = sysconf(_SC_PAGESIZE);
  return pages > 0 && pageSize > 0 ? std::uint64_t(pages) * std::uint64_t(pageSize) : 0;
}

std::uint64_t addressSpaceLimitBytes() {
  rlimit limit{};
  if (::getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return 0;
  return std::uint64_t(limit.rlim_cur);
}

std::uint64_t maxMemoryBytes(const ResourceLimits& limits) {
  if (limits.maxMemoryMiB) return std::uint64_t(*limits.maxMemoryMiB) << 20;
  // Half, to leave room for the libraries, Mesa and the decoders' own
  // buffers. Under an address-space limit, a bound past it ended in the
  // allocator's "Resource temporarily unavailable" or std::bad_alloc instead
  // of a refusal naming max-memory.
  const std::uint64_t physical = physicalMemoryBytes();
  std::uint64_t bound = physical > 0 ? physical / 2 : std::uint64_t(8) << 30;
  if (const std::uint64_t addressSpace = addressSpaceLimitBytes(); addressSpace > 0)
    bound = std::min(bound, addressSpace / 2);
  return bound;
}

std::uint64_t estimateFrameBytes(int width, int height) {
  const std::uint64_t pixels = std::uint64_t(width > 0 ? width : 0) * std::uint64_t(height > 0 ? height : 0);
  return kFrameBaseBytes + pixels * kFrameBytesPerPixel;
}

namespace {
std::string mib(std::uint64_t bytes) { return std::to_string((bytes + (1u << 20) - 1) >> 20) + " MiB"; }
}  // namespace

void checkFrameFits(int width, int height, std::uint64_t sceneBytes, const ResourceLimits& limits) {
  const std::uint64_t frame = estimateFrameBytes(width, height);
  const std::uint64_t limit = maxMemoryBytes(limits);
  if (frame + sceneBytes > limit) {
    throw LimitError(
        "a " + std::to_string(width) + "x" + std::to_string(height) + " render needs about " + mib(frame + sceneBytes) +
            " (" + std::to_string(kFrameBytesPerPixel) + " bytes per pixel + " + mib(kFrameBaseBytes) +
            " + the scene's " + mib(sceneBytes) + "), more than max-memory allows (" + mib(limit) +
            (limits.maxMemoryMiB ? ""
                                 : ", half of physical memory or of the address-space limit (ulimit -v), the smaller") +
            "); render smaller or raise max-memory",
        {"max-memory"});
  }
}

namespace {

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

class RangeCheck {
 public:
  explicit RangeCheck(const Scene& scene) : scene_(scene) {}

  void run() {
    for (std::size_t index = 0; index < scene_.images.size(); ++index) image(index);
    for (std::size_t index = 0; index < scene_.primitives.size(); ++index) primitive(index);
    for (std::size_t index = 0; index < scene_.instances.size(); ++index) instance(index);
    for (std::size_t index = 0; index < scene_.cameras.size(); ++index) camera(index);
    for (std::size_t index = 0; index < scene_.lights.size(); ++index) light(index);
    for (std::size_t index = 0; index < scene_.materials.size(); ++index) material(index);
    const Sky& sky = scene_.sky;
    for (const glm::vec3& radiance : {sky.zenith, sky.horizon, sky.ground}) {
      lightValue(radiance * sky.intensity, "the sky", "radiance x intensity");
    }
    if (scene_.environment) environment(*scene_.environment);
  }

 private:
  [[noreturn]] void fail(const std::string& message) const { throw SceneError(scene_.source + ": " + message); }

  void magnitude(double value, const std::string& element, const char* what) const {
    if (!(std::abs(value) <= kMaxWorldMagnitude)) {
      fail(element + " has " + what + " " + number(value) + ", expected a magnitude at most " +
           number(kMaxWorldMagnitude) + " so that float rendering stays finite");
    }
  }

  void matrix(const glm::mat4& m, const std::string& element, const char* what) const {
    for (int column = 0; column < 4; ++column)
      for (int row = 0; row < 4; ++row) magnitude(m[column][row], element, what);
  }

  void lightValue(const glm::vec3& value, const std::string& element, const char* what) const {
    for (int channel = 0; channel < 3; ++channel) {
      if (!(value[channel] >= 0.0f && value[channel] <= kMaxLightValue)) {
        fail(element + " has " + what + " " + number(value[channel]) + " in channel " + std::to_string(channel) +
             ", expected 0.." + number(kMaxLightValue) + " so that float rendering stays finite");
      }
    }
  }

  // The map's brightest texel, as a light value: its prefiltered tables and
  // the ambient term sum many texels, and an EXT_lights_image_based
  // intensity of 1e38 (finite, like every texel it made) turned them into
  // infinities and lit into NaN (issue 32).
  void environment(const EnvironmentMap& map) const {
    static constexpr const char* kChannel[] = {"R", "G", "B"};
    const std::size_t values = std::min(map.rgb.size(), std::size_t(map.width) * std::size_t(map.height) * 3);
    for (std::size_t i = 0; i < values; ++i) {
      if (map.rgb[i] >= 0.0f && map.rgb[i] <= kMaxLightValue) continue;
      const std::size_t texel = i / 3;
      fail("environment map " + map.source + " has radiance " + number(map.rgb[i]) + " at texel (" +
           std::to_string(texel % std::size_t(map.width)) + ", " + std::to_string(texel / std::size_t(map.width)) +
           ") " + kChannel[i % 3] + ", expected 0.." + number(kMaxLightValue) +
           " so that float rendering stays finite");
    }
  }

  // Scene.hpp's contract for a primitive: normals for every position, the
  // other attributes none or one per position, every index a position. The
  // GL draws what breaks it with reads past its buffers (undefined; garbage
  // or a crash in the driver), so a scene built in code that breaks it is
  // refused here, as the reference refuses it.
  void primitive(std::size_t index) const {
    const Primitive& primitive = scene_.primitives[index];
    const std::string name = "primitive " + std::to_string(index);
    const std::size_t count = primitive.positions.size();
    const auto attribute = [&](std::size_t size, const char* what, bool optional) {
      if (size == count || (optional && size == 0)) return;
      fail(name + " has " + std::to_string(count) + " positions but " + std::to_string(size) + " " + what +
           ", expected " + (optional ? "none or " : "") + std::to_string(count));
    };
    attribute(primitive.normals.size(), "normals", false);
    attribute(primitive.texcoords.size(), "texcoords (TEXCOORD_0)", true);
    attribute(primitive.texcoords1.size(), "texcoords (TEXCOORD_1)", true);
    attribute(primitive.tangents.size(), "tangents", true);
    attribute(primitive.colors.size(), "colors", true);
    for (std::size_t at = 0; at < primitive.indices.size(); ++at)
      if (primitive.indices[at] >= count)
        fail(name + " has index " + std::to_string(primitive.indices[at]) + " at " + std::to_string(at) +
             ", expected at most " + std::to_string(count) + " - 1 (its position count)");
  }

  // Scene.hpp's contract for an image: RGBA8, width x height texels.
  void image(std::size_t index) const {
    const ImageData& image = scene_.images[index];
    const std::string name = "image " + std::to_string(index) + " '" + image.name + "'";
    if (image.width <= 0 || image.height <= 0)
      fail(name + " is " + std::to_string(image.width) + "x" + std::to_string(image.height) +
           ", expected at least 1x1");
    const std::uint64_t expected = 4 * std::uint64_t(image.width) * std::uint64_t(image.height);
    if (image.rgba.size() != expected)
      fail(name + " has " + std::to_string(image.rgba.size()) + " bytes, expected " + std::to_string(expected) +
           " (RGBA8, " + std::to_string(image.width) + "x" + std::to_string(image.height) + ")");
  }

  // An instance names a primitive and a material (-1: the default) the scene has.
  void instance(std::size_t index) const {
    const Instance& instance = scene_.instances[index];
    const std::string name = "instance " + std::to_string(index);
    if (instance.primitive < 0 || std::size_t(instance.primitive) >= scene_.primitives.size())
      fail(name + " names primitive " + std::to_string(instance.primitive) + ", expected 0.." +
           std::to_string(int(scene_.primitives.size()) - 1) + " (the scene has " +
           std::to_string(scene_.primitives.size()) + ")");
    if (instance.material < -1 || (instance.material >= 0 && std::size_t(instance.material) >= scene_.materials.size()))
      fail(name + " names material " + std::to_string(instance.material) + ", expected -1 (the default) or 0.." +
           std::to_string(int(scene_.materials.size()) - 1) + " (the scene has " +
           std::to_string(scene_.materials.size()) + ")");
    matrix(instance.worldFromLocal, name, "a world transform entry of");
    const Bounds& bounds = scene_.primitives[std::size_t(instance.primitive)].bounds;
    if (bounds.empty()) return;
    const glm::dmat4 world(instance.worldFromLocal);
    for (int corner = 0; corner < 8; ++corner) {
      const glm::dvec3 local((corner & 1) ? bounds.max.x : bounds.min.x, (corner & 2) ? bounds.max.y : bounds.min.y,
                             (corner & 4) ? bounds.max.z : bounds.min.z);
      const glm::dvec4 point = world * glm::dvec4(local, 1.0);
      for (int axis = 0; axis < 3; ++axis)
        magnitude(point[axis], name + " (primitive " + std::to_string(instance.primitive) + ")",
                  "a world-space coordinate of");
    }
  }

  void camera(std::size_t index) const {
    const Camera& camera = scene_.cameras[index];
    const std::string name = "camera " + std::to_string(index) + " '" + camera.name + "'";
    matrix(camera.worldFromCamera, name, "a world transform entry of");
    magnitude(camera.znear, name, "znear");
    magnitude(camera.zfar, name, "zfar");
    magnitude(camera.aspectRatio, name, "aspectRatio");
    if (camera.projection == Camera::Projection::Perspective) {
      if (!(camera.yfov > 0.0f && camera.yfov < 3.1415926f))
        fail(name + " has yfov " + number(camera.yfov) + ", expected 0 < yfov < pi");
    } else {
      magnitude(camera.xmag, name, "xmag");
      magnitude(camera.ymag, name, "ymag");
    }
  }

  void light(std::size_t index) const {
    const Light& light = scene_.lights[index];
    const std::string name = "light " + std::to_string(index) + " '" + light.name + "'";
    lightValue(light.color, name, "colour");
    if (!(light.intensity >= 0.0f)) fail(name + " has intensity " + number(light.intensity) + ", expected >= 0");
    lightValue(light.color * light.intensity, name, "colour x intensity");
    magnitude(light.range, name, "range");
    for (int axis = 0; axis < 3; ++axis) {
      magnitude(light.position[axis], name, "a position coordinate of");
      if (!std::isfinite(light.direction[axis])) fail(name + " has a non-finite direction");
    }
  }

  void material(std::size_t index) const {
    const Material& material = scene_.materials[index];
    const std::string name = "material " + std::to_string(index) + " '" + material.name + "'";
    lightValue(material.emissiveFactor, name, "emissive");
    // Every texture it samples names an image the scene has (the table the
    // upload and the passes walk: lib/scene/material_textures.hpp).
    for (const MaterialTextureRow& row : materialTextureRows()) {
      const TextureRef* ref = row.ref(material);
      if (ref == nullptr || !ref->present()) continue;
      if (std::size_t(ref->image) >= scene_.images.size())
        fail(name + " samples image " + std::to_string(ref->image) + " as its " + row.define +
             " texture, expected 0.." + std::to_string(int(scene_.images.size()) - 1) + " (the scene has " +
             std::to_string(scene_.images.size()) + ")");
    }
    for (int channel = 0; channel < 4; ++channel) {
      if (!std::isfinite(material.baseColorFactor[channel]))
        fail(name + " has a non-finite baseColorFactor in channel " + std::to_string(channel));
    }
  }

  const Scene& scene_;
};

}  // namespace

void checkSceneRanges(const Scene& scene) { RangeCheck(scene).run(); }

int drawPassCount(const Scene& scene) {
  if (scene.lights.empty()) return 2;  // the G-buffer and the default key light's shadow view
  int passes = 1;
  for (const Light& light : scene.lights)
    if (light.castsShadows) passes += light.type == Light::Type::Point ? 6 : 1;
  return passes;
}

void checkDrawBudget(const Scene& scene, const ResourceLimits& limits, int viewDraws) {
  if (scene.lights.size() > std::uint64_t(limits.maxLights))
    throw LimitError(scene.source + ": " + std::to_string(scene.lights.size()) +
                         " punctual lights, more than --max-lights allows (" + std::to_string(limits.maxLights) +
                         "; each is evaluated at every pixel of every view); raise --max-lights",
                     {"max-lights"});
  const std::uint64_t shadowViews = std::uint64_t(drawPassCount(scene) - 1);
  const std::uint64_t views = std::uint64_t(std::max(1, viewDraws));
  // The transmission pass draws each transmissive instance once more (lib/passes/transmission.hpp).
  std::uint64_t redraws = 0, redrawnTriangles = 0;
  for (const Instance& instance : scene.instances) {
    if (instance.material < 0 || !scene.materials[std::size_t(instance.material)].transmissive()) continue;
    ++redraws;
    const Primitive& primitive = scene.primitives[std::size_t(instance.primitive)];
    if (primitive.mode == PrimitiveMode::Triangles) redrawnTriangles += primitive.indices.size() / 3;
  }
  // "x (1 shadow view + 9 views: the pixel centre and 8 antialias samples)"
  const std::string passes =
      " x (" + std::to_string(shadowViews) + " shadow view" + (shadowViews == 1 ? "" : "s") + " + " +
      (views == 1 ? std::string("the view")
                  : std::to_string(views) + " views: the pixel centre and " + std::to_string(views - 1) +
                        " antialias samples") +
      ")" + (redraws ? " + " + std::to_string(redraws) + " transmission redraws" + (views > 1 ? " a view" : "") : "") +
      " = ";
  const std::string orFewerSamples = views > 1 ? ", or lower --antialias" : "";
  const std::uint64_t instances = scene.instances.size();
  const std::uint64_t draws = instances * shadowViews + (instances + redraws) * views;
  if (draws > std::uint64_t(limits.maxDraws))
    throw LimitError(scene.source + ": a frame would draw " + std::to_string(instances) + " instances" + passes +
                         std::to_string(draws) + " draws, more than --max-draws allows (" +
                         std::to_string(limits.maxDraws) + "; about 50 us a shadow-view draw on llvmpipe); raise " +
                         "--max-draws" + orFewerSamples,
                     {"max-draws"});
  const std::uint64_t sceneTriangles = scene.triangleCount();
  const std::uint64_t triangles = sceneTriangles * shadowViews + (sceneTriangles + redrawnTriangles) * views;
  if (triangles > std::uint64_t(limits.maxDrawnTriangles))
    throw LimitError(scene.source + ": a frame would draw " + std::to_string(sceneTriangles) + " triangles" + passes +
                         std::to_string(triangles) + ", more than --max-drawn-triangles allows (" +
                         std::to_string(limits.maxDrawnTriangles) + "); raise --max-drawn-triangles" + orFewerSamples,
                     {"max-drawn-triangles"});
}

namespace {

// The pixels of a width x height image that `bounds` (world space) can
// cover through `view`: the rectangle of its projected corners, clipped to
// the image; the whole image when a corner is not in front of the eye.
std::uint64_t screenRectanglePixels(const Bounds& bounds, const glm::mat4& clipFromWorld, int width, int height) {
  glm::vec2 low(1.0f), high(-1.0f);
  for (int corner = 0; corner < 8; ++corner) {
    const glm::vec3 p((corner & 1) ? bounds.max.x : bounds.min.x, (corner & 2) ? bounds.max.y : bounds.min.y,
                      (corner & 4) ? bounds.max.z : bounds.min.z);
    const glm::vec4 clip = clipFromWorld * glm::vec4(p, 1.0f);
    if (!(clip.w > 1e-6f)) return std::uint64_t(width) * std::uint64_t(height);
    const glm::vec2 ndc = glm::vec2(clip) / clip.w;
    low = corner == 0 ? ndc : glm::min(low, ndc);
    high = corner == 0 ? ndc : glm::max(high, ndc);
  }
  low = glm::clamp(low, glm::vec2(-1.0f), glm::vec2(1.0f));
  high = glm::clamp(high, glm::vec2(-1.0f), glm::vec2(1.0f));
  const double columns = std::ceil(double(high.x - low.x) * 0.5 * width) + 1.0;
  const double rows = std::ceil(double(high.y - low.y) * 0.5 * height) + 1.0;
  return std::uint64_t(std::min(columns, double(width)) * std::min(rows, double(height)));
}

}  // namespace

void checkBlendBudget(const Scene& scene, const CameraView& view, int width, int height, int viewDraws,
                      const ResourceLimits& limits) {
  const glm::mat4 clipFromWorld = view.projection * view.view;
  std::uint64_t layers = 0, fragments = 0;
  for (const Instance& instance : scene.instances) {
    if (instance.material < 0 || scene.materials[std::size_t(instance.material)].alphaMode != AlphaMode::Blend)
      continue;
    ++layers;
    const Bounds local = scene.primitives[std::size_t(instance.primitive)].bounds;
    fragments += screenRectanglePixels(local.transformed(instance.worldFromLocal), clipFromWorld, width, height);
  }
  const std::uint64_t views = std::uint64_t(std::max(1, viewDraws));
  if (fragments * views <= std::uint64_t(limits.maxBlendedFragments)) return;
  throw LimitError(scene.source + ": the blend pass would shade about " + std::to_string(fragments * views) +
                       " pixels a frame (" + std::to_string(layers) + " alphaMode BLEND instances covering " +
                       std::to_string(fragments) + " pixels of the " + std::to_string(width) + "x" +
                       std::to_string(height) + " image" +
                       (views > 1 ? ", x " + std::to_string(views) + " views: the pixel centre and " +
                                        std::to_string(views - 1) + " antialias samples"
                                  : std::string()) +
                       "), more than --max-blended-fragments allows (" + std::to_string(limits.maxBlendedFragments) +
                       "; about 80 ns a blended pixel on llvmpipe); raise --max-blended-fragments" +
                       (views > 1 ? ", or lower --antialias" : ""),
                   {"max-blended-fragments"});
}

std::uint64_t estimateSceneBytes(const Scene& scene) {
  std::uint64_t bytes = 0;
  for (const Primitive& primitive : scene.primitives) {
    bytes += primitive.positions.size() * sizeof(glm::vec3) + primitive.normals.size() * sizeof(glm::vec3) +
             (primitive.texcoords.size() + primitive.texcoords1.size()) * sizeof(glm::vec2) +
             primitive.tangents.size() * sizeof(glm::vec4) +
             primitive.colors.size() * sizeof(glm::vec4) +
             primitive.indices.size() * sizeof(std::uint32_t);
  }
  for (const ImageData& image : scene.images) bytes += image.rgba.size() * 4 / 3;  // with mipmaps on the GPU
  bytes += scene.instances.size() * sizeof(Instance);
  return bytes * 2;  // a CPU copy (the renderer keeps the scene) and the GPU's
}

}  // namespace headlight
