// Batches without a GL context: job files, sharding, the job hash and
// --resume's decision, output sets (frame.json) and their checks, stale
// temporaries, and non-finite values refused or clamped.
#include <doctest/doctest.h>

#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <OpenImageIO/imagebuf.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>

#include "batch.hpp"
#include "batch_plan.hpp"
#include "headlight/diff.hpp"
#include "headlight/error.hpp"
#include "headlight/finite.hpp"
#include "headlight/output.hpp"
#include "headlight/scene_loader.hpp"
#include "io/atomic_file.hpp"
#include "io/bounded_read.hpp"
#include "io/fingerprint.hpp"
#include "output/frame_set.hpp"
#include "scene_catalogue.hpp"
#include "support/gl.hpp"
#include "support/images.hpp"
#include "support/temp_folder.hpp"

using namespace headlight;
using namespace headlight::cli;
namespace fs = std::filesystem;

namespace {

// A CPU-made frame: every target the size of a thumbnail, values finite.
Frame syntheticFrame(float value = 0.5f) {
  Frame frame;
  frame.position = test::makeImage(8, 6, {"position.X", "position.Y", "position.Z", "A"}, value);
  frame.normal = test::makeImage(8, 6, {"normal.X", "normal.Y", "normal.Z"}, value);
  frame.depth = test::makeImage(8, 6, {"depth.Z"}, value);
  frame.lit = test::makeImage(8, 6, {"R", "G", "B", "A"}, value);
  frame.sceneSource = "builtin:synthetic";
  frame.sceneHash = "0123456789abcdef";
  frame.settings.width = 8;
  frame.settings.height = 6;
  return frame;
}

std::vector<Job> numberedJobs(int count) {
  std::vector<Job> jobs(std::size_t(count), Job{});
  for (int k = 0; k < count; ++k) jobs[std::size_t(k)].origin = std::to_string(k);
  return jobs;
}

// A pid that no process has: a child that has exited and been reaped.
pid_t deadPid() {
  const pid_t child = fork();
  if (child == 0) _exit(0);
  int status = 0;
  waitpid(child, &status, 0);
  return child;
}

}  // namespace

namespace {
// A "Name:  N kB" line of /proc/self/status, in kilobytes; -1 if absent.
long statusKilobytes(const char* name) {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind(name, 0) == 0) return std::strtol(line.c_str() + std::strlen(name), nullptr, 10);
  return -1;
}
}  // namespace

TEST_CASE("job lines: each job through the setting table, bad lines named and kept apart") {
  const std::string text =
      "# a comment, then a blank line\n"
      "\n"
      R"({"scene": "builtin:cornell", "out": "a", "size": "64x48", "settings": {"ssgi-samples": 16, "ssgi": false}})"
      "\n"
      R"({"scene": "builtin:spheres", "out": "b", "eye": [0, 1, 5], "target": [0, 1, 0], "fov": 30})"
      "\n"
      R"({"scene": "builtin:cornell", "out": "c", "settings": {"ssgi-samples": 100000}})"
      "\n"
      R"({"scene": "builtin:cornell", "out": "d", "colour": "red"})"
      "\n"
      "{not json\n"
      R"({"scene": "builtin:cornell", "out": "e", "camera": 2})"
      "\n";
  RenderSettings base;
  base.ssgi.seed = 7;
  const std::vector<Job> jobs = parseJobLines(text, "jobs.jsonl", base);
  REQUIRE(jobs.size() == 6);
  CHECK(jobs[0].origin == "jobs.jsonl:3");
  CHECK(jobs[0].error.empty());
  CHECK(jobs[0].settings.width == 64);
  CHECK(jobs[0].settings.height == 48);
  CHECK(jobs[0].settings.ssgi.sampleCount == 16);
  CHECK_FALSE(jobs[0].settings.ssgi.enabled);
  CHECK(jobs[0].settings.ssgi.seed == 7);  // the command line's settings are the base
  CHECK(jobs[1].camera.kind == JobCamera::Kind::LookAt);
  CHECK(jobs[1].camera.fovDegrees == doctest::Approx(30));
  // The setting table's own range message, with the line.
  CHECK(jobs[2].origin == "jobs.jsonl:5");
  CHECK(jobs[2].error.find("ssgi-samples") != std::string::npos);
  CHECK(jobs[3].origin == "jobs.jsonl:6");
  CHECK(jobs[3].error.find("unknown key \"colour\"") != std::string::npos);
  CHECK(jobs[4].origin == "jobs.jsonl:7");
  CHECK(jobs[4].error.find("not valid JSON") != std::string::npos);
  CHECK(jobs[5].error.empty());
  CHECK(jobs[5].settings.camera == 2);
}

