#include "lights/ies.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "core/error.h"
#include "core/math.h"

namespace caligo {
namespace {

// The text after the TILT line, split into numbers. Commas separate values in some files.
class NumberReader {
 public:
  NumberReader(const std::string& body, const std::string& file) : file_(file) {
    std::string cleaned = body;
    std::replace(cleaned.begin(), cleaned.end(), ',', ' ');
    std::istringstream in(cleaned);
    for (std::string token; in >> token;) tokens_.push_back(token);
  }

  double next(const char* what) {
    if (index_ >= tokens_.size())
      fail(std::string("truncated: the file ends where ") + what + " was expected (" +
           std::to_string(index_) + " values read)");
    const std::string& token = tokens_[index_++];
    errno = 0;
    char* end = nullptr;
    const double value = std::strtod(token.c_str(), &end);
    if (end == token.c_str() || *end != '\0' || errno == ERANGE || !std::isfinite(value))
      fail("non-numeric value '" + token + "' where " + what + " was expected (value " +
           std::to_string(index_) + " after TILT)");
    return value;
  }
  int next_count(const char* what, int max) {
    const double v = next(what);
    if (v != std::floor(v) || v < 1 || v > max)
      fail(std::string(what) + " must be a whole number in 1.." + std::to_string(max) + ", got " +
           std::to_string(v));
    return static_cast<int>(v);
  }
  size_t remaining() const { return tokens_.size() - index_; }
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError({file_, ""}, "IES profile: " + what);
  }

 private:
  std::string file_;
  std::vector<std::string> tokens_;
  size_t index_ = 0;
};

// Everything after the TILT=NONE line; rejects files without one or with tilt data.
std::string body_after_tilt(const std::string& text, const NumberReader& failer) {
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    const size_t start = line.find_first_not_of(" \t");
    if (start == std::string::npos || line.compare(start, 5, "TILT=") != 0) continue;
    std::string value = line.substr(start + 5);
    value.erase(std::remove_if(value.begin(), value.end(), [](char c) { return std::isspace(c) != 0; }),
                value.end());
    if (value != "NONE")
      failer.fail("TILT=" + value + " is not supported (only TILT=NONE; lamp tilt tables are not read)");
    std::ostringstream rest;
    rest << in.rdbuf();
    return rest.str();
  }
  failer.fail("missing the TILT= line (is this an IES LM-63 file?)");
}

std::vector<float> read_angles(NumberReader& r, int count, const char* what) {
  std::vector<float> angles(count);
  for (float& a : angles) a = static_cast<float>(r.next(what));
  for (int i = 1; i < count; ++i)
    if (!(angles[i] > angles[i - 1])) r.fail(std::string(what) + "s must increase strictly");
  return angles;
}

void check_vertical(const std::vector<float>& v, const NumberReader& r) {
  if (v.size() < 2) r.fail("at least two vertical angles are needed");
  if (v.front() < 0.0f || v.back() > 180.0f) r.fail("vertical angles must lie within 0..180 degrees");
}

void check_horizontal(const std::vector<float>& h, const NumberReader& r) {
  if (h.front() != 0.0f)
    r.fail("the first horizontal angle must be 0 (got " + std::to_string(h.front()) + ")");
  if (h.size() == 1) return;
  const float last = h.back();
  if (last != 90.0f && last != 180.0f && last != 360.0f)
    r.fail("the last horizontal angle must be 90, 180 or 360 (got " + std::to_string(last) + ")");
}

// Index i with table[i] <= x <= table[i + 1] and the weight of table[i + 1]; x inside the table.
std::pair<size_t, float> bracket(const std::vector<float>& table, float x) {
  const size_t n = table.size();
  if (n == 1) return {0, 0.0f};
  size_t i = static_cast<size_t>(std::upper_bound(table.begin(), table.end(), x) - table.begin());
  i = std::clamp<size_t>(i, 1, n - 1) - 1;
  const float t = (x - table[i]) / (table[i + 1] - table[i]);
  return {i, std::clamp(t, 0.0f, 1.0f)};
}

}  // namespace

