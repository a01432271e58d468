#include "realtime/reference_compare.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "image/compare.h"
#include "image/tonemap.h"

namespace caligo {
namespace {

double mean_rgb(const Image& image, const std::array<int, 3>& c) {
  double sum = 0;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      const RGB v = image.rgb(x, y, c);
      sum += double(v.r) + double(v.g) + double(v.b);
    }
  return sum / (3.0 * double(image.pixel_count()));
}

std::array<int, 3> rgb_of(const Image& image, const char* which) {
  const auto c = image.rgb_indices();
  if (!c) throw std::invalid_argument(std::string(which) + " image has no R, G, B channels");
  return *c;
}

// Black -> red -> yellow -> white for x in [0, 1].
std::array<uint8_t, 3> heat(float x) {
  x = std::clamp(x, 0.0f, 1.0f) * 3.0f;
  const auto unorm = [](float v) { return uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); };
  return {unorm(x), unorm(x - 1.0f), unorm(x - 2.0f)};
}

// A 3x5 pixel font for the scale bar's label: digits, '.', '%'.
constexpr std::array<uint16_t, 12> kGlyphs = {
    0x7B6F, 0x2C97, 0x73E7, 0x73CF, 0x5BC9, 0x79CF, 0x79EF, 0x7249, 0x7BEF, 0x7BCF, 0x0002, 0x52A5,
};

void draw_text(Rgb8Image& img, int x0, int y0, const std::string& text, int scale) {
  for (char ch : text) {
    int glyph = ch == '.' ? 10 : ch == '%' ? 11 : (ch >= '0' && ch <= '9' ? ch - '0' : -1);
    if (glyph >= 0)
      for (int row = 0; row < 5; ++row)
        for (int col = 0; col < 3; ++col)
          if (kGlyphs[size_t(glyph)] & (1u << (14 - (row * 3 + col))))
            for (int sy = 0; sy < scale; ++sy)
              for (int sx = 0; sx < scale; ++sx) {
                const int x = x0 + col * scale + sx, y = y0 + row * scale + sy;
                if (x < 0 || y < 0 || x >= img.width || y >= img.height) continue;
                uint8_t* p = &img.rgb[(size_t(y) * size_t(img.width) + size_t(x)) * 3];
                p[0] = p[1] = p[2] = 255;
              }
    x0 += 4 * scale;
  }
}

}  // namespace

Image to_image(const ColorPlanes& planes) {
  Image image(planes.width(), planes.height(), {"R", "G", "B"});
  for (int y = 0; y < planes.height(); ++y)
    for (int x = 0; x < planes.width(); ++x) image.set_rgb(x, y, 0, planes.at(x, y));
  return image;
}

ReferenceError reference_error(const Image& a, const Image& ref, const std::vector<uint8_t>* cores) {
  if (a.width() != ref.width() || a.height() != ref.height())
    throw std::invalid_argument("reference_error: images differ in size");
  if (cores && cores->size() != ref.pixel_count()) throw std::invalid_argument("reference_error: mask size");
  const auto ca = rgb_of(a, "real-time"), cr = rgb_of(ref, "reference");
  const double mean_ref = mean_rgb(ref, cr);
  const ImageMetrics m = compare_images(a, ref);
  ReferenceError e{(mean_rgb(a, ca) - mean_ref) / mean_ref, std::sqrt(m.relative_mse), m.rmse / mean_ref};
  e.outside_rmse_over_mean = e.rmse_over_mean;
  double a_dark = 0, a_all = 0;
  size_t dark = 0;
  for (int y = 0; y < ref.height(); ++y)
    for (int x = 0; x < ref.width(); ++x) {
      const double va = a.rgb(x, y, ca).average();
      a_all += va;
      if (ref.rgb(x, y, cr).average() < 0.01 * mean_ref) a_dark += va, ++dark;
    }
  e.dark_fraction = double(dark) / double(ref.pixel_count());
  if (a_all > 0) e.dark_share = a_dark / a_all;
  if (!cores) return e;
  // Sums in double over each side of the mask: squared error and reference outside, both images inside.
  double sq = 0, ref_out = 0, a_in = 0, ref_in = 0;
  size_t outside = 0, inside = 0;
  for (int y = 0; y < ref.height(); ++y)
    for (int x = 0; x < ref.width(); ++x) {
      const RGB va = a.rgb(x, y, ca), vr = ref.rgb(x, y, cr);
      if ((*cores)[size_t(y) * size_t(ref.width()) + size_t(x)]) {
        a_in += va.average(), ref_in += vr.average();
        ++inside;
        continue;
      }
      const RGB d = va - vr;
      sq += (double(d.r) * d.r + double(d.g) * d.g + double(d.b) * d.b) / 3.0;
      ref_out += vr.average();
      ++outside;
    }
  if (outside > 0 && ref_out > 0) e.outside_rmse_over_mean = std::sqrt(sq / double(outside)) / (ref_out / double(outside));
  if (ref_in > 0) e.core_mean_error = (a_in - ref_in) / ref_in;
  e.core_fraction = double(inside) / double(ref.pixel_count());
  return e;
}

