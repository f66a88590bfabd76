#pragma once
// Bytes as text, for files the tests write themselves.
#include <string>
#include <vector>

namespace headlight::test {

// RFC 4648 base64 with '=' padding, as glTF data URIs carry it.
std::string base64(const std::vector<unsigned char>& bytes);

}  // namespace headlight::test
