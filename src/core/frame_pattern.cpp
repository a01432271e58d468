#include "core/frame_pattern.h"

#include <cstdio>

namespace caligo {

bool has_frame_pattern(const std::string& text) { return text.find("{frame") != std::string::npos; }

std::optional<std::string> substitute_frame(const std::string& text, int frame, std::string* error) {
  std::string out;
  for (size_t at = 0; at < text.size();) {
    const size_t open = text.find("{frame", at);
    if (open == std::string::npos) {
      out += text.substr(at);
      break;
    }
    out += text.substr(at, open - at);
    const size_t close = text.find('}', open);
    if (close == std::string::npos) {
      *error = "\"{frame\" is not closed by \"}\"";
      return std::nullopt;
    }
    const std::string spec = text.substr(open + 6, close - open - 6);  // "" or ":N"
    int width = 0;
    if (!spec.empty()) {
      // ":N" or ":0N" (the printf spelling): N digits, zero-padded.
      const char digit = spec.size() == 2 ? spec[1] : (spec.size() == 3 && spec[1] == '0' ? spec[2] : 0);
      if (spec[0] != ':' || digit < '1' || digit > '9') {
        *error = "expected {frame}, {frame:N} or {frame:0N} with N from 1 to 9, got \"{frame" + spec + "}\"";
        return std::nullopt;
      }
      width = digit - '0';
    }
    char number[32];
    std::snprintf(number, sizeof number, "%0*d", width, frame);
    out += number;
    at = close + 1;
  }
  return out;
}

}  // namespace caligo