std::vector<uint8_t> light_core_mask(const std::vector<Light>& lights, const View& view, float radius) {
  const Vec2i res = view.resolution;
  std::vector<uint8_t> mask(size_t(res.x) * size_t(res.y), 0);
  for (const Light& light : lights) {
    const auto centre = light_centre(light);
    if (!centre) continue;
    for (const DiscPixel& d : disc_pixels(res, view.project(*centre), radius))
      mask[size_t(d.pixel.y) * size_t(res.x) + size_t(d.pixel.x)] = 1;
  }
  return mask;
}

Rgb8Image comparison_strip(const Image& a, const Image& ref, float exposure, float heat_scale) {
  const int w = a.width(), h = a.height();
  const int bar = std::max(12, h / 12);
  Rgb8Image out{3 * w, h + bar, std::vector<uint8_t>(size_t(3 * w) * size_t(h + bar) * 3, 0)};
  const PreviewSettings preview{exposure, true};
  const std::vector<uint8_t> pa = to_srgb8_preview(a, preview), pr = to_srgb8_preview(ref, preview);
  const auto ca = rgb_of(a, "real-time"), cr = rgb_of(ref, "reference");
  const double norm = heat_scale * mean_rgb(ref, cr);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t src = (size_t(y) * size_t(w) + size_t(x)) * 3;
      uint8_t* row = &out.rgb[size_t(y) * size_t(out.width) * 3];
      std::copy_n(&pa[src], 3, row + size_t(x) * 3);
      std::copy_n(&pr[src], 3, row + size_t(w + x) * 3);
      const RGB d = a.rgb(x, y, ca) - ref.rgb(x, y, cr);
      const double err = (std::abs(d.r) + std::abs(d.g) + std::abs(d.b)) / 3.0;
      const auto c = heat(norm > 0 ? float(err / norm) : 0.0f);
      std::copy_n(c.data(), 3, row + size_t(2 * w + x) * 3);
    }
  // The scale bar under the heat map: the ramp from 0 to heat_scale, labelled in percent of the mean.
  for (int y = h; y < h + bar / 2; ++y)
    for (int x = 0; x < w; ++x) {
      const auto c = heat(float(x) / float(std::max(1, w - 1)));
      std::copy_n(c.data(), 3, &out.rgb[(size_t(y) * size_t(out.width) + size_t(2 * w + x)) * 3]);
    }
  const int glyph_scale = std::max(1, (bar / 2 - 2) / 5);
  char label[32];
  std::snprintf(label, sizeof label, "%.3g%%", double(heat_scale) * 100.0);
  draw_text(out, 2 * w, h + bar / 2 + 1, "0", glyph_scale);
  draw_text(out, 3 * w - int(std::string(label).size()) * 4 * glyph_scale, h + bar / 2 + 1, label, glyph_scale);
  return out;
}

}  // namespace caligo
