#pragma once
// Every file the project writes goes through here: into a hidden temporary
// name in the same folder (so the rename is atomic), then renamed over the
// final name. A crash, a Ctrl-C or an error never leaves a half-written file
// under a name a reader takes for a result; a kill -9 may leave the hidden
// temporary, which removeStaleTemporaries (output/frame_set.hpp) clears once
// its process is gone.
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>

namespace headlight::detail {

// Calls `write` with the temporary path, then renames it to `path`. On any
// exception the temporary is removed and the exception passes on; a failed
// rename is an IoError naming `path`.
void writeAtomically(const std::filesystem::path& path,
                     const std::function<void(const std::filesystem::path& temporary)>& write);

// A text file. Throws IoError.
void writeTextAtomically(const std::filesystem::path& path, std::string_view text);

// Why a write failed: the writer's own message, else the system's (errno
// captured by the caller right after the failure), plus the free space when
// the disk is (nearly) full.
std::string writeFailureReason(const std::filesystem::path& path, std::string writerMessage, int savedErrno);

// The temporary name's parts: ".<name>.<host>.<pid>-<n>.tmp".
std::string temporaryHostTag();  // this machine's host name, dots replaced

}  // namespace headlight::detail