TEST_CASE("command-line jobs: scenes x orbit views or x cameras, each in its own folder") {
  RenderCommand command;
  command.outDir = "out";
  command.scenes = {"builtin:cornell", "a/duck.glb", "b/duck.glb"};
  command.orbit = true;
  command.views = 3;
  std::vector<Job> jobs = expandJobs(command, [](const std::string&) -> int { throw SettingsError("not asked"); });
  REQUIRE(jobs.size() == 9);
  CHECK(jobs[0].outDir == (fs::path("out") / "cornell" / "view_000").string());
  CHECK(jobs[4].outDir == (fs::path("out") / "duck-1" / "view_001").string());
  CHECK(jobs[8].outDir == (fs::path("out") / "duck-2" / "view_002").string());
  CHECK(jobs[5].camera.kind == JobCamera::Kind::Orbit);
  CHECK(jobs[5].camera.orbitIndex == 2);
  CHECK(jobs[5].camera.orbitViews == 3);

  command.orbit = false;
  command.views = 0;
  command.camerasAll = true;
  command.scenes = {"builtin:cornell", "broken.gltf"};
  jobs = expandJobs(command, [](const std::string& scene) {
    if (scene == "broken.gltf") throw SceneError("broken.gltf: no");
    return 2;
  });
  REQUIRE(jobs.size() == 3);
  CHECK(jobs[1].settings.camera == 1);
  CHECK(jobs[1].outDir == (fs::path("out") / "cornell" / "camera_1").string());
  CHECK(jobs[2].error.find("broken.gltf: no") != std::string::npos);  // a job that reports, not an abort
}

TEST_CASE("orbit cameras circle the bounds' centre at one distance, looking at it") {
  Scene scene;
  scene.instances.clear();
  JobCamera orbit;
  orbit.kind = JobCamera::Kind::Orbit;
  orbit.orbitViews = 4;
  std::vector<glm::vec3> eyes;
  for (int v = 0; v < 4; ++v) {
    orbit.orbitIndex = v;
    const std::optional<Camera> camera = orbit.build(scene, 1.0f);
    REQUIRE(camera);
    eyes.push_back(glm::vec3(camera->worldFromCamera[3]));
    const glm::vec3 forward = -glm::vec3(camera->worldFromCamera[2]);
    CHECK(glm::dot(glm::normalize(-eyes.back()), forward) == doctest::Approx(1.0f));  // towards the centre
  }
  for (const glm::vec3& eye : eyes) CHECK(glm::length(eye) == doctest::Approx(glm::length(eyes[0])));
  CHECK(glm::length(eyes[0] - eyes[2]) > glm::length(eyes[0]));  // opposite sides
  CHECK_FALSE(JobCamera{}.build(scene, 1.0f));                   // the settings' camera
  // --orbit-elevation and --orbit-distance: the eye that high above the centre, that much farther.
  orbit.orbitIndex = 0;
  orbit.orbitElevationDegrees = 60.0f;
  orbit.orbitDistanceScale = 2.0f;
  const glm::vec3 raised(orbit.build(scene, 1.0f)->worldFromCamera[3]);
  CHECK(glm::length(raised) == doctest::Approx(2.0f * glm::length(eyes[0])));
  CHECK(std::asin(raised.y / glm::length(raised)) == doctest::Approx(glm::radians(60.0f)));
  CHECK(orbit.describe().find("elevation 60") != std::string::npos);
  // The default's description (and so an orbit's --resume job hash) is what it was.
  CHECK(JobCamera{.kind = JobCamera::Kind::Orbit}.describe() == "orbit 0/1 fov 40.000000");
}

TEST_CASE("a failed write names the system's reason") {
  const std::string reason = detail::writeFailureReason("/tmp/x.exr", "", ENOSPC);
  CHECK(reason.find("No space left on device") != std::string::npos);
  CHECK(detail::writeFailureReason("/tmp/x.exr", "Failed OpenEXR write", 0).find("Failed OpenEXR write") == 0);
  CHECK_FALSE(detail::writeFailureReason("/tmp/x.exr", "", 0).empty());
}

TEST_CASE("shards: every job in exactly one shard, in order, every N-th from I") {
  const std::vector<Job> jobs = numberedJobs(23);
  for (int count : {1, 2, 3, 7, 23, 40}) {
    CAPTURE(count);
    std::multiset<std::string> seen;
    for (int index = 0; index < count; ++index) {
      const std::vector<Job> shard = selectShard(jobs, index, count);
      for (std::size_t k = 0; k < shard.size(); ++k) {
        CHECK(std::stoi(shard[k].origin) == index + int(k) * count);
        seen.insert(shard[k].origin);
      }
    }
    CHECK(seen.size() == jobs.size());
    CHECK(std::set<std::string>(seen.begin(), seen.end()).size() == jobs.size());
  }
  CHECK_THROWS_AS(selectShard(jobs, 3, 3), SettingsError);
  CHECK_THROWS_AS(selectShard(jobs, -1, 3), SettingsError);
}

TEST_CASE("shard index from an environment variable: a scheduler's task id") {
  RenderCommand command;
  command.shardCount = 4;
  command.shardIndexEnv = "HEADLIGHT_TEST_SHARD_INDEX";
  setenv("HEADLIGHT_TEST_SHARD_INDEX", "3", 1);
  CHECK(resolveShardIndex(command) == 3);
  setenv("HEADLIGHT_TEST_SHARD_INDEX", "4", 1);
  CHECK_THROWS_WITH_AS(resolveShardIndex(command), doctest::Contains("HEADLIGHT_TEST_SHARD_INDEX"), SettingsError);
  setenv("HEADLIGHT_TEST_SHARD_INDEX", "1x", 1);
  CHECK_THROWS_AS(resolveShardIndex(command), SettingsError);
  unsetenv("HEADLIGHT_TEST_SHARD_INDEX");
  CHECK_THROWS_WITH_AS(resolveShardIndex(command), doctest::Contains("not set"), SettingsError);
}

