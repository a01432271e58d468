// Gather, upsample, temporal reprojection and depth downsampling: pixel tests.
#include "realtime/passes.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/rng.h"
#include "realtime/scene_buffers.h"
#include "realtime/view.h"

namespace caligo {
namespace {

float gaussian(Pcg32& rng) {
  const float u1 = std::max(rng.next_float(), 1e-7f), u2 = rng.next_float();
  return std::sqrt(-2.0f * std::log(u1)) * std::cos(2.0f * kPi * u2);
}

ColorPlanes random_planes(int w, int h, Pcg32& rng) {
  ColorPlanes c(w, h);
  for (Plane* p : {&c.r, &c.g, &c.b})
    for (float& v : p->data) v = rng.next_float() * 10.0f;
  return c;
}

// Depth with edges: blocks at 2, 5 and 40 metres plus a gentle slope.
Plane blocky_depth(int w, int h) {
  Plane d(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      d.at(x, y) = ((x / 11 + y / 7) % 3 == 0 ? 2.0f : (x + y) % 5 == 0 ? 40.0f : 5.0f) + 0.01f * x;
  return d;
}

void expect_planes_near(const ColorPlanes& a, const ColorPlanes& b, float rel) {
  ASSERT_EQ(a.width(), b.width());
  ASSERT_EQ(a.height(), b.height());
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x)
      for (int c = 0; c < 3; ++c)
        ASSERT_NEAR(a.at(x, y)[c], b.at(x, y)[c], rel * std::abs(a.at(x, y)[c]) + 1e-6f) << x << "," << y;
}

// ---- gather

// A bright region behind a depth edge must not bleed onto the near side: with the
// bilateral weights the near pixels keep their value; without them (falloff 0) they do not.
TEST(Gather, DoesNotBleedAcrossADepthEdge) {
  const int w = 48, h = 24;
  ColorPlanes in(w, h);
  Plane depth(w, h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const bool near = x < 24;
      depth.at(x, y) = near ? 2.0f : 20.0f;
      in.set(x, y, near ? RGB(1.0f) : RGB(100.0f));
    }
  }
  for (bool simd : {false, true}) {
    const ColorPlanes out = bilateral_gather(in, depth, 7, 1000.0f, simd);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < 24; ++x) EXPECT_NEAR(out.r.at(x, y), 1.0f, 1e-4f) << x << "," << y;
    const ColorPlanes plain = bilateral_gather(in, depth, 7, 0.0f, simd);
    EXPECT_GT(plain.r.at(23, 10), 20.0f);  // a plain Gaussian smears the far side over the edge
  }
}

// On flat depth the taps follow the seed's Gaussian (ratios to the centre tap within 3 %).
TEST(Gather, FlatDepthGivesTheSeedsGaussian) {
  const float seed[8] = {0.14446445f, 0.13543542f, 0.11153505f, 0.08055309f,
                         0.05087564f, 0.02798160f, 0.01332457f, 0.00545096f};
  ColorPlanes in(41, 41);
  in.r.at(20, 20) = 1.0f;
  const ColorPlanes out = bilateral_gather(in, Plane(41, 41, 3.0f), 7, 1000.0f, true);
  for (int k = 1; k <= 7; ++k) {
    EXPECT_NEAR(out.r.at(20 + k, 20) / out.r.at(20, 20), seed[k] / seed[0], 0.03f * seed[k] / seed[0]) << k;
    EXPECT_NEAR(out.r.at(20, 20 - k), out.r.at(20 + k, 20), 1e-7f);
  }
  EXPECT_EQ(out.r.at(28, 20), 0.0f);
  double total = 0.0;
  for (float v : out.r.data) total += v;
  EXPECT_NEAR(total, 1.0, 1e-5);  // normalised: energy is kept away from the borders
}

