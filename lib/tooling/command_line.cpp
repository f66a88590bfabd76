#include "tooling/command_line.hpp"

#include "settings/option_binding.hpp"

namespace headlight::detail {

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
  if (defaultValue) line += " [default: " + formatOptionValue(spec, *defaultValue) + "]";
  return line + "\n";
}

}  // namespace headlight::detail
