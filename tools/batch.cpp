// headlight render, in three steps:
//   plan:   batch_plan.cpp: jobs expanded, folders checked, the shard
//           chosen, a status per job (render, skip, refused, invalid);
//   run:    (here) for each job to render, its scene from the catalogue ->
//           Renderer::submit -> collect -> writeFrame on a worker thread
//           while the next job renders;
//   report: a line per job as it ends, then the summary (lines or JSON).
// A single render is a batch of one whose failure is the command's own
// error (exit 1, or 2 for bad settings). The job model is job_file.cpp.
#include "batch.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <exception>
#include <functional>
#include <future>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>

#include "batch_plan.hpp"
#include "frame/frame_plan.hpp"  // isSoftwareRasterizer
#include "headlight/context.hpp"
#include "headlight/error.hpp"
#include "headlight/output.hpp"
#include "headlight/renderer.hpp"
#include "headlight/scene_loader.hpp"
#include "headlight/targets.hpp"
#include "io/folder_lock.hpp"
#include "progress.hpp"
#include "scene_catalogue.hpp"
#include "tooling/command_line.hpp"
#include "tooling/command_setup.hpp"

namespace headlight::cli {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

// ---- Run ---------------------------------------------------------------------------

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
  std::exception_ptr exception;  // the failure itself: a single render's error is the command's
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

double millisecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

void printFrameDetails(const Frame& frame) {
  double total = 0;
  for (const PassTime& time : frame.timings) {
    // Wall time (glFinish-bounded, a first frame's compiles included), then the GPU's own, then the form.
    std::fprintf(stderr, "pass %-10s %9.2f ms", time.pass.c_str(), time.milliseconds);
    if (time.gpuMilliseconds >= 0) std::fprintf(stderr, "  gpu %9.3f ms", time.gpuMilliseconds);
    if (!time.form.empty()) std::fprintf(stderr, "  %s", time.form.c_str());
    if (!time.detail.empty()) std::fprintf(stderr, "  %s", time.detail.c_str());
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
  // A PNG is drawn from its target, written as EXR or not (empty: every target is drawn anyway).
  if (!targets.empty())
    for (const std::string& target : output.pngTargets)
      if (std::find(targets.begin(), targets.end(), target) == targets.end()) targets.push_back(target);
  return targets;
}

void fail(JobResult& result, const std::exception& error) {
  result.status = JobResult::Status::Failed;
  result.error = commandLineMessage(error);
  result.exception = std::current_exception();
}

// What the run hands the report as each job ends (from the writer thread too).
using JobEnded = std::function<void(std::size_t, const JobResult&)>;

struct BatchRun {
  std::vector<JobResult> results;
  std::string rendererName;
};

// Renders and writes every job the plan marks Render, in order, with one
// context and one renderer made at the first of them.
BatchRun runBatch(const RenderCommand& command, const BatchPlan& plan, SceneCatalogue& catalogue, const JobEnded& ended,
                  const std::function<void(std::size_t, const std::string&)>& starting) {
  const bool verbose = command.verbosity == Verbosity::Verbose;
  BatchRun run;
  std::vector<JobResult>& results = run.results;
  results.resize(plan.jobs.size());
  std::optional<Context> context;
  std::optional<Renderer> renderer;
  std::string currentScene;
  bool softwareRasterizer = false;  // llvmpipe and the like: no frame submitted ahead
  const std::vector<std::string> renderTargets = renderTargetsFor(command.output);

  // One write in flight while the next job renders.
  std::future<void> pendingWrite;
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
      const PlannedJob& planned = plan.jobs[i];
      OutputOptions output = command.output;
      output.jobHash = planned.hash.empty()
                           ? catalogue.jobHash(planned.job, command.output, command.sceneLoad.environment)
                           : planned.hash;
      output.waitForFolder = command.wait;
      output.waitForFolderSeconds = command.waitSeconds;
      pendingWrite = std::async(std::launch::async, [&, i, frame, output, folderLock = job.folderLock] {
        // writeFrame takes the folder's lock again: this thread shares the job's.
        const detail::OutputFolderLock::ThreadShare share(*folderLock);
        const auto writeStart = std::chrono::steady_clock::now();
        try {
          results[i].files = writeFrame(*frame, plan.jobs[i].job.outDir, output);
          results[i].status = JobResult::Status::Rendered;
        } catch (const std::exception& error) {
          fail(results[i], error);
        }
        results[i].writeMs = millisecondsSince(writeStart);
        ended(i, results[i]);
      });
    } catch (const ContextError&) {
      throw;
    } catch (const std::exception& error) {
      fail(results[i], error);
      ended(i, results[i]);
    }
  };

