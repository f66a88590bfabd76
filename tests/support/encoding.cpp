#include "support/encoding.hpp"

#include <cstdint>

namespace headlight::test {

std::string base64(const std::vector<unsigned char>& bytes) {
  static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string text;
  for (std::size_t at = 0; at < bytes.size(); at += 3) {
    const std::uint32_t group = (std::uint32_t(bytes[at]) << 16) |
                                (at + 1 < bytes.size() ? std::uint32_t(bytes[at + 1]) << 8 : 0u) |
                                (at + 2 < bytes.size() ? std::uint32_t(bytes[at + 2]) : 0u);
    for (std::size_t sextet = 0; sextet < 4; ++sextet)
      text += at + sextet <= bytes.size() ? kAlphabet[(group >> (18 - 6 * sextet)) & 63] : '=';
  }
  return text;
}

}  // namespace headlight::test
