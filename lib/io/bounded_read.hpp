#pragma once
// Every input file read whole into memory (settings files, job files,
// frame.json) goes through here: only a regular file is opened (a FIFO, a
// device such as /dev/zero or a folder is refused before any read, so
// nothing blocks or grows without end), and at most a stated number of
// bytes is read. Each refusal is an IoError naming the file, what it was
// read as and the limit.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace headlight::detail {

// Sizes a file read whole may have. Each is far above what Headlight
// writes (a tune settings file is about 2 KB, a frame.json about 4 KB) and
// far below what would strain memory.
inline constexpr std::uint64_t kMaxSettingsFileBytes = std::uint64_t(1) << 20;  // 1 MiB
inline constexpr std::uint64_t kMaxJobFileBytes = std::uint64_t(256) << 20;     // 256 MiB: ~1M jobs of 256 bytes
inline constexpr std::uint64_t kMaxJobLineBytes = std::uint64_t(1) << 20;       // 1 MiB: one job line
inline constexpr std::uint64_t kMaxManifestBytes = std::uint64_t(16) << 20;     // 16 MiB: frame.json

// "a FIFO", "a folder", "a character device", ... for a file that is not
// regular; empty for a regular file (symbolic links followed). Never blocks.
std::string nonRegularKind(const std::filesystem::path& path);

// The whole of `path`, read only when it is a regular file of at most
// `maxBytes` bytes. `what` says what the file was read as ("the settings
// file"). Throws IoError: "<path>: cannot read <what>: <problem>".
std::string readRegularFile(const std::filesystem::path& path, std::uint64_t maxBytes, std::string_view what);

// "1.5 MiB", "300 bytes": a size for messages.
std::string byteSizeText(std::uint64_t bytes);

// At most `maxChars` characters of `text` for a message, control and
// non-ASCII bytes (NUL included) written as \xNN, "..." when cut: an error
// never echoes a whole hostile input, nor stops at an embedded NUL.
std::string excerpt(std::string_view text, std::size_t maxChars = 60);

}  // namespace headlight::detail