  for (std::size_t i = 0; i < plan.jobs.size(); ++i) {
    const PlannedJob& planned = plan.jobs[i];
    const Job& job = planned.job;
    JobResult& result = results[i];
    starting(i, job.origin);
    if (planned.status != PlannedJob::Status::Render) {
      if (planned.status == PlannedJob::Status::Skip) {
        result.status = JobResult::Status::Skipped;
      } else {
        result.error = job.error;
        // A single render's refusal is the command's error, as an IoError.
        if (planned.status == PlannedJob::Status::Refused)
          result.exception = std::make_exception_ptr(IoError(job.error));
      }
      ended(i, results[i]);
      continue;
    }
    try {
      if (currentScene != sceneKey(job)) {
        currentScene.clear();
        Scene scene = catalogue.checkOut(job);  // loaded before the context: a bad scene costs no GL start-up
        if (!context) {
          context.emplace(command.context);
          renderer.emplace(*context);
          renderer->setLimits(command.limits);
          run.rendererName = context->renderer();
          softwareRasterizer = isSoftwareRasterizer(run.rendererName);
          // OpenImageIO loads on the other core while this one compiles
          // shaders and renders.
          preloadImageIo();
        }
        if (verbose) std::cerr << verboseHeader(*context, scene);
        renderer->setScene(std::move(scene));
        currentScene = sceneKey(job);
      }
      // Held from before the render until the writer thread has written the set.
      auto folderLock = std::make_shared<detail::OutputFolderLock>(job.outDir, command.wait, command.waitSeconds,
                                                                   waitingNote(command, job.outDir));
      const std::optional<Camera> camera =
          job.camera.build(renderer->scene(), float(job.settings.width) / float(job.settings.height));
      const auto submitStart = std::chrono::steady_clock::now();
      renderer->submit(job.settings, camera ? &*camera : nullptr, renderTargets);
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
      // A scene that failed to load fails every job of it, each with its line.
      fail(result, error);
      ended(i, results[i]);
    }
  }
  collectInFlight();
  waitForWrite();
  return run;
}

// ---- Report ------------------------------------------------------------------------

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

// The line for a job as it ends: its files, a skip, or its failure.
void reportJob(const Job& job, const JobResult& result, bool lines, bool single) {
  if (result.status == JobResult::Status::Failed) {
    if (!single) std::cerr << "headlight: job " << job.origin << " failed: " << result.error << "\n";
  } else if (result.status == JobResult::Status::Rendered) {
    if (lines)
      for (const WrittenFile& file : result.files) std::cout << file.summary << "\n";
    warnSaturated(result.files);
  } else if (lines && result.status == JobResult::Status::Skipped) {
    std::cout << job.outDir << ": skipped (--resume: complete set of the same job)\n";
  }
}

void reportSummary(const RenderCommand& command, const BatchPlan& plan, const BatchRun& run, double wallMs) {
  if (command.json) {
    std::vector<Job> jobs;
    for (const PlannedJob& planned : plan.jobs) jobs.push_back(planned.job);
    std::cout << summaryJson(jobs, run.results, run.rendererName, wallMs).dump(2) << "\n";
    return;
  }
  if (command.verbosity == Verbosity::Quiet) return;
  std::size_t failed = 0, skipped = 0, rendered = 0;
  std::string failedList;
  for (std::size_t i = 0; i < plan.jobs.size(); ++i) {
    if (run.results[i].status == JobResult::Status::Failed) {
      ++failed;
      (failedList += failedList.empty() ? "" : ", ") += plan.jobs[i].job.origin;
    }
    skipped += run.results[i].status == JobResult::Status::Skipped;
    rendered += run.results[i].status == JobResult::Status::Rendered;
  }
  std::cout << "batch: " << plan.jobs.size() << " job" << (plan.jobs.size() == 1 ? "" : "s");
  if (command.shardCount > 1)
    std::cout << " (shard " << plan.shardIndex << "/" << command.shardCount << " of " << plan.allJobs << ")";
  std::cout << ": " << rendered << " rendered, " << skipped << " skipped, " << failed << " failed";
  if (failed) std::cout << " (" << failedList << ")";
  std::cout << "\n";
}

}  // namespace

bool isSingleRender(const RenderCommand& command) {
  return command.jobFiles.empty() && command.scenes.size() <= 1 && !command.orbit && !command.throughTime &&
         !command.camerasAll && command.shardCount == 1 && !command.json;
}

int runRender(const RenderCommand& command) {
  const auto wallStart = std::chrono::steady_clock::now();
  const bool single = isSingleRender(command);
  const bool quiet = command.verbosity == Verbosity::Quiet;
  const bool lines = !quiet && !command.json;
  SceneCatalogue catalogue([&](const Job& job) {
    Scene scene = loadCommandScene(job.scene, loadOptionsFor(job, command.sceneLoad), command.limits, quiet);
    checkDrawBudget(scene, command.limits);  // before the context: a refusal costs no GL start-up
    return scene;
  });
  const BatchPlan plan = planBatch(command, catalogue, single);

  Progress progress(plan.jobs.size(), lines && !single, "views");
  std::mutex reportMutex;  // the writer thread reports too
  const BatchRun run = runBatch(
      command, plan, catalogue,
      [&](std::size_t i, const JobResult& result) {
        const std::lock_guard<std::mutex> lock(reportMutex);
        progress.clear();
        reportJob(plan.jobs[i].job, result, lines, single);
      },
      [&](std::size_t i, const std::string& origin) {
        const std::lock_guard<std::mutex> lock(reportMutex);
        progress.update(i, origin);
      });
  progress.update(plan.jobs.size(), "done");
  progress.finish();
  if (single) {
    const JobResult& result = run.results.at(0);
    if (result.status == JobResult::Status::Failed && result.exception) std::rethrow_exception(result.exception);
    return result.status == JobResult::Status::Failed ? 1 : 0;
  }
  reportSummary(command, plan, run, millisecondsSince(wallStart));
  for (const JobResult& result : run.results)
    if (result.status == JobResult::Status::Failed) return 1;
  return 0;
}

}  // namespace headlight::cli