TEST_CASE("job hash: changes with the settings, camera and targets, not with the output folder") {
  Job job;
  job.scene = "builtin:cornell";
  job.outDir = "x";
  const std::string hash = jobHash(job, {});
  Job moved = job;
  moved.outDir = "y";
  CHECK(jobHash(moved, {}) == hash);
  Job other = job;
  other.settings.ssgi.sampleCount = 8;
  CHECK(jobHash(other, {}) != hash);
  other = job;
  other.camera.kind = JobCamera::Kind::Orbit;
  CHECK(jobHash(other, {}) != hash);
  OutputOptions litOnly;
  litOnly.targets = {"lit"};
  CHECK(jobHash(job, litOnly) != hash);
  // The pose: an animation and its time (a set posed at 1 s is not one at 2 s).
  other = job;
  other.animation = "0";
  const std::string animated = jobHash(other, {});
  CHECK(animated != hash);
  other.animationTime = 1.0f;
  const std::string atOne = jobHash(other, {});
  other.animationTime = 2.0f;
  CHECK(atOne != animated);
  CHECK(jobHash(other, {}) != atOne);
}

TEST_CASE("the scene catalogue: each scene loaded once, each file fingerprinted once, no copy on a scene's last run") {
  int loads = 0, fileReads = 0;
  SceneCatalogue catalogue(
      [&](const Job& job) {
        ++loads;
        if (job.scene == "broken.glb") throw SceneError("broken.glb: not glTF");
        Scene scene;
        scene.source = job.scene;
        scene.sourceHash = "hash-of-" + job.scene;  // what the loader computes from the file's bytes
        scene.images.push_back({"texture", 256, 256, std::vector<std::uint8_t>(256 * 256 * 4, 7)});
        return scene;
      },
      [&](const std::string& path) {
        ++fileReads;
        return "hash-of-" + path;
      });
  auto jobOf = [](const std::string& scene, int view) {
    Job job;
    job.scene = scene;
    job.outDir = "out/" + scene + "/" + std::to_string(view);
    job.camera.kind = JobCamera::Kind::Orbit;
    job.camera.orbitIndex = view;
    job.camera.orbitViews = 100;
    return job;
  };
  std::vector<Job> views;
  for (int view = 0; view < 100; ++view) views.push_back(jobOf("duck.glb", view));
  std::vector<const Job*> order;
  for (const Job& job : views) order.push_back(&job);
  catalogue.countRuns(order);

  // 100 views of one file: one load, and every job's hash from the loaded
  // scene's fingerprint, the same hash the file's own bytes give.
  const Scene taken = catalogue.checkOut(views[0]);
  CHECK(taken.images.at(0).rgba.size() == 256u * 256u * 4u);
  for (const Job& job : views) {
    CHECK(catalogue.jobHash(job, {}, {}) ==
          jobHash(job, {}, {}, [](const std::string& path) { return "hash-of-" + path; }));
  }
  CHECK(loads == 1);
  CHECK(fileReads == 0);

  // --resume hashes before anything loads: the file once, for every job.
  SceneCatalogue resumed([&](const Job&) -> Scene { throw Error("not loaded"); },
                         [&](const std::string& path) {
                           ++fileReads;
                           return "hash-of-" + path;
                         });
  for (const Job& job : views) (void)resumed.jobHash(job, {}, {});
  CHECK(fileReads == 1);

  // Runs A, B, A: the first run of A gets a copy (A is loaded once for both
  // runs), the last runs take their scenes, after which A is loaded again.
  const std::vector<Job> runs{jobOf("a.glb", 0), jobOf("b.glb", 0), jobOf("a.glb", 1)};
  loads = 0;
  catalogue.countRuns({&runs[0], &runs[1], &runs[2]});
  (void)catalogue.checkOut(runs[0]);
  (void)catalogue.checkOut(runs[1]);
  (void)catalogue.checkOut(runs[2]);
  CHECK(loads == 2);
  (void)catalogue.scene(runs[2]);
  CHECK(loads == 3);

  // A file that failed to load fails every job of it, loaded once.
  const Job broken = jobOf("broken.glb", 0);
  loads = 0;
  CHECK_THROWS_AS((void)catalogue.scene(broken), SceneError);
  CHECK_THROWS_WITH_AS((void)catalogue.scene(broken), "broken.glb: not glTF", SceneError);
  CHECK(loads == 1);
}

