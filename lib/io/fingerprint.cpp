// Content fingerprints (io/fingerprint.hpp): scene hashes in the EXR
// metadata, frame.json's file hashes and --resume's job hashes. XXH3-64
// from Debian's libxxhash: stable across runs, builds and machines, and
// without OpenImageIO, so that hashing a scene never loads the image module.
#include <xxhash.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <vector>

#include "headlight/error.hpp"
#include "io/bounded_read.hpp"
#include "io/fingerprint.hpp"

namespace headlight {

std::string textFingerprint(std::string_view text) {
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(XXH3_64bits(text.data(), text.size())));
  return hex;
}

// Streamed in blocks: a file of any size (a 20 GiB one named in a
// frame.json) is hashed in constant memory. Only regular files: a FIFO or
// /dev/zero in place of an output would never end.
std::string fileFingerprint(const std::filesystem::path& path) {
  if (const std::string kind = detail::nonRegularKind(path); !kind.empty())
    throw IoError(path.string() + ": cannot hash it: is " + kind + ", expected a regular file");
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!file) throw IoError(path.string() + ": cannot read to hash it: " + std::strerror(errno));
  std::unique_ptr<XXH3_state_t, XXH_errorcode (*)(XXH3_state_t*)> state(XXH3_createState(), &XXH3_freeState);
  if (!state || XXH3_64bits_reset(state.get()) != XXH_OK) throw IoError(path.string() + ": cannot start a hash");
  std::vector<char> block(std::size_t(1) << 20);
  for (std::size_t got; (got = std::fread(block.data(), 1, block.size(), file.get())) > 0;)
    XXH3_64bits_update(state.get(), block.data(), got);
  if (std::ferror(file.get())) throw IoError(path.string() + ": reading failed while hashing it");
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(XXH3_64bits_digest(state.get())));
  return hex;
}

}  // namespace headlight