// A wall seen edge-on: depth grows 4 % a pixel across the image, and the accumulation holds
// alternate columns of 0 and 2 (what the horizontal pass must average). Following the slope
// the gather gives 1 (within 2 %: the Gaussian's tails see the depth's curvature); the seed's
// weight on depth alone rejects the horizontal taps and leaves vertical streaks (the bright
// columns stay above 1.6).
TEST(Gather, FollowsTheSlopeOfAWallSeenEdgeOn) {
  const int w = 64, h = 24;
  ColorPlanes in(w, h);
  Plane depth(w, h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      depth.at(x, y) = 2.0f * std::pow(1.04f, float(x));
      in.r.at(x, y) = float(2 * (x % 2));
    }
  }
  for (bool simd : {false, true}) {
    const ColorPlanes along = bilateral_gather(in, depth, 7, 1000.0f, simd, true);
    const ColorPlanes seed = bilateral_gather(in, depth, 7, 1000.0f, simd, false);
    for (int y = 8; y < 16; ++y) {
      for (int x = 8; x < 56; ++x) {
        EXPECT_NEAR(along.r.at(x, y), 1.0f, 0.02f) << x << "," << y << " simd " << simd;
        if (x % 2) {
          EXPECT_GT(seed.r.at(x, y), 1.6f) << x << "," << y;
        }
      }
    }
  }
}

TEST(Gather, SimdMatchesScalar) {
  Pcg32 rng(1, 2);
  const ColorPlanes in = random_planes(53, 29, rng);
  const Plane depth = blocky_depth(53, 29);
  for (bool slope : {false, true})
    expect_planes_near(bilateral_gather(in, depth, 7, 30.0f, false, slope),
                       bilateral_gather(in, depth, 7, 30.0f, true, slope), 1e-5f);
}

// ---- upsample

TEST(Upsample, PicksTheTapOfNearestDepthAtAnEdge) {
  ColorPlanes low(16, 16);
  Plane low_depth(16, 16), full_depth(64, 64);
  for (int y = 0; y < 16; ++y) {
    for (int x = 0; x < 16; ++x) {
      low_depth.at(x, y) = x < 8 ? 2.0f : 20.0f;
      low.set(x, y, x < 8 ? RGB(1.0f, 2.0f, 3.0f) : RGB(10.0f, 20.0f, 30.0f));
    }
  }
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) full_depth.at(x, y) = x < 32 ? 2.0f : 20.0f;
  for (bool simd : {false, true}) {
    const ColorPlanes up = upsample_nearest_depth(low, low_depth, full_depth, 0.05f, simd);
    for (int y = 0; y < 64; ++y) {
      // Pixels 30..33 straddle the edge in their bilinear footprints.
      for (int x = 28; x < 36; ++x) {
        const RGB expect = x < 32 ? RGB(1.0f, 2.0f, 3.0f) : RGB(10.0f, 20.0f, 30.0f);
        for (int c = 0; c < 3; ++c)  // the blend of equal taps, within rounding
          EXPECT_NEAR(up.at(x, y)[c], expect[c], 1e-6f * expect[c]) << x << "," << y << " simd " << simd;
      }
    }
  }
}

TEST(Upsample, BilinearWhereDepthIsSmooth) {
  ColorPlanes low(8, 6);
  Plane low_depth(8, 6), full_depth(32, 24);
  for (int y = 0; y < 6; ++y)
    for (int x = 0; x < 8; ++x) {
      low_depth.at(x, y) = 10.0f + 0.01f * x;
      low.set(x, y, RGB(float(x), float(y), float(x + 2 * y)));
    }
  for (int y = 0; y < 24; ++y)
    for (int x = 0; x < 32; ++x) full_depth.at(x, y) = 10.0f + 0.0025f * x;
  for (bool simd : {false, true}) {
    const ColorPlanes up = upsample_nearest_depth(low, low_depth, full_depth, 0.05f, simd);
    for (int y = 2; y < 22; ++y) {
      for (int x = 2; x < 30; ++x) {
        // Away from the clamped border the bilinear blend of a linear ramp is the ramp.
        const float u = (x + 0.5f) / 4.0f - 0.5f, v = (y + 0.5f) / 4.0f - 0.5f;
        EXPECT_NEAR(up.r.at(x, y), u, 1e-5f);
        EXPECT_NEAR(up.g.at(x, y), v, 1e-5f);
        EXPECT_NEAR(up.b.at(x, y), u + 2 * v, 1e-5f);
      }
    }
  }
}

