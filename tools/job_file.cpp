// The job model (job_file.hpp): job lines -> Jobs, the camera a job
// places, job hashes. Pure: no context, no rendering, no writing.
#include "job_file.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "headlight/error.hpp"
#include "headlight/output.hpp"
#include "headlight/scene_loader.hpp"
#include "io/bounded_json.hpp"
#include "io/bounded_read.hpp"
#include "io/fingerprint.hpp"
#include "tooling/command_line.hpp"

namespace headlight::cli {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;
using detail::excerpt;

// A JSON value for a message: never the whole of a long or deep value.
std::string shown(const json& value) { return excerpt(value.dump(-1, ' ', false, json::error_handler_t::replace)); }

std::string vecText(const glm::vec3& v) {
  std::ostringstream text;
  text.precision(9);
  text << v.x << "," << v.y << "," << v.z;
  return text.str();
}

glm::vec3 readVec3(const json& value, const char* key) {
  if (!value.is_array() || value.size() != 3 || !value[0].is_number() || !value[1].is_number() || !value[2].is_number())
    throw SettingsError(std::string("\"") + key + "\": expected [x, y, z] (three numbers), got " + shown(value));
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
  throw SettingsError("setting \"" + excerpt(name) + "\": expected a string, number or boolean, got " + shown(value));
}

Job parseJobLine(const std::string& line, const std::string& origin, const RenderSettings& base) {
  Job job;
  job.origin = origin;
  job.settings = base;
  if (line.size() > detail::kMaxJobLineBytes)
    throw SettingsError("the line is " + detail::byteSizeText(line.size()) + ", more than the " +
                        detail::byteSizeText(detail::kMaxJobLineBytes) + " a job line may have");
  json j;
  try {
    j = detail::parseBoundedJson(line);
  } catch (const detail::JsonError& e) {
    throw SettingsError(e.what());
  }
  if (!j.is_object()) throw SettingsError("expected a JSON object, got " + shown(j));
  static const char* kKeys[] = {"scene", "out",  "camera",        "eye",      "target",           "up",
                                "fov",   "size", "settings_file", "settings", "material_variant", "animation",
                                "time"};
  for (const auto& item : j.items()) {
    const std::string& key = item.key();  // a name, not a structured binding: lambdas capture it (clang 14)
    if (std::find_if(std::begin(kKeys), std::end(kKeys), [&](const char* k) { return key == k; }) == std::end(kKeys))
      throw SettingsError("unknown key \"" + excerpt(key) +
                          "\" (known: scene, out, camera, eye, target, up, fov, size, settings_file, settings, "
                          "material_variant, animation, time)");
  }
  if (!j.contains("scene") || !j["scene"].is_string() || j["scene"].get<std::string>().empty())
    throw SettingsError("\"scene\": expected a file path or builtin:NAME");
  job.scene = j["scene"].get<std::string>();
  if (!j.contains("out") || !j["out"].is_string() || j["out"].get<std::string>().empty())
    throw SettingsError("\"out\": expected the job's output folder");
  job.outDir = j["out"].get<std::string>();
  if (j.contains("material_variant")) {
    if (!j["material_variant"].is_string() || j["material_variant"].get<std::string>().empty())
      throw SettingsError("\"material_variant\": expected the name of one of the scene's KHR_materials_variants");
    job.materialVariant = j["material_variant"].get<std::string>();
  }
  if (j.contains("animation")) {
    // An index as a number or text, or a name.
    if (j["animation"].is_number_unsigned())
      job.animation = std::to_string(j["animation"].get<std::uint64_t>());
    else if (j["animation"].is_string() && !j["animation"].get<std::string>().empty())
      job.animation = j["animation"].get<std::string>();
    else
      throw SettingsError("\"animation\": expected the index or name of one of the scene's animations, got " +
                          shown(j["animation"]));
  }
  if (j.contains("time")) {
    const OptionSpec& spec = findOption(sceneLoadOptions(), "time").spec;
    if (!j["time"].is_number())
      throw SettingsError("\"time\": expected seconds into the animation, got " + shown(j["time"]));
    const OptionValue value = j["time"].get<double>();
    checkOptionValue(spec, value);
    job.animationTime = float(std::get<double>(value));
  }
  for (const std::string* path : {&job.scene, &job.outDir})
    if (path->find('\0') != std::string::npos)
      throw SettingsError("a path holds a NUL character: \"" + excerpt(*path) + "\"");

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
    // Both numbers present: "64x" would otherwise be reported against the height setting.
    if (x == std::string::npos || x == 0 || x + 1 == size.size())
      throw SettingsError("\"size\": expected \"WIDTHxHEIGHT\", got " + shown(j["size"]));
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
      if (!j["fov"].is_number()) throw SettingsError("\"fov\": expected degrees, got " + shown(j["fov"]));
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

}  // namespace

std::string JobCamera::describe() const {
  switch (kind) {
    case Kind::Settings:
      return "settings";
    case Kind::LookAt:
      return "eye " + vecText(eye) + " target " + vecText(target) + " up " + vecText(up) + " fov " +
             std::to_string(fovDegrees);
    case Kind::Orbit: {
      std::string text = "orbit " + std::to_string(orbitIndex) + "/" + std::to_string(orbitViews) + " fov " +
                         std::to_string(fovDegrees);
      // Only when asked for: earlier orbits' job hashes (--resume) stay as they were.
      if (orbitElevationDegrees) text += " elevation " + std::to_string(*orbitElevationDegrees);
      if (orbitDistanceScale != 1.0f) text += " distance " + std::to_string(orbitDistanceScale);
      return text;
    }
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
  // The turntable: fitCamera's framing turned about +Y.
  const float azimuth = 2.0f * glm::pi<float>() * float(orbitIndex) / float(std::max(1, orbitViews));
  camera = fitCamera(scene.worldBounds(), aspect, camera.yfov, azimuth,
                     orbitElevationDegrees ? glm::radians(*orbitElevationDegrees) : kFitElevationRadians,
                     orbitDistanceScale);
  camera.name = "orbit " + std::to_string(orbitIndex);
  return camera;
}

std::vector<Job> parseJobLines(const std::string& text, const std::string& name, const RenderSettings& base) {
  std::vector<Job> jobs;
  int number = 0;
  for (std::size_t start = 0; start < text.size();) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    const std::string line = text.substr(start, end - start);
    start = end + 1;
    ++number;
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    const std::string origin = name + ":" + std::to_string(number);
    try {
      jobs.push_back(parseJobLine(line, origin, base));
    } catch (const std::exception& error) {  // Error, and anything a library throws: one job, not the batch
      Job bad;
      bad.origin = origin;
      bad.error = commandLineMessage(error);
      jobs.push_back(std::move(bad));
    }
  }
  return jobs;
}

std::vector<Job> readJobFile(const fs::path& path, const RenderSettings& base) {
  return parseJobLines(detail::readRegularFile(path, detail::kMaxJobFileBytes, "the job file"), path.string(), base);
}

std::string jobHash(const Job& job, const OutputOptions& output, const std::string& environment,
                    const std::function<std::string(const std::string&)>& fingerprint) {
  const auto fileHash = [&](const std::string& path) {
    return fingerprint ? fingerprint(path) : fileFingerprint(path);
  };
  std::string text = "scene=" + job.scene + "\n";
  if (job.scene.rfind("builtin:", 0) != 0) text += "scene-bytes=" + fileHash(job.scene) + "\n";
  if (!environment.empty()) text += "environment-bytes=" + fileHash(environment) + "\n";
  for (const auto& [name, value] : settingsAsText(job.settings)) text += name + "=" + value + "\n";
  text += "camera=" + job.camera.describe() + "\n";
  if (job.materialVariant) text += "material-variant=" + *job.materialVariant + "\n";
  if (job.animation) text += "animation=" + *job.animation + "\n";
  if (job.animationTime) text += "time=" + std::to_string(*job.animationTime) + "\n";
  text += "targets=";
  for (const std::string& target : output.targets) text += target + ",";
  if (!output.pngTargets.empty()) {  // absent without PNGs: earlier sets keep their hashes
    text += "\npng=";
    for (const std::string& target : output.pngTargets) text += target + ",";
  }
  text += "\nnonfinite=" + std::string(output.nonFinite == NonFinitePolicy::Clamp ? "clamp" : "error") + "\n";
  return textFingerprint(text);
}

}  // namespace headlight::cli