IesProfile IesProfile::parse(const std::string& text, const std::string& file) {
  NumberReader header_failer("", file);
  if (const size_t nul = text.find('\0'); nul != std::string::npos)
    header_failer.fail("a NUL byte at offset " + std::to_string(nul) + ": not an LM-63 text file");
  NumberReader r(body_after_tilt(text, header_failer), file);
  r.next("the number of lamps");
  r.next("lumens per lamp");
  const double multiplier = r.next("the candela multiplier");
  const int nv = r.next_count("the number of vertical angles", 10000);
  const int nh = r.next_count("the number of horizontal angles", 10000);
  const double type = r.next("the photometric type");
  if (type != 1.0) r.fail("only type C photometry (photometric type 1) is supported");
  for (const char* what : {"the units type", "the width", "the length", "the height", "the ballast factor",
                           "the ballast-lamp factor", "the input watts"})
    r.next(what);
  if (!(multiplier > 0.0)) r.fail("the candela multiplier must be positive");

  IesProfile p;
  p.vertical_ = read_angles(r, nv, "vertical angle");
  p.horizontal_ = read_angles(r, nh, "horizontal angle");
  check_vertical(p.vertical_, r);
  check_horizontal(p.horizontal_, r);
  // Allocated only once the file is known to hold the whole table (up to 10^8 values).
  if (r.remaining() < static_cast<size_t>(nv) * nh)
    r.fail("truncated: " + std::to_string(r.remaining()) + " values follow the angles; the " + std::to_string(nv) +
           " x " + std::to_string(nh) + " candela table needs " + std::to_string(static_cast<size_t>(nv) * nh));
  p.values_.resize(static_cast<size_t>(nv) * nh);
  for (float& c : p.values_) {
    c = static_cast<float>(r.next("a candela value") * multiplier);
    if (c < 0.0f) r.fail("negative candela value " + std::to_string(c));
    // Beyond float's range the table would normalise to NaN (inf / inf).
    if (!std::isfinite(c)) r.fail("a candela value times the multiplier exceeds the float range (3.4e38)");
  }
  if (r.remaining() != 0)
    r.fail("wrong counts: " + std::to_string(r.remaining()) + " values follow the " + std::to_string(nv) +
           " x " + std::to_string(nh) + " candela table");
  const float peak = *std::max_element(p.values_.begin(), p.values_.end());
  if (!(peak > 0.0f)) r.fail("every candela value is zero");
  for (float& c : p.values_) c /= peak;
  p.mean_ = p.mean_over_sphere();
  // Only an angle-less sliver could emit nothing; the tree and power samplers would never choose it.
  if (!(p.mean_ > 0.0f)) r.fail("the profile's intensity integrates to zero over the sphere (no light is emitted)");
  return p;
}

IesProfile IesProfile::tabulated(std::vector<float> vertical, std::vector<float> horizontal,
                                 std::vector<float> values) {
  const auto increasing = [](const std::vector<float>& a) {
    for (size_t i = 1; i < a.size(); ++i)
      if (!(a[i] > a[i - 1])) return false;
    return !a.empty();
  };
  if (!increasing(vertical) || !increasing(horizontal) || vertical.front() < 0.0f || vertical.back() > 180.0f ||
      horizontal.front() != 0.0f || horizontal.back() > 360.0f || values.size() != vertical.size() * horizontal.size())
    throw std::invalid_argument("IesProfile::tabulated: angles not increasing within range, or a table of the wrong size");
  const float peak = values.empty() ? 0.0f : *std::max_element(values.begin(), values.end());
  for (float v : values)
    if (!(v >= 0.0f) || !std::isfinite(v)) throw std::invalid_argument("IesProfile::tabulated: a negative or non-finite value");
  if (!(peak > 0.0f)) throw std::invalid_argument("IesProfile::tabulated: every value is zero");
  IesProfile p;
  p.vertical_ = std::move(vertical);
  p.horizontal_ = std::move(horizontal);
  p.values_ = std::move(values);
  for (float& c : p.values_) c /= peak;
  p.mean_ = p.mean_over_sphere();
  return p;
}

