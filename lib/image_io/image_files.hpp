#pragma once
// Image files as headlight diff reads them (OpenImageIO, in the image
// module): only regular files, the header first so that declared sizes can be
// checked before any pixel is decoded, then the pixels as float. Also the
// small helpers the comparison and the written difference images share.
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imageio.h>

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "headlight/diff.hpp"

namespace headlight::diffio {

// Opens `path` for its header; null, with `problem` set, for a missing or
// non-regular file, one OpenImageIO cannot read, a deep or volume image, or
// one declaring no pixels.
std::unique_ptr<OIIO::ImageInput> openImage(const std::filesystem::path& path, std::string& problem);
// Bytes of the image as float, from its header (no overflow: each factor < 2^31).
double declaredFloatBytes(const OIIO::ImageSpec& spec);
// Subimage 0 as float, through ImageInput (not ImageBuf's shared ImageCache,
// which may hand back an older copy of a file rewritten under the same name).
std::optional<OIIO::ImageBuf> readImage(OIIO::ImageInput& input, const std::filesystem::path& path,
                                        std::string& problem);
// openImage then readImage; `integer`: whether the file stores integer pixels
// (display-encoded values, which the Flip metric decodes as sRGB).
std::optional<OIIO::ImageBuf> loadImage(const std::filesystem::path& path, std::string& problem, bool& integer);

// Throws Error naming the ImageBufAlgo operation when `image` holds an error.
void checkOk(const OIIO::ImageBuf& image, const char* operation);
// The indices of R, G and B among `channels` (by name, last component: "R"
// or "<layer>.R"), or empty when one is missing.
std::vector<int> rgbChannels(const std::vector<std::string>& channels);

}  // namespace headlight::diffio
