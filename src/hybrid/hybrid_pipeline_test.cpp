// The methods of `caligo realtime --method` inside the real-time frame: hybrid against brute
// force and the march on a small Wyman-like scene, and the fallbacks to the march.
#include "hybrid/hybrid_pipeline.h"

#include <gtest/gtest.h>

#include "geometry/shapes.h"

#include <cmath>
#include <cstdio>
#include <string>
#include <tuple>

#include "scene/scene.h"
#include "scene/scene_parser.h"

namespace caligo {
namespace {

// A point light in a fog box over a closed ground box, a 1,280-triangle icosphere occluder.
SceneDesc wyman_like(const std::string& ground = R"({"type": "box", "min": [-5, -0.1, -5], "max": [5, 0, 5],
    "material": "grey"})",
                     const std::string& phase = "") {
  return parse_scene_text(R"({
    "camera": {"position": [0, 2.0, 4.5], "look_at": [0, 1.0, 0], "fov": 50, "resolution": [64, 64]},
    "materials": {"grey": {"type": "diffuse", "reflectance": 0.5}},
    "shapes": [)" + ground + R"(,
      {"type": "mesh", "generate": {"kind": "sphere", "triangles": 1280}, "material": "grey",
       "transform": [{"scale": 0.7}, {"translate": [0, 1.5, 0]}]}
    ],
    "lights": [{"type": "point", "position": [0.4, 3.6, -0.3], "color": [1, 0.9, 0.8], "intensity": 30}],
    "media": {"fog": {"sigma_s": 0.25, "sigma_a": 0.03)" +
                              phase + R"(}},
    "volumes": [{"type": "box", "min": [-5, 0, -5], "max": [5, 5, 5], "medium": "fog"}]
  })",
                          "hybrid-pipeline-test", ".");
}

struct Rendered {
  ColorPlanes volumetric;  // low resolution, gathered, no history
  VolumetricMethod used = VolumetricMethod::kMarch;
  std::string open_occluder;
};

Rendered render(const SceneDesc& desc, VolumetricMethod method, int march_samples = 16) {
  RealtimeSettings s = realtime_settings(desc);
  s.resolution = {64, 64};
  s.scale = 2;
  s.temporal = false;
  s.accumulation.samples = march_samples;
  RealtimePipeline pipeline(Scene::build(desc), s);
  HybridScatterer* scatterer = nullptr;
  if (method != VolumetricMethod::kMarch) {
    auto owned = std::make_unique<HybridScatterer>(pipeline.scene(), method);
    scatterer = owned.get();
    pipeline.set_scatterer(std::move(owned));
  }
  Rendered r;
  r.volumetric = pipeline.render(0.0f, 0).low_volumetric;
  if (scatterer) {
    r.used = scatterer->used(0);
    r.open_occluder = scatterer->open_occluder();
  }
  return r;
}

double mean(const ColorPlanes& c) {
  double sum = 0;
  size_t n = 0;
  for (const Plane* p : {&c.r, &c.g, &c.b})
    for (float v : p->data) {
      EXPECT_TRUE(std::isfinite(v));
      EXPECT_GE(v, 0.0f);
      sum += v;
      ++n;
    }
  return sum / double(n);
}

TEST(HybridPipeline, ParsesMethodNames) {
  for (VolumetricMethod m : {VolumetricMethod::kMarch, VolumetricMethod::kNone, VolumetricMethod::kBrute,
                             VolumetricMethod::kHybrid, VolumetricMethod::kTextured})
    EXPECT_EQ(parse_volumetric_method(volumetric_method_name(m)), m);
  EXPECT_FALSE(parse_volumetric_method("spot"));
  EXPECT_FALSE(parse_volumetric_method("Hybrid"));
}