// Along a depth edge the value changes (a beam's falloff along a wall's silhouette): a pixel
// beside the edge blends the taps of its own side, so the value follows the edge linearly
// instead of in steps of a block (the nearest tap alone is off by up to 3.5 rows of change).
TEST(Upsample, FollowsAnEdgeWithoutStairSteps) {
  ColorPlanes low(16, 16);
  Plane low_depth(16, 16), full_depth(64, 64);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      low_depth.at(x, y) = 4 * x + 2 < 30 ? 2.0f : 20.0f;
      low.set(x, y, RGB((1.0f + 0.1f * float(4 * y + 2)) * low_depth.at(x, y)));
    }
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) full_depth.at(x, y) = x < 30 ? 2.0f : 20.0f;
  for (bool simd : {false, true}) {
    const ColorPlanes up = upsample_nearest_depth(low, low_depth, full_depth, 0.05f, simd);
    for (int y = 2; y < 62; ++y)
      for (int x = 0; x < 64; ++x) {
        const float expect = (1.0f + 0.1f * (float(y) + 0.5f)) * full_depth.at(x, y);
        ASSERT_NEAR(up.r.at(x, y), expect, 2e-6f * expect) << x << "," << y << " simd " << simd;
      }
  }
}

// Scales 4 and 2 take the load-and-permute path inside rows and gathers at the right edge;
// scale 1 gathers throughout.
TEST(Upsample, SimdMatchesScalar) {
  Pcg32 rng(3, 4);
  for (int scale : {4, 2, 1}) {
    const ColorPlanes low = random_planes(108 / scale, 68 / scale, rng);
    const Plane full_depth = blocky_depth(108, 68);
    const Plane low_depth = downsample_depth(full_depth, scale);
    ColorPlanes reused;
    upsample_nearest_depth(low, low_depth, full_depth, reused, 0.05f, true);
    expect_planes_near(upsample_nearest_depth(low, low_depth, full_depth, 0.05f, false), reused, 1e-6f);
  }
}

TEST(Upsample, DownsampleDepthTakesThePixelUnderTheCentre) {
  Plane full(12, 8);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 12; ++x) full.at(x, y) = float(100 * y + x);
  const Plane low = downsample_depth(full, 4, LowResolutionDepth::centre);
  ASSERT_EQ(low.width, 3);
  ASSERT_EQ(low.height, 2);
  EXPECT_EQ(low.at(0, 0), 202.0f);
  EXPECT_EQ(low.at(2, 1), 610.0f);
}

// ---- low-resolution depth against thin features

// A fog's in-scattering up to a surface grows with its depth; the synthetic accumulation of
// these tests gives each low-resolution pixel exactly that of its own depth, so an upsampled
// pixel is right exactly when one of its taps has its surface's depth.
float fog_to(float d) { return 1.0f - std::exp(-0.2f * d); }

ColorPlanes fog_of(const Plane& depth) {
  ColorPlanes c(depth.width, depth.height);
  for (int y = 0; y < depth.height; ++y)
    for (int x = 0; x < depth.width; ++x) c.set(x, y, RGB(fog_to(depth.at(x, y))));
  return c;
}

// Thin features in a 96 x 64 image (quarter resolution: 24 x 16), each at every alignment to
// the 4 x 4 blocks, kept 8 pixels from the borders: cables at 5 m in front of a wall at 10 m,
// one and two pixels wide, across, down and along slopes 1, -1, 1/2 and 2; and slits through
// a wall at 5 m to a background at 30 m, across and down.
struct ThinFeature {
  Plane depth;
  int pixels = 0;  // of the feature
};

