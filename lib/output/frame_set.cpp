// frame.json: what makes a folder of outputs a set that a reader can trust
// to be whole (headlight/output.hpp).
#include "output/frame_set.hpp"

#include <signal.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "headlight/error.hpp"
#include "headlight/targets.hpp"
#include "io/atomic_file.hpp"
#include "io/bounded_json.hpp"
#include "io/bounded_read.hpp"
#include "io/fingerprint.hpp"

namespace headlight {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

// 2: "files_hash" (a hash of the file list) and "owned". Version 1 sets
// (the goldens) have no list hash and are checked without it.
constexpr int kManifestVersion = 2;

// What the file list says, hashed: an edited list (an entry removed, the
// list emptied) no longer matches the hash written with it.
std::string fileListHash(const std::vector<ManifestFile>& files) {
  std::string text;
  for (const ManifestFile& file : files) text += file.name + " " + file.hash + " " + std::to_string(file.bytes) + "\n";
  return textFingerprint(text);
}

// A listed name must name a file in the folder itself.
bool plainFileName(const std::string& name) {
  return !name.empty() && name != "." && name != ".." && name.find('/') == std::string::npos &&
         name.find('\0') == std::string::npos;
}

json readManifestJson(const fs::path& path) {
  const std::string text = detail::readRegularFile(path, detail::kMaxManifestBytes, "the frame manifest");
  try {
    return json::parse(text);
  } catch (const json::exception& e) {
    throw IoError(path.string() +
                  ": not a headlight frame manifest: " + detail::excerpt(detail::jsonErrorText(e), 160));
  }
}

// A 4x4 matrix as rows (row-major, as a reader writes M[row][col]).
json matrixRows(const glm::mat4& columnMajor) {
  json rows = json::array();
  for (int row = 0; row < 4; ++row)
    rows.push_back({columnMajor[0][row], columnMajor[1][row], columnMajor[2][row], columnMajor[3][row]});
  return rows;
}

// What a dataset needs of the camera (issue 30): the matrices, the lens as
// pixel intrinsics and fields of view, the planes and the depth convention.
json cameraJson(const Frame& frame) {
  const CameraView& view = frame.view;
  const int width = frame.settings.width, height = frame.settings.height;
  json camera;
  camera["convention"] = "OpenGL camera: right-handed, looks down -Z, +Y up; world +Y up";
  camera["world_to_camera"] = matrixRows(view.view);
  camera["camera_to_world"] = matrixRows(glm::inverse(view.view));
  camera["projection"] = matrixRows(view.projection);  // camera -> clip, depth -1..1
  camera["position"] = {view.position.x, view.position.y, view.position.z};
  camera["width"] = width;
  camera["height"] = height;
  camera["near"] = view.nearPlane;
  camera["far"] = view.farPlane;
  camera["orthographic"] = view.orthographic;
  if (!view.orthographic) {
    // Pixel intrinsics in OpenCV's convention (x right, y down, the camera looking along +Z: the OpenGL
    // camera with Y and Z negated); pixel (0, 0)'s centre is at (0.5, 0.5).
    const double fx = double(view.projection[0][0]) * width / 2.0, fy = double(view.projection[1][1]) * height / 2.0;
    camera["intrinsics"] = {{fx, 0.0, width / 2.0}, {0.0, fy, height / 2.0}, {0.0, 0.0, 1.0}};
    camera["yfov_degrees"] = glm::degrees(2.0 * std::atan(1.0 / double(view.projection[1][1])));
    camera["xfov_degrees"] = glm::degrees(2.0 * std::atan(1.0 / double(view.projection[0][0])));
  } else {
    camera["view_height"] = 2.0 / double(view.projection[1][1]);  // scene units the image spans vertically
    camera["view_width"] = 2.0 / double(view.projection[0][0]);
  }
  camera["depth"] =
      "depth.exr's depth.Z is view-space depth: the distance along the camera's viewing axis (-Z), in scene units, "
      "not the distance to the eye; background pixels hold the far plane";
  return camera;
}

// ids.exr's tables: one entry per id, with its name and where it is in the
// file (keys left out where it is from no file).
json idsJson(const IdNames& names) {
  auto table = [](const std::vector<IdName>& entries, const char* indexKey, const char* subIndexKey) {
    json rows = json::array();
    for (std::size_t k = 0; k < entries.size(); ++k) {
      json row{{"id", k + 1}, {"name", entries[k].name}};
      if (entries[k].index >= 0) row[indexKey] = entries[k].index;
      if (entries[k].subIndex >= 0 && subIndexKey) row[subIndexKey] = entries[k].subIndex;
      rows.push_back(std::move(row));
    }
    return rows;
  };
  json j;
  j["background"] = 0;
  j["channels"] = {
      {"instance.id", "instance"}, {"mesh.id", "mesh"}, {"material.id", "material"}, {"primitive.id", "primitive"}};
  j["instance"] = table(names.meshInstances, "node", "copy");
  j["mesh"] = table(names.meshes, "mesh", nullptr);
  j["material"] = table(names.materials, "material", nullptr);
  j["primitive"] = table(names.meshPrimitives, "mesh", "primitive");
  return j;
}

}  // namespace

