#pragma once
// The job model of `headlight render` batches, pure and context-free: a
// job (scene, camera, settings, folder), job lines and files parsed into
// jobs, and the hash that tells a finished set is a job's. The plan
// (batch_plan.hpp) builds the batch's jobs from these; nothing here renders
// or writes. docs/BATCH.md is the user's guide.
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "headlight/camera.hpp"
#include "headlight/output.hpp"
#include "headlight/scene.hpp"
#include "headlight/settings.hpp"

namespace headlight::cli {

// How a job places its camera.
struct JobCamera {
  enum class Kind {
    Settings,  // settings.camera (an index) or the scene's first / a fitted one
    LookAt,    // eye, target, up, vertical field of view
    Orbit,     // view `orbitIndex` of `orbitViews` on a turntable around the bounds
  };
  Kind kind = Kind::Settings;
  glm::vec3 eye{0.0f}, target{0.0f}, up{0.0f, 1.0f, 0.0f};
  float fovDegrees = 40.0f;  // vertical, LookAt and Orbit
  int orbitIndex = 0, orbitViews = 1;
  // Orbit: degrees above the bounds' centre (fitCamera's 14.04 by default), and a multiple of the
  // distance that frames the bounds whole.
  // (None: fitCamera's own, kFitElevationRadians, with no round trip through degrees.)
  std::optional<float> orbitElevationDegrees;
  float orbitDistanceScale = 1.0f;

  // Text that names the placement exactly (for the job hash and messages).
  std::string describe() const;
  // The camera for `scene` at `aspect` (width / height); nullopt for Settings.
  std::optional<Camera> build(const Scene& scene, float aspect) const;
};

struct Job {
  std::string origin;  // "jobs.jsonl:3", or "command line" (+ the view)
  std::string scene;
  // "material_variant": the glTF KHR_materials_variants variant, over the
  // command's --material-variant (SceneLoadOptions::materialVariant).
  std::optional<std::string> materialVariant;
  // "animation" and "time": the animation to pose the scene by and when,
  // over the command's --animation and --time (SceneLoadOptions::animation,
  // animationTime).
  std::optional<std::string> animation;
  std::optional<float> animationTime;
  JobCamera camera;
  RenderSettings settings;
  std::string outDir;
  std::string error;  // a job that could not be parsed: reported, never rendered
};

// One job per line of `text` (JSON Lines; blank lines and lines starting
// with '#' are skipped). Each job starts from `base` (the command line's
// settings); its "settings" object goes through the setting table
// (applySettingsText). A bad line becomes a Job with `error` set, naming
// the line: one longer than detail::kMaxJobLineBytes, JSON nested deeper than
// scenes may nest (detail::kMaxJsonDepth, io/bounded_json.hpp), an unknown key, a bad value. Echoed
// input is cut to a short excerpt. `name` is the file's name for origins.
std::vector<Job> parseJobLines(const std::string& text, const std::string& name, const RenderSettings& base);

// A job file's jobs: read only when it is a regular file of at most
// detail::kMaxJobFileBytes (IoError naming it otherwise), then parseJobLines.
std::vector<Job> readJobFile(const std::filesystem::path& path, const RenderSettings& base);

// What decides whether a finished set is this job's: the scene's bytes (or
// builtin name), the requested settings, the camera, the output choices and,
// when one is given, the environment map's bytes (--environment; none adds
// nothing, so sets rendered without one keep their hash).
// `fingerprint` reads a file's (io/fingerprint.hpp's fileFingerprint when
// empty): a batch passes one that reads each file once.
std::string jobHash(const Job& job, const OutputOptions& output, const std::string& environment = {},
                    const std::function<std::string(const std::string&)>& fingerprint = {});

}  // namespace headlight::cli
