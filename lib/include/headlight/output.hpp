#pragma once
// Writing frames to disk through OpenImageIO: one EXR per target (float32
// for position and depth, half for the rest) with the metadata a regression
// diff needs, a tonemapped preview.png, and a frame.json manifest.
//
// Every file is written to a temporary name in the same folder and renamed
// into place, so a crash or Ctrl-C never leaves a half-written file under a
// final name. A folder is a *set*: writeFrame first replaces frame.json with
// one that says "incomplete", then writes the files, then writes frame.json
// with each file's hash last. After any kill the folder holds the complete
// old set, the complete new set, or a set whose manifest says it is
// incomplete (checkFrameSet tells which; headlight diff refuses the last).
#include <cstddef>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "headlight/export.hpp"
#include "headlight/frame.hpp"

namespace headlight HEADLIGHT_PUBLIC {

struct WrittenFile {
  std::filesystem::path path;
  // One line: size, type, channels, per-channel range of the finite values,
  // and the count of non-finite values (NaN, +-inf) before any clamping.
  std::string summary;
  std::size_t nonFinite = 0;  // non-finite values found (clamped ones included)
  std::size_t bytes = 0;      // the file's size on disk
  // Pixels of a half-float target with a channel at half's largest value
  // (65504) or beyond: the GPU's half target clamped them (saturated light).
  std::size_t saturatedPixels = 0;
};

// OpenEXR's lossless compressions (b44, dwa and pxr24 lose data and are not
// offered). Measured in docs/BENCHMARKS.md ("Output compression").
enum class ExrCompression { None, Rle, Zips, Zip, Piz };
std::span<const std::string_view> exrCompressionNames();  // "none", "rle", "zips", "zip", "piz"
std::string_view exrCompressionName(ExrCompression compression);

// What a target with NaN or inf values does: refuse the whole set (an
// IoError naming the target and the count; nothing of the set is written) or
// replace each value (NaN -> 0, +-inf -> the largest finite value of the
// file's storage) and say how many in the summary.
enum class NonFinitePolicy { Error, Clamp };

struct OutputOptions {
  // Target names (frameTargets()) and "preview" to write; empty: all of them.
  std::vector<std::string> targets;
  // Frame targets also written as <target>.png, each through its row's look
  // (FrameTarget::png: normals as colours, depth through viridis, ...); a
  // target the frame lacks is left out, as its EXR is.
  std::vector<std::string> pngTargets;
  ExrCompression compression = ExrCompression::Zip;  // docs/BENCHMARKS.md: smallest, and faster than zips and piz
  NonFinitePolicy nonFinite = NonFinitePolicy::Error;
  int threads = 0;  // files encoded at once; 0: one per hardware thread
  // Recorded in frame.json as "job": what a caller needs to decide later
  // whether this set is what it would render now (headlight render --resume).
  std::string jobHash;
  // The folder is locked while the set is written (flock on the folder, as
  // the CLI's renders do): a folder another process is writing is an
  // IoError at once naming that process, or, with this set, waited for up
  // to waitForFolderSeconds (then an IoError naming it).
  bool waitForFolder = false;
  double waitForFolderSeconds = 600.0;
};

// The names OutputOptions::targets accepts: every frame target and "preview".
std::vector<std::string_view> outputTargetNames();

// Writes the frame's targets as <outDir>/<target>.exr, preview.png and
// frame.json (last), holding the folder's lock (waitForFolder). Creates
// outDir if needed, and first removes temporary
// files there whose writing process is gone (left by a killed writer). Throws IoError naming the file
// (with the system's reason, e.g. "No space left on device"), or naming the
// target and the count of non-finite values under NonFinitePolicy::Error.
std::vector<WrittenFile> writeFrame(const Frame& frame, const std::filesystem::path& outDir,
                                    const OutputOptions& options = {});

// frame.json's "ids" object as JSON text: for each kind ("instance",
// "mesh", "material", "primitive") a list of {"id", "name", and where it is
// in the file}; writeFrame writes it beside ids.exr, Python's Frame.id_names
// parses it.
std::string idNamesJson(const IdNames& names);

// Extra string attributes for an EXR, e.g. {"headlight:reference:samples", "4096"}.
using ExrAttributes = std::vector<std::pair<std::string, std::string>>;

// One target as EXR with the frame's metadata (and `extra`); `halfFloat`
// selects half. Non-finite values are an IoError (see NonFinitePolicy).
WrittenFile writeExr(const Frame& frame, const ImageF& image, const std::filesystem::path& path, bool halfFloat,
                     const ExrAttributes& extra = {}, ExrCompression compression = ExrCompression::Zip,
                     NonFinitePolicy nonFinite = NonFinitePolicy::Error);

// Image files are written and read by OpenImageIO, which this library loads
// on first use (its ~260 libraries cost about 0.3 s of CPU on a 2-core
// machine). This starts that load on a background thread and returns at
// once; call it after the Context exists (glibc serialises library loading,
// and EGL loads its driver when the context is made). Optional.
void preloadImageIo();

// Every EXR records each render setting as used (auto values resolved) as
// the string attribute headlight:setting:<row name> (settingsAsText).
inline constexpr std::string_view kSettingAttributePrefix = "headlight:setting:";
// Those attributes of `exr`, by row name: applySettingsText(settings, ...)
// re-creates the settings a file was rendered with. Throws IoError.
std::map<std::string, std::string> readSettingAttributes(const std::filesystem::path& exr);

// The lit image tonemapped (frame.settings.tonemap, .exposure) to 8-bit
// sRGB, in one pass over the floats, over frame.settings.previewBackground
// (the sky as lit has it, alpha from lit's coverage, or a colour). Non-finite
// values become black.
WrittenFile writePreview(const Frame& frame, const std::filesystem::path& path);

// NaN and inf are counted and refused (or clamped) per file by writeFrame;
// headlight/finite.hpp checks a whole frame in memory (countNonFinite,
// requireFinite) for callers that do not write files.

// ---- frame sets (frame.json) ------------------------------------------------

inline constexpr std::string_view kManifestName = "frame.json";

struct ManifestFile {
  std::string name;  // file name in the folder
  std::string hash;  // 16 hex digits: XXH3-64 (libxxhash) of the bytes
  std::size_t bytes = 0;
};

struct FrameManifest {
  bool complete = false;
  std::string scene, sceneHash;
  std::string settingsHash;  // fingerprint of the resolved settings as text
  std::string jobHash;       // OutputOptions::jobHash
  std::map<std::string, std::string> settings;
  std::vector<ManifestFile> files;
};

// The folder's frame.json, or nullopt when it has none. Throws IoError for
// one that cannot be read or parsed.
std::optional<FrameManifest> readManifest(const std::filesystem::path& folder);

enum class FrameSetState {
  NoManifest,  // no frame.json: not written by writeFrame (e.g. older goldens); nothing to check
  Complete,    // frame.json lists every file, and each has the recorded size and hash
  Incomplete,  // frame.json says a write is under way, or a listed file is missing or changed
};

struct FrameSetCheck {
  FrameSetState state = FrameSetState::NoManifest;
  std::string problem;  // for Incomplete: what is missing or different
};

// Checks a folder against its frame.json (reading every listed file to hash it).
FrameSetCheck checkFrameSet(const std::filesystem::path& folder);

}  // namespace HEADLIGHT_PUBLIC
