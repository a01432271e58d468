// The frame loop as a whole: buffer sizes that do not divide by the scale, every light type
// at once, history across frames.
#include "realtime/pipeline.h"
#include "scene/scene.h"

#include <gtest/gtest.h>

#include <cmath>

#include "scene/scene_parser.h"

namespace caligo {
namespace {

SceneDesc every_light_type() {
  return parse_scene_text(R"({
    "camera": {"position": [0, 1.6, 6], "look_at": [0, 1.0, 0], "fov": 50, "resolution": [64, 48]},
    "materials": {"grey": {"type": "diffuse", "reflectance": 0.5}},
    "shapes": [
      {"type": "rectangle", "corner": [-6, 0, -6], "edge1": [0, 0, 12], "edge2": [12, 0, 0], "material": "grey"},
      {"type": "box", "min": [-0.5, 0, -0.5], "max": [0.5, 1.2, 0.5], "material": "grey"}
    ],
    "lights": [
      {"type": "point", "position": [1.5, 3, 1], "intensity": 8},
      {"type": "spot", "position": [-2, 4, 1], "look_at": [0, 0, 0], "inner_angle": 15, "outer_angle": 25,
       "intensity": 30},
      {"type": "box", "position": [0, 4.5, 0], "direction": [0.2, -1, 0], "up": [0, 0, 1], "width": 3,
       "height": 2, "range": 6, "irradiance": 1.5},
      {"type": "directional", "direction": [-0.4, -1, -0.3], "irradiance": 1.2}
    ],
    "media": {"fog": {"sigma_s": 0.15, "sigma_a": 0.02, "phase": {"type": "hg", "g": 0.3}}},
    "volumes": [{"type": "box", "min": [-6, 0, -6], "max": [6, 5, 6], "medium": "fog"}]
  })",
                          "pipeline-test", ".");
}

// 270 / 4 is not whole: the low-resolution buffers are rounded up, and every pass must agree
// on their size (a depth buffer one row short once read garbage and made NaNs).
TEST(RealtimePipeline, SizesThatDoNotDivideByTheScaleGiveFiniteFrames) {
  const SceneDesc desc = every_light_type();
  for (Vec2i res : {Vec2i{98, 67}, Vec2i{61, 45}, Vec2i{33, 17}}) {
    for (int scale : {2, 4}) {
      RealtimeSettings s = realtime_settings(desc);
      s.resolution = res;
      s.scale = scale;
      RealtimePipeline pipeline(Scene::build(desc), s);
      for (uint32_t frame = 0; frame < 3; ++frame) {
        const RealtimeFrame& f = pipeline.render(0.1f * float(frame), frame);
        ASSERT_EQ(f.color.width(), res.x);
        ASSERT_EQ(f.color.height(), res.y);
        double sum = 0;
        for (const Plane* p : {&f.color.r, &f.color.g, &f.color.b})
          for (float v : p->data) {
            ASSERT_TRUE(std::isfinite(v)) << res.x << "x" << res.y << " scale " << scale;
            sum += v;
          }
        EXPECT_GT(sum, 0.0);
      }
    }
  }
}

// Orthographic and thin-lens cameras are the path tracer's only: a located input error, before
// anything is built.
TEST(RealtimePipeline, RefusesOrthographicAndThinLensCameras) {
  for (const char* pointer : {"/camera/projection", "/camera"}) {
    SceneDesc desc = every_light_type();
    if (std::string_view(pointer) == "/camera/projection") {
      desc.camera.projection = CameraProjection::orthographic;
      desc.camera.ortho_width = 4.0f;
    } else {
      desc.camera.fstop = 2.8f;
    }
    try {
      RealtimePipeline pipeline(Scene::build(desc), realtime_settings(desc));
      ADD_FAILURE() << "no error for " << pointer;
    } catch (const InputError& e) {
      EXPECT_EQ(e.where().json_path, pointer);
      EXPECT_NE(std::string(e.what()).find("caligo render"), std::string::npos) << e.what();
    }
  }
}

// A light with volumetric off adds nothing to the volumetric buffer; its surfaces stay lit.
TEST(RealtimePipeline, NonVolumetricLightsLightOnlySurfaces) {
  SceneDesc desc = every_light_type();
  desc.lights.resize(1);
  desc.light_options.resize(1);
  desc.light_options[0].volumetric = false;
  RealtimeSettings s = realtime_settings(desc);
  RealtimePipeline pipeline(Scene::build(desc), s);
  const RealtimeFrame& f = pipeline.render(0.0f, 0);
  double volumetric = 0, surfaces = 0;
  for (size_t i = 0; i < f.volumetric.r.data.size(); ++i) volumetric += f.volumetric.r.data[i];
  for (size_t i = 0; i < f.surfaces.r.data.size(); ++i) surfaces += f.surfaces.r.data[i];
  EXPECT_EQ(volumetric, 0.0);
  EXPECT_GT(surfaces, 0.0);
}

}  // namespace
}  // namespace caligo

