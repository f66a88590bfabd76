#pragma once
// Uniform-block members that carry a render setting unchanged are named once,
// with the setting's row, in glsl/shared_layout.h (HL_SETTING_FIELDS), and
// filled from the settings table here: a setting that reaches a shader needs
// its row (settings.hpp/.cpp), its block member with its HL_SETTING_FIELDS
// line, and the shader, and no line in its pass.
#include <string_view>
#include <type_traits>

#include "headlight/settings.hpp"
#include "shared_layout.h"

namespace headlight {

// The value of the setting row `name` in `settings` as a number (a Bool row
// gives 0 or 1). `settings` must be resolved: an auto value is a
// SettingsError naming the row, as are a Text or Choice row and an unknown
// name.
double settingNumber(const RenderSettings& settings, std::string_view name);

// Sets every member of `block` that HL_SETTING_FIELDS lists for its type.
template <class Block>
void fillSettingFields(Block& block, const RenderSettings& settings) {
#define HL_FILL_SETTING_FIELD(BlockType, member, row)                                 \
  if constexpr (std::is_same_v<Block, gpu::BlockType>)                                \
    block.member = static_cast<std::remove_reference_t<decltype(block.member)>>(      \
        settingNumber(settings, #row));
  HL_SETTING_FIELDS(HL_FILL_SETTING_FIELD)
#undef HL_FILL_SETTING_FIELD
}

}  // namespace headlight
