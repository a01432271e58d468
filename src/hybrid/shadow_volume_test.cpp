#include "hybrid/shadow_volume.h"

#include <gtest/gtest.h>

#include <cstring>
#include <map>
#include <random>
#include <stdexcept>

#include "hybrid/shadow_volume_testing.h"
#include "realtime/scene_buffers.h"

namespace caligo {
namespace {

using testing::box_mesh;
using testing::DVec;
using testing::sphere_mesh;
using testing::torus_mesh;

// --- Geometry -------------------------------------------------------------------------------

// Closed and consistently oriented: every directed edge a -> b is matched by as many
// b -> a (an edge where two silhouette loops touch may carry four faces).
void expect_closed_outward(const ShadowVolume& v) {
  std::map<std::pair<uint32_t, uint32_t>, int> directed;
  const auto& idx = v.mesh.indices;
  for (size_t t = 0; t < v.mesh.triangle_count(); ++t)
    for (int k = 0; k < 3; ++k) ++directed[{idx[3 * t + size_t(k)], idx[3 * t + size_t((k + 1) % 3)]}];
  for (const auto& [e, count] : directed) {
    const auto it = directed.find({e.second, e.first});
    ASSERT_TRUE(it != directed.end()) << "edge " << e.first << "-" << e.second << " has one face";
    EXPECT_EQ(it->second, count);
  }
  double volume = 0;  // divergence theorem, about the light to keep the terms small
  for (size_t t = 0; t < v.mesh.triangle_count(); ++t) {
    const Vec3 a = v.mesh.positions[idx[3 * t]] - v.light, b = v.mesh.positions[idx[3 * t + 1]] - v.light,
               c = v.mesh.positions[idx[3 * t + 2]] - v.light;
    volume += double(dot(a, cross(b, c))) / 6.0;
  }
  EXPECT_GT(volume, 0.0) << "volume wound inwards";
}

TEST(ShadowVolume, VolumesAreClosedAndOutwardForCubeSphereAndTorus) {
  const TriangleMesh meshes[] = {box_mesh({-1, -1, -1}, {1, 1, 1}), sphere_mesh({0, 0, 0}, 1.0f, 3),
                                 torus_mesh({0, 0, 0}, 2.0f, 0.6f, 24, 12)};
  const Vec3 lights[] = {{0.1f, 0.2f, 5.0f}, {4.0f, 5.0f, 6.0f}, {-3.0f, 0.4f, 0.2f}, {0.3f, 6.0f, -0.2f}};
  for (const TriangleMesh& mesh : meshes) {
    const MeshEdges edges(mesh);
    for (Vec3 light : lights) {
      const ShadowVolume v = build_shadow_volume(edges, light, 20.0f);
      EXPECT_EQ(v.side_triangles, 2 * find_silhouette(edges, light).edges.size());
      EXPECT_EQ(v.near_cap_triangles, v.far_cap_triangles);
      EXPECT_EQ(v.mesh.triangle_count(), v.side_triangles + v.near_cap_triangles + v.far_cap_triangles);
      expect_closed_outward(v);
    }
  }
}

TEST(ShadowVolume, RejectsOpenMeshesAndBadExtrusion) {
  TriangleMesh open = box_mesh({0, 0, 0}, {1, 1, 1});
  open.indices.resize(open.indices.size() - 3);
  EXPECT_THROW(build_shadow_volume(MeshEdges(open), {0, 5, 0}, 10.0f), std::invalid_argument);
  const MeshEdges cube(box_mesh({0, 0, 0}, {1, 1, 1}));
  EXPECT_THROW(build_shadow_volume(cube, {0, 5, 0}, 0.0f), std::invalid_argument);
  EXPECT_THROW(build_shadow_volume(cube, {0, 5, 0}, kInfinity), std::invalid_argument);
}

// Brute force: within the extrusion, a point's winding number is the number of lit occluder
// triangles that the segment light -> point crosses (each lit triangle's prism contains it).
int lit_layers_between(const TriangleMesh& mesh, Vec3 light, Vec3 point) {
  int n = 0;
  const DVec o{light.x, light.y, light.z},
      d{double(point.x) - light.x, double(point.y) - light.y, double(point.z) - light.z};
  for (size_t t = 0; t < mesh.triangle_count(); ++t) {
    const Vec3 a = mesh.positions[mesh.indices[3 * t]], b = mesh.positions[mesh.indices[3 * t + 1]],
               c = mesh.positions[mesh.indices[3 * t + 2]];
    if (const auto hit = testing::intersect(o, d, a, b, c); hit && hit->t < 1.0 && hit->d_dot_n < 0.0) ++n;
  }
  return n;
}

TEST(ShadowVolume, PointContainmentMatchesLitLayersCrossed) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-4.0f, 4.0f);
  const TriangleMesh meshes[] = {sphere_mesh({0, 0, 0}, 1.0f, 2), torus_mesh({0, 0, 0}, 2.0f, 0.6f, 24, 12)};
  for (const TriangleMesh& mesh : meshes) {
    const Vec3 light{0.3f, 5.0f, 0.7f};
    const ShadowVolume v = build_shadow_volume(MeshEdges(mesh), light, 30.0f);
    int inside = 0;
    for (int i = 0; i < 2000; ++i) {
      const Vec3 p{u(rng), u(rng) - 2.0f, u(rng)};
      const int expected = lit_layers_between(mesh, light, p);
      EXPECT_EQ(volumes_containing(v, p), expected) << p.x << " " << p.y << " " << p.z;
      inside += expected > 0;
    }
    EXPECT_GT(inside, 100);  // the sample exercises both answers
  }
  // Beyond the far cap nothing is in shadow.
  const ShadowVolume v = build_shadow_volume(MeshEdges(sphere_mesh({0, 0, 0}, 1.0f, 2)), {0, 5, 0}, 3.0f);
  EXPECT_EQ(volumes_containing(v, {0, -1.5f, 0}), 1);
  EXPECT_EQ(volumes_containing(v, {0, -3.5f, 0}), 0);
}

