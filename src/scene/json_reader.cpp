#include "scene/json_reader.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <nlohmann/json.hpp>

namespace caligo {
namespace {

std::string escape_pointer_token(std::string_view key) {
  std::string out;
  for (char c : key) {
    if (c == '~') {
      out += "~0";
    } else if (c == '/') {
      out += "~1";
    } else {
      out += c;
    }
  }
  return out;
}

// Keys and names as messages quote them: escaped, and abbreviated when long.
std::string quote_json(std::string_view s) { return quote_for_message(s); }

// 1-based line and column of the byte at `offset`; columns count UTF-8 characters.
std::pair<size_t, size_t> line_and_column(std::string_view text, size_t offset) {
  offset = std::min(offset, text.size());
  size_t line = 1, column = 1;
  for (size_t i = 0; i < offset; ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else if ((static_cast<unsigned char>(text[i]) & 0xC0) != 0x80) {
      ++column;
    }
  }
  return {line, column};
}

// nlohmann's messages start "[json.exception.parse_error.101] parse error at line 1, column 2: ";
// keep only the part after that, since we give the location ourselves.
std::string strip_nlohmann_prefix(std::string message) {
  if (size_t end = message.find("] "); message.starts_with("[json.exception.") && end != std::string::npos)
    message.erase(0, end + 2);
  if (message.starts_with("parse error"))
    if (size_t colon = message.find(": "); colon != std::string::npos) message.erase(0, colon + 2);
  return message;
}

// Builds the DOM like nlohmann's own SAX DOM parser, but rejects repeated keys (which
// nlohmann would silently resolve to the last value) and reports syntax errors with
// line and column computed from the byte offset.
class StrictDomBuilder {
 public:
  StrictDomBuilder(Json& root, std::string_view text, const std::string& file)
      : root_(root), text_(text), file_(file) {}

  bool null() { return put(nullptr) != nullptr; }
  bool boolean(bool v) { return put(v) != nullptr; }
  bool number_integer(Json::number_integer_t v) { return put(v) != nullptr; }
  bool number_unsigned(Json::number_unsigned_t v) { return put(v) != nullptr; }
  bool number_float(Json::number_float_t v, const Json::string_t&) { return put(v) != nullptr; }
  bool string(Json::string_t& v) { return put(std::move(v)) != nullptr; }
  bool binary(Json::binary_t& v) { return put(Json::binary(std::move(v))) != nullptr; }
  bool start_object(std::size_t) {
    check_depth();
    stack_.push_back({put(Json::object()), {}});
    return true;
  }
  bool key(Json::string_t& k) {
    Frame& top = stack_.back();
    if (top.value->contains(k)) {
      throw InputError({file_, pointer_of_open_values() + "/" + escape_pointer_token(k)},
                       "duplicate key " + quote_json(k) + " (each key may appear once in an object)");
    }
    top.key = k;
    return true;
  }
  bool end_object() {
    stack_.pop_back();
    return true;
  }
  bool start_array(std::size_t) {
    check_depth();
    stack_.push_back({put(Json::array()), {}});
    return true;
  }
  bool end_array() {
    stack_.pop_back();
    return true;
  }
  bool parse_error(std::size_t byte, const std::string&, const nlohmann::detail::exception& ex) {
    // `byte` counts the characters read, the offending one included.
    const auto [line, column] = line_and_column(text_, byte > 0 ? byte - 1 : 0);
    throw InputError({file_, ""}, "line " + std::to_string(line) + ", column " + std::to_string(column) +
                                      ": invalid JSON: " + strip_nlohmann_prefix(ex.what()));
  }

 private:
  struct Frame {
    Json* value;
    std::string key;  // the key being read, for objects
  };

  // nlohmann's parser keeps its own stack and would read any depth, but dump(), the
  // destructor of some versions and every reader walking the DOM recurse: stop here.
  void check_depth() const {
    if (stack_.size() < kMaxJsonDepth) return;
    // The pointer of the value being opened: the next element or the current key.
    const Frame& top = stack_.back();
    std::string pointer = pointer_of_open_values();
    pointer += '/';
    pointer += top.value->is_array() ? std::to_string(top.value->size()) : escape_pointer_token(top.key);
    throw InputError({file_, pointer}, "JSON nested more than " + std::to_string(kMaxJsonDepth) +
                                           " levels deep (the limit for scene files)");
  }

