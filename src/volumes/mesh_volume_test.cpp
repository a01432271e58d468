#include "volumes/mesh_volume.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "core/ray_solids.h"
#include "core/rng.h"
#include "geometry/shapes.h"
#include "scene/mesh_loader.h"

namespace caligo {
namespace {

using Intervals = std::vector<RayRange>;

// The ray's overlap with `box` within its range, as two floats.
bool box_overlap(const Bounds3& box, const Ray& ray, float* t0, float* t1) {
  const auto range = ray_box(ray, box);
  if (range) {
    *t0 = range->t0;
    *t1 = range->t1;
  }
  return range.has_value();
}

const SourceLocation kWhere{"scene.json", "/volumes/0/shape"};

// ---- Meshes --------------------------------------------------------------------------------

// Appends `part` to `mesh`, shifting its indices.
void append(TriangleMesh& mesh, const TriangleMesh& part) {
  const auto base = uint32_t(mesh.positions.size());
  mesh.positions.insert(mesh.positions.end(), part.positions.begin(), part.positions.end());
  for (uint32_t i : part.indices) mesh.indices.push_back(base + i);
}

struct Point2 {
  double x, y;
};

// A prism over a polygon that is star-shaped about `centre` (so a fan from it triangulates the
// caps), for z in [z0, z1].
TriangleMesh prism_mesh(const std::vector<Point2>& polygon, Point2 centre, float z0, float z1) {
  TriangleMesh mesh;
  const auto n = uint32_t(polygon.size());
  for (float z : {z0, z1})
    for (Point2 p : polygon) mesh.positions.push_back({float(p.x), float(p.y), z});
  mesh.positions.push_back({float(centre.x), float(centre.y), z0});
  mesh.positions.push_back({float(centre.x), float(centre.y), z1});
  for (uint32_t i = 0; i < n; ++i) {
    const uint32_t j = (i + 1) % n;
    mesh.indices.insert(mesh.indices.end(),
                        {2 * n, j, i, 2 * n + 1, n + i, n + j, i, j, n + j, i, n + j, n + i});
  }
  return mesh;
}

std::vector<Point2> star_polygon(int points, double inner, double outer) {
  std::vector<Point2> polygon;
  for (int k = 0; k < 2 * points; ++k) {
    const double r = k % 2 == 0 ? outer : inner, angle = M_PI * k / points + 0.1;
    polygon.push_back({r * std::cos(angle), r * std::sin(angle)});
  }
  return polygon;
}

const std::vector<Point2> kLShape = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};

// ---- Brute-force references ----------------------------------------------------------------

// Even/odd crossings of the +x half-line from `p`: a method independent of the mesh and Embree.
bool inside_polygon(const std::vector<Point2>& polygon, Point2 p) {
  bool inside = false;
  for (size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    const Point2 a = polygon[i], b = polygon[j];
    if ((a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y)) inside = !inside;
  }
  return inside;
}

double distance_to_segment(Point2 p, Point2 a, Point2 b) {
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double s = std::clamp(((p.x - a.x) * dx + (p.y - a.y) * dy) / (dx * dx + dy * dy), 0.0, 1.0);
  return std::hypot(p.x - a.x - s * dx, p.y - a.y - s * dy);
}

struct Prism {
  std::vector<Point2> polygon;
  double z0, z1;

