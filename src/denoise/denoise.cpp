#include "denoise/denoise.h"

#include <algorithm>
#include <cmath>

#include "core/parallel.h"

namespace caligo {
namespace {

constexpr int kTerms = 1 + kDenoiseFeatures;           // a constant and one slope per feature
constexpr int kSymmetric = kTerms * (kTerms + 1) / 2;  // the distinct entries of X^T W X
constexpr int kTileSize = 32;
constexpr float kEpsilon = 1e-10f;
constexpr double kRidge = 1e-4;  // on the slopes, relative to the window's total weight

// Mean over a (2r+1)^2 box clamped to the image, separably.
PixelPlane box_mean(const PixelPlane& in, int w, int h, int r) {
  PixelPlane rows(in.size()), out(in.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float sum = 0.0f;
      const int a = std::max(0, x - r), b = std::min(w - 1, x + r);
      for (int i = a; i <= b; ++i) sum += in[size_t(y) * size_t(w) + size_t(i)];
      rows[size_t(y) * size_t(w) + size_t(x)] = sum / float(b - a + 1);
    }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float sum = 0.0f;
      const int a = std::max(0, y - r), b = std::min(h - 1, y + r);
      for (int j = a; j <= b; ++j) sum += rows[size_t(j) * size_t(w) + size_t(x)];
      out[size_t(y) * size_t(w) + size_t(x)] = sum / float(b - a + 1);
    }
  return out;
}

// Solves the SPD system a x = b (8 x 8, rows of the symmetric packed entries) by Cholesky;
// false when it is not positive definite.
bool solve_cholesky(double a[kTerms][kTerms], double b[3][kTerms]) {
  for (int j = 0; j < kTerms; ++j) {
    double d = a[j][j];
    for (int k = 0; k < j; ++k) d -= a[j][k] * a[j][k];
    if (!(d > 1e-30)) return false;
    a[j][j] = std::sqrt(d);
    for (int i = j + 1; i < kTerms; ++i) {
      double s = a[i][j];
      for (int k = 0; k < j; ++k) s -= a[i][k] * a[j][k];
      a[i][j] = s / a[j][j];
    }
  }
  for (int c = 0; c < 3; ++c) {
    for (int i = 0; i < kTerms; ++i) {  // L y = b
      double s = b[c][i];
      for (int k = 0; k < i; ++k) s -= a[i][k] * b[c][k];
      b[c][i] = s / a[i][i];
    }
    for (int i = kTerms - 1; i >= 0; --i) {  // L^T x = y
      double s = b[c][i];
      for (int k = i + 1; k < kTerms; ++k) s -= a[k][i] * b[c][k];
      b[c][i] = s / a[i][i];
    }
  }
  return true;
}

// The regression sums of one tile, planar: each entry a tile-sized plane, so that the loops over
// a tile's pixels run over contiguous floats and vectorise.
struct TileSums {
  explicit TileSums(size_t n) {
    for (PixelPlane& p : xtx) p.assign(n, 0.0f);
    for (auto& c : xty)
      for (PixelPlane& p : c) p.assign(n, 0.0f);
  }
  std::array<PixelPlane, kSymmetric> xtx;
  std::array<std::array<PixelPlane, kTerms>, 3> xty;
};

struct FilterInputs {
  const PixelPlanes3& y;
  const PixelPlanes3& guide;
  const PixelPlane& variance;
  const DenoiseLayers& layers;
  const DenoiseSettings& settings;
};

// NL-means weights of offset (dx, dy) for the tile's pixels (0 where p + offset leaves the image).
void offset_weights(const FilterInputs& in, const Tile& t, int dx, int dy, PixelPlane& patch, PixelPlane& weights) {
  const int w = in.layers.width, h = in.layers.height;
  const int pw = t.x1 - t.x0 + 2, ph = t.y1 - t.y0 + 2;
  const float k2 = in.settings.k * in.settings.k;
  for (int j = 0; j < ph; ++j) {
    const int py = std::clamp(t.y0 - 1 + j, 0, h - 1), qy = std::clamp(py + dy, 0, h - 1);
    for (int i = 0; i < pw; ++i) {
      const int px = std::clamp(t.x0 - 1 + i, 0, w - 1), qx = std::clamp(px + dx, 0, w - 1);
      const size_t p = size_t(py) * size_t(w) + size_t(px), q = size_t(qy) * size_t(w) + size_t(qx);
      float diff2 = 0.0f;
      for (int c = 0; c < 3; ++c) {
        const float d = in.guide[size_t(c)][p] - in.guide[size_t(c)][q];
        diff2 += d * d;
      }
      const float vp = in.variance[p], vq = in.variance[q];
      patch[size_t(j) * size_t(pw) + size_t(i)] = (diff2 / 3.0f - (vp + std::min(vp, vq))) / (kEpsilon + k2 * (vp + vq));
    }
  }
  const int tw = t.x1 - t.x0;
  for (int j = 0; j < t.y1 - t.y0; ++j)
    for (int i = 0; i < tw; ++i) {
      // The patch without its centre: the guide's own value at p must not pick the weights,
      // or the filtered half's error would correlate with the guide at p and the error
      // estimate against it (denoise) would come out low.
      float d2 = -patch[size_t(j + 1) * size_t(pw) + size_t(i + 1)];
      for (int b = 0; b < 3; ++b)
        for (int a = 0; a < 3; ++a) d2 += patch[size_t(j + b) * size_t(pw) + size_t(i + a)];
      const int qx = t.x0 + i + dx, qy = t.y0 + j + dy;
      const bool inside = qx >= 0 && qy >= 0 && qx < w && qy < h;
      weights[size_t(j) * size_t(tw) + size_t(i)] = inside ? std::exp(-std::max(0.0f, d2 / 8.0f)) : 0.0f;
    }
}

// Adds offset (dx, dy)'s terms to the tile's sums.
void accumulate(const FilterInputs& in, const Tile& t, int dx, int dy, const PixelPlane& weights, TileSums& s,
                std::array<PixelPlane, kTerms>& x, PixelPlanes3& yq) {
  const int w = in.layers.width, h = in.layers.height, tw = t.x1 - t.x0;
  for (int j = 0; j < t.y1 - t.y0; ++j) {
    const int py = t.y0 + j, qy = std::clamp(py + dy, 0, h - 1);
    for (int i = 0; i < tw; ++i) {
      const int px = t.x0 + i, qx = std::clamp(px + dx, 0, w - 1);
      const size_t p = size_t(py) * size_t(w) + size_t(px), q = size_t(qy) * size_t(w) + size_t(qx);
      const size_t o = size_t(j) * size_t(tw) + size_t(i);
      x[0][o] = 1.0f;
      for (int f = 0; f < kDenoiseFeatures; ++f)
        x[size_t(f + 1)][o] = in.layers.features[size_t(f)][q] - in.layers.features[size_t(f)][p];
      for (int c = 0; c < 3; ++c) yq[size_t(c)][o] = in.y[size_t(c)][q];
    }
  }
  const size_t n = size_t(tw) * size_t(t.y1 - t.y0);
  int e = 0;
  for (int a = 0; a < kTerms; ++a)
    for (int b = a; b < kTerms; ++b, ++e) {
      float* sum = s.xtx[size_t(e)].data();
      const float *xa = x[size_t(a)].data(), *xb = x[size_t(b)].data(), *wt = weights.data();
      for (size_t o = 0; o < n; ++o) sum[o] += wt[o] * xa[o] * xb[o];
    }
  for (int c = 0; c < 3; ++c)
    for (int a = 0; a < kTerms; ++a) {
      float* sum = s.xty[size_t(c)][size_t(a)].data();
      const float *xa = x[size_t(a)].data(), *wt = weights.data(), *yc = yq[size_t(c)].data();
      for (size_t o = 0; o < n; ++o) sum[o] += wt[o] * xa[o] * yc[o];
    }
}

// The regression's constant term at each pixel of the tile; the weighted mean where the system
// is singular. Clamped at 0: radiance is not negative, and an extrapolating fit near an edge can be.
void solve_tile(const TileSums& s, const Tile& t, int image_width, PixelPlanes3& out) {
  const int tw = t.x1 - t.x0;
  for (int j = 0; j < t.y1 - t.y0; ++j)
    for (int i = 0; i < tw; ++i) {
      const size_t o = size_t(j) * size_t(tw) + size_t(i);
      double a[kTerms][kTerms], b[3][kTerms];
      int e = 0;
      for (int r = 0; r < kTerms; ++r)
        for (int c = r; c < kTerms; ++c, ++e) a[r][c] = a[c][r] = double(s.xtx[size_t(e)][o]);
      const double total = a[0][0];
      for (int r = 1; r < kTerms; ++r) a[r][r] += kRidge * total;
      for (int c = 0; c < 3; ++c)
        for (int r = 0; r < kTerms; ++r) b[c][r] = double(s.xty[size_t(c)][size_t(r)][o]);
      const double mean[3] = {b[0][0] / total, b[1][0] / total, b[2][0] / total};
      const bool solved = total > 0.0 && solve_cholesky(a, b);
      const size_t p = size_t(t.y0 + j) * size_t(image_width) + size_t(t.x0 + i);
      for (int c = 0; c < 3; ++c) out[size_t(c)][p] = float(std::max(0.0, solved ? b[c][0] : mean[c]));
    }
}

}  // namespace

