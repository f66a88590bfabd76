#pragma once
// The scenes of a `headlight render` batch (batch.cpp), by the key a job
// loads its scene under, each loaded on first use and held until the
// renderer takes it, and every file's fingerprint, read once: a loaded
// glTF's own (Scene::sourceHash is the XXH3 of the same bytes that
// fileFingerprint reads), else the file's. So `--views 100` on one .glb
// reads the file once. Not thread-safe: the batch's main thread uses it.
#include <exception>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "headlight/scene.hpp"
#include "headlight/scene_loader.hpp"
#include "job_file.hpp"

namespace headlight::cli {

// A scene as loaded for a job: its name, and the job's material variant,
// animation and time when it sets them.
std::string sceneKey(const Job& job);

// The command's scene-load options with the job's material_variant, animation and time.
SceneLoadOptions loadOptionsFor(const Job& job, SceneLoadOptions options);

class SceneCatalogue {
 public:
  using Load = std::function<Scene(const Job&)>;
  using FileFingerprint = std::function<std::string(const std::string& path)>;
  // `load` loads a job's scene (and may refuse it); `fileFingerprint` hashes
  // a file (io/fingerprint.hpp's, unless a test counts the reads).
  explicit SceneCatalogue(Load load, FileFingerprint fileFingerprint = {});

  // The job's scene, loaded on first use. A load that failed fails alike
  // again, without a second try (every job of a broken file says so).
  const Scene& scene(const Job& job);

  // How many separate runs of consecutive jobs will set each scene on the
  // renderer: the last run takes the scene itself, the others a copy.
  void countRuns(const std::vector<const Job*>& jobsToRender);
  // The scene for the renderer (Renderer::setScene takes it by value):
  // moved out when no later run needs it, so its image bytes are not copied.
  Scene checkOut(const Job& job);

  std::string fingerprint(const std::string& path);
  // jobHash (job_file.hpp) with this catalogue's fingerprints.
  std::string jobHash(const Job& job, const OutputOptions& output, const std::string& environment);

 private:
  Load load_;
  FileFingerprint fileFingerprint_;
  std::map<std::string, Scene> scenes_;
  std::map<std::string, std::exception_ptr> failures_;
  std::map<std::string, int> runsLeft_;
  std::map<std::string, std::string> fingerprints_;
};

}  // namespace headlight::cli
