// headlight render as a batch: expand jobs -> shard -> (resume) -> for each
// job: scene from the cache -> Renderer::render -> writeFrame on a worker
// thread while the next job renders -> one summary (lines or JSON).
#include "batch.hpp"

#include <sys/resource.h>

#include <glm/gtc/matrix_transform.hpp>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <future>
#include <iostream>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <sstream>

#include "headlight/context.hpp"
#include "headlight/error.hpp"
#include "headlight/output.hpp"
#include "headlight/renderer.hpp"
#include "headlight/scene_loader.hpp"
#include "headlight/targets.hpp"
#include "output/fingerprint.hpp"
#include "progress.hpp"

namespace headlight::cli {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

std::string vecText(const glm::vec3& v) {
  std::ostringstream text;
  text.precision(9);
  text << v.x << "," << v.y << "," << v.z;
  return text.str();
}

glm::vec3 readVec3(const json& value, const char* key) {
  if (!value.is_array() || value.size() != 3 || !value[0].is_number() || !value[1].is_number() || !value[2].is_number())
    throw SettingsError(std::string("\"") + key + "\": expected [x, y, z] (three numbers), got " + value.dump());
  glm::vec3 v(value[0].get<float>(), value[1].get<float>(), value[2].get<float>());
  if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
    throw SettingsError(std::string("\"") + key + "\": not finite");
  return v;
}

// A JSON value as the text the setting table parses: strings as they are,
// numbers as written, booleans as on/off.
std::string settingText(const std::string& name, const json& value) {
  if (value.is_string()) return value.get<std::string>();
  if (value.is_boolean()) return value.get<bool>() ? "on" : "off";
  if (value.is_number()) return value.dump();
  throw SettingsError("setting \"" + name + "\": expected a string, number or boolean, got " + value.dump());
}

// "builtin:cornell" -> "cornell", "a/b/duck.glb" -> "duck".
std::string sceneStem(const std::string& scene) {
  if (scene.rfind("builtin:", 0) == 0) return scene.substr(8);
  return fs::path(scene).stem().string();
}

Job parseJobLine(const std::string& line, const std::string& origin, const RenderSettings& base) {
  Job job;
  job.origin = origin;
  job.settings = base;
  json j;
  try {
    j = json::parse(line);
  } catch (const json::exception& e) {
    throw SettingsError(std::string("not valid JSON: ") + e.what());
  }
  if (!j.is_object()) throw SettingsError("expected a JSON object, got " + j.dump());
  static const char* kKeys[] = {"scene", "out", "camera", "eye",           "target",
                                "up",    "fov", "size",   "settings_file", "settings"};
  for (const auto& [key, value] : j.items())
    if (std::find_if(std::begin(kKeys), std::end(kKeys), [&](const char* k) { return key == k; }) == std::end(kKeys))
      throw SettingsError("unknown key \"" + key +
                          "\" (known: scene, out, camera, eye, target, up, fov, size, settings_file, settings)");
  if (!j.contains("scene") || !j["scene"].is_string() || j["scene"].get<std::string>().empty())
    throw SettingsError("\"scene\": expected a file path or builtin:NAME");
  job.scene = j["scene"].get<std::string>();
  if (!j.contains("out") || !j["out"].is_string() || j["out"].get<std::string>().empty())
    throw SettingsError("\"out\": expected the job's output folder");
  job.outDir = j["out"].get<std::string>();

  // A settings file (headlight tune's) first: the line's own keys override it.
  if (j.contains("settings_file")) {
    if (!j["settings_file"].is_string() || j["settings_file"].get<std::string>().empty())
      throw SettingsError("\"settings_file\": expected the path of a settings file");
    applySettingsFile(job.settings, j["settings_file"].get<std::string>());
  }

  // Everything a setting row can say goes through the one table.
  std::map<std::string, std::string> settings;
  if (j.contains("settings")) {
    if (!j["settings"].is_object()) throw SettingsError("\"settings\": expected an object of setting names");
    for (const auto& [name, value] : j["settings"].items()) settings[name] = settingText(name, value);
  }
  if (j.contains("size")) {
    const std::string size = j["size"].is_string() ? j["size"].get<std::string>() : "";
    const auto x = size.find('x');
    if (x == std::string::npos) throw SettingsError("\"size\": expected \"WIDTHxHEIGHT\", got " + j["size"].dump());
    settings["width"] = size.substr(0, x);
    settings["height"] = size.substr(x + 1);
  }
  if (j.contains("camera")) settings["camera"] = settingText("camera", j["camera"]);
  applySettingsText(job.settings, settings);
  job.settings.validate();

  if (j.contains("eye") || j.contains("target")) {
    if (j.contains("camera")) throw SettingsError("\"camera\" and \"eye\"/\"target\": give one");
    if (!j.contains("eye") || !j.contains("target")) throw SettingsError("\"eye\" and \"target\" go together");
    job.camera.kind = JobCamera::Kind::LookAt;
    job.camera.eye = readVec3(j["eye"], "eye");
    job.camera.target = readVec3(j["target"], "target");
    if (j.contains("up")) job.camera.up = readVec3(j["up"], "up");
    if (j.contains("fov")) {
      if (!j["fov"].is_number()) throw SettingsError("\"fov\": expected degrees, got " + j["fov"].dump());
      job.camera.fovDegrees = j["fov"].get<float>();
    }
    if (!(job.camera.fovDegrees > 0.0f && job.camera.fovDegrees < 180.0f))
      throw SettingsError("\"fov\": expected degrees in (0, 180), got " + std::to_string(job.camera.fovDegrees));
    if (glm::length(job.camera.eye - job.camera.target) <= 0.0f)
      throw SettingsError("\"eye\" and \"target\" are the same point");
    if (glm::length(glm::cross(job.camera.target - job.camera.eye, job.camera.up)) <= 0.0f)
      throw SettingsError("\"up\" is parallel to the view direction");
  } else if (j.contains("up") || j.contains("fov")) {
    throw SettingsError("\"up\" and \"fov\" need \"eye\" and \"target\"");
  }
  return job;
}

// ---- running -----------------------------------------------------------------

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

// Loads a scene and names, once, each glTF feature it uses that is not
// rendered (Scene::ignored; frame.json and the EXRs list them too).

// Scenes stay loaded while a later job of this shard uses them.
class SceneCache {
 public:
  SceneCache(const std::vector<Job>& jobs, const SceneLoadOptions& options, const ResourceLimits& limits, bool quiet)
      : options_(options), limits_(limits), quiet_(quiet) {
    for (const Job& job : jobs)
      if (job.error.empty()) ++remaining_[job.scene];
  }
  const Scene& get(const std::string& name) {
    auto found = scenes_.find(name);
    if (found == scenes_.end()) found = scenes_.emplace(name, loadCommandScene(name, options_, limits_, quiet_)).first;
    return found->second;
  }
  // A scene loaded before the batch started (to count its cameras).
  void adopt(const std::string& name, Scene scene) {
    if (remaining_[name] > 0) scenes_.emplace(name, std::move(scene));
  }
  // A job of `name` is done: drop the scene when no later job needs it.
  void release(const std::string& name) {
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
      json passes = json::object();
      for (const PassTime& pass : r.passes) {
        passes[pass.pass] = pass.milliseconds;
        passTotals[pass.pass] += pass.milliseconds;
      }
      json fileList = json::array();
      for (const WrittenFile& file : r.files)
        fileList.push_back({{"path", file.path.string()}, {"bytes", file.bytes}, {"non_finite", file.nonFinite}});
      files += r.files.size();
      entry["passes_ms"] = passes;
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

std::string JobCamera::describe() const {
  switch (kind) {
    case Kind::Settings:
      return "settings";
    case Kind::LookAt:
      return "eye " + vecText(eye) + " target " + vecText(target) + " up " + vecText(up) + " fov " +
             std::to_string(fovDegrees);
    case Kind::Orbit:
      return "orbit " + std::to_string(orbitIndex) + "/" + std::to_string(orbitViews) + " fov " +
             std::to_string(fovDegrees);
  }
  return "";
}

std::optional<Camera> JobCamera::build(const Scene& scene, float aspect) const {
  if (kind == Kind::Settings) return std::nullopt;
  Camera camera;
  camera.yfov = glm::radians(fovDegrees);
  if (kind == Kind::LookAt) {
    camera.name = "job look-at";
    camera.worldFromCamera = glm::inverse(glm::lookAt(eye, target, up));
    return camera;
  }
  // The turntable: fitCamera's framing (the bounding sphere fits the
  // narrower field of view, seen a little from above), turned about +Y.
  const Bounds bounds = scene.worldBounds();
  const float radius = bounds.empty() ? 1.0f : std::max(bounds.radius(), 1e-30f);
  const glm::vec3 center = bounds.empty() ? glm::vec3(0.0f) : bounds.center();
  const float distance = radius / std::sin(0.5f * camera.yfov * std::min(1.0f, aspect));
  const float azimuth = 2.0f * glm::pi<float>() * float(orbitIndex) / float(std::max(1, orbitViews));
  const glm::vec3 direction = glm::normalize(glm::vec3(std::sin(azimuth), 0.25f, std::cos(azimuth)));
  camera.name = "orbit " + std::to_string(orbitIndex);
  camera.worldFromCamera = glm::inverse(glm::lookAt(center + direction * distance, center, glm::vec3(0, 1, 0)));
  return camera;
}

std::vector<Job> parseJobLines(const std::string& text, const std::string& name, const RenderSettings& base) {
  std::vector<Job> jobs;
  std::istringstream stream(text);
  int number = 0;
  for (std::string line; std::getline(stream, line);) {
    ++number;
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    const std::string origin = name + ":" + std::to_string(number);
    try {
      jobs.push_back(parseJobLine(line, origin, base));
    } catch (const Error& error) {
      Job bad;
      bad.origin = origin;
      bad.error = error.what();
      jobs.push_back(std::move(bad));
    }
  }
  return jobs;
}

std::vector<Job> expandJobs(const RenderCommand& command, const std::function<int(const std::string&)>& cameraCount) {
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
    if (command.orbit) {
      for (int v = 0; v < command.views; ++v) {
        Job job = base;
        job.camera.kind = JobCamera::Kind::Orbit;
        job.camera.orbitIndex = v;
        job.camera.orbitViews = command.views;
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
  for (const std::string& file : command.jobFiles) {
    std::ifstream in(file);
    if (!in) throw IoError(file + ": cannot read the job file");
    std::stringstream text;
    text << in.rdbuf();
    for (Job& job : parseJobLines(text.str(), file, command.settings)) jobs.push_back(std::move(job));
  }
  return jobs;
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
                        " (the N of --shard /" + std::to_string(command.shardCount) + "), got '" + value + "'");
  return index;
}

std::string jobHash(const Job& job, const OutputOptions& output) {
  std::string text = "scene=" + job.scene + "\n";
  if (job.scene.rfind("builtin:", 0) != 0) text += "scene-bytes=" + fileFingerprint(job.scene) + "\n";
  for (const auto& [name, value] : settingsAsText(job.settings)) text += name + "=" + value + "\n";
  text += "camera=" + job.camera.describe() + "\n";
  text += "targets=";
  for (const std::string& target : output.targets) text += target + ",";
  text += "\nnonfinite=" + std::string(output.nonFinite == NonFinitePolicy::Clamp ? "clamp" : "error") + "\n";
  return textFingerprint(text);
}

bool jobAlreadyDone(const Job& job, const OutputOptions& output) {
  try {
    const std::optional<FrameManifest> manifest = readManifest(job.outDir);
    if (!manifest || !manifest->complete || manifest->jobHash != jobHash(job, output)) return false;
    return checkFrameSet(job.outDir).state == FrameSetState::Complete;
  } catch (const Error&) {
    return false;  // unreadable: render it again
  }
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
  const std::vector<Job> all = expandJobs(command, cameraCount);
  const std::vector<Job> jobs = selectShard(all, resolveShardIndex(command), command.shardCount);
  // One job from the command line behaves as a plain render: its errors
  // are the command's (exit 1, or 2 for bad settings).
  const bool single = all.size() == 1 && command.jobFiles.empty();

  std::vector<JobResult> results(jobs.size());
  SceneCache cache(jobs, command.sceneLoad, command.limits, quiet);
  for (auto& [name, scene] : countedScenes) cache.adopt(name, std::move(scene));  // loaded once
  countedScenes.clear();
  std::optional<Context> context;
  std::optional<Renderer> renderer;
  std::string currentScene, rendererName;
  // The renderer draws only what the output needs (the preview reads lit).
  std::vector<std::string> renderTargets;
  for (const std::string& target : command.output.targets)
    renderTargets.push_back(target == "preview" ? "lit" : target);

  Progress progress(jobs.size(), !quiet && !single && !command.json, "views");
  // One write in flight while the next job renders.
  std::future<void> pendingWrite;
  std::mutex reportMutex;  // the writer thread reports too
  auto report = [&](std::size_t index) {
    const std::lock_guard<std::mutex> lock(reportMutex);
    const JobResult& r = results[index];
    if (r.status == JobResult::Status::Failed) {
      progress.clear();
      std::cerr << "headlight: job " << jobs[index].origin << " failed: " << r.error << "\n";
    } else if (lines && r.status == JobResult::Status::Rendered) {
      progress.clear();
      for (const WrittenFile& file : r.files) std::cout << file.summary << "\n";
    } else if (lines && r.status == JobResult::Status::Skipped) {
      progress.clear();
      std::cout << jobs[index].outDir << ": skipped (--resume: complete set of the same job)\n";
    }
  };
  auto waitForWrite = [&] {
    if (pendingWrite.valid()) pendingWrite.get();
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
    if (command.resume && jobAlreadyDone(job, command.output)) {
      result.status = JobResult::Status::Skipped;
      cache.release(job.scene);
      report(i);
      continue;
    }
    try {
      const Scene& scene = cache.get(job.scene);
      if (!context) {
        context.emplace(command.context);
        renderer.emplace(*context);
        renderer->setLimits(command.limits);
        rendererName = context->renderer();
        // OpenImageIO loads on the other core while this one compiles
        // shaders and renders.
        preloadImageIo();
      }
      if (currentScene != job.scene) {
        if (verbose) std::cerr << verboseHeader(*context, scene);
        currentScene.clear();
        renderer->setScene(scene);
        currentScene = job.scene;
      }
      const std::optional<Camera> camera =
          job.camera.build(scene, float(job.settings.width) / float(job.settings.height));
      const auto renderStart = std::chrono::steady_clock::now();
      auto frame = std::make_shared<Frame>(renderer->render(job.settings, camera ? &*camera : nullptr, renderTargets));
      result.renderMs = millisecondsSince(renderStart);
      result.passes = frame->timings;
      result.peakRssKb = peakRssKb();
      if (verbose) {
        double total = 0;
        for (const PassTime& time : frame->timings) {
          std::fprintf(stderr, "pass %-10s %9.2f ms\n", time.pass.c_str(), time.milliseconds);
          total += time.milliseconds;
        }
        std::fprintf(stderr, "pass %-10s %9.2f ms\n", "total", total);
        for (const SkippedWork& skipped : frame->skipped)
          std::fprintf(stderr, "skipped %-10s %s\n", skipped.work.c_str(), skipped.reason.c_str());
      }
      cache.release(job.scene);
      if (single) {
        // Nothing to overlap with: write here, and let errors be the command's.
        const auto writeStart = std::chrono::steady_clock::now();
        OutputOptions output = command.output;
        output.jobHash = jobHash(job, command.output);
        result.files = writeFrame(*frame, job.outDir, output);
        result.writeMs = millisecondsSince(writeStart);
        result.status = JobResult::Status::Rendered;
        report(i);
        continue;
      }
      waitForWrite();
      OutputOptions output = command.output;
      output.jobHash = jobHash(job, command.output);
      pendingWrite = std::async(std::launch::async, [&, i, frame, output] {
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
      throw;  // no job can render without a context: the batch stops
    } catch (const std::exception& error) {
      if (single) throw;
      cache.release(job.scene);
      result.status = JobResult::Status::Failed;
      result.error = commandLineMessage(error);
      // A scene that failed to load fails every job of it, each with its line.
      report(i);
    }
  }
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
  } else if (!single && !quiet) {
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