PixelPlanes3 cross_filter(const PixelPlanes3& y, const PixelPlanes3& guide, const PixelPlane& guide_variance, const DenoiseLayers& layers,
                     const DenoiseSettings& settings) {
  const FilterInputs in{y, guide, guide_variance, layers, settings};
  PixelPlanes3 out;
  for (PixelPlane& p : out) p.assign(size_t(layers.width) * size_t(layers.height), 0.0f);
  const int r = settings.radius;
  parallel_for_tiles(make_tiles({layers.width, layers.height}, kTileSize), [&](const Tile& t) {
    const size_t n = size_t(t.x1 - t.x0) * size_t(t.y1 - t.y0);
    TileSums sums(n);
    PixelPlane patch(size_t(t.x1 - t.x0 + 2) * size_t(t.y1 - t.y0 + 2)), weights(n);
    std::array<PixelPlane, kTerms> x;
    for (PixelPlane& p : x) p.resize(n);
    PixelPlanes3 yq;
    for (PixelPlane& p : yq) p.resize(n);
    for (int dy = -r; dy <= r; ++dy)
      for (int dx = -r; dx <= r; ++dx) {
        offset_weights(in, t, dx, dy, patch, weights);
        accumulate(in, t, dx, dy, weights, sums, x, yq);
      }
    solve_tile(sums, t, layers.width, out);
  });
  return out;
}