std::string idNamesJson(const IdNames& names) { return idsJson(names).dump(); }

namespace {

json manifestJson(const Frame& frame, const OutputOptions& options, bool complete) {
  const std::map<std::string, std::string> settings = settingsAsText(frame.settings);
  std::string settingsText;
  for (const auto& [name, value] : settings) settingsText += name + "=" + value + "\n";
  json j;
  j["format"] = "headlight frame set";
  j["version"] = kManifestVersion;
  j["complete"] = complete;
  j["scene"] = frame.sceneSource;
  j["scene_hash"] = frame.sceneHash;
  if (!frame.scenePose.empty()) j["pose"] = frame.scenePose;  // --animation, --time
  j["settings_hash"] = textFingerprint(settingsText);
  j["job_hash"] = options.jobHash;
  j["renderer"] = frame.glRenderer;
  j["ignored"] = frame.ignored;  // glTF features not rendered
  j["settings"] = settings;
  // How each fullscreen pass ran: "fragment" or "compute" (fullscreen-form).
  json forms = json::object();
  for (const PassTime& pass : frame.timings)
    if (!pass.form.empty()) forms[pass.pass] = pass.form;
  j["forms"] = forms;
  j["camera"] = cameraJson(frame);
  const bool idsWritten = options.targets.empty() ||
                          std::find(options.targets.begin(), options.targets.end(), "ids") != options.targets.end();
  if (frame.idNames && !frame.ids.empty() && idsWritten) j["ids"] = idsJson(*frame.idNames);
  j["files"] = json::array();
  return j;
}

// "<anything>.<pid>-<n>.tmp" -> pid, and the host tag before it if any.
bool parseTemporaryName(const std::string& name, std::string& host, long& pid) {
  if (name.size() < 6 || name[0] != '.' || name.compare(name.size() - 4, 4, ".tmp") != 0) return false;
  const std::string stem = name.substr(0, name.size() - 4);
  const auto dash = stem.rfind('-');
  const auto dot = stem.rfind('.', dash);
  if (dash == std::string::npos || dot == std::string::npos || dot + 1 >= dash) return false;
  try {
    std::size_t used = 0;
    pid = std::stol(stem.substr(dot + 1, dash - dot - 1), &used);
    if (used != dash - dot - 1 || pid <= 0) return false;
  } catch (const std::exception&) {
    return false;
  }
  // Older names had no host: ".<file>.<pid>-<n>.tmp". With one, the part
  // before the pid is the host tag.
  const auto hostDot = stem.rfind('.', dot - 1);
  host = hostDot == std::string::npos ? "" : stem.substr(hostDot + 1, dot - hostDot - 1);
  return true;
}

}  // namespace

std::size_t removeStaleTemporaries(const fs::path& folder) {
  static const std::string ourHost = detail::temporaryHostTag();
  std::size_t removed = 0;
  std::error_code error;
  for (fs::directory_iterator it(folder, error), end; !error && it != end; it.increment(error)) {
    std::string host;
    long pid = 0;
    if (!parseTemporaryName(it->path().filename().string(), host, pid)) continue;
    // A known other host's file: its process cannot be asked from here.
    // Names before the host tag ended ".<file>.<ext>.<pid>-<n>.tmp": the
    // "host" read from them is the extension.
    if (host != ourHost && host != "exr" && host != "png" && host != "json") continue;
    if (::kill(pid_t(pid), 0) == 0 || errno != ESRCH) continue;  // alive (or not ours to judge)
    std::error_code ignored;
    if (fs::remove(it->path(), ignored)) ++removed;
  }
  return removed;
}

std::optional<FrameManifest> readManifest(const fs::path& folder) {
  const fs::path path = folder / kManifestName;
  std::error_code error;
  if (!fs::exists(path, error) && !fs::is_symlink(path, error)) return std::nullopt;
  const json j = readManifestJson(path);
  try {
    FrameManifest manifest;
    manifest.complete = j.at("complete").get<bool>();
    manifest.scene = j.value("scene", "");
    manifest.sceneHash = j.value("scene_hash", "");
    manifest.settingsHash = j.value("settings_hash", "");
    manifest.jobHash = j.value("job_hash", "");
    if (j.contains("settings")) manifest.settings = j.at("settings").get<std::map<std::string, std::string>>();
    for (const json& file : j.at("files")) {
      manifest.files.push_back({file.at("name").get<std::string>(), file.at("hash").get<std::string>(),
                                file.at("bytes").get<std::size_t>()});
      if (!plainFileName(manifest.files.back().name))
        throw IoError(path.string() + ": lists \"" + detail::excerpt(manifest.files.back().name) +
                      "\", not a file name in the folder");
    }
    if (manifest.complete && j.value("version", 1) >= 2 && j.value("files_hash", "") != fileListHash(manifest.files))
      throw IoError(path.string() + ": its file list does not match the list hash written with it (edited?)");
    return manifest;
  } catch (const json::exception& e) {
    throw IoError(path.string() +
                  ": not a headlight frame manifest: " + detail::excerpt(detail::jsonErrorText(e), 160));
  }
}

