#pragma once
// GL and EGL enums in messages, written as their headers and specs write them.
#include <cstdio>
#include <string>

namespace headlight::detail {

inline std::string hexCode(unsigned value) {
  char text[16];
  std::snprintf(text, sizeof text, "0x%04X", value);
  return text;
}

}  // namespace headlight::detail
