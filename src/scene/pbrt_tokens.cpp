#include "scene/pbrt_tokens.h"

#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "core/message_text.h"

namespace caligo::pbrt {
namespace {

namespace fs = std::filesystem;

// All files together; the converted scene must fit the JSON reader's 64 MiB as well.
constexpr size_t kMaxBytes = size_t(64) << 20;
constexpr size_t kMaxTokens = size_t(16) << 20;
constexpr int kMaxIncludeDepth = 16;

struct Reader {
  TokenStream& out;
  size_t bytes = 0;
};

void read_text(const std::string& text, uint32_t file, const std::string& base_dir, int depth, Reader& r);

// Strings become JSON strings (names, file names), which must be UTF-8. pbrt-v4 reads its files
// as UTF-8 too; a Latin-1 file name is refused here, where the line is known.
bool is_utf8(std::string_view text) {
  for (size_t i = 0; i < text.size();) {
    if (static_cast<unsigned char>(text[i]) < 0x80) {
      ++i;
      continue;
    }
    const size_t n = message_text_detail::utf8_length(text, i);
    if (n == 0) return false;
    i += n;
  }
  return true;
}

std::string read_file(const std::string& path, const std::string& where, Reader& r) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw InputError(SourceLocation{where, ""}, "cannot read " + quote_for_message(path) + ": no such file");
  if (fs::is_directory(path, ec))
    throw InputError(SourceLocation{where, ""}, "cannot read " + quote_for_message(path) + ": it is a directory");
  const auto size = fs::file_size(path, ec);
  if (!ec && r.bytes + size > kMaxBytes)
    throw InputError(SourceLocation{where, ""}, "the scene's files exceed " + std::to_string(kMaxBytes >> 20) + " MiB");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(SourceLocation{where, ""}, "cannot open " + quote_for_message(path));
  std::ostringstream text;
  text << in.rdbuf();
  r.bytes += text.str().size();
  return text.str();
}

// Include "file" (Import is the same for a renderer that reads everything at once).
void follow_include(const Token& name, const std::string& base_dir, int depth, Reader& r) {
  const std::string where = r.out.where(name);
  if (name.kind != Token::kString) throw InputError(SourceLocation{where, ""}, "Include: expected a quoted file name");
  if (depth >= kMaxIncludeDepth)
    throw InputError(SourceLocation{where, ""}, "Include: nested more than " + std::to_string(kMaxIncludeDepth) + " deep");
  const fs::path path = fs::path(name.text).is_absolute() ? fs::path(name.text) : fs::path(base_dir) / name.text;
  const std::string text = read_file(path.string(), where, r);
  r.out.files.push_back(path.string());
  read_text(text, uint32_t(r.out.files.size() - 1), path.parent_path().string(), depth + 1, r);
}

void push(Reader& r, Token t) {
  if (r.out.tokens.size() >= kMaxTokens)
    throw InputError(SourceLocation{r.out.where(t), ""}, "more than " + std::to_string(kMaxTokens) + " tokens");
  r.out.tokens.push_back(std::move(t));
}

void read_text(const std::string& text, uint32_t file, const std::string& base_dir, int depth, Reader& r) {
  uint32_t line = 1;
  bool include_next = false;
  for (size_t i = 0; i < text.size();) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      ++i;
    } else if (std::isspace(static_cast<unsigned char>(c))) {
      ++i;
    } else if (c == '#') {
      while (i < text.size() && text[i] != '\n') ++i;
    } else if (c == '[' || c == ']') {
      push(r, {c == '[' ? Token::kOpen : Token::kClose, std::string(1, c), file, line});
      ++i;
    } else if (c == '"') {
      const size_t end = text.find_first_of("\"\n", i + 1);
      if (end == std::string::npos || text[end] == '\n')
        throw InputError(SourceLocation{r.out.files[file] + ":" + std::to_string(line), ""}, "a string is not closed on its line");
      Token t{Token::kString, text.substr(i + 1, end - i - 1), file, line};
      if (!is_utf8(t.text))
        throw InputError(SourceLocation{r.out.files[file] + ":" + std::to_string(line), ""},
                         "a string holds bytes that are not UTF-8: " + quote_for_message(t.text));
      i = end + 1;
      if (include_next) {
        include_next = false;
        follow_include(t, base_dir, depth, r);
      } else {
        push(r, std::move(t));
      }
    } else {
      size_t end = i;
      while (end < text.size() && !std::isspace(static_cast<unsigned char>(text[end])) && text[end] != '"' &&
             text[end] != '[' && text[end] != ']' && text[end] != '#')
        ++end;
      const std::string word = text.substr(i, end - i);
      const bool number = std::isdigit(static_cast<unsigned char>(word[0])) || word[0] == '-' || word[0] == '+' || word[0] == '.';
      if (include_next)
        throw InputError(SourceLocation{r.out.files[file] + ":" + std::to_string(line), ""},
                         "Include: expected a quoted file name, got " + quote_for_message(word));
      if (word == "Include" || word == "Import") {
        include_next = true;
      } else {
        push(r, {number ? Token::kNumber : Token::kWord, word, file, line});
      }
      i = end;
    }
  }
  if (include_next)
    throw InputError(SourceLocation{r.out.files[file] + ":" + std::to_string(line), ""}, "Include: no file name");
}

}  // namespace

TokenStream tokenize_pbrt_text(const std::string& text, const std::string& label, const std::string& base_dir) {
  TokenStream out;
  out.files.push_back(label);
  Reader r{out, text.size()};
  read_text(text, 0, base_dir, 0, r);
  return out;
}

TokenStream tokenize_pbrt_file(const std::string& path) {
  TokenStream out;
  Reader r{out};
  const std::string text = read_file(path, path, r);
  out.files.push_back(path);
  read_text(text, 0, fs::path(path).parent_path().string(), 0, r);
  return out;
}

}  // namespace caligo::pbrt
