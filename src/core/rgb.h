// Linear Rec.709 RGB: radiance, reflectance and throughput all use it.
#pragma once

#include <algorithm>
#include <cmath>

namespace caligo {

struct RGB {
  float r = 0, g = 0, b = 0;

  constexpr RGB() = default;
  constexpr RGB(float r_, float g_, float b_) : r(r_), g(g_), b(b_) {}
  constexpr explicit RGB(float s) : r(s), g(s), b(s) {}

  constexpr float operator[](int i) const { return i == 0 ? r : (i == 1 ? g : b); }
  constexpr RGB& operator+=(RGB o) {
    r += o.r;
    g += o.g;
    b += o.b;
    return *this;
  }
  constexpr RGB& operator*=(RGB o) {
    r *= o.r;
    g *= o.g;
    b *= o.b;
    return *this;
  }
  constexpr RGB& operator*=(float s) {
    r *= s;
    g *= s;
    b *= s;
    return *this;
  }
  friend constexpr bool operator==(RGB, RGB) = default;

  constexpr bool is_black() const { return r == 0 && g == 0 && b == 0; }
  float max_component() const { return std::max(r, std::max(g, b)); }
  constexpr float average() const { return (r + g + b) * (1.0f / 3.0f); }
  // Rec.709 luminance weights.
  constexpr float luminance() const { return 0.2126f * r + 0.7152f * g + 0.0722f * b; }
  bool is_finite() const { return std::isfinite(r) && std::isfinite(g) && std::isfinite(b); }
};

constexpr RGB operator+(RGB a, RGB b) { return {a.r + b.r, a.g + b.g, a.b + b.b}; }
constexpr RGB operator-(RGB a, RGB b) { return {a.r - b.r, a.g - b.g, a.b - b.b}; }
constexpr RGB operator*(RGB a, RGB b) { return {a.r * b.r, a.g * b.g, a.b * b.b}; }
constexpr RGB operator*(RGB a, float s) { return {a.r * s, a.g * s, a.b * s}; }
constexpr RGB operator*(float s, RGB a) { return a * s; }
constexpr RGB operator/(RGB a, float s) { return a * (1.0f / s); }

// exp(-depth) per channel: the transmittance of an optical depth.
inline RGB exp_neg(RGB depth) { return {std::exp(-depth.r), std::exp(-depth.g), std::exp(-depth.b)}; }

}  // namespace caligo
