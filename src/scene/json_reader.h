// Strict, located reading of JSON input: every value a reader hands out has passed a type
// and range check, and every failure is an InputError naming the file and the RFC 6901
// pointer of the offending value, with what was expected and what was found.
//
// The mechanism for "unknown keys are errors" (after pbrt-v4's ReportUnused): an
// ObjectReader is told the keys its object may have (allow()), rejects any other key at once
// with the list of allowed ones, and finish() checks that the parser did read every key
// present (a parser bug otherwise, reported as std::logic_error).
//
// Numbers are read as doubles and stored as floats: a value that is finite in JSON but
// not as a 32-bit float (1e39) is rejected. Thread-safety: none needed, readers are local.
#pragma once

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/rgb.h"
#include "core/vec.h"

namespace caligo {

// Objects keep the order of the file, so errors come in file order.
using Json = nlohmann::ordered_json;

// Limits on JSON input (docs/scene-format.md, "Limits"). Real scenes nest under ten levels
// and weigh kilobytes (meshes and grids live in their own files); the limits keep hostile
// input from exhausting the stack (every reader of the DOM recurses) or the memory.
inline constexpr size_t kMaxJsonDepth = 64;               // nested arrays and objects
inline constexpr size_t kMaxJsonBytes = size_t(64) << 20;  // 64 MiB

// Parses strict JSON (no comments, no trailing commas). Syntax errors name the line and
// column (counted in characters, from 1); a key repeated within one object is an error, as
// is text over kMaxJsonBytes or nesting deeper than kMaxJsonDepth (located at the value that
// opens level kMaxJsonDepth + 1).
Json parse_json_text(std::string_view text, const std::string& file_label);

// The numbers a value may take; either end may be open. Describes itself for messages.
struct Range {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false;
  bool hi_open = false;

  static Range any() { return {}; }
  static Range positive() { return {.lo = 0.0, .lo_open = true}; }
  static Range non_negative() { return {.lo = 0.0}; }
  static Range closed(double lo, double hi) { return {.lo = lo, .hi = hi}; }
  static Range open(double lo, double hi) { return {.lo = lo, .hi = hi, .lo_open = true, .hi_open = true}; }
  // (lo, hi]
  static Range above_up_to(double lo, double hi) { return {.lo = lo, .hi = hi, .lo_open = true}; }

  bool contains(double x) const;
  std::string describe() const;  // "> 0", ">= 0", "in [0, 1]", "in (0, 180)"
};

// Formats a number the way messages show it: integers without a decimal point, others
// with up to 6 significant digits.
std::string format_number(double x);
std::string format_vec3(Vec3 v);  // "[1, 0, 2.5]"

// A JSON value plus where it is. Cheap to copy; refers to a Json owned by the caller.
class JsonCursor {
 public:
  JsonCursor(const Json& value, std::string file, std::string pointer);

  const Json& json() const { return *value_; }
  const std::string& pointer() const { return pointer_; }
  const std::string& file() const { return file_; }
  SourceLocation where() const { return {file_, pointer_}; }
  [[noreturn]] void fail(const std::string& message) const;
  // The value as a message shows it after "got": JSON text, shortened when long.
  std::string describe() const;

  bool is_object() const;
  bool is_array() const;
  bool is_number() const;
  bool is_string() const;

  // The member `key` of an object (which must have it) and the elements of an array.
  JsonCursor member(std::string_view key) const;
  // `expected` completes "expected ..." when the value is not an array, e.g. "an array of shapes".
  std::vector<JsonCursor> elements(std::string_view expected) const;

  float number(Range range = Range::any()) const;
  int64_t integer(Range range = Range::any()) const;
  uint64_t unsigned_integer() const;
  std::string string() const;
  bool boolean() const;
  Vec3 vec3(Range component_range = Range::any()) const;
  // A number (grey) or an array of 3 numbers, each within `component_range`.
  RGB rgb(Range component_range = Range::non_negative()) const;

 private:
  const Json* value_;
  std::string file_;
  std::string pointer_;
};

// One JSON object being read. Typical use:
//   ObjectReader r(cursor, "a point light");
//   r.allow({"type", "position", "color", "intensity", "power"});
//   Vec3 p = r.vec3("position"); ...
//   r.finish();
class ObjectReader {
 public:
  // Fails unless `object` is a JSON object. `what` names it in messages: "a point light".
  ObjectReader(JsonCursor object, std::string what);

  // Declares every key the object may have; fails on the first other key, listing these.
  void allow(std::initializer_list<std::string_view> keys);
  // Checks that every key present has been read. A failure is a bug in the caller.
  void finish() const;

  const JsonCursor& cursor() const { return object_; }
  const std::string& what() const { return what_; }
  // Renames the object once more is known, e.g. "a light" -> "a spot light" after its type.
  void set_what(std::string what) { what_ = std::move(what); }
  [[noreturn]] void fail(const std::string& message) const { object_.fail(message); }
  bool has(std::string_view key) const;

  JsonCursor required(std::string_view key);
  std::optional<JsonCursor> optional(std::string_view key);
  // Reads exactly one of two alternative keys; returns the index (0 or 1) of the one given.
  std::pair<int, JsonCursor> exactly_one(std::string_view a, std::string_view b);

  float number(std::string_view key, Range range = Range::any());
  float number_or(std::string_view key, float fallback, Range range = Range::any());
  int64_t integer_or(std::string_view key, int64_t fallback, Range range);
  std::string string(std::string_view key);
  // A string that must be one of `valid`; a "type" key, typically.
  std::string choice(std::string_view key, std::initializer_list<std::string_view> valid);
  bool boolean_or(std::string_view key, bool fallback);
  Vec3 vec3(std::string_view key);
  std::optional<Vec3> optional_vec3(std::string_view key);
  RGB rgb(std::string_view key, Range component_range = Range::non_negative());
  RGB rgb_or(std::string_view key, RGB fallback, Range component_range = Range::non_negative());

 private:
  void mark_read(std::string_view key);

  JsonCursor object_;
  std::string what_;
  std::vector<std::string> allowed_;  // empty until allow()
  std::vector<std::string> read_;
};

// "did you mean "color"?" help: the candidate closest to `word` within a small edit
// distance, or an empty string.
std::string closest_match(std::string_view word, const std::vector<std::string>& candidates);
// Joins names for messages: "a, b, c".
std::string join_names(const std::vector<std::string>& names);

// The members of an object that maps names to definitions, such as "materials" or "media";
// `kind` and `plural` name them in messages ("medium", "media"). Names must be non-empty.
std::vector<std::pair<std::string, JsonCursor>> named_definitions(const JsonCursor& c, std::string_view kind,
                                                                  std::string_view plural);
// The index in `names` of the name `c` holds, or a failure such as
// `unknown material "chrome" (did you mean "chrome2"?); defined materials: a, b`.
size_t find_definition(const JsonCursor& c, const std::vector<std::string>& names, std::string_view kind,
                       std::string_view plural);

}  // namespace caligo
