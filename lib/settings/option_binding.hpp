#pragma once
// Building option rows (headlight/options.hpp): a row bound to a struct's
// field, a row whose setter does its own work, and an inner struct's rows
// lifted into the struct that holds it. The library's tables (settings,
// limits, reference) and the CLI's are made with these; they are not
// installed, since a caller reads rows and does not need to make them.
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "headlight/options.hpp"

namespace headlight {

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

namespace detail {
// The row's range as text: "1..64", "1e-09..1e+09".
std::string optionRangeText(const OptionSpec& spec);
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

}  // namespace headlight