IesProfile IesProfile::load(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError({path, ""}, "cannot open the IES profile");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError({path, ""}, "cannot read the IES profile");
  return parse(text.str(), path);
}

// Maps any horizontal angle onto the measured range using the symmetry the table implies.
float IesProfile::fold_horizontal(float h) const {
  if (horizontal_.size() == 1) return 0.0f;
  h = std::fmod(h, 360.0f);
  if (h < 0.0f) h += 360.0f;
  const float last = horizontal_.back();
  if (last == 360.0f) return h;
  if (h > 180.0f) h = 360.0f - h;  // mirror about the 0-180 plane
  if (last == 180.0f) return h;
  return h > 90.0f ? 180.0f - h : h;  // and about the 90-270 plane
}

float IesProfile::evaluate_degrees(float vertical, float horizontal) const {
  if (!(vertical >= vertical_.front() && vertical <= vertical_.back())) return 0.0f;
  const auto [v, tv] = bracket(vertical_, vertical);
  const auto [h, th] = bracket(horizontal_, fold_horizontal(horizontal));
  const size_t nv = vertical_.size();
  const size_t h1 = horizontal_.size() == 1 ? h : h + 1;
  auto at = [&](size_t hi, size_t vi) { return values_[hi * nv + vi]; };
  const float a = lerp(tv, at(h, v), at(h, v + 1));
  const float b = lerp(tv, at(h1, v), at(h1, v + 1));
  return lerp(th, a, b);
}

float IesProfile::evaluate(float vertical, float horizontal) const {
  return evaluate_degrees(degrees(vertical), degrees(horizontal));
}

// Exact in the vertical angle: at a fixed horizontal angle the profile is linear in theta
// between the table's vertical angles, and the integral of (a + b theta) sin theta over each
// interval has a closed form, so a pencil beam a degree wide integrates as exactly as a wide
// one (a midpoint rule in cos theta put its first sample at 5.07 degrees and saw nothing of
// beams narrower than that). The horizontal angle takes the midpoint rule over 128 angles
// (one for a rotationally symmetric table).
float IesProfile::mean_over_sphere() const {
  constexpr int kPhi = 128;
  const int n_phi = horizontal_.size() == 1 ? 1 : kPhi;
  const size_t nv = vertical_.size();
  double sum = 0.0;
  for (int j = 0; j < n_phi; ++j) {
    // Not a structured binding: clang 14 cannot capture one in the lambda below.
    const auto bracketed = bracket(horizontal_, fold_horizontal(360.0f * (j + 0.5f) / n_phi));
    const size_t h = bracketed.first, h1 = horizontal_.size() == 1 ? h : h + 1;
    const float th = bracketed.second;
    const auto value = [&](size_t v) { return double(lerp(th, values_[h * nv + v], values_[h1 * nv + v])); };
    for (size_t k = 0; k + 1 < nv; ++k) {
      const double a = radians(double(vertical_[k])), b = radians(double(vertical_[k + 1]));
      if (!(b > a)) continue;
      const double va = value(k), vb = value(k + 1);
      // integral over [a, b] of (va + (vb - va)(t - a)/(b - a)) sin t dt
      sum += va * (std::cos(a) - std::cos(b)) + (vb - va) / (b - a) * (std::sin(b) - std::sin(a) - (b - a) * std::cos(b));
    }
  }
  // (1 / 4 pi) * (2 pi / n_phi) * sum
  return static_cast<float>(sum / (2.0 * n_phi));
}

}  // namespace caligo
