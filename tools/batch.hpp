#pragma once
// `headlight render` as a batch: jobs from the command line (scenes x views)
// and from job files (JSON Lines), sharded, resumable, rendered by one
// context and one renderer, written on a worker thread while the next view
// renders. docs/BATCH.md is the user's guide.
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "cli_options.hpp"
#include "headlight/scene.hpp"

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

  // Text that names the placement exactly (for the job hash and messages).
  std::string describe() const;
  // The camera for `scene` at `aspect` (width / height); nullopt for Settings.
  std::optional<Camera> build(const Scene& scene, float aspect) const;
};

struct Job {
  std::string origin;  // "jobs.jsonl:3", or "command line" (+ the view)
  std::string scene;
  JobCamera camera;
  RenderSettings settings;
  std::string outDir;
  std::string error;  // a job that could not be parsed: reported, never rendered
};

// One job per line of `text` (JSON Lines; blank lines and lines starting
// with '#' are skipped). Each job starts from `base` (the command line's
// settings); its "settings" object goes through the setting table
// (applySettingsText). A bad line becomes a Job with `error` set, naming
// the line. `name` is the file's name for origins.
std::vector<Job> parseJobLines(const std::string& text, const std::string& name, const RenderSettings& base);

// Jobs from the command: its scenes (x --views/--cameras all; `cameraCount`
// tells how many cameras a scene has, loading it if needed) then every job
// file's lines, in order.
std::vector<Job> expandJobs(const RenderCommand& command, const std::function<int(const std::string&)>& cameraCount);

// Jobs k with k % count == index, in order.
std::vector<Job> selectShard(const std::vector<Job>& jobs, int index, int count);

// The shard index: `command.shardIndex`, or the value of the environment
// variable command.shardIndexEnv (a SettingsError when it is unset or not
// an index below shardCount).
int resolveShardIndex(const RenderCommand& command);

// What decides whether a finished set is this job's: the scene's bytes (or
// builtin name), the requested settings, the camera and the output choices.
std::string jobHash(const Job& job, const OutputOptions& output);

// True when `job.outDir` holds a complete set (checkFrameSet) written for
// the same job hash: --resume skips it.
bool jobAlreadyDone(const Job& job, const OutputOptions& output);

// Runs `render` as a batch; returns the exit code (0, or 1 when any job failed).
int runRenderBatch(const RenderCommand& command);

}  // namespace headlight::cli