FrameSetCheck checkFrameSet(const fs::path& folder) {
  FrameSetCheck check;
  std::optional<FrameManifest> manifest;
  try {
    manifest = readManifest(folder);
  } catch (const IoError& error) {
    return {FrameSetState::Incomplete, error.what()};
  }
  if (!manifest) return check;
  const std::string where = (folder / kManifestName).string();
  if (!manifest->complete)
    return {FrameSetState::Incomplete, where + " says a write was under way and never finished (a killed render?)"};
  if (manifest->files.empty()) return {FrameSetState::Incomplete, where + " lists no file"};
  // A target in the folder the list leaves out: an entry removed, or a
  // file from some other write.
  for (const FrameTarget& target : frameTargets()) {
    const std::string name = std::string(target.name) + ".exr";
    std::error_code error;
    if (!fs::exists(folder / name, error)) continue;
    if (std::none_of(manifest->files.begin(), manifest->files.end(),
                     [&](const ManifestFile& file) { return file.name == name; }))
      return {FrameSetState::Incomplete, where + " does not list " + name + ", which is in the folder"};
  }
  for (const ManifestFile& file : manifest->files) {
    const fs::path path = folder / file.name;
    std::error_code error;
    const auto bytes = fs::file_size(path, error);
    if (error) return {FrameSetState::Incomplete, where + " lists " + file.name + ", which is missing"};
    if (bytes != file.bytes || fileFingerprint(path) != file.hash)
      return {FrameSetState::Incomplete,
              where + ": " + file.name + " is not the file this set wrote (size or hash differs)"};
  }
  check.state = FrameSetState::Complete;
  return check;
}

namespace detail {

std::vector<std::string> ownedFileNames(const fs::path& folder) {
  const fs::path path = folder / kManifestName;
  std::error_code error;
  if (!fs::exists(path, error) && !fs::is_symlink(path, error)) return {};
  const json j = readManifestJson(path);
  std::vector<std::string> names{std::string(kManifestName)};
  try {
    for (const char* key : {"files", "owned"}) {
      if (!j.contains(key)) continue;
      for (const json& entry : j.at(key)) {
        const std::string name = entry.is_string() ? entry.get<std::string>() : entry.at("name").get<std::string>();
        if (plainFileName(name)) names.push_back(name);
      }
    }
  } catch (const json::exception& e) {
    throw IoError(path.string() +
                  ": not a headlight frame manifest: " + detail::excerpt(detail::jsonErrorText(e), 160));
  }
  return names;
}

void beginFrameSet(const Frame& frame, const fs::path& folder, const OutputOptions& options,
                   const std::vector<std::string>& planned) {
  json j = manifestJson(frame, options, false);
  std::vector<std::string> owned = planned;
  try {
    for (const std::string& name : ownedFileNames(folder))
      if (name != kManifestName && std::find(owned.begin(), owned.end(), name) == owned.end()) owned.push_back(name);
  } catch (const IoError&) {
    // Not a manifest (the caller was told to replace it): nothing more is ours.
  }
  j["owned"] = owned;
  writeTextAtomically(folder / kManifestName, j.dump(2) + "\n");
}

void finishFrameSet(const Frame& frame, const fs::path& folder, const OutputOptions& options,
                    const std::vector<WrittenFile>& files) {
  json j = manifestJson(frame, options, true);
  for (const WrittenFile& file : files) {
    std::error_code error;
    const auto bytes = fs::file_size(file.path, error);
    if (error) throw IoError(file.path.string() + ": written, but now unreadable: " + error.message());
    j["files"].push_back({{"name", file.path.filename().string()},
                          {"hash", fileFingerprint(file.path)},
                          {"bytes", std::size_t(bytes)},
                          {"non_finite", file.nonFinite}});
  }
  std::vector<ManifestFile> listed;
  for (const json& file : j["files"])
    listed.push_back(
        {file["name"].get<std::string>(), file["hash"].get<std::string>(), file["bytes"].get<std::size_t>()});
  j["files_hash"] = fileListHash(listed);
  writeTextAtomically(folder / kManifestName, j.dump(2) + "\n");
}

}  // namespace detail
}  // namespace headlight