DenoiseResult denoise(const DenoiseLayers& layers, const DenoiseSettings& settings) {
  const int w = layers.width, h = layers.height;
  const size_t n = size_t(w) * size_t(h);
  PixelPlane half_variance(n);
  for (size_t i = 0; i < n; ++i) half_variance[i] = 2.0f * layers.variance[i];  // a half has half the samples
  const PixelPlanes3 oa = cross_filter(layers.half_a, layers.half_b, half_variance, layers, settings);
  const PixelPlanes3 ob = cross_filter(layers.half_b, layers.half_a, half_variance, layers, settings);
  // Per-pixel error estimates: each filtered half against the other half, less that half's
  // variance; their mean bounds the error of the two halves' mean (convexity).
  PixelPlane err_filtered(n), err_input(n);
  for (size_t i = 0; i < n; ++i) {
    double e = 0;
    for (int c = 0; c < 3; ++c) {
      const double da = oa[size_t(c)][i] - layers.half_b[size_t(c)][i], db = ob[size_t(c)][i] - layers.half_a[size_t(c)][i];
      e += 0.5 * (da * da + db * db) - half_variance[i];
    }
    err_filtered[i] = float(e / 3.0);
    err_input[i] = layers.variance[i];
  }
  const PixelPlane ef = box_mean(err_filtered, w, h, settings.selection_radius);
  const PixelPlane ei = box_mean(err_input, w, h, settings.selection_radius);
  PixelPlane choice(n);
  for (size_t i = 0; i < n; ++i) choice[i] = ef[i] < ei[i] ? 1.0f : 0.0f;
  DenoiseResult result;
  result.filtered = box_mean(choice, w, h, 1);  // a soft seam between the two
  result.image.resize(n);
  double mse_in = 0, mse_out = 0;
  for (size_t i = 0; i < n; ++i) {
    const float s = result.filtered[i];
    float v[3];
    for (int c = 0; c < 3; ++c) {
      const float input = 0.5f * (layers.half_a[size_t(c)][i] + layers.half_b[size_t(c)][i]);
      const float filtered = 0.5f * (oa[size_t(c)][i] + ob[size_t(c)][i]);
      v[c] = s * filtered + (1.0f - s) * input;
    }
    result.image[i] = RGB(v[0], v[1], v[2]);
    mse_in += ei[i];
    mse_out += s * std::min(ef[i], ei[i]) + (1.0f - s) * ei[i];
  }
  result.estimated_mse_input = mse_in / double(n);
  // The per-pixel estimates subtract a variance and can be negative; so, within its noise, can
  // their mean when the result is nearly exact. Clamped at 0 only as a whole (per pixel would bias it).
  result.estimated_mse_output = std::max(0.0, mse_out / double(n));
  return result;
}

}  // namespace caligo
