#include "scene/pbrt_params.h"

#include <charconv>
#include <cmath>
#include <sstream>

#include "core/error.h"
#include "core/message_text.h"
#include "media/blackbody.h"

namespace caligo::pbrt {
namespace {

[[noreturn]] void fail(const std::string& where, const std::string& what) {
  throw InputError(SourceLocation{where, ""}, what);
}

double to_number(const TokenStream& s, const Token& t) {
  double v = 0;
  const char* end = t.text.data() + t.text.size();
  const char* begin = t.text.data() + (t.text[0] == '+' ? 1 : 0);
  const auto [ptr, ec] = std::from_chars(begin, end, v);
  // Within float's range: every value ends up a float (and a cast beyond it is undefined).
  if (ec != std::errc() || ptr != end || !(std::abs(v) <= 3.0e38))
    fail(s.where(t), "expected a finite number, got " + quote_for_message(t.text));
  return v;
}

bool is_numeric_type(const std::string& type) {
  for (const char* t : {"float", "integer", "point2", "vector2", "point3", "vector3", "normal3", "normal", "point",
                        "vector", "rgb", "blackbody", "color"})
    if (type == t) return true;
  return false;
}

void add_value(const TokenStream& s, const Token& t, Param& p) {
  const bool numeric = is_numeric_type(p.type) || (p.type == "spectrum" && t.kind == Token::kNumber);
  if (numeric) {
    if (t.kind != Token::kNumber) fail(s.where(t), "parameter \"" + p.name + "\": expected numbers, got " + quote_for_message(t.text));
    p.numbers.push_back(to_number(s, t));
  } else if (p.type == "bool") {
    const std::string v = t.text;
    if (v != "true" && v != "false") fail(s.where(t), "parameter \"" + p.name + "\": expected true or false, got " + quote_for_message(v));
    p.strings.push_back(v);
  } else {
    if (t.kind != Token::kString) fail(s.where(t), "parameter \"" + p.name + "\": expected a quoted string, got " + quote_for_message(t.text));
    p.strings.push_back(t.text);
  }
}

}  // namespace

ParamList ParamList::read(const TokenStream& s, size_t* at) {
  ParamList list;
  while (*at < s.tokens.size() && s.tokens[*at].kind == Token::kString) {
    const Token& decl = s.tokens[*at];
    std::istringstream words(decl.text);
    Param p;
    std::string extra;
    if (!(words >> p.type >> p.name) || (words >> extra)) break;  // not "type name": a positional string
    p.where = s.where(decl);
    ++*at;
    if (*at >= s.tokens.size()) fail(p.where, "parameter \"" + p.name + "\" has no value");
    if (s.tokens[*at].kind == Token::kOpen) {
      for (++*at; *at < s.tokens.size() && s.tokens[*at].kind != Token::kClose; ++*at) add_value(s, s.tokens[*at], p);
      if (*at >= s.tokens.size()) fail(p.where, "parameter \"" + p.name + "\": \"[\" is not closed");
      ++*at;
    } else {
      add_value(s, s.tokens[*at], p);
      ++*at;
    }
    for (const Param& q : list.params_)
      if (q.name == p.name) fail(p.where, "parameter \"" + p.name + "\" is given twice");
    list.params_.push_back(std::move(p));
  }
  return list;
}

const Param* ParamList::find(const std::string& name) const {
  for (const Param& p : params_)
    if (p.name == name) return &p;
  return nullptr;
}

std::string ParamList::type_of(const std::string& name) const {
  const Param* p = find(name);
  return p ? p->type : std::string();
}

const Param& ParamList::typed(const std::string& name, std::initializer_list<const char*> types) const {
  const Param& p = *find(name);
  std::string list;
  for (const char* t : types) {
    if (p.type == t) {
      const_cast<Param&>(p).used = true;
      return p;
    }
    list += (list.empty() ? "" : " or ") + std::string(t);
  }
  fail(p.where, "parameter \"" + p.name + "\": expected type " + list + ", got " + quote_for_message(p.type));
}

double ParamList::number(const std::string& name, double fallback) const {
  if (!has(name)) return fallback;
  const Param& p = typed(name, {"float", "integer"});
  if (p.numbers.size() != 1) fail(p.where, "parameter \"" + name + "\": expected one number");
  return p.numbers[0];
}

int ParamList::integer(const std::string& name, int fallback) const {
  if (!has(name)) return fallback;
  const Param& p = typed(name, {"integer"});
  if (p.numbers.size() != 1 || p.numbers[0] != std::floor(p.numbers[0]) || std::abs(p.numbers[0]) > 1e9)
    fail(p.where, "parameter \"" + name + "\": expected one integer");
  return int(p.numbers[0]);
}

bool ParamList::boolean(const std::string& name, bool fallback) const {
  if (!has(name)) return fallback;
  const Param& p = typed(name, {"bool"});
  if (p.strings.size() != 1) fail(p.where, "parameter \"" + name + "\": expected one value");
  return p.strings[0] == "true";
}

std::string ParamList::string(const std::string& name, const std::string& fallback) const {
  if (!has(name)) return fallback;
  const Param& p = typed(name, {"string", "texture"});
  if (p.strings.size() != 1) fail(p.where, "parameter \"" + name + "\": expected one string");
  return p.strings[0];
}

std::vector<double> ParamList::numbers(const std::string& name) const {
  if (!has(name)) return {};
  return typed(name, {"float", "point3", "point", "normal3", "normal", "vector3", "vector", "point2", "vector2"}).numbers;
}

std::vector<double> ParamList::rgb_numbers(const std::string& name) const {
  if (!has(name)) return {};
  return typed(name, {"rgb"}).numbers;
}

std::vector<int> ParamList::integers(const std::string& name) const {
  if (!has(name)) return {};
  const Param& p = typed(name, {"integer"});
  std::vector<int> out;
  for (double v : p.numbers) {
    if (v != std::floor(v) || v < 0 || v > 2147483647.0)
      fail(p.where, "parameter \"" + name + "\": expected non-negative integers");
    out.push_back(int(v));
  }
  return out;
}

Vec3 ParamList::point(const std::string& name, Vec3 fallback) const {
  if (!has(name)) return fallback;
  const Param& p = typed(name, {"point3", "point", "vector3", "vector", "normal3", "normal"});
  if (p.numbers.size() != 3) fail(p.where, "parameter \"" + name + "\": expected 3 numbers");
  return {float(p.numbers[0]), float(p.numbers[1]), float(p.numbers[2])};
}

RGB ParamList::spectrum(const std::string& name, RGB fallback, std::vector<std::string>& warnings) const {
  if (!has(name)) return fallback;
  const Param& p = typed(name, {"rgb", "color", "blackbody", "spectrum", "float", "texture"});
  if (p.type == "rgb" || p.type == "color") {
    if (p.numbers.size() != 3) fail(p.where, "parameter \"" + name + "\": expected 3 numbers (r g b)");
    return RGB(float(p.numbers[0]), float(p.numbers[1]), float(p.numbers[2]));
  }
  if (p.type == "float") {
    if (p.numbers.size() != 1) fail(p.where, "parameter \"" + name + "\": expected one number");
    return RGB(float(p.numbers[0]));
  }
  if (p.type == "blackbody") {
    if (p.numbers.size() != 1 || !(p.numbers[0] > 0)) fail(p.where, "parameter \"" + name + "\": expected one temperature > 0 K");
    return blackbody_color(float(p.numbers[0]));
  }
  if (p.type == "texture") {
    warnings.push_back(p.where + ": parameter \"" + name + "\" is a texture; Caligo reads no pbrt textures, so the "
                       "default value is used instead");
    return fallback;
  }
  // A sampled spectrum [lambda value ...]: its mean value, grey; a named one: the fallback.
  if (!p.numbers.empty()) {
    if (p.numbers.size() % 2 != 0) fail(p.where, "parameter \"" + name + "\": expected wavelength-value pairs");
    double sum = 0;
    for (size_t i = 1; i < p.numbers.size(); i += 2) sum += p.numbers[i];
    warnings.push_back(p.where + ": parameter \"" + name + "\": a sampled spectrum becomes its mean value (grey)");
    return RGB(float(sum / double(p.numbers.size() / 2)));
  }
  warnings.push_back(p.where + ": parameter \"" + name + "\": the named spectrum " +
                     quote_for_message(p.strings.empty() ? "" : p.strings[0]) + " is not known; the default is used");
  return fallback;
}

void ParamList::warn_unused(const std::string& directive, std::vector<std::string>& warnings) const {
  for (const Param& p : params_)
    if (!p.used)
      warnings.push_back(p.where + ": " + directive + ": parameter \"" + p.type + " " + p.name +
                         "\" is not used by Caligo");
}

}  // namespace caligo::pbrt
