// frame.json: what makes a folder of outputs a set that a reader can trust
// to be whole (headlight/output.hpp).
#include "output/frame_set.hpp"

#include <signal.h>

#include <cerrno>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "headlight/error.hpp"
#include "output/atomic_file.hpp"
#include "output/fingerprint.hpp"

namespace headlight {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

constexpr int kManifestVersion = 1;

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
  j["settings_hash"] = textFingerprint(settingsText);
  j["job_hash"] = options.jobHash;
  j["renderer"] = frame.glRenderer;
  j["ignored"] = frame.ignored;  // glTF features not rendered
  j["settings"] = settings;
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
  if (!fs::exists(path, error)) return std::nullopt;
  std::ifstream in(path);
  if (!in) throw IoError(path.string() + ": cannot read");
  try {
    const json j = json::parse(in);
    FrameManifest manifest;
    manifest.complete = j.at("complete").get<bool>();
    manifest.scene = j.value("scene", "");
    manifest.sceneHash = j.value("scene_hash", "");
    manifest.settingsHash = j.value("settings_hash", "");
    manifest.jobHash = j.value("job_hash", "");
    if (j.contains("settings")) manifest.settings = j.at("settings").get<std::map<std::string, std::string>>();
    for (const json& file : j.at("files"))
      manifest.files.push_back({file.at("name").get<std::string>(), file.at("hash").get<std::string>(),
                                file.at("bytes").get<std::size_t>()});
    return manifest;
  } catch (const json::exception& e) {
    throw IoError(path.string() + ": not a headlight frame manifest: " + e.what());
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

void beginFrameSet(const Frame& frame, const fs::path& folder, const OutputOptions& options) {
  writeTextAtomically(folder / kManifestName, manifestJson(frame, options, false).dump(2) + "\n");
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
  writeTextAtomically(folder / kManifestName, j.dump(2) + "\n");
}

}  // namespace detail
}  // namespace headlight