  bool inside(Vec3 p) const { return p.z > z0 && p.z < z1 && inside_polygon(polygon, {p.x, p.y}); }
  double distance_to_boundary(Vec3 p) const {
    double d = std::min(std::abs(p.z - z0), std::abs(p.z - z1));
    const bool in_slab = p.z > z0 && p.z < z1;
    for (size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
      const double edge = distance_to_segment({p.x, p.y}, polygon[i], polygon[j]);
      d = std::min(d, in_slab ? edge : std::hypot(edge, d));
    }
    return d;
  }
};

bool covered(const Intervals& intervals, float t) {
  return std::any_of(intervals.begin(), intervals.end(),
                     [t](const auto& i) { return i.t0 <= t && t <= i.t1; });
}

// Ordered, disjoint, non-empty, inside [tmin, tmax].
void expect_well_formed(const Intervals& intervals, const Ray& ray) {
  for (size_t i = 0; i < intervals.size(); ++i) {
    EXPECT_LT(intervals[i].t0, intervals[i].t1);
    EXPECT_GE(intervals[i].t0, ray.tmin);
    EXPECT_LE(intervals[i].t1, ray.tmax);
    if (i > 0) {
      EXPECT_LE(intervals[i - 1].t1, intervals[i].t0);
    }
  }
}

// Compares coverage with the brute-force inside test at `samples` points along the ray's part
// in `box`, skipping points within `margin` of the boundary, where either answer is right.
// Returns how many points were compared.
int compare_with_brute_force(const MeshVolume& volume, const Prism& prism, const Ray& ray, int samples,
                             double margin, std::vector<SurfaceHit>& hits) {
  Intervals intervals;
  volume.intervals(ray, hits, intervals);
  expect_well_formed(intervals, ray);
  float t0 = 0.0f, t1 = 0.0f;
  Bounds3 box = volume.bounds();
  box.lo = box.lo - Vec3(0.1f);
  box.hi = box.hi + Vec3(0.1f);
  if (!box_overlap(box, ray, &t0, &t1)) return 0;
  int compared = 0;
  for (int k = 0; k < samples; ++k) {
    const float t = t0 + (t1 - t0) * (float(k) + 0.5f) / float(samples);
    const Vec3 p = ray.at(t);
    if (prism.distance_to_boundary(p) < margin) continue;
    ++compared;
    EXPECT_EQ(covered(intervals, t), prism.inside(p))
        << "t " << t << " at (" << p.x << ", " << p.y << ", " << p.z << ") on the ray from (" << ray.origin.x
        << ", " << ray.origin.y << ", " << ray.origin.z << ") along (" << ray.direction.x << ", "
        << ray.direction.y << ", " << ray.direction.z << ")";
  }
  return compared;
}

Vec3 random_in(Pcg32& rng, Vec3 lo, Vec3 hi) {
  return {lo.x + (hi.x - lo.x) * rng.next_float(), lo.y + (hi.y - lo.y) * rng.next_float(),
          lo.z + (hi.z - lo.z) * rng.next_float()};
}

// A random direction of random length in [0.1, 10): t is not a distance.
Vec3 random_direction(Pcg32& rng) {
  Vec3 d;
  do d = random_in(rng, Vec3(-1.0f), Vec3(1.0f));
  while (length_squared(d) > 1.0f || length_squared(d) < 1e-4f);
  return normalize(d) * std::pow(10.0f, 2.0f * rng.next_float() - 1.0f);
}

// ---- Analytic shapes -----------------------------------------------------------------------

TEST(MeshVolumeTest, CubeMatchesTheSlabIntervals) {
  const Vec3 lo(-1.0f, 0.0f, -0.5f), hi(2.0f, 1.0f, 0.5f);
  const auto volume = MeshVolume::build(box_mesh(lo, hi), kWhere);
  EXPECT_EQ(volume->bounds().lo.x, lo.x);
  EXPECT_EQ(volume->bounds().hi.z, hi.z);
  const Bounds3 box{lo, hi};
  Pcg32 rng(7, 1);
  std::vector<SurfaceHit> hits;
  int inside_origins = 0, retried = 0;
  for (int i = 0; i < 5000; ++i) {
    // A third of the origins inside the cube, the rest anywhere around it.
    const Vec3 origin = i % 3 == 0 ? random_in(rng, lo, hi) : random_in(rng, Vec3(-3, -2, -2), Vec3(4, 3, 2));
    Ray ray{origin, random_direction(rng)};
    ray.tmin = rng.next_float() < 0.5f ? 0.0f : 0.3f * rng.next_float();
    ray.tmax = rng.next_float() < 0.5f ? kInfinity : ray.tmin + 3.0f * rng.next_float();
    inside_origins += box.contains(ray.at(ray.tmin));
    Intervals out;
    volume->intervals(ray, hits, out);
    const bool perturbed = volume->query_count(ray, hits) > 1;
    retried += perturbed;
    // A perturbed ray moves by up to 1e-3 of the diagonal (about 3.3 here).
    const float tolerance = (perturbed ? 1e-2f : 1e-5f * 8.0f) / length(ray.direction);
    float t0 = 0.0f, t1 = 0.0f;
    if (!box_overlap(box, ray, &t0, &t1) || t1 - t0 <= tolerance) {
      EXPECT_TRUE(out.empty() || (out.size() == 1 && out[0].t1 - out[0].t0 <= tolerance)) << i;
      continue;
    }
    ASSERT_EQ(out.size(), 1u) << "ray " << i;
    EXPECT_NEAR(out[0].t0, t0, tolerance) << i;
    EXPECT_NEAR(out[0].t1, t1, tolerance) << i;
  }
  EXPECT_GT(inside_origins, 1500);  // the ray-starts-inside case is well exercised
  EXPECT_LT(retried, 5);            // random rays almost never meet an edge exactly
}

// A small box seen from far away: the ray's own parameter resolves only ~1e-3 there, 1/10 of
// the box, so finding where the line enters the box and telling an edge's two hits apart must
// not be done in it. Rays aim at random points of the box, a few through face diagonals.
TEST(MeshVolumeTest, SmallBoxFarAway) {
  const Bounds3 box{Vec3(0.0f), Vec3(0.01f)};
  const auto volume = MeshVolume::build(box_mesh(box.lo, box.hi), kWhere);
  Pcg32 rng(13, 3);
  std::vector<SurfaceHit> hits;
  for (int i = 0; i < 1000; ++i) {
    const Vec3 target = i % 10 == 0 ? Vec3(0.0025f, 0.005f, 0.0025f) : random_in(rng, box.lo, box.hi);
    const Vec3 from =
        i % 10 == 0 ? Vec3(0.0025f, -1e4f, 0.0025f) : target - normalize(random_direction(rng)) * 1e4f;
    const Ray ray{from, normalize(target - from)};
    Intervals out;
    volume->intervals(ray, hits, out);
    // The reference slab test in double: in float it misses the box itself.
    double t0 = 0.0, t1 = 1e30;
    for (int a = 0; a < 3; ++a) {
      const double tn = (double(box.lo[a]) - ray.origin[a]) / ray.direction[a];
      const double tf = (double(box.hi[a]) - ray.origin[a]) / ray.direction[a];
      t0 = std::max(t0, std::min(tn, tf));
      t1 = std::min(t1, std::max(tn, tf));
    }
    if (t1 - t0 < 4e-3) continue;  // a corner clipped: below what t resolves
    ASSERT_EQ(out.size(), 1u) << i;
    EXPECT_NEAR(out[0].t0, t0, 2e-3f) << i;
    EXPECT_NEAR(out[0].t1, t1, 2e-3f) << i;
  }
}

// Two boxes, one inside the other, as one mesh: even/odd makes the space between them a shell.
TEST(MeshVolumeTest, NestedBoxesMakeAShell) {
  TriangleMesh mesh = box_mesh(Vec3(-2.0f), Vec3(2.0f));
  append(mesh, box_mesh(Vec3(-1.0f), Vec3(1.0f)));
  const auto volume = MeshVolume::build(std::move(mesh), kWhere);
  const Bounds3 outer{Vec3(-2.0f), Vec3(2.0f)}, inner{Vec3(-1.0f), Vec3(1.0f)};
  Pcg32 rng(3, 5);
  std::vector<SurfaceHit> hits;
  int through_both = 0;
  for (int i = 0; i < 2000; ++i) {
    Ray ray{random_in(rng, Vec3(-3.0f), Vec3(3.0f)), random_direction(rng)};
    Intervals out;
    volume->intervals(ray, hits, out);
    // Expected: the outer box's stretch minus the inner box's.
    Intervals expected;
    float a0, a1, b0, b1;
    if (box_overlap(outer, ray, &a0, &a1)) {
      if (box_overlap(inner, ray, &b0, &b1)) {
        if (b0 > a0) expected.push_back({a0, b0});
        if (a1 > b1) expected.push_back({b1, a1});
        ++through_both;
      } else {
        expected.push_back({a0, a1});
      }
    }
    const float tolerance = 1e-5f * 8.0f / length(ray.direction);
    std::erase_if(expected, [&](const auto& e) { return e.t1 - e.t0 <= tolerance; });
    std::erase_if(out, [&](const auto& e) { return e.t1 - e.t0 <= tolerance; });
    ASSERT_EQ(out.size(), expected.size()) << "ray " << i;
    for (size_t k = 0; k < out.size(); ++k) {
      EXPECT_NEAR(out[k].t0, expected[k].t0, tolerance) << i;
      EXPECT_NEAR(out[k].t1, expected[k].t1, tolerance) << i;
    }
  }
  EXPECT_GT(through_both, 200);
}

TEST(MeshVolumeTest, ConcaveStarPrismMatchesPointInPolygon) {
  const Prism prism{star_polygon(7, 0.35, 1.0), -0.25, 0.5};
  const auto volume =
      MeshVolume::build(prism_mesh(prism.polygon, {0, 0}, float(prism.z0), float(prism.z1)), kWhere);
  Pcg32 rng(11, 2);
  std::vector<SurfaceHit> hits;
  int compared = 0;
  for (int i = 0; i < 1000; ++i) {
    Ray ray{random_in(rng, Vec3(-1.5f), Vec3(1.5f)), random_direction(rng)};
    if (i % 2 == 0) ray.tmin = -1.0f / length(ray.direction);  // parameters before the origin count too
    compared += compare_with_brute_force(*volume, prism, ray, 100, 1e-3, hits);
  }
  EXPECT_GT(compared, 30000);
}

// ---- Edges, vertices and faces -------------------------------------------------------------

// box_mesh() splits each face along the diagonal from its first corner (index bits x, y, z)
// to its third: on y = 0 from corner 0 to 5, on y = 1 from 2 to 7, both along x = z.
// A ray through the diagonal edges of two faces hits two triangles at each; counted twice, the
// parity would flip and the cube's inside would be lost.
TEST(MeshVolumeTest, RayThroughSharedEdgesAndVertices) {
  const auto volume = MeshVolume::build(box_mesh(Vec3(0.0f), Vec3(1.0f)), kWhere);
  std::vector<SurfaceHit> hits;
  const struct {
    Ray ray;
    float t0, t1;
  } cases[] = {
      {{{0.25f, -1.0f, 0.25f}, {0.0f, 0.5f, 0.0f}}, 2.0f, 4.0f},  // face diagonals x = z of y = 0 and y = 1
      {{{-1.0f, -1.0f, -1.0f}, {1.0f, 1.0f, 1.0f}}, 1.0f, 2.0f},  // in at corner 0, out at corner 7
      {{{0.5f, 0.5f, 0.5f}, {1.0f, 1.0f, 1.0f}}, 0.0f, 0.5f},     // from inside, out through a corner
      {{{-1.0f, 0.0f, 0.5f}, {1.0f, 1.0f, 0.0f}}, 1.0f, 1.0f},    // touches the edge x = 0, y = 1 only
  };
  bool perturbed = false;
  for (const auto& c : cases) {
    Intervals out;
    volume->intervals(c.ray, hits, out);
    perturbed = perturbed || volume->query_count(c.ray, hits) > 1;
    const float tolerance = 4e-3f;  // a perturbed ray moves by up to 1e-3 of the diagonal
    if (c.t1 == c.t0) {
      EXPECT_TRUE(out.empty() || (out.size() == 1 && out[0].t1 - out[0].t0 < tolerance));
      continue;
    }
    ASSERT_EQ(out.size(), 1u) << c.ray.origin.x;
    EXPECT_NEAR(out[0].t0, c.t0, tolerance);
    EXPECT_NEAR(out[0].t1, c.t1, tolerance);
  }
  EXPECT_TRUE(perturbed);  // the cases do exercise the retry
}

// Rays through every vertex of a concave prism from many directions, along its faces and along
// its edges: wherever the answer is not ambiguous (off the boundary), it must match.
TEST(MeshVolumeTest, GrazingRaysKeepTheParity) {
  const Prism prism{kLShape, 0.0, 1.0};
  const TriangleMesh mesh = prism_mesh(prism.polygon, {0.5, 0.5}, 0.0f, 1.0f);
  const auto volume = MeshVolume::build(mesh, kWhere);
  Pcg32 rng(5, 9);
  std::vector<SurfaceHit> hits;
  std::vector<Ray> rays;
  for (Vec3 v : mesh.positions)
    for (int k = 0; k < 40; ++k) {
      const Vec3 d = random_direction(rng);
      rays.push_back({v - d * 10.0f, d});
    }
  // Axis-aligned rays in the planes of faces and along edges, e.g. y = 1 over the short arm's
  // top, which goes on into the inside of the tall arm.
  for (float a : {0.0f, 0.5f, 1.0f, 2.0f})
    for (float b : {0.0f, 0.5f, 1.0f, 2.0f}) {
      rays.push_back({{-1.0f, a, b}, {1.0f, 0.0f, 0.0f}});
      rays.push_back({{a, -1.0f, b}, {0.0f, 1.0f, 0.0f}});
      rays.push_back({{a, b, -1.0f}, {0.0f, 0.0f, 1.0f}});
      rays.push_back({{a, b, 3.0f}, {1.0f, -1.0f, -1.0f}});
    }
  int compared = 0, perturbed = 0;
  for (const Ray& ray : rays) {
    compared += compare_with_brute_force(*volume, prism, ray, 200, 1e-2, hits);
    perturbed += volume->query_count(ray, hits) > 1;
  }
  EXPECT_GT(compared, 20000);
  EXPECT_GT(perturbed, 10);
}

// ---- Meshes that bound no volume -----------------------------------------------------------

std::string build_error(TriangleMesh mesh) {
  try {
    MeshVolume::build(std::move(mesh), kWhere);
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().json_path, kWhere.json_path);
    return e.what();
  }
  ADD_FAILURE() << "no error";
  return {};
}

