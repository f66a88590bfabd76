#pragma once
// Images written the way io/atomic_file.hpp writes every file (temporary
// name, then rename), by OpenImageIO. Only code inside the image module
// (lib/image_io/image_module.hpp) includes this.
#include <OpenImageIO/imagebuf.h>

#include <filesystem>

namespace headlight::detail {

// `buffer` written with `spec` (its format decides the pixel type) by
// OpenImageIO's writer named `format` ("openexr", "png"). Throws IoError.
void writeImageAtomically(const std::filesystem::path& path, const OIIO::ImageBuf& buffer, const OIIO::ImageSpec& spec,
                          const char* format);

// `pixels` (of `pixelType`, interleaved, rows top first) written with
// `spec` by the writer named `format`, without an ImageBuf copy.
void writePixelsAtomically(const std::filesystem::path& path, const void* pixels, OIIO::TypeDesc pixelType,
                           const OIIO::ImageSpec& spec, const char* format);

}  // namespace headlight::detail
