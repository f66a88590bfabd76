#pragma once
// XXH3-64 (libxxhash) of a file's bytes, or of a text, as 16 hex digits:
// stable across runs and machines. Scene hashes, frame.json's file hashes
// and batch job hashes are these. fileFingerprint throws IoError.
#include <filesystem>
#include <string>
#include <string_view>

namespace headlight {

std::string fileFingerprint(const std::filesystem::path& path);
std::string textFingerprint(std::string_view text);

}  // namespace headlight