TEST(MeshVolumeTest, OpenMeshIsALocatedError) {
  TriangleMesh mesh = box_mesh(Vec3(0.0f), Vec3(1.0f));
  mesh.indices.resize(mesh.indices.size() - 6);  // no top face
  const std::string message = build_error(mesh);
  EXPECT_NE(message.find("scene.json: /volumes/0/shape: the mesh cannot bound a volume"), std::string::npos)
      << message;
  EXPECT_NE(message.find("is used by 1 triangle (an open boundary); 4 edges of the mesh are not shared"),
            std::string::npos)
      << message;
}

TEST(MeshVolumeTest, NonManifoldEdgeIsALocatedError) {
  TriangleMesh mesh = box_mesh(Vec3(0.0f), Vec3(1.0f));
  mesh.positions.push_back({0.5f, 0.5f, 3.0f});
  mesh.indices.insert(mesh.indices.end(), {4, 5, 8});  // a fin on the edge y = 0, z = 1
  const std::string message = build_error(mesh);
  EXPECT_NE(message.find("the edge between vertices 4 and 5 is used by 3 triangles (non-manifold)"),
            std::string::npos)
      << message;
}

TEST(MeshVolumeTest, InvalidMeshIsALocatedError) {
  TriangleMesh mesh = box_mesh(Vec3(0.0f), Vec3(1.0f));
  mesh.positions[3].y = NAN;
  EXPECT_NE(build_error(mesh).find("vertex 3 has a non-finite coordinate"), std::string::npos);
}

