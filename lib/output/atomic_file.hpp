#pragma once
// Every file the project writes goes through here: into a hidden temporary
// name in the same folder (so the rename is atomic), then renamed over the
// final name. A crash, a Ctrl-C or an error never leaves a half-written file
// under a name a reader takes for a result.
#include <filesystem>
#include <functional>
#include <string_view>

#include <OpenImageIO/imagebuf.h>

namespace headlight::detail {

// Calls `write` with the temporary path, then renames it to `path`. On any
// exception the temporary is removed and the exception passes on; a failed
// rename is an IoError naming `path`.
void writeAtomically(const std::filesystem::path& path,
                     const std::function<void(const std::filesystem::path& temporary)>& write);

// `buffer` written with `spec` (its format decides the pixel type) by
// OpenImageIO's writer named `format` ("openexr", "png"). Throws IoError.
void writeImageAtomically(const std::filesystem::path& path, const OIIO::ImageBuf& buffer, const OIIO::ImageSpec& spec,
                          const char* format);

// A text file. Throws IoError.
void writeTextAtomically(const std::filesystem::path& path, std::string_view text);

}  // namespace headlight::detail