namespace caligo {
namespace {

// A pane of glass between the camera and a lit wall: the wall shows through it, dimmed by the
// two interfaces' Fresnel transmission, (1 - F)^2 = 0.9216 at normal incidence for n = 1.5;
// the pixels beside the pane are untouched. (It was drawn as opaque black.)
TEST(RealtimePipeline, GlassShowsWhatIsBehindItThroughItsTransmission) {
  auto scene = [](bool pane) {
    std::string json = R"({
      "camera": {"position": [0, 1, 5], "look_at": [0, 1, 0], "fov": 40, "resolution": [48, 32]},
      "materials": {"grey": {"type": "diffuse", "reflectance": 0.5}, "glass": {"type": "dielectric", "ior": 1.5}},
      "lights": [{"type": "point", "position": [0, 1, 1], "intensity": 4}],
      "shapes": [{"type": "rectangle", "corner": [-4, -2, 0], "edge1": [8, 0, 0], "edge2": [0, 6, 0], "material": "grey"})";
    if (pane)
      json += R"(, {"type": "rectangle", "corner": [-0.5, 0.5, 3], "edge1": [1, 0, 0], "edge2": [0, 1, 0], "material": "glass"})";
    return parse_scene_text(json + "]}", "glass-test", ".");
  };
  const SceneDesc with = scene(true), without = scene(false);
  RealtimeSettings s = realtime_settings(with);
  s.temporal = false;
  RealtimePipeline a(Scene::build(with), s), b(Scene::build(without), s);
  const ColorPlanes seen = a.render(0.0f, 0).color, bare = b.render(0.0f, 0).color;
  int behind = 0;
  for (int y = 0; y < 32; ++y) {
    for (int x = 0; x < 48; ++x) {
      const float ratio = seen.g.at(x, y) / bare.g.at(x, y);
      ASSERT_GT(bare.g.at(x, y), 0.0f) << x << "," << y;
      if (ratio < 0.999f) {
        ++behind;
        EXPECT_NEAR(ratio, 0.9216f, 0.004f) << x << "," << y;  // the pane spans +-4 degrees
      } else {
        EXPECT_EQ(ratio, 1.0f) << x << "," << y;
      }
    }
  }
  EXPECT_GT(behind, 20);
  EXPECT_NEAR(seen.g.at(24, 16) / bare.g.at(24, 16), 0.9216f, 1e-3f);
}

}  // namespace
}  // namespace caligo

namespace caligo {
namespace {

// A cable 4 cm thick at 5 m, in front of a wall at 10 m, in fog lit by an unshadowed sun: at
// quarter resolution the cable is one pixel tall and falls between the low-resolution centres
// in three rows of blocks in four. Against the same frame at full resolution (no interleaving,
// no gather: the march is the same on both), the point-sampled low-resolution depth lights the
// cable with the fog up to the wall behind it (up to 49 % too bright); the min/max depth keeps it.
// What min/max costs: the wall beside the cable in its blocks has one row of taps of its own
// depth, so it takes their value without the vertical gradient of the sun's fog (2.1 % here).
TEST(RealtimePipeline, AThinCableKeepsItsOwnFogAtQuarterResolution) {
  const SceneDesc desc = parse_scene_text(R"({
    "camera": {"position": [0, 1, 0], "look_at": [0, 1, -1], "fov": 40, "resolution": [160, 96]},
    "materials": {"grey": {"type": "diffuse", "reflectance": 0.5}},
    "shapes": [
      {"type": "rectangle", "corner": [-8, -4, -10], "edge1": [16, 0, 0], "edge2": [0, 10, 0], "material": "grey"},
      {"type": "box", "min": [-3, 1.23, -5.02], "max": [3, 1.27, -4.98], "material": "grey"},
      {"type": "box", "min": [-0.73, -1, -5.02], "max": [-0.69, 3, -4.98], "material": "grey"}
    ],
    "lights": [{"type": "directional", "direction": [0.3, -1, -0.2], "irradiance": 2, "shadow": false}],
    "media": {"fog": {"sigma_s": 0.2, "sigma_a": 0.02}},
    "volumes": [{"type": "box", "min": [-9, -5, -11], "max": [9, 7, 1], "medium": "fog"}],
    "realtime": {"tile_size": 1, "samples": 32, "gather_radius": 0, "temporal": false}
  })",
                                          "cable-test", ".");
  const auto volumetric = [&](int scale, LowResolutionDepth mode) {
    RealtimeSettings s = realtime_settings(desc);
    s.scale = scale;
    s.low_depth = mode;
    RealtimePipeline pipeline(Scene::build(desc), s);
    return pipeline.render(0.0f, 0).volumetric;
  };
  const ColorPlanes full = volumetric(1, LowResolutionDepth::min_max);
  struct Errors {
    int wrong = 0;  // pixels more than 10 % off
    double max = 0;
  };
  const auto errors = [&](LowResolutionDepth mode) {
    const ColorPlanes quarter = volumetric(4, mode);
    Errors e;
    for (size_t i = 0; i < full.g.data.size(); ++i) {
      const double rel = std::abs(quarter.g.data[i] - full.g.data[i]) / full.g.data[i];
      e.wrong += rel > 0.1;
      e.max = std::max(e.max, rel);
    }
    return e;
  };
  const Errors point = errors(LowResolutionDepth::centre), min_max = errors(LowResolutionDepth::min_max);
  EXPECT_GT(point.wrong, 100);  // the cables' pixels where no centre hit them
  EXPECT_GT(point.max, 0.3);
  EXPECT_EQ(min_max.wrong, 0) << "point-sampled: " << point.wrong;
  EXPECT_LT(min_max.max, 0.03);
}

}  // namespace
}  // namespace caligo
