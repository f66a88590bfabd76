#pragma once
// One option system for the library and every command. An option is a row:
// name, type, range, whether it may be "auto", help, bound to one field of a
// struct. The command-line parser, --help, the EXR metadata, bench sweeps and
// embedding code all read rows; none keeps a list of its own.
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
#include <type_traits>
#include <variant>
#include <vector>

#include "headlight/error.hpp"
#include "headlight/export.hpp"

namespace headlight HEADLIGHT_PUBLIC {

enum class OptionType {
  Switch,  // a flag without a value (--verbose); sets true
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
  std::string_view name{};  // the flag without "--"; EXR key headlight:setting:<name>; Python: '-' -> '_'
  OptionType type = OptionType::Text;
  std::string_view help{};
  double minimum = 0;  // Int, Float: inclusive range
  double maximum = 0;
  std::span<const std::string_view> choices{};  // Choice: the accepted names
  std::string_view autoMeaning{};               // non-empty: "auto" is accepted, and this says what it becomes
  std::string_view valueName{};                 // Text: shown in help (e.g. "DIR"); other types derive theirs
};

// Parses `text` for the row: on|off, a number in range, one of the choices,
// or "auto" where allowed. Throws SettingsError: "--name: expected ..., got '...'".
OptionValue parseOptionValue(const OptionSpec& spec, std::string_view text);
// Text that parseOptionValue reads back to the same value (floats keep 9
// significant digits, enough for a float to round-trip exactly).
std::string formatOptionValue(const OptionSpec& spec, const OptionValue& value);
// Throws SettingsError when `value` is of the wrong kind or out of range.
void checkOptionValue(const OptionSpec& spec, const OptionValue& value);
// What the help shows after the flag: "N", "auto|FLOAT", "fast|default|high", "DIR".
std::string optionValueName(const OptionSpec& spec);

template <class Target>
struct Option {
  OptionSpec spec;
  std::function<void(Target&, const OptionValue&)> set;  // checks the value, then stores it
  std::function<OptionValue(const Target&)> get;         // empty for write-only rows (--help, --preset)
};

namespace detail {

template <class T>
struct IsOptional : std::false_type {};
template <class T>
struct IsOptional<std::optional<T>> : std::true_type {};

template <class Field>
OptionValue toOptionValue(const Field& field) {
  if constexpr (IsOptional<Field>::value)
    return field ? toOptionValue(*field) : OptionValue(AutoValue{});
  else if constexpr (std::is_same_v<Field, bool>)
    return field;
  else if constexpr (std::is_enum_v<Field>)
    return std::int64_t(field);  // the choice's index
  else if constexpr (std::is_integral_v<Field>)
    return std::int64_t(field);
  else if constexpr (std::is_floating_point_v<Field>)
    return double(field);
  else
    return std::string(field);
}

template <class Field>
void fromOptionValue(const OptionValue& value, Field& field) {
  if constexpr (IsOptional<Field>::value) {
    if (std::holds_alternative<AutoValue>(value)) {
      field.reset();
    } else {
      typename Field::value_type inner{};
      fromOptionValue(value, inner);
      field = inner;
    }
  } else if constexpr (std::is_same_v<Field, bool>) {
    field = std::get<bool>(value);
  } else if constexpr (std::is_enum_v<Field> || std::is_integral_v<Field>) {
    field = Field(std::get<std::int64_t>(value));
  } else if constexpr (std::is_floating_point_v<Field>) {
    field = Field(std::get<double>(value));
  } else {
    field = std::get<std::string>(value);
  }
}

// Choice rows carry the name in parseOptionValue's result; fields hold the index.
OptionValue choiceToIndex(const OptionSpec& spec, const OptionValue& value);
OptionValue indexToChoice(const OptionSpec& spec, const OptionValue& value);

}  // namespace detail

// A row bound to the field `access` returns (a generic lambda, so it serves
// const and non-const targets): [](auto& s) -> auto& { return s.ssgi.radius; }.
template <class Target, class Access>
Option<Target> bindOption(OptionSpec spec, Access access) {
  return {spec,
          [spec, access](Target& target, const OptionValue& value) {
            checkOptionValue(spec, value);
            detail::fromOptionValue(detail::choiceToIndex(spec, value), access(target));
          },
          [spec, access](const Target& target) {
            return detail::indexToChoice(spec, detail::toOptionValue(access(target)));
          }};
}

// A row whose setter does its own work (a preset, a list, a path).
template <class Target>
Option<Target> actionOption(OptionSpec spec, std::function<void(Target&, const OptionValue&)> action,
                            std::function<OptionValue(const Target&)> get = {}) {
  return {spec,
          [spec, action](Target& target, const OptionValue& value) {
            checkOptionValue(spec, value);
            action(target, value);
          },
          std::move(get)};
}

// Rows of an inner struct as rows of the struct that holds it.
template <class Outer, class Inner>
std::vector<Option<Outer>> liftOptions(std::span<const Option<Inner>> options, Inner Outer::*member) {
  std::vector<Option<Outer>> lifted;
  for (const Option<Inner>& option : options) {
    Option<Outer> row{
        option.spec, [set = option.set, member](Outer& o, const OptionValue& v) { set(o.*member, v); }, {}};
    if (option.get) row.get = [get = option.get, member](const Outer& o) { return get(o.*member); };
    lifted.push_back(std::move(row));
  }
  return lifted;
}

// The row named `name`; throws SettingsError listing the names when none is.
template <class Target>
const Option<Target>& findOption(std::span<const Option<Target>> options, std::string_view name) {
  for (const Option<Target>& option : options)
    if (option.spec.name == name) return option;
  std::string known;
  for (const Option<Target>& option : options) (known += known.empty() ? "" : ", ") += option.spec.name;
  throw SettingsError("unknown setting '" + std::string(name) + "' (known: " + known + ")");
}

namespace detail {
// "--name=value" / "--name" / "--no-name" against one spec: how it matches.
struct FlagMatch {
  bool matches = false;
  bool negated = false;  // --no-name of a Bool row
};
FlagMatch matchFlag(const OptionSpec& spec, std::string_view flagName);
// Splits "--name=value" into name and value; false if `arg` is not a long flag.
bool splitFlag(const std::string& arg, std::string& name, std::optional<std::string>& inlineValue);
std::string helpLine(const OptionSpec& spec, const std::optional<OptionValue>& defaultValue);
}  // namespace detail

// Parses a command line against `options`; returns the positional
// arguments in order. Values come as --name VALUE or --name=VALUE; Bool rows
// take --name, --no-name or --name=on|off; Switch rows take no value. Throws
// SettingsError naming the flag for an unknown flag or a bad value.
template <class Target>
std::vector<std::string> parseCommandLine(const std::vector<std::string>& args, std::span<const Option<Target>> options,
                                          Target& target, std::string_view command) {
  std::vector<std::string> positional;
  for (std::size_t i = 0; i < args.size(); ++i) {
    std::string name;
    std::optional<std::string> inlineValue;
    if (!detail::splitFlag(args[i], name, inlineValue)) {
      if (args[i].size() > 1 && args[i][0] == '-')
        throw SettingsError("unknown option '" + args[i] + "' (see headlight " + std::string(command) + " --help)");
      positional.push_back(args[i]);
      continue;
    }
    const Option<Target>* found = nullptr;
    detail::FlagMatch match;
    for (const Option<Target>& option : options)
      if ((match = detail::matchFlag(option.spec, name)).matches) {
        found = &option;
        break;
      }
    if (!found)
      throw SettingsError("unknown option '--" + name + "' (see headlight " + std::string(command) + " --help)");
    const OptionSpec& spec = found->spec;
    if (spec.type == OptionType::Switch || spec.type == OptionType::Bool) {
      if (inlineValue && (spec.type == OptionType::Switch || match.negated))
        throw SettingsError("--" + name + " takes no value");
      found->set(target, inlineValue ? parseOptionValue(spec, *inlineValue) : OptionValue(!match.negated));
      continue;
    }
    if (!inlineValue) {
      if (i + 1 >= args.size()) throw SettingsError("--" + name + " needs a value (" + optionValueName(spec) + ")");
      inlineValue = args[++i];
    }
    found->set(target, parseOptionValue(spec, *inlineValue));
  }
  return positional;
}

// One help line per row, with the default read from `defaults`.
template <class Target>
std::string optionHelp(std::span<const Option<Target>> options, const Target& defaults) {
  std::string text;
  for (const Option<Target>& option : options) {
    std::optional<OptionValue> value;
    if (option.get && option.spec.type != OptionType::Switch) value = option.get(defaults);
    text += detail::helpLine(option.spec, value);
  }
  return text;
}

}  // namespace HEADLIGHT_PUBLIC
