#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <exception>
#include <limits>
#include <sstream>
#include <thread>

#include "headlight/error.hpp"
#include "headlight/output.hpp"
#include "headlight/targets.hpp"
#include "image_io/atomic_image.hpp"
#include "image_io/target_pngs.hpp"
#include "io/atomic_file.hpp"
#include "output/frame_set.hpp"
#include "settings/preview_background.hpp"

namespace headlight {
namespace {

namespace fs = std::filesystem;

// Half's largest finite value: a clamped +inf must stay finite once stored.
constexpr float kHalfMax = 65504.0f;

void addMatrix(OIIO::ImageSpec& spec, const char* name, const glm::mat4& columnMajor) {
  // glm stores column vectors column by column; OpenEXR's M44f multiplies
  // row vectors (p * M), whose matrix is the transpose, stored row by row:
  // the same sixteen floats in the same order.
  spec.attribute(name, OIIO::TypeDesc::TypeMatrix44, &columnMajor[0][0]);
}

void addMetadata(OIIO::ImageSpec& spec, const Frame& frame) {
  addMatrix(spec, "worldToCamera", frame.view.view);
  addMatrix(spec, "worldToNDC", frame.view.projection * frame.view.view);
  spec.attribute("headlight:near", frame.view.nearPlane);
  spec.attribute("headlight:far", frame.view.farPlane);
  spec.attribute("headlight:projection", frame.view.orthographic ? "orthographic" : "perspective");
  spec.attribute("headlight:renderer", frame.glRenderer);
  spec.attribute("headlight:glVersion", frame.glVersion);
  spec.attribute("headlight:backend", frame.backend);
  spec.attribute("headlight:scene", frame.sceneSource);
  spec.attribute("headlight:sceneHash", frame.sceneHash);
  if (!frame.scenePose.empty()) spec.attribute("headlight:pose", frame.scenePose);
  // glTF features the scene uses that are not rendered, "; "-separated (empty: none).
  std::string ignored;
  for (const std::string& feature : frame.ignored) ignored += (ignored.empty() ? "" : "; ") + feature;
  spec.attribute("headlight:ignored", ignored);
  spec.attribute("headlight:conventions",
                 "right-handed world, +Y up; camera looks down -Z; rows top first; depth.Z = view-space depth");
  // How each fullscreen pass ran (fragment or compute; fullscreen-form).
  for (const PassTime& pass : frame.timings)
    if (!pass.form.empty()) spec.attribute("headlight:form:" + pass.pass, pass.form);
  // As used: "auto" values appear as the numbers they resolved to.
  for (const auto& [name, value] : settingsAsText(frame.settings))
    spec.attribute(std::string(kSettingAttributePrefix) + name, value);
}

// Per-channel range of the finite values and the non-finite count, in one
// pass (OpenImageIO's computePixelStats needs an ImageBuf copy first).
struct ImageStats {
  std::vector<float> min, max;
  std::size_t nonFinite = 0;
  std::size_t saturatedPixels = 0;  // pixels with a finite channel at +-kHalfMax or beyond
};

ImageStats imageStats(const ImageF& image) {
  const std::size_t channels = image.channels.size();
  ImageStats stats{std::vector<float>(channels, std::numeric_limits<float>::infinity()),
                   std::vector<float>(channels, -std::numeric_limits<float>::infinity()), 0, 0};
  for (std::size_t i = 0; i < image.pixels.size(); i += channels) {
    bool saturated = false;
    for (std::size_t c = 0; c < channels; ++c) {
      const float v = image.pixels[i + c];
      if (!std::isfinite(v)) {
        ++stats.nonFinite;
        continue;
      }
      saturated = saturated || std::abs(v) >= kHalfMax;
      stats.min[c] = std::min(stats.min[c], v);
      stats.max[c] = std::max(stats.max[c], v);
    }
    stats.saturatedPixels += saturated;
  }
  return stats;
}

std::string saturationNote(std::size_t pixels) {
  return "; " + std::to_string(pixels) + " pixels saturated at half float's 65504 (light beyond the half-float " +
         "target's range was clamped)";
}

std::string summarize(const fs::path& path, const ImageF& image, const char* type, const ImageStats& stats,
                      NonFinitePolicy policy) {
  std::ostringstream line;
  line << path.string() << ": " << image.width << "x" << image.height << " " << type << " ";
  for (std::size_t c = 0; c < image.channels.size(); ++c) {
    line << (c ? ", " : "") << image.channels[c];
    if (stats.min[c] <= stats.max[c])
      line << " [" << stats.min[c] << ", " << stats.max[c] << "]";
    else
      line << " [no finite value]";
  }
  line << "; non-finite " << stats.nonFinite;
  if (stats.nonFinite && policy == NonFinitePolicy::Clamp) line << " (clamped)";
  return line.str();
}

// NaN -> 0, +-inf -> +-limit.
ImageF clampedCopy(const ImageF& image, float limit) {
  ImageF copy = image;
  for (float& v : copy.pixels)
    if (std::isnan(v))
      v = 0.0f;
    else if (std::isinf(v))
      v = v > 0 ? limit : -limit;
  return copy;
}

std::string nonFiniteMessage(std::string_view what, std::size_t count, std::size_t total) {
  return std::string(what) + ": " + std::to_string(count) + " of " + std::to_string(total) +
         " values are NaN or infinite (pass clamp-nonfinite, NonFinitePolicy::Clamp, to write them clamped: NaN "
         "-> 0, inf -> the largest finite value)";
}

// Runs `tasks` on up to `threads` threads; rethrows the first exception
// after all have finished (so no task outlives the data it reads).
void runParallel(const std::vector<std::function<void()>>& tasks, int threads) {
  const std::size_t workers = std::min<std::size_t>(tasks.size(), std::size_t(std::max(1, threads)));
  std::vector<std::exception_ptr> errors(tasks.size());
  std::atomic<std::size_t> next{0};
  auto work = [&] {
    for (std::size_t i; (i = next++) < tasks.size();) try {
        tasks[i]();
      } catch (...) {
        errors[i] = std::current_exception();
      }
  };
  std::vector<std::thread> pool;
  for (std::size_t w = 1; w < workers; ++w) pool.emplace_back(work);
  work();
  for (std::thread& thread : pool) thread.join();
  for (const std::exception_ptr& error : errors)
    if (error) std::rethrow_exception(error);
}

// How an EXR stores a target's values.
enum class Stored { Half, Float, Uint32 };

// Light is half unless the frame was rendered with float radiance: then its
// GPU target held float32, and half would clamp what it kept. A target that
// is half where it fits is float when its image holds a finite value beyond
// half. Ids are integers and stay integers.
Stored storedAs(const FrameTarget& target, const Frame& frame, const ImageStats& stats) {
  switch (target.storage) {
    case ExrStorage::Radiance:
      return frame.settings.radiancePrecision == RadiancePrecision::Float ? Stored::Float : Stored::Half;
    case ExrStorage::HalfWhereItFits:
      return stats.saturatedPixels == 0 ? Stored::Half : Stored::Float;
    case ExrStorage::Half:
      return Stored::Half;
    case ExrStorage::Float:
      return Stored::Float;
    case ExrStorage::Uint32:
      return Stored::Uint32;
  }
  return Stored::Float;
}

bool wanted(const OutputOptions& options, std::string_view name) {
  return options.targets.empty() ||
         std::find(options.targets.begin(), options.targets.end(), name) != options.targets.end();
}

WrittenFile writeExrChecked(const Frame& frame, const ImageF& image, const fs::path& path, Stored stored,
                            const ExrAttributes& extra, ExrCompression compression, NonFinitePolicy policy,
                            const ImageStats& stats) {
  const bool halfFloat = stored == Stored::Half;
  if (stats.nonFinite && policy == NonFinitePolicy::Error)
    throw IoError(nonFiniteMessage(path.string(), stats.nonFinite, image.pixels.size()), {"clamp-nonfinite"});
  const ImageF* source = &image;
  ImageF clamped;
  if (stats.nonFinite) {
    clamped = clampedCopy(image, halfFloat ? kHalfMax : std::numeric_limits<float>::max());
    source = &clamped;
  }
  const OIIO::TypeDesc fileType = stored == Stored::Half     ? OIIO::TypeDesc::HALF
                                  : stored == Stored::Uint32 ? OIIO::TypeDesc::UINT
                                                             : OIIO::TypeDesc::FLOAT;
  OIIO::ImageSpec spec(image.width, image.height, image.channelCount(), fileType);
  spec.channelnames = image.channels;
  spec.alpha_channel = -1;
  for (int c = 0; c < image.channelCount(); ++c)
    if (image.channels[std::size_t(c)] == "A") spec.alpha_channel = c;
  spec.attribute("compression", std::string(exrCompressionName(compression)));
  addMetadata(spec, frame);
  for (const auto& [name, value] : extra) spec.attribute(name, value);
  if (stored == Stored::Uint32) {
    // Handed over as integers: OpenImageIO would scale floats to 0..2^32-1.
    std::vector<std::uint32_t> values(source->pixels.size());
    std::transform(source->pixels.begin(), source->pixels.end(), values.begin(),
                   [](float value) { return std::uint32_t(std::clamp(value, 0.0f, 4294967040.0f)); });
    detail::writePixelsAtomically(path, values.data(), OIIO::TypeDesc::UINT, spec, "openexr");
  } else {
    detail::writePixelsAtomically(path, source->pixels.data(), OIIO::TypeDesc::FLOAT, spec, "openexr");
  }
  // Only a half target saturates (a float one holds 3.4e38): counted after
  // the readback, where the GPU's half texture has already clamped.
  const std::size_t saturated = halfFloat ? stats.saturatedPixels : 0;
  WrittenFile file{path,
                   summarize(path, image,
                             halfFloat                  ? "half"
                             : stored == Stored::Uint32 ? "uint32"
                                                        : "float",
                             stats, policy) +
                       (saturated ? saturationNote(saturated) : ""),
                   stats.nonFinite, 0, saturated};
  std::error_code error;
  file.bytes = std::size_t(fs::file_size(path, error));
  return file;
}

}  // namespace

WrittenFile writeExr(const Frame& frame, const ImageF& image, const fs::path& path, bool halfFloat,
                     const ExrAttributes& extra, ExrCompression compression, NonFinitePolicy nonFinite) {
  return writeExrChecked(frame, image, path, halfFloat ? Stored::Half : Stored::Float, extra, compression, nonFinite,
                         imageStats(image));
}

std::vector<WrittenFile> writeFrame(const Frame& frame, const fs::path& outDir, const OutputOptions& options) {
  for (const std::string& name : options.targets)
    if (name != "preview" && !findFrameTarget(name))
      throw SettingsError("output target '" + name + "': not a frame target");
  for (const std::string& name : options.pngTargets)
    if (!findFrameTarget(name)) throw SettingsError("PNG target '" + name + "': not a frame target");
  // Checked before anything is written, like the images: a bad background
  // must not leave the folder half replaced.
  parsePreviewBackground(frame.settings.previewBackground);

  // Every target checked before anything is written: a refused set leaves
  // the folder as it was.
  enum class Kind { Exr, Png, Preview };
  struct Job {
    Kind kind;
    const FrameTarget* target;  // null: the preview
    ImageStats stats;
    std::string file() const {
      return kind == Kind::Preview ? "preview.png" : std::string(target->name) + (kind == Kind::Exr ? ".exr" : ".png");
    }
  };
  std::vector<Job> jobs;
  std::string refused;
  for (const FrameTarget& target : frameTargets()) {
    const ImageF& image = frame.*target.image;
    if (image.empty() || !wanted(options, target.name)) continue;
    jobs.push_back({Kind::Exr, &target, imageStats(image)});
    if (jobs.back().stats.nonFinite && options.nonFinite == NonFinitePolicy::Error)
      refused += (refused.empty() ? "" : "; ") +
                 nonFiniteMessage(std::string(target.name) + ".exr", jobs.back().stats.nonFinite, image.pixels.size());
  }
  if (!refused.empty()) throw IoError(outDir.string() + ": not written: " + refused, {"clamp-nonfinite"});
  const bool preview = wanted(options, "preview") && !frame.lit.empty();
  if (preview) jobs.push_back({Kind::Preview, nullptr, {}});
  // A PNG is a look at a target the frame has (non-finite values show black).
  for (const FrameTarget& target : frameTargets())
    if (!(frame.*target.image).empty() &&
        std::find(options.pngTargets.begin(), options.pngTargets.end(), target.name) != options.pngTargets.end())
      jobs.push_back({Kind::Png, &target, {}});

  // The caller's side of the module holds the folder's lock (image_module.cpp).
  std::error_code error;
  fs::create_directories(outDir, error);
  if (error) throw IoError(outDir.string() + ": cannot create the output folder: " + error.message());
  removeStaleTemporaries(outDir);
  // Only files an earlier Headlight set here listed are removed below (the
  // CLI refuses, without --force, a folder whose target-named files are not).
  std::vector<std::string> owned;
  try {
    owned = detail::ownedFileNames(outDir);
  } catch (const IoError&) {
    // Not a Headlight manifest: nothing in the folder is ours to remove.
  }
  std::vector<std::string> planned;
  for (const Job& job : jobs) planned.push_back(job.file());
  detail::beginFrameSet(frame, outDir, options, planned);

  std::vector<WrittenFile> written(jobs.size());
  std::vector<std::function<void()>> tasks;
  for (std::size_t i = 0; i < jobs.size(); ++i)
    tasks.push_back([&, i] {
      const Job& job = jobs[i];
      const fs::path path = outDir / job.file();
      switch (job.kind) {
        case Kind::Exr:
          written[i] = writeExrChecked(frame, frame.*job.target->image, path, storedAs(*job.target, frame, job.stats),
                                       {}, options.compression, options.nonFinite, job.stats);
          break;
        case Kind::Png:
          written[i] = writeTargetPng(frame, *job.target, path);
          break;
        case Kind::Preview:
          written[i] = writePreview(frame, path);
          break;
      }
    });
  runParallel(tasks, options.threads > 0 ? options.threads : int(std::max(1u, std::thread::hardware_concurrency())));

  // A target this frame lacks (ssgi with SSGI off, emissive for a scene
  // without glow) or that was not asked for must not survive from an
  // earlier render into the folder, where a diff would take it for this one's.
  auto removeIfOurs = [&](const std::string& name) {
    if (std::find(owned.begin(), owned.end(), name) != owned.end()) fs::remove(outDir / name, error);
  };
  for (const FrameTarget& target : frameTargets())
    for (const char* extension : {".exr", ".png"})
      if (const std::string file = std::string(target.name) + extension;
          std::find(planned.begin(), planned.end(), file) == planned.end())
        removeIfOurs(file);
  if (!preview) removeIfOurs("preview.png");
  detail::finishFrameSet(frame, outDir, options, written);
  return written;
}

std::map<std::string, std::string> readSettingAttributes(const fs::path& exr) {
  auto input = OIIO::ImageInput::open(exr.string());
  if (!input) throw IoError(exr.string() + ": cannot read: " + OIIO::geterror());
  std::map<std::string, std::string> settings;
  for (const OIIO::ParamValue& attribute : input->spec().extra_attribs) {
    const std::string name = attribute.name().string();
    if (name.rfind(kSettingAttributePrefix, 0) == 0)
      settings[name.substr(kSettingAttributePrefix.size())] = attribute.get_string();
  }
  return settings;
}

}  // namespace headlight