TEST_CASE("frame sets: frame.json lists each file; a changed or missing file, or a pending write, is incomplete") {
  test::TempFolder folder("frameset");
  const fs::path out = folder.path() / "set";
  OutputOptions options;
  options.jobHash = "job-1";
  const auto written = writeFrame(syntheticFrame(), out, options);
  CHECK(written.size() == 5);  // position, normal, depth, lit, preview
  const std::optional<FrameManifest> manifest = readManifest(out);
  REQUIRE(manifest);
  CHECK(manifest->complete);
  CHECK(manifest->jobHash == "job-1");
  CHECK(manifest->files.size() == 5);
  CHECK(checkFrameSet(out).state == FrameSetState::Complete);

  // Another render's lit.exr under the same name (a mixed set).
  fs::copy_file(out / "depth.exr", out / "lit.exr", fs::copy_options::overwrite_existing);
  FrameSetCheck check = checkFrameSet(out);
  CHECK(check.state == FrameSetState::Incomplete);
  CHECK(check.problem.find("lit.exr") != std::string::npos);

  writeFrame(syntheticFrame(), out, options);
  fs::remove(out / "normal.exr");
  check = checkFrameSet(out);
  CHECK(check.state == FrameSetState::Incomplete);
  CHECK(check.problem.find("normal.exr, which is missing") != std::string::npos);

  // What a kill between the first and the last file leaves: the pending manifest.
  writeFrame(syntheticFrame(), out, options);
  std::ofstream(out / "frame.json") << R"({"complete": false, "files": []})";
  CHECK(checkFrameSet(out).state == FrameSetState::Incomplete);
  CHECK(checkFrameSet(folder.path()).state == FrameSetState::NoManifest);
}

TEST_CASE("headlight diff refuses an incomplete set with its own status") {
  test::TempFolder folder("diffset");
  writeFrame(syntheticFrame(), folder.path() / "a");
  writeFrame(syntheticFrame(), folder.path() / "b");
  CHECK(diffDirectories(folder.path() / "a", folder.path() / "b").status == DiffStatus::Pass);
  std::ofstream(folder.path() / "b" / "frame.json") << R"({"complete": false, "files": []})";
  const DirectoryDiff diff = diffDirectories(folder.path() / "a", folder.path() / "b");
  CHECK(diff.incompleteSet);
  CHECK(diff.targets.empty());
  CHECK(diff.problem.find("incomplete output set") != std::string::npos);
}

TEST_CASE("--resume's decision: a complete set of the same job hash, nothing else") {
  test::TempFolder folder("resume");
  Job job;
  job.scene = "builtin:cornell";
  job.outDir = (folder.path() / "job").string();
  CHECK_FALSE(jobAlreadyDone(job, {}));  // nothing there
  OutputOptions options;
  options.jobHash = jobHash(job, {});
  writeFrame(syntheticFrame(), job.outDir, options);
  CHECK(jobAlreadyDone(job, {}));
  Job changed = job;
  changed.settings.ssgi.sampleCount = 4;
  CHECK_FALSE(jobAlreadyDone(changed, {}));  // other settings: render again
  fs::remove(fs::path(job.outDir) / "lit.exr");
  CHECK_FALSE(jobAlreadyDone(job, {}));  // a file gone: render again
}

TEST_CASE("stale temporaries: a dead writer's are removed, a live one's kept") {
  test::TempFolder folder("stale");
  const fs::path dead = folder.write(".lit.exr.x." + std::to_string(deadPid()) + "-1.tmp", "partial");
  const fs::path deadOld = folder.write(".lit.exr." + std::to_string(deadPid()) + "-2.tmp", "partial");
  const fs::path live = folder.write(".lit.exr." + std::to_string(getpid()) + "-3.tmp", "partial");
  const fs::path other = folder.write("notes.tmp", "not ours");
  // ".x." is another host's tag: not ours to judge.
  CHECK(removeStaleTemporaries(folder.path()) == 1);
  CHECK(fs::exists(dead));
  CHECK_FALSE(fs::exists(deadOld));
  CHECK(fs::exists(live));
  CHECK(fs::exists(other));
}

TEST_CASE("non-finite values: an error naming the target and the count, or clamped when asked") {
  test::TempFolder folder("nonfinite");
  Frame frame = syntheticFrame();
  frame.depth.pixels[3] = std::numeric_limits<float>::quiet_NaN();
  frame.lit.pixels[0] = std::numeric_limits<float>::infinity();
  frame.lit.pixels[5] = -std::numeric_limits<float>::infinity();
  CHECK(countNonFinite(frame.lit, "lit").count == 2);
  const fs::path out = folder.path() / "refused";
  try {
    writeFrame(frame, out);
    FAIL("expected an IoError");
  } catch (const IoError& error) {
    const std::string message = error.what();
    CHECK(message.find("depth.exr: 1 of 48 values") != std::string::npos);
    CHECK(message.find("lit.exr: 2 of 192 values") != std::string::npos);
  }
  CHECK_FALSE(fs::exists(out));  // nothing written

  OutputOptions clamp;
  clamp.nonFinite = NonFinitePolicy::Clamp;
  const auto written = writeFrame(frame, folder.path() / "clamped", clamp);
  bool sawLit = false;
  for (const WrittenFile& file : written)
    if (file.path.filename() == "lit.exr") {
      sawLit = true;
      CHECK(file.nonFinite == 2);
      CHECK(file.summary.find("non-finite 2 (clamped)") != std::string::npos);
    }
  CHECK(sawLit);
  OIIO::ImageBuf lit((folder.path() / "clamped" / "lit.exr").string());
  REQUIRE(lit.read(0, 0, true, OIIO::TypeDesc::FLOAT));
  CHECK(lit.getchannel(0, 0, 0, 0) == doctest::Approx(65504.0f));  // half's largest
  CHECK(std::isfinite(lit.getchannel(1, 0, 0, 1)));
}

