// "{frame}" in a file name: the frame number of a sequence render (`caligo render --frames
// A..B`), for the grids an effects tool exports one per frame and for the outputs. "{frame}" is
// the plain number, "{frame:N}" or "{frame:0N}" the number zero-padded to N digits (N in 1..9).
#pragma once

#include <optional>
#include <string>

namespace caligo {

bool has_frame_pattern(const std::string& text);

// `text` with every pattern replaced by `frame`; std::nullopt with `*error` set when a pattern
// is malformed ("{frame:x}", an unclosed "{frame").
std::optional<std::string> substitute_frame(const std::string& text, int frame, std::string* error);

}  // namespace caligo
