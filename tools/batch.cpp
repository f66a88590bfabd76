// headlight render: one scene straight through (runSingleRender), or a
// batch: expand jobs -> check their folders -> shard -> (resume) -> for
// each job: lock its folder -> scene from the cache -> Renderer::render ->
// writeFrame on a worker thread while the next job renders -> one summary
// (lines or JSON). The job model is job_file.cpp.
#include "batch.hpp"

#include <sys/resource.h>

#include <chrono>
#include <cstdlib>
#include <functional>
#include <future>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>

#include "frame/frame_plan.hpp"
#include "headlight/context.hpp"
#include "headlight/error.hpp"
#include "headlight/output.hpp"
#include "headlight/renderer.hpp"
#include "headlight/scene_loader.hpp"
#include "headlight/targets.hpp"
#include "output/fingerprint.hpp"
#include "output/folder_lock.hpp"
#include "output/frame_set.hpp"
#include "progress.hpp"
#include "tooling/command_line.hpp"
#include "tooling/command_setup.hpp"

namespace headlight::cli {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

// ---- running -----------------------------------------------------------------

// With --wait, says once whom a render waits for before it waits (unless --quiet).
std::function<void(const std::string&)> waitingNote(const RenderCommand& command, const fs::path& folder) {
  if (command.verbosity == Verbosity::Quiet) return {};
  return [folder, seconds = command.waitSeconds](const std::string& holder) {
    std::cerr << "headlight: " << folder.string() << ": waiting for " << holder
              << " to release the folder's lock (at most " << seconds << " s: --wait-timeout)\n";
  };
}

struct JobResult {
  enum class Status { Rendered, Skipped, Failed } status = Status::Failed;
  std::string error;
  std::vector<WrittenFile> files;
  std::vector<PassTime> passes;
  double renderMs = 0, writeMs = 0;
  long peakRssKb = 0;  // the process's peak resident memory after the job's render
};

long peakRssKb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss;  // kilobytes on Linux
}

// The command's scene-load options with the job's material_variant, animation and time.
SceneLoadOptions loadOptionsFor(const Job& job, SceneLoadOptions options) {
  if (job.materialVariant) options.materialVariant = *job.materialVariant;
  if (job.animation) options.animation = *job.animation;
  if (job.animationTime) options.animationTime = *job.animationTime;
  return options;
}

// A scene as loaded for a job: its name, and the job's variant, animation
// and time when it sets them.
std::string sceneKey(const Job& job) {
  std::string key = job.scene;
  if (job.materialVariant) key += "\n#material-variant=" + *job.materialVariant;
  if (job.animation) key += "\n#animation=" + *job.animation;
  if (job.animationTime) key += "\n#time=" + std::to_string(*job.animationTime);
  return key;
}

// Scenes stay loaded while a later job of this shard uses them.
class SceneCache {
 public:
  SceneCache(const std::vector<Job>& jobs, const SceneLoadOptions& options, const ResourceLimits& limits, bool quiet)
      : options_(options), limits_(limits), quiet_(quiet) {
    for (const Job& job : jobs)
      if (job.error.empty()) ++remaining_[sceneKey(job)];
  }
  const Scene& get(const Job& job) {
    const std::string name = sceneKey(job);
    auto found = scenes_.find(name);
    if (found == scenes_.end()) {
      Scene scene = loadCommandScene(job.scene, loadOptionsFor(job, options_), limits_, quiet_);
      checkDrawBudget(scene, limits_);  // before the context: a refusal costs no GL start-up
      found = scenes_.emplace(name, std::move(scene)).first;
    }
    return found->second;
  }
  // A scene loaded before the batch started (to count its cameras).
  void adopt(const std::string& name, Scene scene) {
    if (remaining_[name] > 0) scenes_.emplace(name, std::move(scene));
  }
  // A job is done: drop its scene when no later job needs it.
  void release(const Job& job) {
    const std::string name = sceneKey(job);
    if (--remaining_[name] <= 0) scenes_.erase(name);
  }

 private:
  SceneLoadOptions options_;
  ResourceLimits limits_;
  bool quiet_;
  std::map<std::string, int> remaining_;
  std::map<std::string, Scene> scenes_;
};

double millisecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

json summaryJson(const std::vector<Job>& jobs, const std::vector<JobResult>& results, const std::string& renderer,
                 double wallMs) {
  json list = json::array(), failures = json::array();
  std::map<std::string, double> passTotals;
  std::size_t rendered = 0, skipped = 0, files = 0;
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    const JobResult& r = results[i];
    static const char* kStatus[] = {"rendered", "skipped", "failed"};
    json entry{{"origin", jobs[i].origin},
               {"scene", jobs[i].scene},
               {"out", jobs[i].outDir},
               {"camera", jobs[i].camera.describe()},
               {"status", kStatus[int(r.status)]}};
    if (r.status == JobResult::Status::Failed) {
      entry["error"] = r.error;
      failures.push_back({{"origin", jobs[i].origin}, {"error", r.error}});
    }
    if (r.status == JobResult::Status::Rendered) {
      ++rendered;
      json passes = json::object(), gpuPasses = json::object(), forms = json::object();
      for (const PassTime& pass : r.passes) {
        passes[pass.pass] = pass.milliseconds;
        passTotals[pass.pass] += pass.milliseconds;
        if (pass.gpuMilliseconds >= 0) gpuPasses[pass.pass] = pass.gpuMilliseconds;
        if (!pass.form.empty()) forms[pass.pass] = pass.form;
      }
      json fileList = json::array();
      for (const WrittenFile& file : r.files)
        fileList.push_back({{"path", file.path.string()},
                            {"bytes", file.bytes},
                            {"non_finite", file.nonFinite},
                            {"saturated_pixels", file.saturatedPixels}});
      files += r.files.size();
      entry["passes_ms"] = passes;
      entry["passes_gpu_ms"] = gpuPasses;
      entry["forms"] = forms;
      entry["render_ms"] = r.renderMs;
      entry["write_ms"] = r.writeMs;
      entry["peak_rss_kb"] = r.peakRssKb;
      entry["files"] = fileList;
    }
    if (r.status == JobResult::Status::Skipped) ++skipped;
    list.push_back(entry);
  }
  return {{"jobs", jobs.size()},  {"rendered", rendered}, {"skipped", skipped},   {"failed", failures.size()},
          {"files", files},       {"wall_ms", wallMs},    {"renderer", renderer}, {"pass_totals_ms", passTotals},
          {"failures", failures}, {"results", list}};
}

}  // namespace

bool jobAlreadyDone(const Job& job, const OutputOptions& output, const std::string& environment) {
  try {
    const std::optional<FrameManifest> manifest = readManifest(job.outDir);
    if (!manifest || !manifest->complete || manifest->jobHash != jobHash(job, output, environment)) return false;
    return checkFrameSet(job.outDir).state == FrameSetState::Complete;
  } catch (const Error&) {
    return false;  // unreadable: render it again
  }
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
  for (const FrameTarget& target : frameTargets()) names.push_back(std::string(target.name) + ".exr");
  std::string foreign;
  for (const std::string& name : names) {
    if (!fs::exists(folder / name, error) && !fs::is_symlink(folder / name, error)) continue;
    if (name == kManifestName && fs::is_regular_file(folder / name, error)) continue;  // read above: ours
    if (std::find(owned.begin(), owned.end(), name) == owned.end()) (foreign += foreign.empty() ? "" : ", ") += name;
  }
  if (foreign.empty()) return "";
  return folder.string() + " holds " + foreign +
         ", which no earlier Headlight set in this folder wrote; pass --force to replace them, or choose another --out";
}

bool isSingleRender(const RenderCommand& command) {
  return command.jobFiles.empty() && command.scenes.size() <= 1 && !command.orbit && !command.throughTime &&
         !command.camerasAll && command.shardCount == 1 && !command.json;
}

