#include "lights/environment_map.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace caligo {
namespace {

int wrap(int i, int n) {
  const int m = i % n;
  return m < 0 ? m + n : m;
}

// The weights of the pixels left, centre and right in the mean of the bilinear lookup over
// one cell (the same in y): each half cell blends its pixel (mean weight 3/4) with one
// neighbour (1/4).
constexpr double kSide = 0.125, kCentre = 0.75;

}  // namespace

Vec2 direction_to_latlong(Vec3 w) {
  float u = 0.5f + std::atan2(w.x, -w.z) * kInv2Pi;
  if (u >= 1.0f) u -= 1.0f;  // atan2 returns pi for w = (0, y, +z)
  const float v = std::acos(std::clamp(w.y, -1.0f, 1.0f)) * kInvPi;
  return {std::max(0.0f, u), v};
}

Vec3 latlong_to_direction(Vec2 uv) {
  const float phi = 2.0f * kPi * (uv.x - 0.5f);
  const float theta = kPi * uv.y;
  const float sin_theta = std::sin(theta);
  return {sin_theta * std::sin(phi), std::cos(theta), -sin_theta * std::cos(phi)};
}

EnvironmentMap::EnvironmentMap(int width, int height, std::vector<RGB> pixels)
    : width_(width), height_(height), pixels_(std::move(pixels)) {
  if (width <= 0 || height <= 0 || pixels_.size() != size_t(width) * size_t(height))
    throw std::invalid_argument("EnvironmentMap: size does not match the pixel count");
  for (size_t p = 0; p < pixels_.size(); ++p) {
    const RGB& c = pixels_[p];
    if (!c.is_finite() || c.r < 0.0f || c.g < 0.0f || c.b < 0.0f)
      throw std::invalid_argument("pixel (" + std::to_string(p % size_t(width)) + ", " +
                                  std::to_string(p / size_t(width)) + ") is negative or not finite");
  }
  cos_edge_.resize(size_t(height) + 1);
  for (int y = 0; y <= height; ++y) cos_edge_[size_t(y)] = std::cos(M_PI * double(y) / height);
  cos_edge_.back() = -1.0;  // exact, so the last row's band reaches the pole
  cell_solid_angle_.resize(size_t(height));
  double sum[3] = {0.0, 0.0, 0.0};
  for (int y = 0; y < height; ++y) {
    const double omega = 2.0 * M_PI / width * (cos_edge_[size_t(y)] - cos_edge_[size_t(y) + 1]);
    cell_solid_angle_[size_t(y)] = float(omega);
    for (int x = 0; x < width; ++x) {
      const RGB c = pixel(x, y);
      sum[0] += c.r * omega;
      sum[1] += c.g * omega;
      sum[2] += c.b * omega;
    }
  }
  integral_ = RGB(float(sum[0]), float(sum[1]), float(sum[2]));
  if (!integral_.is_finite())
    throw std::invalid_argument("the pixel values are too large: their integral over the sphere overflows");
  build_distribution();
}

void EnvironmentMap::build_distribution() {
  const size_t w = size_t(width_), h = size_t(height_);
  // Luminance filtered in x (wrapping), then in y (clamping): the cell means of the lookup.
  std::vector<double> fx(w * h);
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x)
      fx[size_t(y) * w + size_t(x)] = kSide * pixel(wrap(x - 1, width_), y).luminance() +
                                      kCentre * pixel(x, y).luminance() +
                                      kSide * pixel(wrap(x + 1, width_), y).luminance();
  std::vector<float> row_weights(h);
  std::vector<float> cells(w);
  conditional_.reserve(h);
  for (int y = 0; y < height_; ++y) {
    const size_t up = size_t(std::max(y - 1, 0)), down = size_t(std::min(y + 1, height_ - 1));
    double row = 0.0;
    for (size_t x = 0; x < w; ++x) {
      const double f = kSide * fx[up * w + x] + kCentre * fx[size_t(y) * w + x] + kSide * fx[down * w + x];
      // Round up so a cell whose lookup is positive somewhere never gets weight 0.
      cells[x] = f > 0.0 ? std::max(float(f), std::numeric_limits<float>::min()) : 0.0f;
      row += cells[x];
    }
    row_weights[size_t(y)] = float(row * cell_solid_angle_[size_t(y)]);
    if (row > 0.0 && row_weights[size_t(y)] == 0.0f) row_weights[size_t(y)] = std::numeric_limits<float>::min();
    // A black row is never chosen (its marginal weight is 0); a uniform conditional keeps it valid.
    if (row > 0.0)
      conditional_.emplace_back(cells);
    else
      conditional_.emplace_back(std::vector<float>(w, 1.0f));
  }
  double total = 0.0;
  for (float r : row_weights) total += r;
  if (total > 0.0)
    marginal_ = DiscreteDistribution(row_weights);
  else
    conditional_.clear();
}

int EnvironmentMap::cell_x(float u) const { return std::clamp(int(u * float(width_)), 0, width_ - 1); }
int EnvironmentMap::cell_y(float v) const { return std::clamp(int(v * float(height_)), 0, height_ - 1); }

RGB EnvironmentMap::lookup(Vec3 w) const {
  const Vec2 uv = direction_to_latlong(w);
  const float x = uv.x * float(width_) - 0.5f;
  const float y = uv.y * float(height_) - 0.5f;
  if (!std::isfinite(x) || !std::isfinite(y)) return RGB(0.0f);
  const float fx = std::floor(x), fy = std::floor(y);
  const float tx = x - fx, ty = y - fy;
  const int x0 = wrap(int(fx), width_), x1 = wrap(int(fx) + 1, width_);
  const int y0 = std::clamp(int(fy), 0, height_ - 1), y1 = std::clamp(int(fy) + 1, 0, height_ - 1);
  const RGB top = pixel(x0, y0) * (1.0f - tx) + pixel(x1, y0) * tx;
  const RGB bottom = pixel(x0, y1) * (1.0f - tx) + pixel(x1, y1) * tx;
  return top * (1.0f - ty) + bottom * ty;
}

std::optional<EnvironmentSample> EnvironmentMap::sample(Vec2 u) const {
  if (marginal_.empty()) return std::nullopt;
  float row_pmf = 0.0f, column_pmf = 0.0f, v_in = 0.0f, u_in = 0.0f;
  const int y = marginal_.sample(u.y, &row_pmf, &v_in);
  const int x = conditional_[size_t(y)].sample(u.x, &column_pmf, &u_in);
  // Uniform in cos(theta) and phi inside the cell: uniform in solid angle.
  const double c0 = cos_edge_[size_t(y)], c1 = cos_edge_[size_t(y) + 1];
  const float cos_theta = float(c0 + (c1 - c0) * double(v_in));
  const float sin_theta = safe_sqrt(1.0f - cos_theta * cos_theta);
  const float phi = 2.0f * kPi * ((float(x) + u_in) / float(width_) - 0.5f);
  const Vec3 w{sin_theta * std::sin(phi), cos_theta, -sin_theta * std::cos(phi)};
  const float pdf = row_pmf * column_pmf / cell_solid_angle_[size_t(y)];
  if (!(pdf > 0.0f) || !std::isfinite(pdf)) return std::nullopt;
  return EnvironmentSample{w, pdf};
}

float EnvironmentMap::pdf(Vec3 w) const {
  if (marginal_.empty()) return 0.0f;
  const Vec2 uv = direction_to_latlong(w);
  const int x = cell_x(uv.x), y = cell_y(uv.y);
  return marginal_.pmf(y) * conditional_[size_t(y)].pmf(x) / cell_solid_angle_[size_t(y)];
}

}  // namespace caligo