// The hybrid marches only inside the shadow volumes and takes the closed form elsewhere: the
// same integral as brute force (150 steps over the whole ray), so the frames agree closely;
// with no shadows at all every pixel is at least as bright, and clearly brighter overall
// because the sphere's shadow shaft crosses the view.
TEST(HybridPipeline, HybridMatchesBruteForceAndNoShadowsIsBrighter) {
  const SceneDesc desc = wyman_like();
  const Rendered hybrid = render(desc, VolumetricMethod::kHybrid);
  const Rendered brute = render(desc, VolumetricMethod::kBrute);
  const Rendered none = render(desc, VolumetricMethod::kNone);
  EXPECT_EQ(hybrid.used, VolumetricMethod::kHybrid);
  EXPECT_EQ(brute.used, VolumetricMethod::kBrute);
  EXPECT_EQ(none.used, VolumetricMethod::kNone);
  EXPECT_TRUE(hybrid.open_occluder.empty()) << hybrid.open_occluder;
  const double h = mean(hybrid.volumetric), b = mean(brute.volumetric), n = mean(none.volumetric);
  std::printf("volumetric means: hybrid %.6g, brute %.6g, none %.6g (hybrid/brute - 1 = %+.3f %%)\n", h, b, n,
              (h / b - 1.0) * 100.0);
  ASSERT_GT(b, 0.0);
  // Both frames are deterministic: their means measured +0.006 % apart (2026-12), held to twice
  // that (the tolerance was 1 %).
  EXPECT_NEAR(h / b, 1.0, 1.2e-4);
  // Measured: the shaft covers a small part of the view, none is +2.2 % over the frame.
  EXPECT_GT(n, 1.01 * b);
  EXPECT_GT(n, 1.01 * h);
  // Pixel by pixel: the shadowed integrand never exceeds the unshadowed one, and in the
  // shaft (the pixels the shadow darkens by 10 % or more) the hybrid is as dark as brute force.
  const float tolerance = 1e-4f * float(n);
  int shaft = 0;
  double shaft_h = 0, shaft_b = 0;
  for (size_t i = 0; i < none.volumetric.r.data.size(); ++i) {
    const float vn = none.volumetric.r.data[i], vb = brute.volumetric.r.data[i],
                vh = hybrid.volumetric.r.data[i];
    EXPECT_GE(vn + tolerance, vb) << i;
    EXPECT_GE(vn + tolerance, vh) << i;
    if (vb < 0.9f * vn) {
      ++shaft;
      shaft_h += vh;
      shaft_b += vb;
    }
  }
  std::printf("shaft: %d pixels, hybrid/brute - 1 = %+.3f %%\n", shaft, (shaft_h / shaft_b - 1.0) * 100.0);
  EXPECT_GE(shaft, 20);
  // Measured +0.009 % in the shaft (2026-12), held to twice that (was 2 %).
  EXPECT_NEAR(shaft_h / shaft_b, 1.0, 1.8e-4);
}

// The march (accumulate_light, 64 steps, interleaved) integrates the same single scattering of
// the same light in the same medium. Both frames are deterministic; their means measured
// +0.28 % apart (2026-12), held to twice that.
TEST(HybridPipeline, HybridAgreesWithTheMarch) {
  const SceneDesc desc = wyman_like();
  const double h = mean(render(desc, VolumetricMethod::kHybrid).volumetric);
  const double m = mean(render(desc, VolumetricMethod::kMarch, 64).volumetric);
  std::printf("volumetric means: hybrid %.6g, march %.6g (hybrid/march - 1 = %+.2f %%)\n", h, m,
              (h / m - 1.0) * 100.0);
  EXPECT_NEAR(h / m, 1.0, 0.006);
}

// An anisotropic phase is outside the airlight model: the light is left to the march, and the
// frame is the plain pipeline's bit for bit.
TEST(HybridPipeline, AnisotropicPhaseFallsBackToTheMarch) {
  const SceneDesc desc =
      wyman_like(R"({"type": "box", "min": [-5, -0.1, -5], "max": [5, 0, 5], "material": "grey"})",
                 R"(, "phase": {"type": "hg", "g": 0.3})");
  const Rendered hybrid = render(desc, VolumetricMethod::kHybrid);
  const Rendered march = render(desc, VolumetricMethod::kMarch);
  EXPECT_EQ(hybrid.used, VolumetricMethod::kMarch);
  EXPECT_EQ(hybrid.volumetric.r.data, march.volumetric.r.data);
  EXPECT_EQ(hybrid.volumetric.b.data, march.volumetric.b.data);
}