ThinFeature line_feature(float base, float feature, int width, int dx, int dy, int offset) {
  ThinFeature f{Plane(96, 64)};
  for (float& v : f.depth.data) v = base;
  const int steps = std::max(std::abs(dx), std::abs(dy));
  for (int t = -200; t <= 200; ++t)
    for (int k = 0; k < width; ++k) {
      // Lines through (48 + offset, 32) (across: offset moves it down).
      const int x = 48 + (dy == 0 ? 0 : offset) + (t * dx) / steps + (dy == 0 ? 0 : k);
      const int y = 32 + (dy == 0 ? offset : 0) + (t * dy) / steps + (dy == 0 ? k : 0);
      if (x < 8 || x >= 88 || y < 8 || y >= 56 || f.depth.at(x, y) == feature) continue;
      f.depth.at(x, y) = feature;
      ++f.pixels;
    }
  return f;
}

std::vector<ThinFeature> thin_features() {
  std::vector<ThinFeature> all;
  const int directions[6][2] = {{1, 0}, {0, 1}, {1, 1}, {1, -1}, {2, 1}, {1, 2}};
  for (int offset = 0; offset < 4; ++offset) {
    for (int width : {1, 2})
      for (const auto& d : directions) all.push_back(line_feature(10.0f, 5.0f, width, d[0], d[1], offset));
    all.push_back(line_feature(5.0f, 30.0f, 1, 1, 0, offset));
    all.push_back(line_feature(5.0f, 30.0f, 1, 0, 1, offset));
  }
  return all;
}

// Pixels (of the feature, of everything) whose upsampled fog is their own surface's.
struct Kept {
  int feature = 0, feature_total = 0, all = 0, total = 0;
};

Kept kept_pixels(LowResolutionDepth mode, bool simd) {
  Kept k;
  for (const ThinFeature& f : thin_features()) {
    const Plane low_depth = downsample_depth(f.depth, 4, mode);
    const ColorPlanes up = upsample_nearest_depth(fog_of(low_depth), low_depth, f.depth, 0.05f, simd);
    const float base = f.depth.at(0, 0);
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 96; ++x) {
        const float d = f.depth.at(x, y);
        const bool ok = std::abs(up.r.at(x, y) - fog_to(d)) <= 1e-5f * fog_to(d);
        k.all += ok;
        ++k.total;
        if (d != base) {
          k.feature += ok;
          ++k.feature_total;
        }
      }
  }
  return k;
}

// The point-sampled depth loses half of a thin cable or slit: the upsample then lights the
// cable with the fog in front of the wall (a leak) or fills the slit with the wall's. The
// min/max depth keeps a tap of every surface: every pixel, feature or not, gets its own fog.
TEST(LowResolutionDepth, MinMaxKeepsThinCablesAndSlits) {
  for (bool simd : {false, true}) {
    const Kept point = kept_pixels(LowResolutionDepth::centre, simd);
    const Kept min_max = kept_pixels(LowResolutionDepth::min_max, simd);
    // Point-sampled: 2214 of the 4574 feature pixels keep their own fog (48 %).
    EXPECT_LT(point.feature, 0.6 * point.feature_total) << point.feature << " of " << point.feature_total;
    EXPECT_EQ(min_max.feature, min_max.feature_total) << "simd " << simd;
    EXPECT_EQ(min_max.all, min_max.total) << "simd " << simd;
  }
}