TEST_CASE("--targets: only the named files, and stale ones of an earlier set removed") {
  test::TempFolder folder("targets");
  writeFrame(syntheticFrame(), folder.path());
  OutputOptions depthOnly;
  depthOnly.targets = {"depth"};
  const auto written = writeFrame(syntheticFrame(), folder.path(), depthOnly);
  REQUIRE(written.size() == 1);
  CHECK(fs::exists(folder.path() / "depth.exr"));
  CHECK_FALSE(fs::exists(folder.path() / "lit.exr"));
  CHECK_FALSE(fs::exists(folder.path() / "preview.png"));
  CHECK(checkFrameSet(folder.path()).state == FrameSetState::Complete);
  depthOnly.targets = {"depht"};
  CHECK_THROWS_AS(writeFrame(syntheticFrame(), folder.path(), depthOnly), SettingsError);
}

TEST_CASE("every lossless EXR compression writes the same pixels") {
  test::TempFolder folder("compression");
  Frame frame = syntheticFrame();
  for (std::size_t i = 0; i < frame.depth.pixels.size(); ++i) frame.depth.pixels[i] = 0.1f * float(i);
  for (std::size_t i = 0; i < exrCompressionNames().size(); ++i) {
    const std::string_view name = exrCompressionNames()[i];
    CAPTURE(name);
    OutputOptions options;
    options.compression = ExrCompression(i);
    options.targets = {"depth"};
    writeFrame(frame, folder.path() / std::string(name), options);
    OIIO::ImageBuf depth((folder.path() / std::string(name) / "depth.exr").string());
    REQUIRE(depth.read(0, 0, true, OIIO::TypeDesc::FLOAT));
    CHECK(depth.spec().get_string_attribute("compression") == name);
    int differing = 0;
    for (int y = 0; y < 6; ++y)
      for (int x = 0; x < 8; ++x) differing += depth.getchannel(x, y, 0, 0) != frame.depth.at(x, y, 0);
    CHECK(differing == 0);
  }
}

TEST_CASE("job lines: a settings file, overridden by the line's own settings, and a bad one named") {
  const fs::path folder = test::freshFolder("job-settings-file");
  const fs::path file = folder / "tuned.settings";
  std::ofstream(file) << "ssgi-slices = 3\nssgi-steps = 5\n";
  const std::string text = R"({"scene": "builtin:cornell", "out": "a", "settings_file": ")" + file.string() + "\"" +
                           R"(, "settings": {"ssgi-steps": 9}})" + "\n" +
                           R"({"scene": "builtin:cornell", "out": "b", "settings_file": "no-such.settings"})" + "\n";
  const std::vector<Job> jobs = parseJobLines(text, "jobs.jsonl", RenderSettings{});
  REQUIRE(jobs.size() == 2);
  CHECK(jobs[0].error.empty());
  CHECK(jobs[0].settings.ssgi.sliceCount == 3);
  CHECK(jobs[0].settings.ssgi.stepCount == 9);
  CHECK(jobs[1].error.find("no-such.settings: cannot read the settings file") != std::string::npos);
  fs::remove_all(folder);
}

// ---- Hardening, round two (issue 15): the job model and frame sets ----------

TEST_CASE("job lines: deep JSON, a long line and echoed input are bounded, each naming its line") {
  const std::string deep = std::string(100000, '[') + std::string(100000, ']');
  std::string text = deep + "\n";
  for (const char* key : {"settings", "size", "eye", "fov", "camera"})
    text += std::string(R"({"scene": "builtin:cornell", "out": "o", ")") + key + "\": " + deep + "}\n";
  text += R"({"scene": "builtin:cornell", "out": "fine"})"
          "\n";
  text +=
      R"({"scene": "builtin:cornell", "out": "o", "target": [0, 0, 0], "eye": ")" + std::string(5000, 'x') + "\"}\n";
  text += std::string(detail::kMaxJobLineBytes + 1, ' ') + "{}\n";
  const std::vector<Job> jobs = parseJobLines(text, "jobs.jsonl", RenderSettings{});
  REQUIRE(jobs.size() == 9);
  for (std::size_t line = 0; line < 6; ++line) {
    CAPTURE(line);
    CHECK(jobs[line].origin == "jobs.jsonl:" + std::to_string(line + 1));
    CHECK(jobs[line].error.find("JSON nests deeper than 64 levels") != std::string::npos);
  }
  CHECK(jobs[6].error.empty());  // the lines after a refused one still parse
  CHECK(jobs[7].error.find("\"eye\": expected [x, y, z]") != std::string::npos);
  CHECK(jobs[7].error.size() < 300);  // the 5,000-character value is cut to an excerpt
  CHECK(jobs[8].error.find("more than the 1.0 MiB a job line may have") != std::string::npos);
  // 64 levels are fine (the limit is a refusal above it, not a crash below it).
  const std::string settings64 = R"({"scene": "builtin:cornell", "out": "o", "settings": {"x": )" +
                                 std::string(62, '[') + std::string(62, ']') + "}}";
  const std::vector<Job> nested = parseJobLines(settings64, "n.jsonl", RenderSettings{});
  CHECK(nested.at(0).error.find("expected a string, number or boolean") != std::string::npos);
}