// An open ground rectangle cannot bound a shadow volume of its own: its bounding box stands in
// (bounding_box_proxy), rays ending inside a volume are marched to their surface, and the hybrid
// still runs as the hybrid, agreeing with brute force as closely as with closed occluders only
// (the sphere's shaft is still found) and saying which geometry is open.
TEST(HybridPipeline, AnOpenOccluderStandsInByItsBoundingBox) {
  const SceneDesc desc =
      wyman_like(R"({"type": "rectangle", "corner": [-5, 0, -5], "edge1": [0, 0, 10], "edge2": [10, 0, 0],
                     "material": "grey"})");
  const Rendered hybrid = render(desc, VolumetricMethod::kHybrid);
  const Rendered brute = render(desc, VolumetricMethod::kBrute);
  const Rendered none = render(desc, VolumetricMethod::kNone);
  EXPECT_EQ(hybrid.used, VolumetricMethod::kHybrid);
  EXPECT_NE(hybrid.open_occluder.find("boundary"), std::string::npos) << hybrid.open_occluder;
  const double h = mean(hybrid.volumetric), b = mean(brute.volumetric), n = mean(none.volumetric);
  std::printf("open ground: hybrid %.6g, brute %.6g, none %.6g (hybrid/brute - 1 = %+.4f %%)\n", h, b, n,
              (h / b - 1.0) * 100.0);
  EXPECT_GT(n, 1.01 * b);  // the shaft is there
  EXPECT_NEAR(h / b, 1.0, 1.2e-4);
}

// ShapeDesc::proxy: the hybrid builds the shape's shadow volumes from its proxy alone. A sphere
// proxy of the occluder's own size gives the brute-force march's shafts (the mesh is a 1,280-
// triangle sphere, the proxy a 5,120-triangle one 0.2 % larger); a box proxy around it casts the
// box's wider shadow, so less light reaches the camera than brute force sees.
TEST(HybridPipeline, AShadowProxyStandsInForItsShape) {
  SceneDesc desc = wyman_like();
  const double brute = mean(render(desc, VolumetricMethod::kBrute).volumetric);
  desc.shapes[1].proxy = SphereShape{{0, 0, 0}, 1.0f};
  const Rendered sphere = render(desc, VolumetricMethod::kHybrid);
  desc.shapes[1].proxy = BoxShape{{-1, -1, -1}, {1, 1, 1}};
  const Rendered box = render(desc, VolumetricMethod::kHybrid);
  EXPECT_EQ(sphere.used, VolumetricMethod::kHybrid);
  const double s = mean(sphere.volumetric), b = mean(box.volumetric);
  std::printf("proxies: sphere/brute - 1 = %+.4f %%, box/brute - 1 = %+.4f %%\n", (s / brute - 1) * 100,
              (b / brute - 1) * 100);
  EXPECT_NEAR(s / brute, 1.0, 2e-3);
  EXPECT_LT(b, 0.99 * brute);
  // An open proxy is refused, naming the shape.
  desc.shapes[1].proxy = RectangleShape{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  EXPECT_THROW(Scene::build(desc), InputError);
}

// The proxy: closed, and it holds every vertex of the mesh (so its shadow holds the mesh's).
TEST(HybridPipeline, TheBoundingBoxProxyIsClosedAndHoldsTheMesh) {
  TriangleMesh card = rectangle_mesh({-1, 0, -1}, {0, 0, 2}, {2, 0, 0});
  EXPECT_FALSE(MeshEdges(card).closed());
  const TriangleMesh proxy = bounding_box_proxy(card);
  EXPECT_TRUE(MeshEdges(proxy).closed()) << MeshEdges(proxy).problem();
  Bounds3 b;
  for (Vec3 p : proxy.positions) b.extend(p);
  for (Vec3 p : card.positions) EXPECT_TRUE(b.contains(p));
  EXPECT_GT(b.diagonal().y, 0.0f);
}

}  // namespace
}  // namespace caligo

