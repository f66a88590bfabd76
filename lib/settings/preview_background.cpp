#include "settings/preview_background.hpp"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <string>

#include "headlight/error.hpp"

namespace headlight {

PreviewBackground parsePreviewBackground(std::string_view text) {
  const auto refuse = [&]() -> PreviewBackground {
    throw SettingsError("preview-background '" + std::string(text) +
                            "': expected sky, transparent, a colour #rrggbb, or R,G,B with each in 0..1",
                        {"preview-background"});
  };
  if (text == "sky") return {};
  if (text == "transparent") return {PreviewBackground::Kind::Transparent, {}};
  PreviewBackground background{PreviewBackground::Kind::Color, {}};
  if (text.size() == 7 && text[0] == '#') {
    for (std::size_t c = 0; c < 3; ++c) {
      unsigned value = 0;
      const char* first = text.data() + 1 + 2 * c;
      const auto [end, error] = std::from_chars(first, first + 2, value, 16);
      if (error != std::errc() || end != first + 2) return refuse();
      background.color[c] = float(value) / 255.0f;
    }
    return background;
  }
  std::size_t at = 0;
  for (std::size_t c = 0; c < 3; ++c) {
    const std::size_t comma = c < 2 ? text.find(',', at) : text.size();
    if (comma == std::string_view::npos) return refuse();
    const std::string part(text.substr(at, comma - at));
    char* end = nullptr;
    const float value = std::strtof(part.c_str(), &end);
    if (part.empty() || end != part.c_str() + part.size() || !(value >= 0.0f && value <= 1.0f)) return refuse();
    background.color[c] = value;
    at = comma + 1;
  }
  return background;
}

}  // namespace headlight
