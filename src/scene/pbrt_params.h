// A pbrt-v4 directive's parameter list ("float radius" [2] "rgb L" [1 1 1] ...): read from the
// tokens, looked up by name with the type checked, and at the end every parameter no one read
// is a located warning (a setting Caligo does not honour is never dropped silently).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/rgb.h"
#include "core/vec.h"
#include "scene/pbrt_tokens.h"

namespace caligo::pbrt {

struct Param {
  std::string type, name;
  std::vector<double> numbers;
  std::vector<std::string> strings;  // string, texture, and bool as "true"/"false"
  std::string where;                 // file:line
  bool used = false;
};

class ParamList {
 public:
  // Reads parameters from tokens[*at] on while they look like "type name"; advances *at.
  static ParamList read(const TokenStream& s, size_t* at);

  bool has(const std::string& name) const { return find(name) != nullptr; }
  const Param* find(const std::string& name) const;
  // The parameter's type, or empty when it is not given.
  std::string type_of(const std::string& name) const;

  double number(const std::string& name, double fallback) const;
  int integer(const std::string& name, int fallback) const;
  bool boolean(const std::string& name, bool fallback) const;
  std::string string(const std::string& name, const std::string& fallback) const;
  std::vector<double> numbers(const std::string& name) const;  // empty when not given
  std::vector<double> rgb_numbers(const std::string& name) const;  // an "rgb" array's values; empty when not given
  std::vector<int> integers(const std::string& name) const;
  Vec3 point(const std::string& name, Vec3 fallback) const;
  // A spectrum as pbrt converts it to RGB: "rgb" as given; "blackbody" T as the blackbody's
  // colour at luminance 1 (pbrt-v4 normalises a light's spectrum by its luminance); a
  // "spectrum" (named or sampled) with a warning, as `fallback` for a named one or as the
  // mean of its samples; "texture" with a warning (the fallback is used).
  RGB spectrum(const std::string& name, RGB fallback, std::vector<std::string>& warnings) const;

  // "file:line: <directive>: parameter "x" is not used by Caligo" for each unread parameter.
  void warn_unused(const std::string& directive, std::vector<std::string>& warnings) const;
  // For a directive whose whole effect is left out on purpose (an interface that bounds nothing).
  void mark_all_used() const {
    for (const Param& p : params_) const_cast<Param&>(p).used = true;
  }

 private:
  const Param& typed(const std::string& name, std::initializer_list<const char*> types) const;
  std::vector<Param> params_;
};

}  // namespace caligo::pbrt