namespace caligo {
namespace {

// A spot over a ground box with a sphere in its cone, in a fog box of the given medium.
SceneDesc spot_scene(const std::string& medium = R"("sigma_s": 0.25, "sigma_a": 0.03)") {
  return parse_scene_text(R"({
    "camera": {"position": [0, 2.0, 4.5], "look_at": [0, 1.0, 0], "fov": 50, "resolution": [64, 64]},
    "materials": {"grey": {"type": "diffuse", "reflectance": 0.5}},
    "shapes": [{"type": "box", "min": [-5, -0.1, -5], "max": [5, 0, 5], "material": "grey"},
      {"type": "mesh", "generate": {"kind": "sphere", "triangles": 1280}, "material": "grey",
       "transform": [{"scale": 0.5}, {"translate": [0.1, 1.8, 0]}]}],
    "lights": [{"type": "spot", "position": [0.3, 3.8, -0.2], "look_at": [0, 0, 0], "inner_angle": 18,
                "outer_angle": 26, "color": [1, 0.9, 0.8], "intensity": 40}],
    "media": {"fog": {)" + medium + R"(}},
    "volumes": [{"type": "box", "min": [-5, 0, -5], "max": [5, 5, 5], "medium": "fog"}]
  })",
                          "textured-spot-test", ".");
}

// --method textured: a spot light takes the textured-spotlight pass, and agrees with the
// Lords of the Fallen march of the same light (both single scattering, shadow-mapped).
TEST(HybridPipeline, TexturedSpotAgreesWithTheMarch) {
  const SceneDesc desc = spot_scene();
  const Rendered textured = render(desc, VolumetricMethod::kTextured);
  EXPECT_EQ(textured.used, VolumetricMethod::kTextured);
  const double t = mean(textured.volumetric);
  const double m = mean(render(desc, VolumetricMethod::kMarch, 64).volumetric);
  ASSERT_GT(m, 0.0);
  std::printf("volumetric means: textured %.6g, march %.6g (textured/march - 1 = %+.2f %%)\n", t, m,
              (t / m - 1.0) * 100.0);
  // Deterministic frames, measured +1.47 % apart (2026-12; the two passes place the shadow edge
  // differently: the march's 64 interleaved steps against the textured pass's 16-150), held to
  // twice that.
  EXPECT_NEAR(t / m, 1.0, 0.03) << "textured " << t << ", march " << m;
  // Under kHybrid the spot is not taken (the point-light model): it keeps the march.
  EXPECT_EQ(render(desc, VolumetricMethod::kHybrid).used, VolumetricMethod::kMarch);
}

// A spot in a coloured, forward-scattering fog: outside the airlight, so kTextured takes
// Hoffman and Preetham's model (one pass, the scene's phase) and agrees with the march per channel.
TEST(HybridPipeline, TexturedSpotInAnisotropicColouredFogTakesHoffmanPreetham) {
  const SceneDesc desc = spot_scene(R"("sigma_s": [0.15, 0.25, 0.35], "sigma_a": 0.03, "phase": {"type": "hg", "g": 0.5})");
  const Rendered textured = render(desc, VolumetricMethod::kTextured);
  EXPECT_EQ(textured.used, VolumetricMethod::kTextured);
  const Rendered march = render(desc, VolumetricMethod::kMarch, 64);
  for (const auto& [name, t, m] : {std::tuple{"r", &textured.volumetric.r, &march.volumetric.r},
                                   std::tuple{"b", &textured.volumetric.b, &march.volumetric.b}}) {
    double st = 0, sm = 0;
    for (size_t i = 0; i < t->data.size(); ++i) st += t->data[i], sm += m->data[i];
    ASSERT_GT(sm, 0.0);
    std::printf("anisotropic coloured fog, channel %s: textured/march - 1 = %+.2f %%\n", name, (st / sm - 1) * 100);
    // As in the isotropic test above (+1.47 % there): the passes place the shadow edge differently.
    EXPECT_NEAR(st / sm, 1.0, 0.03) << name;
  }
}

}  // namespace
}  // namespace caligo
