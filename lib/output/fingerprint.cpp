// Content fingerprints (output/fingerprint.hpp): scene hashes in the EXR
// metadata, frame.json's file hashes and --resume's job hashes. XXH3-64
// from Debian's libxxhash: stable across runs, builds and machines, and
// without OpenImageIO, so that hashing a scene never loads the image module.
#include <xxhash.h>

#include <cstdio>
#include <fstream>
#include <iterator>

#include "headlight/error.hpp"
#include "output/fingerprint.hpp"

namespace headlight {

std::string textFingerprint(std::string_view text) {
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(XXH3_64bits(text.data(), text.size())));
  return hex;
}

std::string fileFingerprint(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path.string() + ": cannot read to hash it");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return textFingerprint(bytes);
}

}  // namespace headlight
