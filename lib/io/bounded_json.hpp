#pragma once
// JSON read from untrusted text at a cost bounded by the text: nesting past
// kMaxJsonDepth is refused as the parser meets it (nlohmann's parser does not
// recurse, but dump() and error texts over a deeper value would), and so is a
// key given twice in one object (JSON parsers disagree on which one wins, so
// the text does not say what it asks for). Job lines parse with it; glTF files
// scan their text against the same depth before tinygltf, which recurses.
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <string_view>

namespace headlight::detail {

// Deeper JSON than this is refused. glTF's own schema nests 7 levels;
// extras and extensions in real files stay well below 32.
inline constexpr int kMaxJsonDepth = 64;

// What parseBoundedJson refuses; the message names the rule, not the source,
// which the caller knows.
struct JsonError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

nlohmann::ordered_json parseBoundedJson(std::string_view text);

// nlohmann-json's message for a person: without its "[json.exception.
// parse_error.101] " tag, and a missing key said as a missing field
// ("no \"complete\" field" for "key 'complete' not found").
std::string jsonErrorText(const nlohmann::json::exception& error);

}  // namespace headlight::detail