// --- The eye pass against ray casting ----------------------------------------------------------

struct TestScene {
  TriangleMesh opaque;  // ground and occluders
  std::vector<TriangleMesh> occluders;
  Vec3 light;
  View view;
  std::vector<ShadowVolume> volumes;
};

TestScene make_scene(std::vector<TriangleMesh> occluders, Vec3 light, Vec3 eye, Vec3 target) {
  TestScene s;
  testing::add_triangle(s.opaque, {-20, 0, -20}, {-20, 0, 20}, {20, 0, 20});
  testing::add_triangle(s.opaque, {-20, 0, -20}, {20, 0, 20}, {20, 0, -20});
  for (const auto& o : occluders) testing::append(s.opaque, o);
  s.occluders = std::move(occluders);
  s.light = light;
  s.view = View::perspective_view(eye, normalize(target - eye), {0, 1, 0}, radians(55.0f), {96, 72});
  Bounds3 b;
  for (Vec3 p : s.opaque.positions) b.extend(p);
  for (const auto& o : s.occluders)
    s.volumes.push_back(build_shadow_volume(MeshEdges(o), light, extrusion_for(b, light)));
  return s;
}

double nearest_hit(const TriangleMesh& mesh, DVec o, DVec d) {
  double best = kInfinity;
  for (size_t t = 0; t < mesh.triangle_count(); ++t)
    if (const auto hit = testing::intersect(o, d, mesh.positions[mesh.indices[3 * t]],
                                            mesh.positions[mesh.indices[3 * t + 1]],
                                            mesh.positions[mesh.indices[3 * t + 2]]))
      best = std::min(best, hit->t);
  return best;
}

Plane opaque_depth(const TestScene& s, bool with_occluders) {
  Plane depth(s.view.resolution.x, s.view.resolution.y);
  TriangleMesh mesh = s.opaque;
  if (!with_occluders) {  // the ground alone: its two triangles come first
    mesh.positions.resize(6);
    mesh.indices.resize(6);
  }
  for (int y = 0; y < depth.height; ++y)
    for (int x = 0; x < depth.width; ++x) {
      const Ray r = s.view.ray({float(x) + 0.5f, float(y) + 0.5f});
      const double t = nearest_hit(mesh, {r.origin.x, r.origin.y, r.origin.z},
                                   {r.direction.x, r.direction.y, r.direction.z});
      depth.at(x, y) = std::isfinite(t) ? float(t * s.view.depth_per_t(r.direction)) : kSkyDepth;
    }
  return depth;
}

struct PixelTruth {
  bool covered = false;
  double front = kInfinity, back = -kInfinity;
  int tail = 0;
  bool near_cut = false;  // some surface within 0.1 % of the opaque depth cut
};

