// User text inside error messages: keys, names, values and file names come from files and
// command lines we do not control, and an error must stay one readable line whatever they
// hold. Every message that quotes user text goes through these two functions:
//
//   - control characters are escaped: \n \r \t, other bytes below 0x20 and 0x7f as \xHH, C1
//     controls (U+0080..U+009F, which terminals obey) as \u00HH, and bytes that are not
//     UTF-8 as \xHH; other UTF-8 is kept as it is;
//   - text longer than `max_bytes` (after escaping) is cut at a character boundary to about
//     max_bytes - 20 bytes and followed by "... (N bytes)", N being the original length.
//
// printable_for_message() leaves quotes and backslashes alone, so it can run once more over a
// whole message that already holds escaped parts (caligo's main does, as a safety net) without
// changing them; quote_for_message() adds double quotes and escapes " and \ inside them.
// Header-only so that core/error.h can use it. Thread-safety: pure functions.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace caligo {

inline constexpr size_t kMessageQuoteBytes = 80;   // one quoted key, name or value
inline constexpr size_t kMessageFileBytes = 200;   // a file name in a location
inline constexpr size_t kMessageTokenBytes = 40;   // one token of a JSON pointer (the message quotes it too)
inline constexpr size_t kMessageLineBytes = 2000;  // a whole message line (main's safety net)

namespace message_text_detail {

inline void append_hex(std::string& out, const char* prefix, unsigned value, int digits) {
  static constexpr char kHex[] = "0123456789abcdef";
  out += prefix;
  for (int d = digits - 1; d >= 0; --d) out += kHex[(value >> (4 * d)) & 0xf];
}

// The length of the valid UTF-8 sequence starting at text[i] (1 to 4), or 0 if there is none.
inline size_t utf8_length(std::string_view text, size_t i) {
  const auto byte = [&](size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char lead = byte(i);
  size_t n = 0;
  uint32_t code = 0;
  if (lead >= 0xc2 && lead <= 0xdf) {
    n = 2, code = lead & 0x1fu;
  } else if (lead >= 0xe0 && lead <= 0xef) {
    n = 3, code = lead & 0x0fu;
  } else if (lead >= 0xf0 && lead <= 0xf4) {
    n = 4, code = lead & 0x07u;
  } else {
    return 0;
  }
  if (i + n > text.size()) return 0;
  for (size_t k = 1; k < n; ++k) {
    if ((byte(i + k) & 0xc0) != 0x80) return 0;
    code = code << 6 | (byte(i + k) & 0x3fu);
  }
  // Overlong forms, surrogates and code points past U+10FFFF are not UTF-8.
  const uint32_t smallest[5] = {0, 0, 0x80, 0x800, 0x10000};
  if (code < smallest[n] || (code >= 0xd800 && code <= 0xdfff) || code > 0x10ffff) return 0;
  return n;
}

// Appends the escaped form of the character at text[i]; returns how many bytes it consumed.
inline size_t append_escaped(std::string& out, std::string_view text, size_t i, bool quoted) {
  const unsigned char c = static_cast<unsigned char>(text[i]);
  if (c < 0x80) {
    if (c == '\n') {
      out += "\\n";
    } else if (c == '\r') {
      out += "\\r";
    } else if (c == '\t') {
      out += "\\t";
    } else if (c < 0x20 || c == 0x7f) {
      append_hex(out, "\\x", c, 2);
    } else if (quoted && (c == '"' || c == '\\')) {
      out += '\\';
      out += char(c);
    } else {
      out += char(c);
    }
    return 1;
  }
  const size_t n = utf8_length(text, i);
  if (n == 0) {
    append_hex(out, "\\x", c, 2);
    return 1;
  }
  if (n == 2 && c == 0xc2 && static_cast<unsigned char>(text[i + 1]) < 0xa0) {
    append_hex(out, "\\u", 0x80u + (static_cast<unsigned char>(text[i + 1]) & 0x1fu), 4);  // C1 control
    return 2;
  }
  out.append(text.substr(i, n));
  return n;
}

inline std::string escape_and_abbreviate(std::string_view text, size_t max_bytes, bool quoted) {
  constexpr size_t kTail = 20;  // room for "... (123456789 bytes)"
  const size_t keep = max_bytes > 2 * kTail ? max_bytes - kTail : max_bytes / 2;
  std::string out;
  size_t i = 0, cut = 0;  // `cut`: the longest whole-character prefix of `out` within `keep`
  while (i < text.size() && out.size() <= max_bytes) {
    if (out.size() <= keep) cut = out.size();
    i += append_escaped(out, text, i, quoted);
  }
  if (out.size() <= max_bytes) return out;
  out.resize(cut);
  out += "... (" + std::to_string(text.size()) + " bytes)";
  return out;
}

}  // namespace message_text_detail

// `text` made safe to print inside a one-line message, without quotes (see above).
inline std::string printable_for_message(std::string_view text, size_t max_bytes = kMessageQuoteBytes) {
  return message_text_detail::escape_and_abbreviate(text, max_bytes, false);
}

// `text` in double quotes, escaped and abbreviated as above: "name", "a\nb", "aaaa... (1048576 bytes)".
inline std::string quote_for_message(std::string_view text, size_t max_bytes = kMessageQuoteBytes) {
  // Appended rather than "\"" + temporary, on which GCC 12 warns falsely (-Wrestrict).
  std::string out = "\"";
  out += message_text_detail::escape_and_abbreviate(text, max_bytes, true);
  out += '"';
  return out;
}

}  // namespace caligo
