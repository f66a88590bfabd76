#pragma once
// The plan of a `headlight render` batch, made once before anything
// renders: the command line's scenes x views expanded into jobs and every
// job file's lines after them, output folders normalised and checked for
// clashes, the shard chosen, each job's folder checked and, with --resume,
// its hash held against the set already there. Its steps are here in the
// order planBatch takes them; the job model they build is job_file.hpp, the
// run and the report are batch.cpp. docs/BATCH.md is the user's guide.
#include <cstddef>
#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "cli_options.hpp"
#include "job_file.hpp"
#include "scene_catalogue.hpp"

namespace headlight::cli {

// The camera --eye, --target, --up and --fov place (Kind::Settings without --eye).
JobCamera commandLineCamera(const RenderCommand& command);

// Jobs from the command: its scenes (x --views/--cameras all; `cameraCount`
// tells how many cameras a scene has, `animationLength` how long the
// animation --through-time steps through lasts, each loading the scene if
// needed) then every job file's lines, in order.
std::vector<Job> expandJobs(const RenderCommand& command, const std::function<int(const std::string&)>& cameraCount,
                            const std::function<float(const std::string&)>& animationLength = {});

// The folder a job writes, as compared for clashes: absolute, normalised,
// without a trailing separator ("dup", "./dup/" and "$PWD/dup" are one).
std::filesystem::path normalizedOutDir(const std::string& outDir);

// SettingsError naming both jobs when two jobs (errors aside) write into
// one folder; nothing has rendered yet when it is called.
void checkDistinctOutDirs(const std::vector<Job>& jobs);

// Jobs k with k % count == index, in order.
std::vector<Job> selectShard(const std::vector<Job>& jobs, int index, int count);

// The shard index: `command.shardIndex`, or the value of the environment
// variable command.shardIndexEnv (a SettingsError when it is unset or not
// an index below shardCount).
int resolveShardIndex(const RenderCommand& command);

// Why a job may not write into its folder, or "" when it may: the folder
// holds the scene file (out = the scene's folder), or, without `force`, a
// file with a target's name (lit.exr, frame.json, ...) that no earlier
// Headlight set there listed (a user's own file, which writing would replace).
std::string outputFolderRefusal(const Job& job, bool force);

// The files among `names` that `folder` holds and `ours` does not recognise
// as an earlier `writer`'s (e.g. "headlight reference"), as a refusal naming
// them; "" when there are none or `force`. What render, reference and bench
// write over, each with its own rule for "ours".
std::string foreignFilesRefusal(const std::filesystem::path& folder, std::span<const std::string> names,
                                const std::function<bool(const std::filesystem::path&)>& ours, std::string_view writer,
                                bool force);

// True when `job.outDir` holds a complete set (checkFrameSet) written for
// the same job hash (with `environment`, the --environment file: jobHash):
// --resume skips it.
bool jobAlreadyDone(const Job& job, const OutputOptions& output, const std::string& environment = {});

struct PlannedJob {
  enum class Status { Render, Skip, Refused, Invalid } status = Status::Render;
  Job job;
  std::string hash;  // computed once: by the plan with --resume, else when the job's set is written
};

struct BatchPlan {
  std::vector<PlannedJob> jobs;  // this shard's, in order
  std::size_t allJobs = 0;       // every shard's
  int shardIndex = 0;
};

// The plan: the steps above, a status per job (render, skip, refused,
// invalid). A scene is loaded (through `catalogue`) only where the
// expansion must count its cameras or time its animation; `single` (a
// single render) has no camera list. Tells the catalogue how often each
// scene will be set on the renderer.
BatchPlan planBatch(const RenderCommand& command, SceneCatalogue& catalogue, bool single);

}  // namespace headlight::cli
