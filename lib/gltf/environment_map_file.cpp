// loadEnvironmentMap (headlight/scene_loader.hpp): the file's kind and
// existence are checked here, its header and pixels in the image module
// (lib/image_io/environment_decode.cpp), so OpenImageIO never opens a FIFO,
// a device or a folder, and never decodes more than max-memory allows.
#include <string_view>

#include "headlight/error.hpp"
#include "headlight/scene_loader.hpp"
#include "image_io/environment_decode.hpp"
#include "io/bounded_read.hpp"
#include "io/fingerprint.hpp"

namespace headlight {
namespace {

// GL 4.5 guarantees 16384 texels a side; the map is uploaded whole as the background.
constexpr int kMaxEnvironmentSide = 16384;

}  // namespace

std::shared_ptr<const EnvironmentMap> loadEnvironmentMap(const std::filesystem::path& path,
                                                         const ResourceLimits& limits) {
  const std::string name = path.string();
  std::error_code error;
  if (!std::filesystem::exists(path, error)) throw IoError(name + ": cannot read the environment map: no such file");
  if (const std::string kind = detail::nonRegularKind(path); !kind.empty())
    throw IoError(name + ": cannot read the environment map: it is " + kind + ", not a regular file");
  detail::DecodedEnvironment decoded;
  const std::string problem =
      detail::decodeEnvironment(name.c_str(), maxMemoryBytes(limits), kMaxEnvironmentSide, decoded);
  if (!problem.empty()) {
    const std::string message = name + ": environment map " + problem;
    if (problem.find("max-memory") != std::string::npos) throw LimitError(message, {"max-memory"});
    throw SceneError(message);
  }
  auto map = std::make_shared<EnvironmentMap>();
  map->source = name;
  map->width = decoded.width;
  map->height = decoded.height;
  map->rgb = std::move(decoded.rgb);
  map->sourceHash = textFingerprint(
      std::string_view(reinterpret_cast<const char*>(map->rgb.data()), map->rgb.size() * sizeof(float)));
  return map;
}

}  // namespace headlight
