#include "denoise/denoise.h"

#include <algorithm>
#include <cmath>

#include <xsimd/xsimd.hpp>

#include <memory>

#include "core/parallel.h"

namespace caligo {
namespace {

constexpr int kTerms = 1 + kDenoiseFeatures;           // a constant and one slope per feature
constexpr int kSymmetric = kTerms * (kTerms + 1) / 2;  // the distinct entries of X^T W X
constexpr float kEpsilon = 1e-10f;
constexpr double kRidge = 1e-4;  // on the slopes, relative to the window's total weight

// Every plane the filter reads, padded by replicating its edges, so that the loops over a tile's
// rows read contiguous floats with no clamping (and vectorise).
struct PaddedPlanes {
  int width = 0, height = 0, border = 0, stride = 0;
  PixelPlanes3 y, guide;
  PixelPlane variance;
  std::array<PixelPlane, kDenoiseFeatures> features;
  size_t at(int x, int y_) const { return size_t(y_ + border) * size_t(stride) + size_t(x + border); }
};

PixelPlane padded(const PixelPlane& in, const PaddedPlanes& g) {
  PixelPlane out(size_t(g.stride) * size_t(g.height + 2 * g.border));
  for (int y = -g.border; y < g.height + g.border; ++y)
    for (int x = -g.border; x < g.width + g.border; ++x)
      out[g.at(x, y)] = in[size_t(std::clamp(y, 0, g.height - 1)) * size_t(g.width) + size_t(std::clamp(x, 0, g.width - 1))];
  return out;
}

using Batch = xsimd::batch<float>;
constexpr int kLanes = int(Batch::size);
constexpr int kTileWidth = 2 * kLanes, kTileHeight = 8;  // 16 x 8 with AVX2: its sums fit the L1 cache

// The regression sums of one tile as batches of kLanes pixels.
struct TileSums {
  static constexpr int kChunks = kTileWidth * kTileHeight / kLanes;
  std::array<std::array<Batch, kChunks>, kSymmetric> xtx{};
  std::array<std::array<std::array<Batch, kChunks>, kTerms>, 3> xty{};
};

// The patch rows offset_weights fills: the tile's width and its 1-pixel border, in whole batches.
constexpr int kPatchWidth = ((kTileWidth + 2 + kLanes - 1) / kLanes) * kLanes;

// NL-means weights of offset (dx, dy) for a tile's pixels, rows of kTileWidth (0 where p +
// offset leaves the image, and in the columns past the tile's own width).
void offset_weights(const PaddedPlanes& g, float k2, const Tile& t, int dx, int dy, float* patch, float* weights) {
  const int tw = t.x1 - t.x0, th = t.y1 - t.y0;
  const std::ptrdiff_t offset = std::ptrdiff_t(dy) * g.stride + dx;
  const Batch third(1.0f / 3.0f), eps(kEpsilon), kk(k2);
  for (int j = 0; j < th + 2; ++j) {
    const size_t p = g.at(t.x0 - 1, t.y0 - 1 + j);
    for (int i = 0; i < kPatchWidth; i += kLanes) {
      const size_t a = p + size_t(i), b = size_t(std::ptrdiff_t(a) + offset);
      Batch diff2(0.0f);
      for (int c = 0; c < 3; ++c) {
        const Batch d = Batch::load_unaligned(&g.guide[size_t(c)][a]) - Batch::load_unaligned(&g.guide[size_t(c)][b]);
        diff2 = xsimd::fma(d, d, diff2);
      }
      const Batch vp = Batch::load_unaligned(&g.variance[a]), vq = Batch::load_unaligned(&g.variance[b]);
      const Batch d = (diff2 * third - (vp + xsimd::min(vp, vq))) / xsimd::fma(kk, vp + vq, eps);
      d.store_unaligned(patch + j * kPatchWidth + i);
    }
  }
  // Columns inside the tile whose neighbour at dx is inside the image, as 0 / 1.
  alignas(64) std::array<float, kTileWidth> column{};
  for (int i = 0; i < kTileWidth; ++i) {
    const int qx = t.x0 + i + dx;
    column[size_t(i)] = i < tw && qx >= 0 && qx < g.width ? 1.0f : 0.0f;
  }
  for (int j = 0; j < kTileHeight; ++j) {
    const int qy = t.y0 + j + dy;
    const bool row_inside = j < th && qy >= 0 && qy < g.height;
    for (int i = 0; i < kTileWidth; i += kLanes) {
      if (!row_inside) {
        Batch(0.0f).store_unaligned(weights + j * kTileWidth + i);
        continue;
      }
      // The patch without its centre: the guide's own value at p must not pick the weights,
      // or the filtered half's error would correlate with the guide at p and the error
      // estimate against it (denoise) would come out low.
      Batch d2 = -Batch::load_unaligned(patch + (j + 1) * kPatchWidth + i + 1);
      for (int b = 0; b < 3; ++b)
        for (int a = 0; a < 3; ++a) d2 += Batch::load_unaligned(patch + (j + b) * kPatchWidth + i + a);
      const Batch w = xsimd::exp(-xsimd::max(Batch(0.0f), d2 * Batch(0.125f)));
      (w * Batch::load_aligned(column.data() + i)).store_unaligned(weights + j * kTileWidth + i);
    }
  }
}

// Adds offset (dx, dy)'s terms to the tile's sums, kLanes pixels at a time.
void accumulate(const PaddedPlanes& g, const Tile& t, int dx, int dy, const float* weights, TileSums& s) {
  const std::ptrdiff_t offset = std::ptrdiff_t(dy) * g.stride + dx;
  for (int j = 0; j < std::min(kTileHeight, t.y1 - t.y0); ++j)
    for (int half = 0; half < kTileWidth / kLanes; ++half) {
      const int chunk = j * (kTileWidth / kLanes) + half;
      const size_t p = g.at(t.x0 + half * kLanes, t.y0 + j), q = size_t(std::ptrdiff_t(p) + offset);
      const Batch w = Batch::load_unaligned(weights + j * kTileWidth + half * kLanes);
      std::array<Batch, kTerms> x;
      x[0] = w;  // the weight folded into the constant term: x^T W x = sum (w x_a) x_b
      std::array<Batch, kTerms> xu;
      xu[0] = Batch(1.0f);
      for (int f = 0; f < kDenoiseFeatures; ++f) {
        xu[size_t(f + 1)] = Batch::load_unaligned(&g.features[size_t(f)][q]) - Batch::load_unaligned(&g.features[size_t(f)][p]);
        x[size_t(f + 1)] = w * xu[size_t(f + 1)];
      }
      int e = 0;
      for (int a = 0; a < kTerms; ++a)
        for (int b = a; b < kTerms; ++b, ++e) s.xtx[size_t(e)][size_t(chunk)] = xsimd::fma(x[size_t(a)], xu[size_t(b)], s.xtx[size_t(e)][size_t(chunk)]);
      for (int c = 0; c < 3; ++c) {
        const Batch yc = Batch::load_unaligned(&g.y[size_t(c)][q]);
        for (int a = 0; a < kTerms; ++a)
          s.xty[size_t(c)][size_t(a)][size_t(chunk)] = xsimd::fma(x[size_t(a)], yc, s.xty[size_t(c)][size_t(a)][size_t(chunk)]);
      }
    }
}

// The constant term of the weighted least-squares fits whose normal equations are a x = b,
// kLanes pixels at once (SPD, the constant ordered LAST): after the Cholesky factorisation
// a = L L^T and the forward substitution L z = b, the last unknown is z_last / L_last,last, with
// no back substitution. Lanes whose system is not positive definite keep `fallback`.
void solve_constant_terms(std::array<std::array<Batch, kTerms>, kTerms>& a, std::array<std::array<Batch, kTerms>, 3>& b,
                          std::array<Batch, 3>& constant) {
  auto valid = Batch(1.0f) > Batch(0.0f);
  for (int j = 0; j < kTerms; ++j) {
    Batch d = a[size_t(j)][size_t(j)];
    for (int k = 0; k < j; ++k) d = xsimd::fnma(a[size_t(j)][size_t(k)], a[size_t(j)][size_t(k)], d);
    valid = valid && d > Batch(1e-20f);
    const Batch root = xsimd::sqrt(xsimd::select(valid, d, Batch(1.0f)));
    a[size_t(j)][size_t(j)] = root;
    const Batch inverse = Batch(1.0f) / root;
    for (int i = j + 1; i < kTerms; ++i) {
      Batch s = a[size_t(i)][size_t(j)];
      for (int k = 0; k < j; ++k) s = xsimd::fnma(a[size_t(i)][size_t(k)], a[size_t(j)][size_t(k)], s);
      a[size_t(i)][size_t(j)] = s * inverse;
    }
  }
  for (int c = 0; c < 3; ++c) {
    for (int i = 0; i < kTerms; ++i) {
      Batch s = b[size_t(c)][size_t(i)];
      for (int k = 0; k < i; ++k) s = xsimd::fnma(a[size_t(i)][size_t(k)], b[size_t(c)][size_t(k)], s);
      b[size_t(c)][size_t(i)] = s / a[size_t(i)][size_t(i)];
    }
    const Batch solved = b[size_t(c)][kTerms - 1] / a[kTerms - 1][kTerms - 1];
    constant[size_t(c)] = xsimd::select(valid, solved, constant[size_t(c)]);
  }
}

// The regression's constant term at each pixel of the tile; the weighted mean where the system
// is singular. Clamped at 0: radiance is not negative, and an extrapolating fit near an edge can be.
void solve_tile(const TileSums& s, const Tile& t, int image_width, PixelPlanes3& out) {
  // Term t of the sums goes to row (t + kTerms - 1) % kTerms: the constant (term 0) last.
  constexpr auto row = [](int term) { return size_t((term + kTerms - 1) % kTerms); };
  for (int j = 0; j < t.y1 - t.y0; ++j)
    for (int half = 0; half < kTileWidth / kLanes; ++half) {
      const size_t chunk = size_t(j * (kTileWidth / kLanes) + half);
      std::array<std::array<Batch, kTerms>, kTerms> a;
      std::array<std::array<Batch, kTerms>, 3> b;
      int e = 0;
      for (int r = 0; r < kTerms; ++r)
        for (int c = r; c < kTerms; ++c, ++e) a[row(r)][row(c)] = a[row(c)][row(r)] = s.xtx[size_t(e)][chunk];
      const Batch total = s.xtx[0][chunk];
      for (size_t r = 0; r + 1 < kTerms; ++r) a[r][r] = xsimd::fma(Batch(float(kRidge)), total, a[r][r]);
      std::array<Batch, 3> constant;
      const auto has_weight = total > Batch(0.0f);
      for (int c = 0; c < 3; ++c) {
        for (int r = 0; r < kTerms; ++r) b[size_t(c)][row(r)] = s.xty[size_t(c)][size_t(r)][chunk];
        constant[size_t(c)] = xsimd::select(has_weight, s.xty[size_t(c)][0][chunk] / xsimd::select(has_weight, total, Batch(1.0f)),
                                            Batch(0.0f));
      }
      solve_constant_terms(a, b, constant);
      alignas(64) float values[3][kLanes];
      for (int c = 0; c < 3; ++c) xsimd::max(constant[size_t(c)], Batch(0.0f)).store_aligned(values[c]);
      for (int lane = 0; lane < kLanes && half * kLanes + lane < t.x1 - t.x0; ++lane) {
        const size_t p = size_t(t.y0 + j) * size_t(image_width) + size_t(t.x0 + half * kLanes + lane);
        for (int c = 0; c < 3; ++c) out[size_t(c)][p] = values[c][lane];
      }
    }
}

std::vector<Tile> filter_tiles(int w, int h) {
  std::vector<Tile> tiles;
  for (int y = 0; y < h; y += kTileHeight)
    for (int x = 0; x < w; x += kTileWidth)
      tiles.push_back({x, y, std::min(w, x + kTileWidth), std::min(h, y + kTileHeight), int(tiles.size())});
  return tiles;
}

}  // namespace

PixelPlanes3 cross_filter(const PixelPlanes3& y, const PixelPlanes3& guide, const PixelPlane& guide_variance,
                          const DenoiseLayers& layers, const DenoiseSettings& settings) {
  const int r = settings.radius;
  PaddedPlanes g;
  g.width = layers.width, g.height = layers.height;
  g.border = r + 2 + kPatchWidth;  // the window, the patch, and a tile's columns past the image
  g.stride = g.width + 2 * g.border;
  for (int c = 0; c < 3; ++c) g.y[size_t(c)] = padded(y[size_t(c)], g), g.guide[size_t(c)] = padded(guide[size_t(c)], g);
  g.variance = padded(guide_variance, g);
  for (int f = 0; f < kDenoiseFeatures; ++f) g.features[size_t(f)] = padded(layers.features[size_t(f)], g);
  PixelPlanes3 out;
  for (PixelPlane& p : out) p.assign(size_t(layers.width) * size_t(layers.height), 0.0f);
  const float k2 = settings.k * settings.k;
  parallel_for_tiles(filter_tiles(layers.width, layers.height), [&](const Tile& t) {
    auto sums = std::make_unique<TileSums>();
    std::array<float, kPatchWidth * (kTileHeight + 2) + kLanes> patch;
    alignas(64) std::array<float, kTileWidth * kTileHeight> weights;
    for (int dy = -r; dy <= r; ++dy)
      for (int dx = -r; dx <= r; ++dx) {
        offset_weights(g, k2, t, dx, dy, patch.data(), weights.data());
        accumulate(g, t, dx, dy, weights.data(), *sums);
      }
    solve_tile(*sums, t, layers.width, out);
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