// On smooth depth (a floor seen at a grazing angle, whose inverse depth is affine in the
// image, and a sphere) every block's depths lie between its centre and its neighbours': the
// min/max depth is the point-sampled one, so the gather sees the same smooth surface.
TEST(LowResolutionDepth, SmoothSurfacesKeepTheirCentres) {
  const View view = View::perspective_view({0, 1.0f, 0}, normalize(Vec3(0, -0.15f, -1)), {0, 1, 0}, radians(60.0f),
                                           {160, 96});
  Plane depth(160, 96);
  for (int y = 0; y < 96; ++y)
    for (int x = 0; x < 160; ++x) {
      const Vec3 dir = view.ray({float(x) + 0.5f, float(y) + 0.5f}).direction;
      float t = dir.y < 0.0f ? 1.0f / -dir.y : 1e9f;  // the floor y = 0
      const Vec3 oc = Vec3(0, 1.0f, 0) - Vec3(0.8f, 0.6f, -4.0f);  // a sphere of radius 0.6
      const float b = dot(oc, dir), c = dot(oc, oc) - 0.36f, disc = b * b - c;
      if (disc > 0.0f && -b - std::sqrt(disc) > 0.0f) t = std::min(t, -b - std::sqrt(disc));
      depth.at(x, y) = t * view.depth_per_t(dir);
    }
  const Plane centre = downsample_depth(depth, 4, LowResolutionDepth::centre);
  const Plane min_max = downsample_depth(depth, 4, LowResolutionDepth::min_max);
  int changed = 0, sphere_edge = 0;
  for (size_t i = 0; i < centre.data.size(); ++i) changed += centre.data[i] != min_max.data[i];
  // Only blocks on the sphere's silhouette (a depth edge) may change.
  for (int y = 0; y < centre.height; ++y)
    for (int x = 0; x < centre.width; ++x)
      if (centre.data[size_t(y * centre.width + x)] != min_max.data[size_t(y * centre.width + x)]) {
        const float d = centre.at(x, y);
        sphere_edge += d < 6.0f && d > 2.0f;
      }
  EXPECT_EQ(changed, sphere_edge);
  EXPECT_LT(changed, 16);  // 5 of the 960 blocks
}

// ---- temporal

View test_view(Vec3 eye) {
  return View::perspective_view(eye, {0, 0, -1}, {0, 1, 0}, radians(50.0f), {64, 48});
}

// A static scene with noisy frames (truth + zero-mean noise) converges to the truth: the
// exponential history has variance alpha / (2 - alpha) of one frame's (alpha ~ 0.1 -> RMS
// 0.23 sigma, 0.24 with the luminance weight at this noise level), and its mean error over
// the image shrinks as 1/sqrt(pixels).
TEST(Temporal, StaticNoisySceneConvergesToTheMean) {
  const View view = test_view({0, 0, 0});
  Plane depth(64, 48);
  ColorPlanes truth(64, 48);
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x) {
      depth.at(x, y) = 5.0f + 0.05f * x;
      truth.set(x, y, RGB(1.0f + 0.01f * x, 0.8f + 0.01f * y, 1.2f));
    }
  const float sigma = 0.1f;
  for (bool simd : {false, true}) {
    Pcg32 rng(42, simd);
    auto noisy = [&] {
      ColorPlanes c = truth;
      for (Plane* p : {&c.r, &c.g, &c.b})
        for (float& v : p->data) v += sigma * gaussian(rng);
      return c;
    };
    ColorPlanes history = noisy();
    for (int frame = 0; frame < 120; ++frame)
      history = temporal_reproject(noisy(), depth, view, history, depth, view, 0.1f, simd);
    double sum = 0.0, sum2 = 0.0;
    for (size_t i = 0; i < truth.g.data.size(); ++i) {
      const double e = history.g.data[i] - truth.g.data[i];
      sum += e;
      sum2 += e * e;
    }
    const double n = double(truth.g.data.size());
    const double rms = std::sqrt(sum2 / n);
    EXPECT_GT(rms, 0.20 * sigma) << simd;
    EXPECT_LT(rms, 0.28 * sigma) << simd;
    EXPECT_LT(std::abs(sum / n), 4.0 * 0.24 * sigma / std::sqrt(n)) << simd;
  }
}