  Json* put(Json v) {
    if (stack_.empty()) {
      root_ = std::move(v);
      return &root_;
    }
    Frame& top = stack_.back();
    if (top.value->is_array()) {
      top.value->push_back(std::move(v));
      return &top.value->back();
    }
    Json& slot = (*top.value)[top.key];
    slot = std::move(v);
    return &slot;
  }

  // The pointer of the innermost open object or array.
  std::string pointer_of_open_values() const {
    std::string p;
    for (size_t i = 0; i + 1 < stack_.size(); ++i) {
      const Frame& f = stack_[i];
      p += '/';  // appended piecewise: GCC 12 warns falsely (-Wrestrict) on "/" + temporary
      p += f.value->is_array() ? std::to_string(f.value->size() - 1) : escape_pointer_token(f.key);
    }
    return p;
  }

  Json& root_;
  std::string_view text_;
  const std::string& file_;
  std::vector<Frame> stack_;
};

size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

}  // namespace

Json parse_json_text(std::string_view text, const std::string& file_label) {
  if (text.size() > kMaxJsonBytes)
    throw InputError({file_label, ""}, "the file is " + std::to_string(text.size()) +
                                           " bytes; JSON input is limited to " +
                                           std::to_string(kMaxJsonBytes) + " bytes (64 MiB)");
  Json root;
  StrictDomBuilder builder(root, text, file_label);
  Json::sax_parse(text, &builder);
  return root;
}

// ---- Range and formatting ----

bool Range::contains(double x) const {
  const bool above = lo_open ? x > lo : x >= lo;
  const bool below = hi_open ? x < hi : x <= hi;
  return above && below;
}

std::string Range::describe() const {
  const bool has_lo = std::isfinite(lo), has_hi = std::isfinite(hi);
  if (has_lo && has_hi)
    return std::string("in ") + (lo_open ? "(" : "[") + format_number(lo) + ", " + format_number(hi) +
           (hi_open ? ")" : "]");
  if (has_lo) return (lo_open ? "> " : ">= ") + format_number(lo);
  if (has_hi) return (hi_open ? "< " : "<= ") + format_number(hi);
  return "";
}

std::string format_number(double x) {
  if (std::isfinite(x) && x == std::floor(x) && std::fabs(x) < 1e15) return std::to_string(int64_t(x));
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", x);
  return buf;
}

std::string format_vec3(Vec3 v) {
  return "[" + format_number(v.x) + ", " + format_number(v.y) + ", " + format_number(v.z) + "]";
}

std::string join_names(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

std::string closest_match(std::string_view word, const std::vector<std::string>& candidates) {
  std::string best;
  size_t best_distance = std::max<size_t>(1, std::min<size_t>(2, word.size() / 3)) + 1;
  for (const std::string& c : candidates) {
    const size_t d = edit_distance(word, c);
    if (d < best_distance) {
      best = c;
      best_distance = d;
    }
  }
  return best;
}

// ---- JsonCursor ----

JsonCursor::JsonCursor(const Json& value, std::string file, std::string pointer)
    : value_(&value), file_(std::move(file)), pointer_(std::move(pointer)) {}

void JsonCursor::fail(const std::string& message) const { throw InputError(where(), message); }

std::string JsonCursor::describe() const {
  constexpr size_t kMax = 48;
  // Values hold valid UTF-8 (the parser checks), but replace rather than throw regardless.
  std::string text = value_->dump(-1, ' ', false, Json::error_handler_t::replace);
  if (text.size() <= kMax) return text;
  return text.substr(0, kMax - 3) + "...";
}

bool JsonCursor::is_object() const { return value_->is_object(); }
bool JsonCursor::is_array() const { return value_->is_array(); }
bool JsonCursor::is_number() const { return value_->is_number(); }
bool JsonCursor::is_string() const { return value_->is_string(); }

JsonCursor JsonCursor::member(std::string_view key) const {
  return {value_->at(std::string(key)), file_, pointer_ + "/" + escape_pointer_token(key)};
}

std::vector<JsonCursor> JsonCursor::elements(std::string_view expected) const {
  if (!value_->is_array()) fail("expected " + std::string(expected) + ", got " + describe());
  std::vector<JsonCursor> out;
  out.reserve(value_->size());
  for (size_t i = 0; i < value_->size(); ++i)
    out.push_back({(*value_)[i], file_, pointer_ + "/" + std::to_string(i)});
  return out;
}

float JsonCursor::number(Range range) const {
  const std::string in_range = range.describe().empty() ? "" : " " + range.describe();
  if (!value_->is_number()) fail("expected a number" + in_range + ", got " + describe());
  const double x = value_->get<double>();
  const float f = static_cast<float>(x);
  if (!std::isfinite(f))
    fail("expected a finite number, got " + describe() + " (too large for a 32-bit float)");
  if (!range.contains(x)) fail("expected a number" + in_range + ", got " + describe());
  return f;
}

int64_t JsonCursor::integer(Range range) const {
  const std::string in_range = range.describe().empty() ? "" : " " + range.describe();
  const bool integral_float = value_->is_number_float() && std::fabs(value_->get<double>()) < 9e15 &&
                              value_->get<double>() == std::floor(value_->get<double>());
  if (value_->is_number_unsigned() && value_->get<uint64_t>() > uint64_t(INT64_MAX))
    fail("expected an integer" + in_range + ", got " + describe());
  if (!value_->is_number_integer() && !integral_float)
    fail("expected an integer" + in_range + ", got " + describe());
  const int64_t v = value_->is_number_float() ? int64_t(value_->get<double>()) : value_->get<int64_t>();
  if (!range.contains(double(v))) fail("expected an integer" + in_range + ", got " + describe());
  return v;
}

uint64_t JsonCursor::unsigned_integer() const {
  if (value_->is_number_unsigned()) return value_->get<uint64_t>();
  fail("expected an integer >= 0, got " + describe());
}

std::string JsonCursor::string() const {
  if (!value_->is_string()) fail("expected a string, got " + describe());
  return value_->get<std::string>();
}

bool JsonCursor::boolean() const {
  if (!value_->is_boolean()) fail("expected true or false, got " + describe());
  return value_->get<bool>();
}

Vec3 JsonCursor::vec3(Range component_range) const {
  if (!value_->is_array() || value_->size() != 3) fail("expected an array of 3 numbers, got " + describe());
  const auto e = elements("");
  return {e[0].number(component_range), e[1].number(component_range), e[2].number(component_range)};
}

RGB JsonCursor::rgb(Range component_range) const {
  if (value_->is_number()) return RGB(number(component_range));
  if (!value_->is_array() || value_->size() != 3 ||
      !std::all_of(value_->begin(), value_->end(), [](const Json& j) { return j.is_number(); }))
    fail("expected a number or an array of 3 numbers, got " + describe());
  const auto e = elements("");
  return {e[0].number(component_range), e[1].number(component_range), e[2].number(component_range)};
}

// ---- ObjectReader ----

ObjectReader::ObjectReader(JsonCursor object, std::string what)
    : object_(std::move(object)), what_(std::move(what)) {
  if (!object_.is_object()) object_.fail("expected " + what_ + " (a JSON object), got " + object_.describe());
}

void ObjectReader::allow(std::initializer_list<std::string_view> keys) {
  allowed_.assign(keys.begin(), keys.end());
  for (const auto& [key, value] : object_.json().items()) {
    if (std::find(allowed_.begin(), allowed_.end(), key) != allowed_.end()) continue;
    std::string message = "unknown key " + quote_json(key) + " in " + what_;
    if (std::string guess = closest_match(key, allowed_); !guess.empty())
      message += " (did you mean " + quote_json(guess) + "?)";
    object_.member(key).fail(message + "; allowed keys: " + join_names(allowed_));
  }
}

void ObjectReader::finish() const {
  for (const auto& [key, value] : object_.json().items())
    if (std::find(read_.begin(), read_.end(), key) == read_.end())
      throw std::logic_error("scene parser bug: " + object_.member(key).where().to_string() +
                             " was never read");
}

bool ObjectReader::has(std::string_view key) const { return object_.json().contains(std::string(key)); }

void ObjectReader::mark_read(std::string_view key) {
  if (!allowed_.empty() && std::find(allowed_.begin(), allowed_.end(), key) == allowed_.end())
    throw std::logic_error("scene parser bug: reads key \"" + std::string(key) + "\" it did not allow in " +
                           what_);
  if (std::find(read_.begin(), read_.end(), key) == read_.end()) read_.emplace_back(key);
}

JsonCursor ObjectReader::required(std::string_view key) {
  mark_read(key);
  if (!has(key)) fail("missing required key " + quote_json(key) + " in " + what_);
  return object_.member(key);
}

std::optional<JsonCursor> ObjectReader::optional(std::string_view key) {
  mark_read(key);
  if (!has(key)) return std::nullopt;
  return object_.member(key);
}

std::pair<int, JsonCursor> ObjectReader::exactly_one(std::string_view a, std::string_view b) {
  auto first = optional(a);
  auto second = optional(b);
  const std::string expected =
      "expected exactly one of " + quote_json(a) + " or " + quote_json(b) + " in " + what_;
  if (first && second) fail(expected + ", got both");
  if (!first && !second) fail(expected + ", got neither");
  return first ? std::pair{0, *first} : std::pair{1, *second};
}

float ObjectReader::number(std::string_view key, Range range) { return required(key).number(range); }

float ObjectReader::number_or(std::string_view key, float fallback, Range range) {
  auto c = optional(key);
  return c ? c->number(range) : fallback;
}

int64_t ObjectReader::integer_or(std::string_view key, int64_t fallback, Range range) {
  auto c = optional(key);
  return c ? c->integer(range) : fallback;
}

std::string ObjectReader::string(std::string_view key) { return required(key).string(); }

std::string ObjectReader::choice(std::string_view key, std::initializer_list<std::string_view> valid) {
  const JsonCursor c = required(key);
  const std::string value = c.string();
  const std::vector<std::string> names(valid.begin(), valid.end());
  if (std::find(names.begin(), names.end(), value) != names.end()) return value;
  std::string message = "unknown " + std::string(key) + " " + quote_json(value) + " for " + what_;
  if (std::string guess = closest_match(value, names); !guess.empty())
    message += " (did you mean " + quote_json(guess) + "?)";
  c.fail(message + "; valid values: " + join_names(names));
}

bool ObjectReader::boolean_or(std::string_view key, bool fallback) {
  auto c = optional(key);
  return c ? c->boolean() : fallback;
}

Vec3 ObjectReader::vec3(std::string_view key) { return required(key).vec3(); }

std::optional<Vec3> ObjectReader::optional_vec3(std::string_view key) {
  auto c = optional(key);
  if (!c) return std::nullopt;
  return c->vec3();
}

RGB ObjectReader::rgb(std::string_view key, Range component_range) {
  return required(key).rgb(component_range);
}

RGB ObjectReader::rgb_or(std::string_view key, RGB fallback, Range component_range) {
  auto c = optional(key);
  return c ? c->rgb(component_range) : fallback;
}

std::vector<std::pair<std::string, JsonCursor>> named_definitions(const JsonCursor& c, std::string_view kind,
                                                                  std::string_view plural) {
  if (!c.is_object())
    c.fail("expected an object mapping " + std::string(kind) + " names to " + std::string(plural) + ", got " +
           c.describe());
  std::vector<std::pair<std::string, JsonCursor>> members;
  for (const auto& [name, value] : c.json().items()) {
    const JsonCursor m = c.member(name);
    if (name.empty()) m.fail("expected a non-empty " + std::string(kind) + " name");
    members.emplace_back(name, m);
  }
  return members;
}

size_t find_definition(const JsonCursor& c, const std::vector<std::string>& names, std::string_view kind,
                       std::string_view plural) {
  const std::string name = c.string();
  const auto it = std::find(names.begin(), names.end(), name);
  if (it != names.end()) return size_t(it - names.begin());
  std::string message = "unknown ";
  message += kind;
  message += " " + quote_for_message(name);
  if (names.empty()) c.fail(message + ": the scene defines no " + std::string(plural));
  if (std::string guess = closest_match(name, names); !guess.empty())
    message += " (did you mean " + quote_for_message(guess) + "?)";
  c.fail(message + "; defined " + std::string(plural) + ": " + join_names(names));
}

}  // namespace caligo
