// preview.png's background (RenderSettings::previewBackground) as the
// writer uses it, parsed from its text.
#pragma once

#include <array>
#include <string_view>

namespace headlight {

struct PreviewBackground {
  enum class Kind { Sky, Transparent, Color };
  Kind kind = Kind::Sky;
  std::array<float, 3> color{};  // Kind::Color: display (sRGB-encoded) values, 0..1
};

// "sky", "transparent", "#rrggbb" or "R,G,B" (0..1 each); anything else is a
// SettingsError naming preview-background and the forms it takes.
PreviewBackground parsePreviewBackground(std::string_view text);

}  // namespace headlight
