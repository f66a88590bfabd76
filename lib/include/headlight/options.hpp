#pragma once
// Settings as rows: name, type, range, whether it may be "auto", help, bound
// to one field of a struct. The EXR metadata, settings files, embedding code
// (and Headlight's own command line) all read the rows; none keeps a list of
// its own. A row's name is the setting's name ("ssgi-samples"), which error
// messages use.
//
//   const Option<RenderSettings>& row = findOption(settingOptions(), "ssgi-samples");
//   row.set(settings, parseOptionValue(row.spec, "16"));   // range-checked
//   std::string text = formatOptionValue(row.spec, row.get(settings));
//
// A field's type decides how its value is stored: int/unsigned (Int), float
// (Float), bool (Bool), an enum whose enumerators are 0..n-1 in the order of
// the row's `choices` (Choice), std::string (Text), and std::optional<T> of
// any of those for a row that may be "auto" (std::nullopt).
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "headlight/error.hpp"
#include "headlight/export.hpp"

namespace headlight HEADLIGHT_PUBLIC {

enum class OptionType {
  Switch,  // a row without a value (a command's --verbose); setting it sets true
  Bool,    // --name / --no-name; as text on|off
  Int,     // an integer in [minimum, maximum]
  Float,   // a finite number in [minimum, maximum]
  Choice,  // one of `choices`
  Text,    // any text: a path, or a list the row's setter parses itself
};

// "auto": the row resolves it from the scene or the image (OptionSpec::autoMeaning).
struct AutoValue {
  bool operator==(const AutoValue&) const = default;
};
using OptionValue = std::variant<AutoValue, bool, std::int64_t, double, std::string>;

struct OptionSpec {
  // The setting's name: errors use it, the CLI's flag is --<name>, the EXR key
  // headlight:setting:<name>, the Python keyword <name> with '-' -> '_'.
  std::string_view name{};
  OptionType type = OptionType::Text;
  std::string_view help{};
  double minimum = 0;  // Int, Float: inclusive range
  double maximum = 0;
  std::span<const std::string_view> choices{};  // Choice: the accepted names
  std::string_view autoMeaning{};               // non-empty: "auto" is accepted, and this says what it becomes
  std::string_view valueName{};                 // Text: shown in help (e.g. "DIR"); other types derive theirs
  // Text: what the row accepts, checked wherever a value is parsed (command
  // line, settings file, EXR attributes, Python): throws SettingsError naming
  // the row for a value it refuses. Null: any text.
  void (*checkText)(std::string_view text) = nullptr;
  std::string_view example{};  // Text: a value the row accepts other than its default (the option tests set it)
};

// Parses `text` for the row: on|off, a number in range, one of the choices,
// or "auto" where allowed. Throws SettingsError: "name: expected ..., got '...'".
OptionValue parseOptionValue(const OptionSpec& spec, std::string_view text);
// Text that parseOptionValue reads back to the same value (floats keep 9
// significant digits, enough for a float to round-trip exactly).
std::string formatOptionValue(const OptionSpec& spec, const OptionValue& value);
// Throws SettingsError when `value` is of the wrong kind or out of range.
void checkOptionValue(const OptionSpec& spec, const OptionValue& value);
// What a value of the row looks like: "N", "auto|FLOAT", "fast|default|high", "DIR".
std::string optionValueName(const OptionSpec& spec);

template <class Target>
struct Option {
  OptionSpec spec;
  std::function<void(Target&, const OptionValue&)> set;  // checks the value, then stores it
  std::function<OptionValue(const Target&)> get;         // empty for write-only rows (preset)
};

// The row named `name`; throws SettingsError listing the names when none is.
template <class Target>
const Option<Target>& findOption(std::span<const Option<Target>> options, std::string_view name) {
  for (const Option<Target>& option : options)
    if (option.spec.name == name) return option;
  std::string known;
  for (const Option<Target>& option : options) (known += known.empty() ? "" : ", ") += option.spec.name;
  throw SettingsError("unknown setting '" + std::string(name) + "' (known: " + known + ")");
}

}  // namespace HEADLIGHT_PUBLIC
