// The plan of `headlight render` (batch_plan.hpp): jobs expanded,
// folders checked, the shard chosen, --resume's finished sets found. Reads
// files (job files, folders, scene fingerprints) and writes nothing.
#include "batch_plan.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <optional>

#include "headlight/error.hpp"
#include "headlight/output.hpp"
#include "headlight/targets.hpp"
#include "io/bounded_read.hpp"
#include "output/frame_set.hpp"
#include "tooling/command_line.hpp"

namespace headlight::cli {
namespace {

namespace fs = std::filesystem;
using detail::excerpt;

// "builtin:cornell" -> "cornell", "a/b/duck.glb" -> "duck".
std::string sceneStem(const std::string& scene) {
  if (scene.rfind("builtin:", 0) == 0) return scene.substr(8);
  return fs::path(scene).stem().string();
}

// True when the folder holds a complete set written for `hash`.
bool setMatches(const std::string& outDir, const std::string& hash) {
  try {
    const std::optional<FrameManifest> manifest = readManifest(outDir);
    if (!manifest || !manifest->complete || manifest->jobHash != hash) return false;
    return checkFrameSet(outDir).state == FrameSetState::Complete;
  } catch (const Error&) {
    return false;  // unreadable: render it again
  }
}

// The job a command-line scene expands to before its views: the key its
// jobs load the scene under (the command's --animation and --time).
Job commandLineJob(const RenderCommand& command, const std::string& scene) {
  Job job;
  job.scene = scene;
  if (!command.sceneLoad.animation.empty()) job.animation = command.sceneLoad.animation;
  job.animationTime = command.sceneLoad.animationTime;
  return job;
}

}  // namespace

JobCamera commandLineCamera(const RenderCommand& command) {
  JobCamera camera;
  if (!command.eye) return camera;  // checked by parseRenderArgs: with --target, not with --orbit or --cameras
  camera.kind = JobCamera::Kind::LookAt;
  camera.eye = *command.eye;
  camera.target = *command.target;
  if (command.up) camera.up = *command.up;
  if (command.fovDegrees) camera.fovDegrees = *command.fovDegrees;
  return camera;
}

std::vector<Job> expandJobs(const RenderCommand& command, const std::function<int(const std::string&)>& cameraCount,
                            const std::function<float(const std::string&)>& animationLength) {
  std::vector<Job> jobs;
  std::vector<std::string> scenes = command.scenes;
  if (scenes.empty() && command.jobFiles.empty()) scenes.push_back(command.scene);
  std::map<std::string, int> stems;
  for (const std::string& scene : scenes) ++stems[sceneStem(scene)];
  const bool severalScenes = scenes.size() > 1;
  for (std::size_t s = 0; s < scenes.size(); ++s) {
    const std::string& scene = scenes[s];
    // Each scene its own folder when there are several (two of one stem get their position).
    fs::path folder = command.outDir;
    if (severalScenes)
      folder /= stems[sceneStem(scene)] > 1 ? sceneStem(scene) + "-" + std::to_string(s) : sceneStem(scene);
    Job base;
    base.scene = scene;
    base.settings = command.settings;
    base.origin = "command line: " + scene;
    base.camera = commandLineCamera(command);
    if (command.orbit || command.throughTime) {
      // --through-time: view v poses the animation at v / N of its length
      // (a loop's last view is a step before its first again).
      float length = 0.0f;
      if (command.throughTime) {
        try {
          length = animationLength(scene);
        } catch (const Error& error) {
          Job bad = base;
          bad.error = commandLineMessage(error);
          jobs.push_back(bad);
          continue;
        }
        base.animation = command.sceneLoad.animation.empty() ? "0" : command.sceneLoad.animation;
      }
      for (int v = 0; v < command.views; ++v) {
        Job job = base;
        if (command.throughTime) job.animationTime = length * float(v) / float(command.views);
        if (command.orbit) {
          job.camera.kind = JobCamera::Kind::Orbit;
          job.camera.orbitIndex = v;
          job.camera.orbitViews = command.views;
          job.camera.orbitElevationDegrees = command.orbitElevationDegrees;
          job.camera.orbitDistanceScale = command.orbitDistanceScale.value_or(1.0f);
        }
        char name[32];
        std::snprintf(name, sizeof name, "view_%03d", v);
        job.outDir = (folder / name).string();
        job.origin += " view " + std::to_string(v);
        jobs.push_back(job);
      }
    } else if (command.camerasAll) {
      int count = 0;
      try {
        count = cameraCount(scene);
      } catch (const Error& error) {
        Job bad = base;
        bad.error = commandLineMessage(error);
        jobs.push_back(bad);
        continue;
      }
      for (int c = 0; c < count; ++c) {
        Job job = base;
        job.settings.camera = c;
        job.outDir = (folder / ("camera_" + std::to_string(c))).string();
        job.origin += " camera " + std::to_string(c);
        jobs.push_back(job);
      }
      if (count == 0) {
        Job bad = base;
        bad.error = "--cameras all: the scene has no camera";
        jobs.push_back(bad);
      }
    } else {
      base.outDir = folder.string();
      jobs.push_back(base);
    }
  }
  for (const std::string& file : command.jobFiles)
    for (Job& job : readJobFile(file, command.settings)) jobs.push_back(std::move(job));
  // The command's --animation and --time are every job's unless it sets its
  // own: the job's hash (--resume) and the scene cache then tell poses apart.
  for (Job& job : jobs) {
    if (!job.animation && !command.sceneLoad.animation.empty()) job.animation = command.sceneLoad.animation;
    if (!job.animationTime && command.sceneLoad.animationTime) job.animationTime = command.sceneLoad.animationTime;
  }
  return jobs;
}

fs::path normalizedOutDir(const std::string& outDir) {
  std::error_code error;
  // Links in the part that exists are followed: a folder, a symlink to it
  // and /proc/self/cwd/... are one folder.
  fs::path path = fs::absolute(fs::path(outDir), error);
  if (error) path = outDir;
  if (fs::path resolved = fs::weakly_canonical(path, error); !error) path = resolved;
  path = path.lexically_normal();
  // "a/b/" normalises to "a/b/" (an empty last element): drop it.
  if (!path.has_filename() && path.has_parent_path() && path != path.root_path()) path = path.parent_path();
  return path;
}

void checkDistinctOutDirs(const std::vector<Job>& jobs) {
  std::map<fs::path, const Job*> seen;
  // Folders that exist, by identity: two paths that no link resolution
  // joins (a bind mount) are still one folder.
  std::map<std::pair<dev_t, ino_t>, const Job*> seenFolders;
  auto clash = [](const Job& first, const Job& second, const fs::path& folder) {
    return SettingsError(first.origin + " and " + second.origin + " both write into '" + folder.string() + "' (out \"" +
                         excerpt(first.outDir) + "\" and \"" + excerpt(second.outDir) +
                         "\"): their files would mix; give each job its own folder");
  };
  for (const Job& job : jobs) {
    if (!job.error.empty()) continue;
    const fs::path folder = normalizedOutDir(job.outDir);
    const auto [at, inserted] = seen.emplace(folder, &job);
    if (!inserted) throw clash(*at->second, job, at->first);
    struct stat info {};
    if (::stat(folder.c_str(), &info) == 0 && S_ISDIR(info.st_mode)) {
      const auto [same, firstTime] = seenFolders.emplace(std::pair{info.st_dev, info.st_ino}, &job);
      if (!firstTime) throw clash(*same->second, job, folder);
    }
  }
}

std::vector<Job> selectShard(const std::vector<Job>& jobs, int index, int count) {
  if (count < 1 || index < 0 || index >= count)
    throw SettingsError("shard " + std::to_string(index) + "/" + std::to_string(count) + ": expected 0 <= I < N");
  std::vector<Job> selected;
  for (std::size_t k = 0; k < jobs.size(); ++k)
    if (int(k % std::size_t(count)) == index) selected.push_back(jobs[k]);
  return selected;
}

int resolveShardIndex(const RenderCommand& command) {
  if (command.shardIndexEnv.empty()) return command.shardIndex;
  const char* value = std::getenv(command.shardIndexEnv.c_str());
  const std::string where = "--shard-index-env " + command.shardIndexEnv;
  if (!value || !*value) throw SettingsError(where + ": the variable is not set");
  int index = -1;
  try {
    std::size_t used = 0;
    index = std::stoi(value, &used);
    if (used != std::string(value).size()) index = -1;
  } catch (const std::exception&) {
  }
  if (index < 0 || index >= command.shardCount)
    throw SettingsError(where + ": expected an index 0.." + std::to_string(command.shardCount - 1) +
                        " (the N of --shard /" + std::to_string(command.shardCount) + "), got '" + excerpt(value) +
                        "'");
  return index;
}

bool jobAlreadyDone(const Job& job, const OutputOptions& output, const std::string& environment) {
  return setMatches(job.outDir, jobHash(job, output, environment));
}

std::string outputFolderRefusal(const Job& job, bool force) {
  const fs::path folder = normalizedOutDir(job.outDir);
  if (job.scene.rfind("builtin:", 0) != 0 && normalizedOutDir(fs::path(job.scene).parent_path().string()) == folder)
    return "the output folder " + folder.string() + " holds the scene " + job.scene +
           " (and its buffers and textures): Headlight writes only into a folder of its own; choose another --out";
  if (force) return "";
  std::error_code error;
  if (!fs::is_directory(folder, error)) return "";
  std::vector<std::string> owned;
  try {
    owned = detail::ownedFileNames(folder);
  } catch (const Error& problem) {
    return std::string(problem.what()) + " (not a Headlight set's; pass --force to replace it)";
  }
  std::vector<std::string> names{std::string(kManifestName), "preview.png"};
  for (const FrameTarget& target : frameTargets())
    for (const char* extension : {".exr", ".png"}) names.push_back(std::string(target.name) + extension);
  // frame.json, read above, is a set's; the other files are ours when it lists them.
  return foreignFilesRefusal(
      folder, names,
      [&](const fs::path& file) {
        std::error_code ignored;
        if (file.filename() == kManifestName) return fs::is_regular_file(file, ignored);
        return std::find(owned.begin(), owned.end(), file.filename().string()) != owned.end();
      },
      "Headlight set in this folder", false);
}

std::string foreignFilesRefusal(const fs::path& folder, std::span<const std::string> names,
                                const std::function<bool(const fs::path&)>& ours, std::string_view writer, bool force) {
  if (force) return "";
  std::error_code error;
  std::string foreign;
  int count = 0;
  for (const std::string& name : names) {
    const fs::path file = folder / name;
    if (!fs::exists(file, error) && !fs::is_symlink(file, error)) continue;
    if (!ours(file)) (foreign += count++ ? ", " : "") += name;
  }
  if (foreign.empty()) return "";
  return folder.string() + " holds " + foreign + ", which no earlier " + std::string(writer) +
         " wrote; pass --force to replace " + (count == 1 ? "it" : "them") + ", or choose another --out";
}

BatchPlan planBatch(const RenderCommand& command, SceneCatalogue& catalogue, bool single) {
  auto cameraCount = [&](const std::string& scene) {
    if (single) throw SettingsError("internal: a single render has no camera list");
    return int(catalogue.scene(commandLineJob(command, scene)).cameras.size());
  };
  auto animationLength = [&](const std::string& name) {
    const Scene& scene = catalogue.scene(commandLineJob(command, name));
    if (scene.animations.empty())
      throw SceneError(name + ": --through-time: the scene has no animations", {"through-time"});
    return scene.animations[std::size_t(std::max(scene.animation, 0))].end;
  };
  const std::vector<Job> all = expandJobs(command, cameraCount, animationLength);
  // Over all jobs, not the shard: every shard refuses a clash alike.
  checkDistinctOutDirs(all);
  BatchPlan plan;
  plan.allJobs = all.size();
  plan.shardIndex = resolveShardIndex(command);
  for (Job& job : selectShard(all, plan.shardIndex, command.shardCount)) {
    PlannedJob& planned = plan.jobs.emplace_back();
    planned.job = std::move(job);
    if (!planned.job.error.empty()) {
      planned.status = PlannedJob::Status::Invalid;
    } else if (const std::string refusal = outputFolderRefusal(planned.job, command.force); !refusal.empty()) {
      planned.status = PlannedJob::Status::Refused;
      planned.job.error = refusal;
    } else if (command.resume) {
      try {
        planned.hash = catalogue.jobHash(planned.job, command.output, command.sceneLoad.environment);
        if (setMatches(planned.job.outDir, planned.hash)) planned.status = PlannedJob::Status::Skip;
      } catch (const Error&) {
        planned.hash.clear();  // a scene that cannot be read: rendered, and its load names the problem
      }
    }
  }
  std::vector<const Job*> toRender;
  for (const PlannedJob& planned : plan.jobs)
    if (planned.status == PlannedJob::Status::Render) toRender.push_back(&planned.job);
  catalogue.countRuns(toRender);
  return plan;
}

}  // namespace headlight::cli