PixelTruth cast(const TestScene& s, Vec2 film, float opaque, const ShadowVolumeOptions& options,
                int eye_count) {
  const Ray r = s.view.ray(film);
  const DVec o{r.origin.x, r.origin.y, r.origin.z}, d{r.direction.x, r.direction.y, r.direction.z};
  const double per_t = s.view.depth_per_t(r.direction);
  const double cut = double(opaque) * (1.0 - double(options.depth_bias));
  PixelTruth p;
  p.tail = eye_count;
  for (const ShadowVolume& v : s.volumes) {
    auto range = [&](size_t begin, size_t count) {
      for (size_t t = begin; t < begin + count; ++t) {
        const auto hit = testing::intersect(o, d, v.mesh.positions[v.mesh.indices[3 * t]],
                                            v.mesh.positions[v.mesh.indices[3 * t + 1]],
                                            v.mesh.positions[v.mesh.indices[3 * t + 2]]);
        if (!hit) continue;
        const double depth = hit->t * per_t;
        if (std::abs(depth - cut) < 1e-3 * cut) p.near_cut = true;
        if (depth < 1e-3 || depth >= cut) continue;
        p.covered = true;
        p.front = std::min(p.front, hit->t);
        p.back = std::max(p.back, hit->t);
        p.tail += hit->d_dot_n < 0.0 ? 1 : -1;  // against the outward normal: entering
      }
    };
    range(v.side_begin(), v.side_triangles);
    if (options.near_caps) range(v.near_cap_begin(), v.near_cap_triangles);
    if (options.far_caps) range(v.far_cap_begin(), v.far_cap_triangles);
  }
  if (eye_count > 0) {
    p.covered = true;
    p.front = 0.0;
    if (p.back < 0.0) p.back = 0.0;
  }
  return p;
}

bool same(const PixelTruth& a, const PixelTruth& b) {
  if (a.covered != b.covered || a.tail != b.tail) return false;
  if (!a.covered) return true;
  return std::abs(a.front - b.front) <= 1e-3 * b.front + 1e-4 &&
         std::abs(a.back - b.back) <= 1e-3 * b.back + 1e-4;
}

struct Comparison {
  int covered = 0, ambiguous = 0, compared = 0;
};

// Pixels whose ray-cast answer changes within 0.002 pixels (the volume's outline on screen)
// or that have a surface within 0.1 % of the depth cut are ambiguous: the rasteriser may
// decide them either way. Everywhere else coverage and crossing counts must agree exactly
// and the distances to 0.1 %.
Comparison compare_with_ray_casting(const TestScene& s, const Plane& depth, const ShadowVolumeBuffers& b,
                                    const ShadowVolumeOptions& options, int eye_count) {
  Comparison c;
  constexpr float kDelta = 0.002f;
  const Vec2 offsets[4] = {{kDelta, 0}, {-kDelta, 0}, {0, kDelta}, {0, -kDelta}};
  for (int y = 0; y < depth.height; ++y)
    for (int x = 0; x < depth.width; ++x) {
      const float front = b.front.at(x, y), back = b.back.at(x, y);
      EXPECT_FALSE(std::isnan(front) || std::isnan(back));
      EXPECT_GE(b.tail(x, y), 0);
      if (b.covered(x, y)) {
        EXPECT_LE(front, back);
      }
      const Vec2 centre{float(x) + 0.5f, float(y) + 0.5f};
      const PixelTruth truth = cast(s, centre, depth.at(x, y), options, eye_count);
      bool ambiguous = truth.near_cut;
      for (Vec2 off : offsets)
        ambiguous |=
            !same(cast(s, {centre.x + off.x, centre.y + off.y}, depth.at(x, y), options, eye_count), truth);
      c.covered += truth.covered;
      if (ambiguous) {
        ++c.ambiguous;
        continue;
      }
      ++c.compared;
      PixelTruth got;
      got.covered = b.covered(x, y);
      got.front = front, got.back = back, got.tail = b.tail(x, y);
      EXPECT_TRUE(same(got, truth)) << "pixel " << x << "," << y << ": covered " << got.covered << "/"
                                    << truth.covered << " front " << got.front << "/" << truth.front
                                    << " back " << got.back << "/" << truth.back << " tail " << got.tail
                                    << "/" << truth.tail;
    }
  return c;
}

void check_scene(const TestScene& s, int expected_eye_count, const ShadowVolumeOptions& options = {},
                 bool occluders_in_depth = true) {
  const Plane depth = opaque_depth(s, occluders_in_depth);
  const ShadowVolumeBuffers b = rasterize_shadow_volumes(s.volumes, s.view, depth, options);
  int eye_truth = 0;
  for (const auto& o : s.occluders) eye_truth += lit_layers_between(o, s.light, s.view.eye);
  EXPECT_EQ(b.eye_count, eye_truth);
  EXPECT_EQ(b.eye_count, expected_eye_count);
  const Comparison c = compare_with_ray_casting(s, depth, b, options, b.eye_count);
  const int pixels = depth.width * depth.height;
  EXPECT_GT(c.covered, pixels / 40) << "the scene must put shadow volumes on screen";
  EXPECT_LT(c.ambiguous, pixels / 20) << "too many pixels excluded from the comparison";
  std::printf("    %d of %d pixels covered, %d compared, %d on outlines or the depth cut\n", c.covered,
              pixels, c.compared, c.ambiguous);
  // The scalar tile loop gives the same buffers bit for bit.
  ShadowVolumeOptions scalar = options;
  scalar.simd = !options.simd;
  const ShadowVolumeBuffers other = rasterize_shadow_volumes(s.volumes, s.view, depth, scalar);
  EXPECT_EQ(other.tail_count, b.tail_count);
  int differing = 0;
  for (size_t i = 0; i < b.front.data.size(); ++i)
    differing += std::memcmp(&b.front.data[i], &other.front.data[i], sizeof(float)) != 0 ||
                 std::memcmp(&b.back.data[i], &other.back.data[i], sizeof(float)) != 0;
  EXPECT_EQ(differing, 0) << "pixels where the SIMD and scalar tile loops differ";
}

