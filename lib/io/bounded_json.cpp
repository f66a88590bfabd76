#include "io/bounded_json.hpp"

#include <set>
#include <string>
#include <vector>

#include "io/bounded_read.hpp"

namespace headlight::detail {

nlohmann::ordered_json parseBoundedJson(std::string_view text) {
  using json = nlohmann::ordered_json;
  std::vector<std::set<std::string>> keysByObject;  // the objects open at this point, innermost last
  const json::parser_callback_t depthCheck = [&keysByObject](int depth, json::parse_event_t event, json& parsed) {
    if ((event == json::parse_event_t::object_start || event == json::parse_event_t::array_start) &&
        depth >= kMaxJsonDepth)
      throw JsonError("JSON nests deeper than " + std::to_string(kMaxJsonDepth) + " levels (the limit for scenes too)");
    if (event == json::parse_event_t::object_start) keysByObject.emplace_back();
    if (event == json::parse_event_t::object_end && !keysByObject.empty()) keysByObject.pop_back();
    if (event == json::parse_event_t::key && !keysByObject.empty() && parsed.is_string() &&
        !keysByObject.back().insert(parsed.get<std::string>()).second)
      throw JsonError("the key \"" + excerpt(parsed.get<std::string>()) + "\" appears twice in one object");
    return true;
  };
  try {
    return json::parse(text.begin(), text.end(), depthCheck);
  } catch (const json::exception& e) {
    throw JsonError("not valid JSON: " + excerpt(jsonErrorText(e), 160));
  }
}

std::string jsonErrorText(const nlohmann::json::exception& error) {
  std::string text = error.what();
  if (const std::size_t end = text.find("] "); text.rfind("[json.exception.", 0) == 0 && end != std::string::npos)
    text.erase(0, end + 2);
  constexpr std::string_view kKey = "key '", kNotFound = "' not found";
  if (text.size() > kKey.size() + kNotFound.size() && text.rfind(kKey, 0) == 0 && text.ends_with(kNotFound))
    text = "no \"" + text.substr(kKey.size(), text.size() - kKey.size() - kNotFound.size()) + "\" field";
  return text;
}

}  // namespace headlight::detail
