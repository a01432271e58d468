// pbrt-v4 scene text as tokens: quoted strings, numbers and words, "[" and "]", with '#'
// comments skipped and Include/Import followed (relative to the including file). Each token
// knows its file and line, so every later message is "file:line: ...". Untrusted input: files
// are size-limited, nesting is bounded and an unterminated string is a located error.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace caligo::pbrt {

struct Token {
  enum Kind : uint8_t { kWord, kString, kNumber, kOpen, kClose } kind = kWord;
  std::string text;  // a string without its quotes
  uint32_t file = 0;  // index into TokenStream::files
  uint32_t line = 0;
};

struct TokenStream {
  std::vector<std::string> files;  // as named (the first is the scene file)
  std::vector<Token> tokens;
  std::string where(const Token& t) const { return files[t.file] + ":" + std::to_string(t.line); }
};

// Reads `path` and every file it includes. Throws InputError at "file:line" (or the file
// alone when it cannot be read).
TokenStream tokenize_pbrt_file(const std::string& path);

// The same for text in memory (tests); Include is resolved against `base_dir`.
TokenStream tokenize_pbrt_text(const std::string& text, const std::string& label, const std::string& base_dir);

}  // namespace caligo::pbrt