namespace {

void printFrameDetails(const Frame& frame) {
  double total = 0;
  for (const PassTime& time : frame.timings) {
    // Wall time (glFinish-bounded, a first frame's compiles included), then the GPU's own, then the form.
    std::fprintf(stderr, "pass %-10s %9.2f ms", time.pass.c_str(), time.milliseconds);
    if (time.gpuMilliseconds >= 0) std::fprintf(stderr, "  gpu %9.3f ms", time.gpuMilliseconds);
    if (!time.form.empty()) std::fprintf(stderr, "  %s", time.form.c_str());
    std::fprintf(stderr, "\n");
    total += time.milliseconds;
  }
  std::fprintf(stderr, "pass %-10s %9.2f ms\n", "total", total);
  for (const SkippedWork& skipped : frame.skipped)
    std::fprintf(stderr, "skipped %-10s %s\n", skipped.work.c_str(), skipped.reason.c_str());
}

// A half-float target that clamped is said on stderr, with the way out:
// the summary line alone is easy to miss in a batch.
void warnSaturated(const std::vector<WrittenFile>& files) {
  for (const WrittenFile& file : files)
    if (file.saturatedPixels)
      std::cerr << "headlight: warning: " << file.path.string() << ": " << file.saturatedPixels
                << " pixels saturated at 65504, half float's largest value: the scene's light exceeds the "
                   "half-float target's range (render with --radiance-precision float to keep it)\n";
}

// The renderer draws only what the output needs (the preview reads lit).
std::vector<std::string> renderTargetsFor(const OutputOptions& output) {
  std::vector<std::string> targets;
  for (const std::string& target : output.targets) targets.push_back(target == "preview" ? "lit" : target);
  return targets;
}

}  // namespace

int runSingleRender(const RenderCommand& command) {
  const std::vector<Job> jobs = expandJobs(
      command, [](const std::string&) -> int { throw SettingsError("internal: a single render has no camera list"); });
  const Job& job = jobs.at(0);
  if (const std::string refusal = outputFolderRefusal(job, command.force); !refusal.empty()) throw IoError(refusal);
  if (command.resume && jobAlreadyDone(job, command.output, command.sceneLoad.environment)) {
    if (command.verbosity != Verbosity::Quiet)
      std::cout << job.outDir << ": skipped (--resume: complete set of the same job)\n";
    return 0;
  }
  Scene scene = loadCommandScene(job.scene, loadOptionsFor(job, command.sceneLoad), command.limits,
                                 command.verbosity == Verbosity::Quiet);
  checkDrawBudget(scene, command.limits);  // before the context: a refusal costs no GL start-up
  Context context(command.context);
  preloadImageIo();  // OpenImageIO loads on the other core while this one compiles shaders and renders
  if (command.verbosity == Verbosity::Verbose) std::cerr << verboseHeader(context, scene);
  Renderer renderer(context);
  renderer.setLimits(command.limits);
  renderer.setScene(std::move(scene));
  // Held from before the render until the set is written: a second render
  // into this folder waits (--wait) or stops here.
  const detail::OutputFolderLock lock(job.outDir, command.wait, command.waitSeconds, waitingNote(command, job.outDir));
  const std::optional<Camera> camera =
      job.camera.build(renderer.scene(), float(job.settings.width) / float(job.settings.height));
  const Frame frame = renderer.render(job.settings, camera ? &*camera : nullptr, renderTargetsFor(command.output));
  if (command.verbosity == Verbosity::Verbose) printFrameDetails(frame);
  OutputOptions output = command.output;
  output.jobHash = jobHash(job, command.output, command.sceneLoad.environment);
  output.waitForFolder = command.wait;
  output.waitForFolderSeconds = command.waitSeconds;
  const std::vector<WrittenFile> files = writeFrame(frame, job.outDir, output);
  if (command.verbosity != Verbosity::Quiet)
    for (const WrittenFile& file : files) std::cout << file.summary << "\n";
  warnSaturated(files);
  return 0;
}

