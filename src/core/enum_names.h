// Names of a closed enum's values, written once as a table: the scene parser, the command line
// and messages read the same one. A table may list a value twice (an alias, e.g. "blackman-harris");
// its first name is the value's name.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace caligo {

template <class E>
struct EnumName {
  E value;
  std::string_view name;
};

template <class E, size_t N>
constexpr std::optional<E> enum_from_name(const std::array<EnumName<E>, N>& names, std::string_view name) {
  for (const EnumName<E>& n : names)
    if (n.name == name) return n.value;
  return std::nullopt;
}

template <class E, size_t N>
constexpr std::string_view enum_name(const std::array<EnumName<E>, N>& names, E value) {
  for (const EnumName<E>& n : names)
    if (n.value == value) return n.name;
  return "?";
}

// "a, b or c": the first name of each value, for "expected ..." messages.
template <class E, size_t N>
std::string enum_choices(const std::array<EnumName<E>, N>& names) {
  std::string out;
  size_t listed = 0, count = 0;
  for (size_t i = 0; i < N; ++i) count += enum_name(names, names[i].value) == names[i].name;
  for (size_t i = 0; i < N; ++i) {
    if (enum_name(names, names[i].value) != names[i].name) continue;  // an alias
    if (listed > 0) out += listed + 1 == count ? " or " : ", ";
    out += names[i].name;
    ++listed;
  }
  return out;
}

}  // namespace caligo