TEST_CASE("job lines: a key given twice and a size missing a number are refused, naming them (issue 32)") {
  const std::string text = R"({"scene": "builtin:cornell", "out": "a", "out": "b"})"
                           "\n"
                           R"({"scene": "builtin:cornell", "out": "c", "settings": {"ssgi": "off", "ssgi": "on"}})"
                           "\n"
                           R"({"scene": "builtin:cornell", "out": "d", "size": "64x"})"
                           "\n"
                           R"({"scene": "builtin:cornell", "out": "e", "size": "x48"})"
                           "\n"
                           R"({"scene": "builtin:cornell", "out": "f", "settings": {"ssgi": "off"}, "size": "64x48"})"
                           "\n";
  const std::vector<Job> jobs = parseJobLines(text, "jobs.jsonl", RenderSettings{});
  REQUIRE(jobs.size() == 5);
  CHECK(jobs[0].error.find("the key \"out\" appears twice in one object") != std::string::npos);
  CHECK(jobs[1].error.find("the key \"ssgi\" appears twice in one object") != std::string::npos);
  CHECK(jobs[2].error.find("\"size\": expected \"WIDTHxHEIGHT\", got \"64x\"") != std::string::npos);
  CHECK(jobs[3].error.find("\"size\": expected \"WIDTHxHEIGHT\", got \"x48\"") != std::string::npos);
  CHECK(jobs[4].error.empty());  // the same keys once each are fine
  CHECK(jobs[4].settings.width == 64);
}

TEST_CASE("job files and settings files: only regular files, within their size limits") {
  test::TempFolder folder("bounded-reads");
  CHECK_THROWS_WITH_AS(readJobFile(folder.path(), {}), doctest::Contains("is a folder, expected a regular file"),
                       IoError);
  RenderSettings settings;
  CHECK_THROWS_WITH_AS(applySettingsFile(settings, folder.path()), doctest::Contains("is a folder"), SettingsError);
  if (fs::exists("/dev/zero")) {
    CHECK_THROWS_WITH_AS(readJobFile("/dev/zero", {}),
                         doctest::Contains("/dev/zero: cannot read the job file: is a "
                                           "character device"),
                         IoError);
    CHECK_THROWS_WITH_AS(applySettingsFile(settings, "/dev/zero"), doctest::Contains("character device"),
                         SettingsError);
    CHECK_THROWS_WITH_AS(fileFingerprint("/dev/zero"), doctest::Contains("character device"), IoError);
  }
  const fs::path fifo = folder.path() / "fifo";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  CHECK_THROWS_WITH_AS(readJobFile(fifo, {}), doctest::Contains("is a FIFO"), IoError);  // returns, never blocks
  CHECK_THROWS_WITH_AS(applySettingsFile(settings, fifo), doctest::Contains("is a FIFO"), SettingsError);
  const fs::path big = folder.write("big.settings", std::string(detail::kMaxSettingsFileBytes + 1, '#'));
  CHECK_THROWS_WITH_AS(applySettingsFile(settings, big), doctest::Contains("more than the 1.0 MiB"), SettingsError);
  // A sparse 1 GiB file hashes in constant memory (streamed, not read
  // whole): hashed in a child, whose peak resident memory stays far below it.
  const fs::path sparse = folder.path() / "sparse";
  std::ofstream(sparse).close();
  fs::resize_file(sparse, std::uintmax_t(1) << 30);
  // The child's own growth: its resident memory before hashing (what it
  // shares with this process after fork, large under sanitizers) against
  // its peak after. Exit 0: hashed, and grew by under 256 MiB.
  const pid_t child = fork();
  if (child == 0) {
    const long before = statusKilobytes("VmRSS:");
    const bool hashed = fileFingerprint(sparse).size() == 16;
    const long peak = statusKilobytes("VmHWM:");
    _exit(!hashed ? 1 : (before < 0 || peak < 0) ? 3 : peak - before < 256 * 1024 ? 0 : 2);
  }
  int status = 0;
  REQUIRE(waitpid(child, &status, 0) == child);
  REQUIRE(WIFEXITED(status));
  CHECK_MESSAGE(WEXITSTATUS(status) != 1, "the fingerprint failed");
  CHECK_MESSAGE(WEXITSTATUS(status) != 2, "hashing a 1 GiB file grew the process by 256 MiB or more");
  CHECK_MESSAGE(WEXITSTATUS(status) != 3, "/proc/self/status has no VmRSS or VmHWM");
  CHECK(detail::excerpt(std::string("a\0b", 3)) == "a\\x00b");  // a NUL shown, not an end of the message
}

