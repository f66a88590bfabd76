#include "io/message_text.hpp"

#include <algorithm>

namespace headlight {

std::string quotedName(std::string_view text) {
  constexpr std::size_t kShown = 80;
  if (text.size() <= kShown) return "'" + std::string(text) + "'";
  return "'" + std::string(text.substr(0, kShown)) + "...' (" + std::to_string(text.size()) + " bytes)";
}

std::string joinedList(const std::vector<std::string>& shown, std::size_t total) {
  std::string list;
  for (const std::string& item : shown) list += (list.empty() ? "" : ", ") + item;
  if (total > shown.size()) list += " ... and " + std::to_string(total - shown.size()) + " more";
  return list;
}

std::string quotedList(const std::vector<std::string>& items) {
  std::vector<std::string> shown;
  for (std::size_t i = 0; i < std::min(items.size(), kListShown); ++i) shown.push_back(quotedName(items[i]));
  return joinedList(shown, items.size());
}

std::string oneLine(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  for (std::string::size_type newline; (newline = text.find('\n')) != std::string::npos;)
    text.replace(newline, 1, "; ");
  return text;
}

}  // namespace headlight
