#include "io/message_text.hpp"

#include <algorithm>

namespace headlight {

std::string quotedName(std::string_view text) {
  constexpr std::size_t kShown = 80;
  if (text.size() <= kShown) return "'" + std::string(text) + "'";
  return "'" + std::string(text.substr(0, kShown)) + "...' (" + std::to_string(text.size()) + " bytes)";
}

std::string quotedList(const std::vector<std::string>& items) {
  constexpr std::size_t kShown = 20;
  std::string list;
  for (std::size_t i = 0; i < std::min(items.size(), kShown); ++i) list += (i == 0 ? "" : ", ") + quotedName(items[i]);
  if (items.size() > kShown) list += " ... and " + std::to_string(items.size() - kShown) + " more";
  return list;
}

}  // namespace headlight