// Files split vertices at normal and UV seams; welding equal positions sees the closed surface.
TEST(MeshVolumeTest, SplitVerticesAreWelded) {
  const TriangleMesh cube = box_mesh(Vec3(-0.0f), Vec3(1.0f));
  TriangleMesh split;
  for (size_t t = 0; t < cube.triangle_count(); ++t)
    for (int k = 0; k < 3; ++k) {
      Vec3 p = cube.positions[cube.indices[3 * t + size_t(k)]];
      if (p.x == 0.0f && t % 2 == 0) p.x = -0.0f;  // both zeros weld too
      split.indices.push_back(uint32_t(split.positions.size()));
      split.positions.push_back(p);
    }
  const auto volume = MeshVolume::build(split, kWhere);
  std::vector<SurfaceHit> hits;
  Intervals out;
  volume->intervals({{0.3f, 0.4f, -1.0f}, {0.0f, 0.0f, 2.0f}}, hits, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_NEAR(out[0].t0, 0.5f, 1e-6f);
  EXPECT_NEAR(out[0].t1, 1.0f, 1e-6f);
}

// ---- Real meshes (Debian's assimp-testmodels, when installed) ------------------------------

std::filesystem::path test_models_dir() {
  const char* override_dir = std::getenv("CALIGO_TEST_MODELS_DIR");
  return override_dir != nullptr ? std::filesystem::path(override_dir) : "/usr/share/assimp/models";
}

TEST(MeshVolumeRealTest, WusonIsOpenAndRejected) {
  const std::string path = (test_models_dir() / "PLY/Wuson.ply").string();
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "assimp-testmodels is not installed";
  const std::string message = build_error(load_mesh(path, kWhere));
  EXPECT_NE(message.find("(an open boundary); 412 edges"), std::string::npos) << message;
}

bool near_an_end(const Intervals& intervals, float t, float tolerance) {
  return std::any_of(intervals.begin(), intervals.end(), [=](const auto& i) {
    return std::abs(i.t0 - t) < tolerance || std::abs(i.t1 - t) < tolerance;
  });
}

// A closed real mesh: every ray agrees with the same ray reversed, and points inside by one
// ray are inside by an axis-aligned ray through them (two independent queries).
// Run on the two closed meshes of assimp-testmodels that are not boxes: a cylinder (OBJ, 256
// triangles) and the COLLADA duck (4212).
class ClosedRealMeshTest : public ::testing::TestWithParam<std::pair<const char*, size_t>> {};

TEST_P(ClosedRealMeshTest, IsConsistent) {
  const std::string path = (test_models_dir() / GetParam().first).string();
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "assimp-testmodels is not installed";
  const auto volume = MeshVolume::build(load_mesh(path, kWhere), kWhere);
  EXPECT_EQ(volume->mesh().triangle_count(), GetParam().second);
  const Bounds3 b = volume->bounds();
  const float size = length(b.diagonal());
  Pcg32 rng(1, 1);
  std::vector<SurfaceHit> hits;
  double inside_length = 0.0;
  int inside_points = 0;
  for (int i = 0; i < 500; ++i) {
    const Vec3 p = random_in(rng, b.lo - Vec3(0.2f * size), b.hi + Vec3(0.2f * size));
    const Vec3 q = random_in(rng, b.lo - Vec3(0.2f * size), b.hi + Vec3(0.2f * size));
    Intervals forward, backward;
    volume->intervals({p, q - p, 0.0f, 1.0f}, hits, forward);
    volume->intervals({q, p - q, 0.0f, 1.0f}, hits, backward);
    ASSERT_EQ(forward.size(), backward.size()) << i;
    for (size_t k = 0; k < forward.size(); ++k) {
      const auto& back = backward[backward.size() - 1 - k];
      EXPECT_NEAR(forward[k].t0, 1.0f - back.t1, 1e-4f) << i;
      EXPECT_NEAR(forward[k].t1, 1.0f - back.t0, 1e-4f) << i;
      inside_length += forward[k].t1 - forward[k].t0;
    }
    for (int s = 0; s < 10; ++s) {
      const float t = rng.next_float();
      const Vec3 x = p + (q - p) * t;
      Intervals axis;
      volume->intervals({{b.lo.x - 1.0f, x.y, x.z}, {1.0f, 0.0f, 0.0f}}, hits, axis);
      const float tx = x.x - (b.lo.x - 1.0f);
      if (near_an_end(forward, t, 1e-3f) || near_an_end(axis, tx, 1e-3f * size)) continue;
      EXPECT_EQ(covered(forward, t), covered(axis, tx)) << i;
      inside_points += covered(axis, tx);
    }
  }
  EXPECT_GT(inside_length, 10.0);
  EXPECT_GT(inside_points, 100);
}

INSTANTIATE_TEST_SUITE_P(AssimpTestModels, ClosedRealMeshTest,
                         ::testing::Values(std::pair<const char*, size_t>{"OBJ/empty_mat.obj", 256},
                                           std::pair<const char*, size_t>{"Collada/duck.dae", 4212}));

}  // namespace
}  // namespace caligo
