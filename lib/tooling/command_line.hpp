#pragma once
// The command line of Headlight's tools: flags parsed against option rows
// (headlight/options.hpp) and the --help lines written from them. Part of the
// internal support library (lib/tooling) that the CLI, the Python module and
// the tests link; not in libheadlight and not installed.
#include <exception>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "headlight/error.hpp"
#include "headlight/options.hpp"

namespace headlight {

// The error's message as the command line words it: each setting the library
// names (Error::settings(), "camera 3: ...", "raise max-memory") becomes its
// flag ("--camera 3: ...", "raise --max-memory"). Other exceptions: what().
std::string commandLineMessage(const std::exception& error);

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
// A flag of another tool (F3D's: --output, --resolution, --hdri, ...) that a
// user may type for ours: what to write instead; empty for any other name.
std::string_view foreignFlagHint(std::string_view flagName);
// "on", "off", "true", "false", "yes", "no", "1", "0": a Bool row's value
// given as a separate word (--ssgi off), which would otherwise be taken for
// a scene.
bool isBoolWord(std::string_view word);
// "a,b,c" split at `separator`; an empty item (a stray, doubled or trailing
// separator) is a SettingsError naming `flag` and the list: it is a typo, not
// a request for fewer items.
std::vector<std::string> splitList(std::string_view flag, const std::string& list, char separator = ',');
}  // namespace detail

// Sets a row from the command line: `text` parsed, or without text a
// switch's `flagValue`. A SettingsError names the flag, not the setting. An
// empty text value (`--environment ""`, an unset shell variable) is refused:
// on a command line it is a mistake, never a request for the default.
template <class Target>
void setFromCommandLine(const Option<Target>& option, Target& target, const std::optional<std::string>& text,
                        bool flagValue) {
  if (text && text->empty() && option.spec.type == OptionType::Text)
    throw SettingsError("--" + std::string(option.spec.name) + ": expected " + optionValueName(option.spec) +
                        ", got an empty value");
  try {
    option.set(target, text ? parseOptionValue(option.spec, *text) : OptionValue(flagValue));
  } catch (const SettingsError& error) {
    throw SettingsError(commandLineMessage(error));
  }
}

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
    if (!found) {
      const std::string_view hint = detail::foreignFlagHint(name);
      throw SettingsError("unknown option '--" + name + "'" + (hint.empty() ? "" : ": " + std::string(hint)) +
                          " (see headlight " + std::string(command) + " --help)");
    }
    const OptionSpec& spec = found->spec;
    if (spec.type == OptionType::Switch || spec.type == OptionType::Bool) {
      if (inlineValue && (spec.type == OptionType::Switch || match.negated))
        throw SettingsError("--" + name + " takes no value");
      // --ssgi off (F3D's habit) would render the scene "off" with SSGI on.
      if (!inlineValue && i + 1 < args.size() && detail::isBoolWord(args[i + 1]))
        throw SettingsError("--" + name + " " + args[i + 1] + ": --" + name + " takes no separate value; write " +
                            (spec.type == OptionType::Bool
                                 ? "--" + std::string(spec.name) + " or --no-" + std::string(spec.name) + " (or --" +
                                       name + "=" + args[i + 1] + ")"
                                 : "--" + name + " alone"));
      setFromCommandLine(*found, target, inlineValue, !match.negated);
      continue;
    }
    if (!inlineValue) {
      if (i + 1 >= args.size()) throw SettingsError("--" + name + " needs a value (" + optionValueName(spec) + ")");
      inlineValue = args[++i];
    }
    setFromCommandLine(*found, target, inlineValue, false);
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

}  // namespace headlight
