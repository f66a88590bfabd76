#include "headlight/options.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>

#include "io/message_text.hpp"
#include "settings/option_binding.hpp"

namespace headlight {
namespace {

// Errors name the row's setting (Error::settings() lists it for front ends).
[[noreturn]] void settingError(const OptionSpec& spec, const std::string& problem) {
  throw SettingsError(std::string(spec.name) + ": " + problem, {std::string(spec.name)});
}

// Shortest text of `value` that reads back as the same double (and so the same float).
std::string formatNumber(double value) {
  char text[32];
  for (int digits = 6; digits <= 17; ++digits) {
    std::snprintf(text, sizeof text, "%.*g", digits, value);
    double back = 0;
    std::from_chars(text, text + std::char_traits<char>::length(text), back);
    if (back == value || float(back) == float(value)) break;
  }
  return text;
}

std::string choiceList(const OptionSpec& spec, const char* separator) {
  std::string text;
  for (std::string_view choice : spec.choices) (text += text.empty() ? "" : separator) += choice;
  return text;
}

std::string rangeText(const OptionSpec& spec) {
  if (spec.type == OptionType::Int)
    return std::to_string(std::int64_t(spec.minimum)) + ".." + std::to_string(std::int64_t(spec.maximum));
  return formatNumber(spec.minimum) + ".." + formatNumber(spec.maximum);
}

[[noreturn]] void expected(const OptionSpec& spec, const std::string& what, std::string_view got) {
  settingError(spec, "expected " + what + ", got " + quotedName(got));
}

template <class Number>
bool parseNumber(std::string_view text, Number& value) {
  const char* begin = text.data();
  const char* end = begin + text.size();
  if (begin != end && *begin == '+') ++begin;  // from_chars takes no '+'
  auto [stop, error] = std::from_chars(begin, end, value);
  return error == std::errc() && stop == end && begin != end;
}

}  // namespace

std::string optionValueName(const OptionSpec& spec) {
  std::string name;
  switch (spec.type) {
    case OptionType::Switch:
      return "";
    case OptionType::Bool:
      return "";
    case OptionType::Int:
      name = "N";
      break;
    case OptionType::Float:
      name = "FLOAT";
      break;
    case OptionType::Choice:
      name = choiceList(spec, "|");
      break;
    case OptionType::Text:
      name = spec.valueName.empty() ? "TEXT" : std::string(spec.valueName);
      break;
  }
  return spec.autoMeaning.empty() ? name : "auto|" + name;
}

OptionValue parseOptionValue(const OptionSpec& spec, std::string_view text) {
  if (!spec.autoMeaning.empty() && text == "auto") return AutoValue{};
  const std::string expectedAuto = spec.autoMeaning.empty() ? "" : "auto or ";
  switch (spec.type) {
    case OptionType::Switch:
    case OptionType::Bool:
      if (text == "on" || text == "true" || text == "1") return true;
      if (text == "off" || text == "false" || text == "0") return false;
      expected(spec, "on or off", text);
    case OptionType::Int: {
      std::int64_t value = 0;
      if (!parseNumber(text, value)) expected(spec, expectedAuto + "an integer in " + rangeText(spec), text);
      checkOptionValue(spec, value);
      return value;
    }
    case OptionType::Float: {
      double value = 0;
      // Infinity only where the range reaches it (diff's "hardfail inf" = off).
      if (!parseNumber(text, value) || std::isnan(value) || (std::isinf(value) && !std::isinf(spec.maximum)))
        expected(spec, expectedAuto + "a number in " + rangeText(spec), text);
      checkOptionValue(spec, value);
      return value;
    }
    case OptionType::Choice:
      for (std::string_view choice : spec.choices)
        if (choice == text) return std::string(text);
      expected(spec, expectedAuto + "one of " + choiceList(spec, ", "), text);
    case OptionType::Text:
      if (spec.checkText) spec.checkText(text);
      return std::string(text);
  }
  return std::string(text);
}

void checkOptionValue(const OptionSpec& spec, const OptionValue& value) {
  if (std::holds_alternative<AutoValue>(value)) {
    if (spec.autoMeaning.empty()) settingError(spec, "cannot be auto");
    return;
  }
  auto wrongKind = [&] { settingError(spec, "value of the wrong type for this setting"); };
  switch (spec.type) {
    case OptionType::Switch:
    case OptionType::Bool:
      if (!std::holds_alternative<bool>(value)) wrongKind();
      return;
    case OptionType::Int: {
      if (!std::holds_alternative<std::int64_t>(value)) wrongKind();
      const auto number = std::get<std::int64_t>(value);
      if (double(number) < spec.minimum || double(number) > spec.maximum)
        settingError(spec, "must be in " + rangeText(spec) + ", got " + std::to_string(number));
      return;
    }
    case OptionType::Float: {
      if (!std::holds_alternative<double>(value)) wrongKind();
      const double number = std::get<double>(value);
      if (!(number >= spec.minimum && number <= spec.maximum))  // NaN fails too
        settingError(spec, "must be in " + rangeText(spec) + ", got " + formatNumber(number));
      return;
    }
    case OptionType::Choice: {
      if (std::holds_alternative<std::int64_t>(value)) {
        const auto index = std::get<std::int64_t>(value);
        if (index < 0 || std::size_t(index) >= spec.choices.size())
          settingError(spec, "no choice number " + std::to_string(index));
        return;
      }
      if (!std::holds_alternative<std::string>(value)) wrongKind();
      parseOptionValue(spec, std::get<std::string>(value));
      return;
    }
    case OptionType::Text:
      if (!std::holds_alternative<std::string>(value)) wrongKind();
      if (spec.checkText) spec.checkText(std::get<std::string>(value));
      return;
  }
}

std::string formatOptionValue(const OptionSpec& spec, const OptionValue& value) {
  if (std::holds_alternative<AutoValue>(value)) return "auto";
  if (std::holds_alternative<bool>(value)) return std::get<bool>(value) ? "on" : "off";
  if (std::holds_alternative<double>(value)) return formatNumber(std::get<double>(value));
  if (std::holds_alternative<std::int64_t>(value)) {
    const auto number = std::get<std::int64_t>(value);
    if (spec.type == OptionType::Choice && number >= 0 && std::size_t(number) < spec.choices.size())
      return std::string(spec.choices[std::size_t(number)]);
    return std::to_string(number);
  }
  return std::get<std::string>(value);
}

namespace detail {

OptionValue choiceToIndex(const OptionSpec& spec, const OptionValue& value) {
  if (spec.type != OptionType::Choice || !std::holds_alternative<std::string>(value)) return value;
  for (std::size_t i = 0; i < spec.choices.size(); ++i)
    if (spec.choices[i] == std::get<std::string>(value)) return std::int64_t(i);
  return value;  // checkOptionValue has refused it already
}

OptionValue indexToChoice(const OptionSpec& spec, const OptionValue& value) {
  if (spec.type != OptionType::Choice || !std::holds_alternative<std::int64_t>(value)) return value;
  return std::string(spec.choices[std::size_t(std::get<std::int64_t>(value))]);
}

std::string optionRangeText(const OptionSpec& spec) { return rangeText(spec); }

}  // namespace detail
}  // namespace headlight
