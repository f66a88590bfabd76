#pragma once
// Writing frames to disk through OpenImageIO: one EXR per target (float32
// for position and depth, half for the rest) with the metadata a regression
// diff needs, and a tonemapped preview.png. Every file is written to a
// temporary name in the same folder and renamed into place, so a crash or
// Ctrl-C never leaves a half-written file under a final name.
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "headlight/export.hpp"
#include "headlight/frame.hpp"

namespace headlight HEADLIGHT_PUBLIC {

struct WrittenFile {
  std::filesystem::path path;
  std::string summary;  // one line: size, type, channels, per-channel range
};

// Writes every target of `frame` as <outDir>/<target>.exr and preview.png.
// Creates outDir if needed. Throws IoError naming the file.
std::vector<WrittenFile> writeFrame(const Frame& frame, const std::filesystem::path& outDir);

// Extra string attributes for an EXR, e.g. {"headlight:reference:samples", "4096"}.
using ExrAttributes = std::vector<std::pair<std::string, std::string>>;

// One target as EXR with the frame's metadata (and `extra`); `halfFloat`
// selects half.
WrittenFile writeExr(const Frame& frame, const ImageF& image, const std::filesystem::path& path, bool halfFloat,
                     const ExrAttributes& extra = {});

// Every EXR records each render setting as used (auto values resolved) as
// the string attribute headlight:setting:<row name> (settingsAsText).
inline constexpr std::string_view kSettingAttributePrefix = "headlight:setting:";
// Those attributes of `exr`, by row name: applySettingsText(settings, ...)
// re-creates the settings a file was rendered with. Throws IoError.
std::map<std::string, std::string> readSettingAttributes(const std::filesystem::path& exr);

// The lit image tonemapped (frame.settings.tonemap, .exposure) to 8-bit sRGB.
WrittenFile writePreview(const Frame& frame, const std::filesystem::path& path);

// Tone curves on linear radiance, exposed for tests.
float tonemapAces(float x);      // Narkowicz's fit of the ACES filmic curve
float tonemapReinhard(float x);  // x / (1 + x)

}  // namespace HEADLIGHT_PUBLIC