TEST_CASE("two jobs writing one folder are refused before anything renders, naming both") {
  const std::string text = R"({"scene": "builtin:cornell", "out": "dup"})"
                           "\n"
                           R"({"scene": "builtin:spheres", "out": "elsewhere"})"
                           "\n"
                           R"({"scene": "builtin:spheres", "out": "./dup/"})"
                           "\n";
  const std::vector<Job> jobs = parseJobLines(text, "jobs.jsonl", RenderSettings{});
  CHECK(normalizedOutDir("dup") == normalizedOutDir("./dup/"));
  CHECK(normalizedOutDir("dup") == normalizedOutDir((fs::current_path() / "x" / ".." / "dup").string()));
  CHECK_THROWS_WITH_AS(checkDistinctOutDirs(jobs), doctest::Contains("jobs.jsonl:1 and jobs.jsonl:3 both write into"),
                       SettingsError);
  CHECK_NOTHROW(checkDistinctOutDirs({jobs[0], jobs[1]}));

  // A folder and a symlink to it, or the folder through /proc/self/cwd, are
  // one folder (issue 32: "2 rendered", exit 0, and the first set was lost).
  test::TempFolder folder("distinct-outs");
  fs::create_directories(folder.path() / "real");
  fs::create_directory_symlink(folder.path() / "real", folder.path() / "link");
  auto jobInto = [](const fs::path& out, const char* origin) {
    Job job;
    job.scene = "builtin:cornell";
    job.origin = origin;
    job.outDir = out.string();
    return job;
  };
  CHECK_THROWS_WITH_AS(checkDistinctOutDirs({jobInto(folder.path() / "real", "jobs.jsonl:1"),
                                             jobInto(folder.path() / "link", "jobs.jsonl:2")}),
                       doctest::Contains("jobs.jsonl:1 and jobs.jsonl:2 both write into"), SettingsError);
  // Not yet made: the link in the part that exists is followed all the same.
  CHECK_THROWS_AS(checkDistinctOutDirs(
                      {jobInto(folder.path() / "real" / "new", "a"), jobInto(folder.path() / "link" / "new", "b")}),
                  SettingsError);
  const fs::path before = fs::current_path();
  fs::current_path(folder.path());
  CHECK_THROWS_AS(checkDistinctOutDirs({jobInto("real", "a"), jobInto("/proc/self/cwd/real", "b")}), SettingsError);
  CHECK_NOTHROW(checkDistinctOutDirs({jobInto("real", "a"), jobInto("link/../other", "b")}));
  fs::current_path(before);
}

TEST_CASE("frame sets: an edited file list (an entry removed, the list emptied) is incomplete") {
  test::TempFolder folder("frameset-list");
  const fs::path out = folder.path() / "set";
  writeFrame(syntheticFrame(), out, {});
  auto edit = [&](const std::function<void(nlohmann::json&)>& change) {
    nlohmann::json j;
    std::ifstream(out / "frame.json") >> j;
    change(j);
    std::ofstream(out / "frame.json") << j.dump(2);
  };
  edit([](nlohmann::json& j) { j["files"].erase(j["files"].begin()); });  // position.exr left out
  FrameSetCheck check = checkFrameSet(out);
  CHECK(check.state == FrameSetState::Incomplete);
  CHECK(check.problem.find("does not match the list hash") != std::string::npos);

  writeFrame(syntheticFrame(), out, {});
  edit([](nlohmann::json& j) { j["files"] = nlohmann::json::array(); });
  for (const char* name : {"position.exr", "normal.exr", "depth.exr", "lit.exr", "preview.png"}) fs::remove(out / name);
  CHECK(checkFrameSet(out).state == FrameSetState::Incomplete);

  // A version-1 set (the goldens') has no list hash: a target it does not list is still caught.
  writeFrame(syntheticFrame(), out, {});
  edit([](nlohmann::json& j) {
    j["version"] = 1;
    j.erase("files_hash");
    j["files"].erase(j["files"].begin());
  });
  check = checkFrameSet(out);
  CHECK(check.state == FrameSetState::Incomplete);
  CHECK(check.problem.find("does not list position.exr") != std::string::npos);
  edit([](nlohmann::json& j) { j["files"][0]["name"] = "../../etc/passwd"; });
  CHECK(checkFrameSet(out).state == FrameSetState::Incomplete);

  fs::remove(out / "frame.json");
  fs::create_directory(out / "frame.json");
  check = checkFrameSet(out);
  CHECK(check.state == FrameSetState::Incomplete);
  CHECK(check.problem.find("frame.json: cannot read the frame manifest: is a folder") != std::string::npos);
}