TEST(ShadowVolumeBuffers, SphereOverGroundMatchesRayCasting) {
  check_scene(make_scene({sphere_mesh({0, 1.5f, 0}, 1.0f, 2)}, {0.7f, 6.0f, 0.4f}, {0, 3, 9}, {0, 0.8f, 0}),
              0);
}

TEST(ShadowVolumeBuffers, LowLightSendsTheVolumeIntoTheSkyThroughItsFarCap) {
  check_scene(
      make_scene({sphere_mesh({0, 1.5f, 0}, 1.0f, 2)}, {-6.0f, 1.2f, 0.3f}, {-1, 2, 10}, {4, 1.8f, 0}), 0);
}

TEST(ShadowVolumeBuffers, BoxAndTorusMatchRayCasting) {
  check_scene(make_scene({box_mesh({-1, 1, -0.5f}, {1, 2.5f, 0.5f})}, {2, 7, 1}, {1, 4, 9}, {0, 1, 0}), 0);
  check_scene(make_scene({torus_mesh({0, 1.5f, 0}, 1.5f, 0.4f, 32, 12)}, {0.5f, 5.0f, -3.0f}, {0, 6, 8},
                         {0, 0.5f, 0}),
              0);
}

TEST(ShadowVolumeBuffers, OverlappingVolumesOfTwoBoxesCountTwice) {
  const TestScene s =
      make_scene({box_mesh({-1, 3, -1}, {1, 3.5f, 1}), box_mesh({-0.5f, 1, -0.5f}, {1.5f, 2, 0.5f})},
                 {0.3f, 8, 0.2f}, {2, 5, 8}, {0, 0.5f, 0});
  check_scene(s, 0);
  const Plane depth = opaque_depth(s, true);
  const ShadowVolumeBuffers b = rasterize_shadow_volumes(s.volumes, s.view, depth);
  int twice = 0;
  for (int32_t c : b.tail_count) twice += c == 2;
  EXPECT_GT(twice, 0) << "no pixel sees ground in both shadows";
}

TEST(ShadowVolumeBuffers, CameraInsideTheShadowStartsAtZero) {
  const TestScene s =
      make_scene({box_mesh({-1, 3, -1}, {1, 4, 1})}, {0, 10, 0}, {0.2f, 1.0f, 0.1f}, {0, 0.3f, 5});
  check_scene(s, 1);
  const ShadowVolumeBuffers b = rasterize_shadow_volumes(s.volumes, s.view, opaque_depth(s, true));
  int lit_tail = 0, dark_tail = 0;
  for (int y = 0; y < b.front.height; ++y)
    for (int x = 0; x < b.front.width; ++x) {
      EXPECT_EQ(b.front.at(x, y), 0.0f);
      (b.tail(x, y) == 0 ? lit_tail : dark_tail)++;
    }
  EXPECT_GT(lit_tail, 0);   // ground beyond the shadow
  EXPECT_GT(dark_tail, 0);  // ground inside it
}

TEST(ShadowVolumeBuffers, NearCapsAgreeWhenTheOccluderIsMissingFromTheDepth) {
  ShadowVolumeOptions options;
  options.near_caps = true;
  const TestScene s =
      make_scene({sphere_mesh({0, 1.5f, 0}, 1.0f, 2)}, {0.7f, 6.0f, 0.4f}, {0, 3, 9}, {0, 0.8f, 0});
  check_scene(s, 0, options, /*occluders_in_depth=*/false);
  check_scene(s, 0, options, /*occluders_in_depth=*/true);
}

TEST(ShadowVolumeBuffers, RejectsADepthBufferOfAnotherSize) {
  const TestScene s = make_scene({box_mesh({-1, 1, -1}, {1, 2, 1})}, {0, 6, 0}, {0, 3, 9}, {0, 1, 0});
  EXPECT_THROW(rasterize_shadow_volumes(s.volumes, s.view, Plane(10, 10, 1.0f)), std::invalid_argument);
}

}  // namespace
}  // namespace caligo
