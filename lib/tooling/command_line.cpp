#include "tooling/command_line.hpp"

#include <string_view>
#include <utility>

#include "settings/option_binding.hpp"

namespace headlight {
namespace {

// The name at `at` stands alone: not part of a longer word or path, nor
// "camera(s)", nor already a flag.
bool standsAlone(const std::string& text, std::size_t at, std::size_t length) {
  const std::size_t end = at + length;
  return (at == 0 || std::string_view(" (\n'").find(text[at - 1]) != std::string_view::npos) &&
         (end == text.size() || std::string_view(" :;,)=\n'").find(text[end]) != std::string_view::npos);
}

}  // namespace

std::string commandLineMessage(const std::exception& error) {
  std::string text = error.what();
  const auto* named = dynamic_cast<const Error*>(&error);
  if (!named) return text;
  for (const std::string& setting : named->settings()) {
    if (setting.empty()) continue;
    for (std::size_t at = text.find(setting); at != std::string::npos; at = text.find(setting, at)) {
      if (standsAlone(text, at, setting.size())) {
        text.insert(at, "--");
        at += 2;
      }
      at += setting.size();
    }
  }
  return text;
}

namespace detail {

FlagMatch matchFlag(const OptionSpec& spec, std::string_view flagName) {
  if (flagName == spec.name) return {true, false};
  if (spec.type == OptionType::Bool && flagName.size() == spec.name.size() + 3 && flagName.substr(0, 3) == "no-" &&
      flagName.substr(3) == spec.name)
    return {true, true};
  return {};
}

bool splitFlag(const std::string& arg, std::string& name, std::optional<std::string>& inlineValue) {
  if (arg.size() < 3 || arg.compare(0, 2, "--") != 0) return false;
  const auto equals = arg.find('=');
  name = arg.substr(2, equals == std::string::npos ? std::string::npos : equals - 2);
  if (equals != std::string::npos) inlineValue = arg.substr(equals + 1);
  return true;
}

std::string_view foreignFlagHint(std::string_view flagName) {
  // F3D's flags (and the like) that have a headlight answer.
  static constexpr std::pair<std::string_view, std::string_view> kHints[] = {
      {"output", "headlight writes a folder of images: --out DIR (lit.exr, preview.png, ... inside it)"},
      {"resolution", "use --width W --height H"},
      {"hdri", "use --environment FILE (an equirectangular .hdr or .exr)"},
      {"hdri-file", "use --environment FILE (an equirectangular .hdr or .exr)"},
      {"ssao", "SSGI (its ambient occlusion included) is on by default; --no-ssgi turns it off"},
      {"fxaa", "headlight has no anti-aliasing yet"},
      {"camera-position", "an explicit camera is a job file's eye, target, up and fov (docs/BATCH.md)"},
  };
  for (const auto& [name, hint] : kHints)
    if (name == flagName) return hint;
  return {};
}

std::vector<std::string> splitList(std::string_view flag, const std::string& list, char separator) {
  std::vector<std::string> items;
  std::size_t start = 0;
  while (true) {
    const std::size_t end = list.find(separator, start);
    std::string item = list.substr(start, end == std::string::npos ? std::string::npos : end - start);
    if (item.empty())
      throw SettingsError("--" + std::string(flag) + " '" + list + "': an empty item (a stray '" +
                          std::string(1, separator) + "'?)");
    items.push_back(std::move(item));
    if (end == std::string::npos) return items;
    start = end + 1;
  }
}

bool isBoolWord(std::string_view word) {
  for (std::string_view value : {"on", "off", "true", "false", "yes", "no", "1", "0"})
    if (word == value) return true;
  return false;
}

std::string helpLine(const OptionSpec& spec, const std::optional<OptionValue>& defaultValue) {
  constexpr std::size_t kHelpColumn = 34;
  std::string left = spec.type == OptionType::Bool ? "  --[no-]" : "  --";
  left += spec.name;
  if (const std::string value = optionValueName(spec); !value.empty()) (left += " ") += value;
  left +=
      left.size() < kHelpColumn ? std::string(kHelpColumn - left.size(), ' ') : "\n" + std::string(kHelpColumn, ' ');
  std::string line = left + std::string(spec.help);
  if (!spec.autoMeaning.empty()) line += " (auto: " + std::string(spec.autoMeaning) + ")";
  if (spec.type == OptionType::Int || spec.type == OptionType::Float) line += " [" + optionRangeText(spec) + "]";
  // An empty text default says nothing; such rows say their default in their help.
  const bool emptyText = defaultValue && std::holds_alternative<std::string>(*defaultValue) &&
                         std::get<std::string>(*defaultValue).empty();
  if (defaultValue && !emptyText) line += " [default: " + formatOptionValue(spec, *defaultValue) + "]";
  return line + "\n";
}

}  // namespace detail
}  // namespace headlight
