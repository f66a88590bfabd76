#pragma once
// The image module: every use of OpenImageIO (EXR and PNG writing, EXR
// metadata reading, image diff, glTF texture decoding) is built into
// libheadlight-image-io.so and loaded with dlopen on first use.
//
// Why: OpenImageIO brings about 260 shared libraries (ffmpeg, OpenCV, DCMTK,
// ...) whose dynamic linking costs about 0.3 s of CPU before main() on the
// 2-core reference machine (docs/BENCHMARKS.md, "Start-up"). Linked
// directly, `headlight --version` paid it; loaded here, a command that
// writes no image never pays it, and `render` loads it on a second thread
// while the first renders (headlight::preloadImageIo).
//
// The public functions it implements (writeFrame, writeExr, writePreview,
// readSettingAttributes, diffImages, diffDirectories, writeDiffImages and
// detail::decodeTexture, detail::decodeEnvironment) keep their declarations; in the library and the CLI
// they are forwarders (image_module.cpp) to the module's table below.
#include <cstdint>
#include <filesystem>
#include <string>

#include "headlight/diff.hpp"
#include "headlight/output.hpp"
#include "image_io/environment_decode.hpp"
#include "image_io/texture_decode.hpp"

namespace headlight::detail {

// Bumped whenever the table or a type crossing it changes: a module from
// another build is refused, not called.
// 2: DiffOptions::maxMemoryMiB, WrittenFile::saturatedPixels; 3: decodeEnvironment; 4: OutputOptions::waitForFolder;
// 5: OutputOptions::waitForFolderSeconds, DiffOptions::maxFlipExposures; 6: Frame::scenePose;
// 7: OutputOptions::pngTargets, RenderSettings::previewBackground; 8: RenderSettings::antialiasSamples,
// antialiasSsgi, Frame::litForeground; 9: Frame::ids, Frame::idNames, TextureDecodeLimits::byteBudget, refusedBy
inline constexpr std::uint32_t kImageModuleAbi = 9;

struct ImageModuleTable {
  std::uint32_t abi;
  std::uint32_t tableSize;  // sizeof(ImageModuleTable) as the module saw it
  decltype(&headlight::writeFrame) writeFrame;
  decltype(&headlight::writeExr) writeExr;
  decltype(&headlight::writePreview) writePreview;
  decltype(&headlight::readSettingAttributes) readSettingAttributes;
  decltype(&headlight::diffImages) diffImages;
  decltype(&headlight::diffDirectories) diffDirectories;
  decltype(&headlight::writeDiffImages) writeDiffImages;
  decltype(&detail::decodeTexture) decodeTexture;
  decltype(&detail::decodeEnvironment) decodeEnvironment;
};

// The module's one exported symbol.
inline constexpr const char* kImageModuleEntry = "headlightImageModuleTable";
using ImageModuleEntry = const ImageModuleTable* (*)();

// The file name; it is looked for (first hit wins) in $HEADLIGHT_IMAGE_MODULE
// (a full path), beside the binary that holds this code (the build tree,
// libheadlight.so's folder), in headlight/ under that folder, in the parent
// folder (tests and the Python module in the build tree), in
// ../<libdir>/headlight/ (an installed CLI, wherever the tree was moved), and
// in <prefix>/<libdir>/headlight/.
inline constexpr const char* kImageModuleFile = "libheadlight-image-io.so";

// The loaded table; loads the module on the first call (thread-safe).
// Throws IoError naming every path tried and dlopen's reason.
const ImageModuleTable& imageModule();

}  // namespace headlight::detail
