// Priorities of surfaces that bound media (media/medium_stack.h), as scene files and the
// command line write them: a non-negative integer up to kMaxPriority (0: off; smaller is
// higher) or one of the named levels. Shared by the scene parser and `caligo render --priority`.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include "media/medium_stack.h"

namespace caligo {

inline constexpr int kMaxPriority = 100000;

inline constexpr std::array<std::pair<std::string_view, int>, 6> kPriorityNames = {{
    {"off", kPriorityOff},
    {"very_high", kPriorityVeryHigh},
    {"high", kPriorityHigh},
    {"normal", kPriorityNormal},
    {"low", kPriorityLow},
    {"very_low", kPriorityVeryLow},
}};

// The level a name stands for, or nullopt.
inline std::optional<int> priority_from_name(std::string_view name) {
  for (const auto& [n, level] : kPriorityNames)
    if (n == name) return level;
  return std::nullopt;
}

// "off, very_high, high, normal, low, very_low"
inline std::string priority_names() {
  std::string s;
  for (const auto& [n, level] : kPriorityNames) s += (s.empty() ? "" : ", ") + std::string(n);
  return s;
}

}  // namespace caligo
