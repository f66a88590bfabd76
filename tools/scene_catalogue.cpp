#include "scene_catalogue.hpp"

#include <utility>

#include "io/fingerprint.hpp"

namespace headlight::cli {

std::string sceneKey(const Job& job) {
  std::string key = job.scene;
  if (job.materialVariant) key += "\n#material-variant=" + *job.materialVariant;
  if (job.animation) key += "\n#animation=" + *job.animation;
  if (job.animationTime) key += "\n#time=" + std::to_string(*job.animationTime);
  return key;
}

SceneLoadOptions loadOptionsFor(const Job& job, SceneLoadOptions options) {
  if (job.materialVariant) options.materialVariant = *job.materialVariant;
  if (job.animation) options.animation = *job.animation;
  if (job.animationTime) options.animationTime = *job.animationTime;
  return options;
}

SceneCatalogue::SceneCatalogue(Load load, FileFingerprint fileFingerprint)
    : load_(std::move(load)),
      fileFingerprint_(fileFingerprint ? std::move(fileFingerprint)
                                       : [](const std::string& path) { return headlight::fileFingerprint(path); }) {}

const Scene& SceneCatalogue::scene(const Job& job) {
  const std::string key = sceneKey(job);
  if (const auto failed = failures_.find(key); failed != failures_.end()) std::rethrow_exception(failed->second);
  auto found = scenes_.find(key);
  if (found == scenes_.end()) {
    try {
      Scene scene = load_(job);
      if (job.scene.rfind("builtin:", 0) != 0) fingerprints_.emplace(job.scene, scene.sourceHash);
      found = scenes_.emplace(key, std::move(scene)).first;
    } catch (...) {
      failures_.emplace(key, std::current_exception());
      throw;
    }
  }
  return found->second;
}

void SceneCatalogue::countRuns(const std::vector<const Job*>& jobsToRender) {
  std::string previous;
  for (const Job* job : jobsToRender) {
    const std::string key = sceneKey(*job);
    if (key != previous) ++runsLeft_[key];
    previous = key;
  }
}

Scene SceneCatalogue::checkOut(const Job& job) {
  const Scene& held = scene(job);
  const std::string key = sceneKey(job);
  if (--runsLeft_[key] > 0) return held;
  Scene taken = std::move(scenes_.at(key));
  scenes_.erase(key);
  return taken;
}

std::string SceneCatalogue::fingerprint(const std::string& path) {
  auto found = fingerprints_.find(path);
  if (found == fingerprints_.end()) found = fingerprints_.emplace(path, fileFingerprint_(path)).first;
  return found->second;
}

std::string SceneCatalogue::jobHash(const Job& job, const OutputOptions& output, const std::string& environment) {
  return cli::jobHash(job, output, environment, [this](const std::string& path) { return fingerprint(path); });
}

}  // namespace headlight::cli