int runRenderBatch(const RenderCommand& command) {
  const auto wallStart = std::chrono::steady_clock::now();
  const bool quiet = command.verbosity == Verbosity::Quiet;
  const bool verbose = command.verbosity == Verbosity::Verbose;
  const bool lines = !quiet && !command.json;

  std::map<std::string, Scene> countedScenes;  // scenes loaded only to count cameras, handed to the cache
  auto cameraCount = [&](const std::string& scene) {
    auto found = countedScenes.find(scene);
    if (found == countedScenes.end())
      found = countedScenes.emplace(scene, loadCommandScene(scene, command.sceneLoad, command.limits, quiet)).first;
    return int(found->second.cameras.size());
  };
  auto animationLength = [&](const std::string& name) {
    cameraCount(name);  // loads it once
    const Scene& scene = countedScenes.at(name);
    if (scene.animations.empty())
      throw SceneError(name + ": --through-time: the scene has no animations", {"through-time"});
    return scene.animations[std::size_t(std::max(scene.animation, 0))].end;
  };
  const std::vector<Job> all = expandJobs(command, cameraCount, animationLength);
  // Over all jobs, not the shard: every shard refuses a clash alike.
  checkDistinctOutDirs(all);
  std::vector<Job> jobs = selectShard(all, resolveShardIndex(command), command.shardCount);
  for (Job& job : jobs)
    if (job.error.empty()) job.error = outputFolderRefusal(job, command.force);

  std::vector<JobResult> results(jobs.size());
  SceneCache cache(jobs, command.sceneLoad, command.limits, quiet);
  // Loaded once, with the command's load options: the key a job with the
  // command's --animation and --time has.
  for (auto& [name, scene] : countedScenes) {
    Job probe;
    probe.scene = name;
    if (!command.sceneLoad.animation.empty()) probe.animation = command.sceneLoad.animation;
    probe.animationTime = command.sceneLoad.animationTime;
    cache.adopt(sceneKey(probe), std::move(scene));
  }
  countedScenes.clear();
  std::optional<Context> context;
  std::optional<Renderer> renderer;
  std::string currentScene, rendererName;
  bool softwareRasterizer = false;  // llvmpipe and the like: no frame submitted ahead
  const std::vector<std::string> renderTargets = renderTargetsFor(command.output);

  Progress progress(jobs.size(), !quiet && !command.json, "views");
  // One write in flight while the next job renders.
  std::future<void> pendingWrite;
  std::mutex reportMutex;  // the writer thread reports too
  auto report = [&](std::size_t index) {
    const std::lock_guard<std::mutex> lock(reportMutex);
    const JobResult& r = results[index];
    if (r.status == JobResult::Status::Failed) {
      progress.clear();
      std::cerr << "headlight: job " << jobs[index].origin << " failed: " << r.error << "\n";
    } else if (r.status == JobResult::Status::Rendered) {
      progress.clear();
      if (lines)
        for (const WrittenFile& file : r.files) std::cout << file.summary << "\n";
      warnSaturated(r.files);
    } else if (lines && r.status == JobResult::Status::Skipped) {
      progress.clear();
      std::cout << jobs[index].outDir << ": skipped (--resume: complete set of the same job)\n";
    }
  };
  auto waitForWrite = [&] {
    if (pendingWrite.valid()) pendingWrite.get();
  };

  // The job submitted to the renderer and not yet collected: frame N+1 is
  // submitted before frame N is collected (Renderer::submit), so the GPU
  // draws one while the other's pixels come back.
  struct InFlight {
    std::size_t index;
    std::shared_ptr<detail::OutputFolderLock> folderLock;
    double submitMs;
  };
  std::optional<InFlight> inFlight;
  auto collectInFlight = [&] {
    if (!inFlight) return;
    const InFlight job = std::move(*inFlight);
    inFlight.reset();
    const std::size_t i = job.index;
    try {
      const auto collectStart = std::chrono::steady_clock::now();
      auto frame = std::make_shared<Frame>(renderer->collect());
      results[i].renderMs = job.submitMs + millisecondsSince(collectStart);
      results[i].passes = frame->timings;
      results[i].peakRssKb = peakRssKb();
      if (verbose) printFrameDetails(*frame);
      waitForWrite();
      OutputOptions output = command.output;
      output.jobHash = jobHash(jobs[i], command.output, command.sceneLoad.environment);
      output.waitForFolder = command.wait;
      output.waitForFolderSeconds = command.waitSeconds;
      pendingWrite = std::async(std::launch::async, [&, i, frame, output, folderLock = job.folderLock] {
        const auto writeStart = std::chrono::steady_clock::now();
        try {
          results[i].files = writeFrame(*frame, jobs[i].outDir, output);
          results[i].status = JobResult::Status::Rendered;
        } catch (const std::exception& error) {
          results[i].status = JobResult::Status::Failed;
          results[i].error = commandLineMessage(error);
        }
        results[i].writeMs = millisecondsSince(writeStart);
        report(i);
      });
    } catch (const ContextError&) {
      throw;
    } catch (const std::exception& error) {
      results[i].status = JobResult::Status::Failed;
      results[i].error = commandLineMessage(error);
      report(i);
    }
  };

  for (std::size_t i = 0; i < jobs.size(); ++i) {
    const Job& job = jobs[i];
    JobResult& result = results[i];
    {
      const std::lock_guard<std::mutex> lock(reportMutex);  // the writer thread prints too
      progress.update(i, job.origin);
    }
    if (!job.error.empty()) {
      result.error = job.error;
      report(i);
      continue;
    }
    if (command.resume && jobAlreadyDone(job, command.output, command.sceneLoad.environment)) {
      result.status = JobResult::Status::Skipped;
      cache.release(job);
      report(i);
      continue;
    }
    try {
      const Scene& scene = cache.get(job);
      if (!context) {
        context.emplace(command.context);
        renderer.emplace(*context);
        renderer->setLimits(command.limits);
        rendererName = context->renderer();
        softwareRasterizer = isSoftwareRasterizer(rendererName);
        // OpenImageIO loads on the other core while this one compiles
        // shaders and renders.
        preloadImageIo();
      }
      if (currentScene != sceneKey(job)) {
        if (verbose) std::cerr << verboseHeader(*context, scene);
        currentScene.clear();
        renderer->setScene(scene);
        currentScene = sceneKey(job);
      }
      // Held from before the render until the writer thread has written the set.
      auto folderLock = std::make_shared<detail::OutputFolderLock>(job.outDir, command.wait, command.waitSeconds,
                                                                   waitingNote(command, job.outDir));
      const std::optional<Camera> camera =
          job.camera.build(scene, float(job.settings.width) / float(job.settings.height));
      const auto submitStart = std::chrono::steady_clock::now();
      renderer->submit(job.settings, camera ? &*camera : nullptr, renderTargets);
      cache.release(job);
      // On a GPU the previous job's pixels come back while the GPU draws
      // this one. On a software rasteriser each job is collected at once:
      // there the CPU renders, and submitting ahead made a batch slower
      // (docs/BENCHMARKS.md, "Readback and pipelined frames").
      InFlight submitted{i, std::move(folderLock), millisecondsSince(submitStart)};
      collectInFlight();
      inFlight = std::move(submitted);
      if (softwareRasterizer) collectInFlight();
    } catch (const ContextError&) {
      throw;  // no job can render without a context: the batch stops
    } catch (const std::exception& error) {
      cache.release(job);
      result.status = JobResult::Status::Failed;
      result.error = commandLineMessage(error);
      // A scene that failed to load fails every job of it, each with its line.
      report(i);
    }
  }
  collectInFlight();
  waitForWrite();
  progress.update(jobs.size(), "done");
  progress.finish();

  std::size_t failed = 0, skipped = 0, rendered = 0;
  std::string failedList;
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    if (results[i].status == JobResult::Status::Failed) {
      ++failed;
      (failedList += failedList.empty() ? "" : ", ") += jobs[i].origin;
    }
    skipped += results[i].status == JobResult::Status::Skipped;
    rendered += results[i].status == JobResult::Status::Rendered;
  }
  if (command.json) {
    std::cout << summaryJson(jobs, results, rendererName, millisecondsSince(wallStart)).dump(2) << "\n";
  } else if (!quiet) {
    std::cout << "batch: " << jobs.size() << " job" << (jobs.size() == 1 ? "" : "s");
    if (command.shardCount > 1)
      std::cout << " (shard " << resolveShardIndex(command) << "/" << command.shardCount << " of " << all.size() << ")";
    std::cout << ": " << rendered << " rendered, " << skipped << " skipped, " << failed << " failed";
    if (failed) std::cout << " (" << failedList << ")";
    std::cout << "\n";
  }
  return failed ? 1 : 0;
}

}  // namespace headlight::cli