// History from a surface that is no longer there (an occluder moved away: history depth 2,
// current depth 10) is rejected, so the current frame is taken unchanged; with matching
// depth the same history would have been blended in.
TEST(Temporal, RejectsDisoccludedHistory) {
  const View view = test_view({0, 0, 0});
  ColorPlanes current(64, 48), history(64, 48);
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x) {
      current.set(x, y, RGB(1.0f));
      history.set(x, y, RGB(1.5f));
    }
  const Plane depth(64, 48, 10.0f), occluder(64, 48, 2.0f);
  for (bool simd : {false, true}) {
    const ColorPlanes out = temporal_reproject(current, depth, view, history, occluder, view, 0.1f, simd);
    for (float v : out.r.data) EXPECT_EQ(v, 1.0f);
    const ColorPlanes kept = temporal_reproject(current, depth, view, history, depth, view, 0.1f, simd);
    // alpha = 0.1 + 0.9 (0.5 / 1.5)^2 = 0.2 -> 1.5 + (1 - 1.5) 0.2 = 1.4
    for (float v : kept.r.data) EXPECT_NEAR(v, 1.4f, 1e-5f);
  }
}

// A camera moving sideways past a wall: history is found where the wall point was (a
// world-space ramp reprojects exactly), pixels that were outside the old image take the
// current frame, and a foreground object that has moved away leaves no ghost.
TEST(Temporal, ReprojectsAMovingCameraAndRejectsTheOldOccluder) {
  const View old_view = test_view({0, 0, 0}), new_view = test_view({0.6f, 0, 0});
  auto ramp = [](Vec3 p) { return 1.0f + 0.1f * p.x; };
  Plane old_depth(64, 48, 10.0f), new_depth(64, 48, 10.0f);
  ColorPlanes history(64, 48), current(64, 48);
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x) {
      const Vec2 film{x + 0.5f, y + 0.5f};
      // A post 3 m away stood in the old frame's columns 20..27.
      if (x >= 20 && x < 28) old_depth.at(x, y) = 3.0f;
      history.set(x, y, RGB(x >= 20 && x < 28 ? 5.0f : ramp(old_view.unproject(film, 10.0f))));
      current.set(x, y, RGB(ramp(new_view.unproject(film, 10.0f)) + 0.2f));  // biased, so blending shows
    }
  const ColorPlanes scalar =
      temporal_reproject(current, new_depth, new_view, history, old_depth, old_view, 0.1f, false);
  const ColorPlanes simd =
      temporal_reproject(current, new_depth, new_view, history, old_depth, old_view, 0.1f, true);
  expect_planes_near(scalar, simd, 1e-5f);
  int blended = 0, fresh = 0;
  for (int y = 0; y < 48; ++y) {
    for (int x = 0; x < 64; ++x) {
      const Vec3 p = new_view.unproject({x + 0.5f, y + 0.5f}, 10.0f);
      const Vec3 q = old_view.project(p);
      const float truth = ramp(p), cur = current.r.at(x, y);
      // Within 1.5 old pixels of the post or the image border the taps mix: skip those.
      const bool inside = q.x >= 1.5f && q.x < 62.5f && q.y >= 0.0f && q.y < 48.0f;
      const bool clear = q.x < 18.5f || q.x > 29.5f;
      if (q.x < 0.0f || q.x >= 64.0f || (q.x > 20.5f && q.x < 27.5f)) {
        EXPECT_EQ(scalar.r.at(x, y), cur) << x << "," << y;
        ++fresh;
      } else if (inside && clear) {
        // History = truth (a linear ramp reprojects exactly), so the result is
        // lerp(truth, truth + 0.2, alpha) with the luminance weight's alpha: far from both
        // the history-free answer (truth + 0.2) and a ghost of the post (5).
        const float c = 0.2f / (truth + 0.2f);
        const float alpha = 0.1f + 0.9f * c * c;
        EXPECT_NEAR(scalar.r.at(x, y), truth + 0.2f * alpha, 1e-3f) << x << "," << y;
        ++blended;
      }
    }
  }
  EXPECT_GT(blended, 1500);
  EXPECT_GT(fresh, 48 * 8);
}

}  // namespace
}  // namespace caligo