TEST_CASE("render touches only its own files") {
  test::TempFolder folder("own-files");
  const fs::path out = folder.path() / "set";
  fs::create_directories(out);
  std::ofstream(out / "lit.exr") << "a user's file";
  Job job;
  job.scene = "builtin:cornell";
  job.outDir = out.string();
  CHECK(outputFolderRefusal(job, false).find("holds lit.exr, which no earlier Headlight set") != std::string::npos);
  CHECK(outputFolderRefusal(job, true).empty());
  fs::remove(out / "lit.exr");
  writeFrame(syntheticFrame(), out, {});
  CHECK(outputFolderRefusal(job, false).empty());  // our own set: replaced freely

  // A target this frame lacks is removed only when an earlier set listed it.
  std::ofstream(out / "emissive.exr") << "not Headlight's";
  writeFrame(syntheticFrame(), out, {});
  CHECK(fs::exists(out / "emissive.exr"));
  OutputOptions depthOnly;
  depthOnly.targets = {"depth"};
  writeFrame(syntheticFrame(), out, depthOnly);
  CHECK_FALSE(fs::exists(out / "lit.exr"));  // listed by the earlier set: removed
  CHECK(fs::exists(out / "emissive.exr"));

  const fs::path scene = folder.write("scenes/scene.gltf", "{}");
  job.scene = scene.string();
  job.outDir = (folder.path() / "scenes" / ".").string();
  CHECK(outputFolderRefusal(job, true).find("holds the scene") != std::string::npos);  // even with --force
}

TEST_CASE("a write failure with its own errno is not blamed on a full disk") {
  const std::string reason = detail::writeFailureReason("/proc/no-such-folder/x.exr", "", ENOENT);
  CHECK(reason.find("No such file or directory") != std::string::npos);
  CHECK(reason.find("disk full") == std::string::npos);  // /proc has 0 bytes free, and is no disk
}

TEST_CASE("a NUL in a settings file is named, not the end of the message") {
  RenderSettings settings;
  CHECK_THROWS_WITH_AS(applySettingsFileText(settings, std::string("ssgi-slices = 3\nssgi-st\0eps = 4\n", 32), "x"),
                       doctest::Contains("x:2: holds a NUL byte"), SettingsError);
}

TEST_CASE("frame.json's camera projects every geometry pixel's position onto that pixel, at its depth") {
  const Frame frame = test::renderFresh(loadScene("builtin:cornell"), test::smallSettings(40, 30));
  const test::TempFolder folder("camera-json");
  writeFrame(frame, folder.path() / "out");
  std::ifstream manifest(folder.path() / "out" / "frame.json");
  const nlohmann::json camera = nlohmann::json::parse(manifest)["camera"];
  REQUIRE(camera.contains("intrinsics"));
  CHECK(camera["width"] == 40);
  CHECK(camera["height"] == 30);
  CHECK(camera["orthographic"] == false);
  const auto worldToCamera = camera["world_to_camera"], cameraToWorld = camera["camera_to_world"];
  const auto k = camera["intrinsics"];
  int checked = 0;
  for (int y = 0; y < 30; ++y)
    for (int x = 0; x < 40; ++x) {
      if (frame.position.at(x, y, 3) != 1.0f) continue;
      const double world[4] = {frame.position.at(x, y, 0), frame.position.at(x, y, 1), frame.position.at(x, y, 2), 1};
      double cam[3] = {0, 0, 0};
      for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 4; ++col) cam[row] += worldToCamera[row][col].get<double>() * world[col];
      // OpenCV's axes: x right, y down, looking along +Z (the OpenGL camera's Y and Z negated).
      const double zCv = -cam[2];
      const double u = k[0][0].get<double>() * cam[0] / zCv + k[0][2].get<double>();
      const double v = k[1][1].get<double>() * -cam[1] / zCv + k[1][2].get<double>();
      CAPTURE(x);
      CAPTURE(y);
      CHECK(std::abs(u - (x + 0.5)) < 2e-3);  // pixel units
      CHECK(std::abs(v - (y + 0.5)) < 2e-3);
      CHECK(frame.depth.at(x, y, 0) == doctest::Approx(zCv).epsilon(1e-4));  // depth.Z: along the axis
      ++checked;
    }
  CHECK(checked > 600);  // 960 of the 1200 pixels are the box
  // camera_to_world is the inverse: it takes the camera's origin to the recorded position.
  for (int row = 0; row < 3; ++row)
    CHECK(cameraToWorld[row][3].get<double>() == doctest::Approx(camera["position"][row].get<double>()).epsilon(1e-5));
}

TEST_CASE("a broken frame.json is named in words, not in nlohmann's tags (issue 32, unclear messages)") {
  test::TempFolder folder("manifest-words");
  auto reasonFor = [&](const std::string& manifest) {
    std::ofstream(folder.path() / "frame.json") << manifest;
    return checkFrameSet(folder.path()).problem;
  };
  const std::string truncated = reasonFor(R"({"version": 2, "files": [)");
  CHECK(truncated.find("frame.json: not a headlight frame manifest: parse error at line 1") != std::string::npos);
  CHECK(truncated.find("[json.exception") == std::string::npos);
  const std::string noComplete = reasonFor(R"({"version": 2, "files": []})");
  CHECK(noComplete.find("not a headlight frame manifest: no \"complete\" field") != std::string::npos);
  CHECK(noComplete.find("[json.exception") == std::string::npos);
}
