// Mesh volumes: inside intervals per second for a closed icosphere of 320, 5120 and 81920
// triangles and for the COLLADA duck of assimp-testmodels (4212), against rays through the
// box (half from outside, half starting inside), next to the bare all-hits query the intervals
// are built from. Counter: intervals per ray.
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <utility>
#include <vector>

#include "core/rng.h"
#include "core/sampling.h"
#include "scene/mesh_loader.h"
#include "volumes/mesh_volume.h"

namespace caligo {
namespace {

// The unit sphere as an icosahedron subdivided `levels` times (20 * 4^levels triangles).
TriangleMesh icosphere(int levels) {
  const float g = 1.618034f;
  TriangleMesh mesh;
  mesh.positions = {{-1, g, 0},  {1, g, 0},  {-1, -g, 0}, {1, -g, 0}, {0, -1, g},  {0, 1, g},
                    {0, -1, -g}, {0, 1, -g}, {g, 0, -1},  {g, 0, 1},  {-g, 0, -1}, {-g, 0, 1}};
  // clang-format off
  mesh.indices = {0, 11, 5,  0, 5, 1,   0, 1, 7,   0, 7, 10,  0, 10, 11,
                  1, 5, 9,   5, 11, 4,  11, 10, 2, 10, 7, 6,  7, 1, 8,
                  3, 9, 4,   3, 4, 2,   3, 2, 6,   3, 6, 8,   3, 8, 9,
                  4, 9, 5,   2, 4, 11,  6, 2, 10,  8, 6, 7,   9, 8, 1};
  // clang-format on
  for (int level = 0; level < levels; ++level) {
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> midpoint;
    const auto middle = [&](uint32_t a, uint32_t b) {
      const auto [it, added] = midpoint.try_emplace({std::min(a, b), std::max(a, b)}, 0u);
      if (added) {
        it->second = uint32_t(mesh.positions.size());
        mesh.positions.push_back((mesh.positions[a] + mesh.positions[b]) * 0.5f);
      }
      return it->second;
    };
    std::vector<uint32_t> finer;
    for (size_t t = 0; t < mesh.indices.size(); t += 3) {
      const uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
      const uint32_t ab = middle(a, b), bc = middle(b, c), ca = middle(c, a);
      finer.insert(finer.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
    }
    mesh.indices = std::move(finer);
  }
  for (Vec3& p : mesh.positions) p = normalize(p);
  return mesh;
}

std::vector<Ray> rays_through_box(const Bounds3& box, int count) {
  Pcg32 rng(3, 7);
  const Vec3 size = box.diagonal();
  const auto in_box = [&] {
    return box.lo + Vec3(size.x * rng.next_float(), size.y * rng.next_float(), size.z * rng.next_float());
  };
  std::vector<Ray> rays;
  for (int i = 0; i < count; ++i) {
    const Vec3 origin =
        i % 2 == 0
            ? box.center() + 1.5f * length(size) * sample_uniform_sphere({rng.next_float(), rng.next_float()})
            : in_box();
    rays.push_back({origin, in_box() - origin});
  }
  return rays;
}

// Argument 0-9: an icosphere subdivided that often; 10: the duck (null when not installed).
constexpr int kDuck = 10;
const MeshVolume* mesh_volume(int which) {
  static std::map<int, std::shared_ptr<const MeshVolume>> cache;
  auto& volume = cache[which];
  if (!volume && which != kDuck) volume = MeshVolume::build(icosphere(which), {"bench", "icosphere"});
  if (!volume && which == kDuck) try {
      const std::string path = "/usr/share/assimp/models/Collada/duck.dae";
      volume = MeshVolume::build(load_mesh(path, {path, ""}), {path, ""});
    } catch (const InputError&) {
      return nullptr;
    }
  return volume.get();
}

void BM_MeshVolumeIntervals(benchmark::State& state) {
  const MeshVolume* found = mesh_volume(int(state.range(0)));
  if (found == nullptr) return state.SkipWithError("assimp-testmodels is not installed");
  const MeshVolume& volume = *found;
  const std::vector<Ray> rays = rays_through_box(volume.bounds(), 4096);
  std::vector<SurfaceHit> hits;
  std::vector<RayRange> out;
  size_t i = 0, intervals = 0;
  for (auto _ : state) {
    out.clear();
    volume.intervals(rays[i++ & 4095], hits, out);
    intervals += out.size();
    benchmark::DoNotOptimize(out.data());
  }
  state.SetItemsProcessed(int64_t(state.iterations()));
  state.counters["triangles"] = double(volume.mesh().triangle_count());
  state.counters["intervals_per_ray"] = double(intervals) / double(state.iterations());
}
BENCHMARK(BM_MeshVolumeIntervals)->Arg(2)->Arg(4)->Arg(6)->Arg(kDuck);

// The Embree all-hits query alone, over the same rays: what the even/odd pairing costs on top.
void BM_MeshVolumeAllHitsOnly(benchmark::State& state) {
  const MeshVolume* found = mesh_volume(int(state.range(0)));
  if (found == nullptr) return state.SkipWithError("assimp-testmodels is not installed");
  EmbreeScene scene;
  scene.add_mesh(found->mesh());
  scene.commit();
  const std::vector<Ray> rays = rays_through_box(found->bounds(), 4096);
  std::vector<SurfaceHit> hits;
  size_t i = 0;
  for (auto _ : state) {
    scene.all_hits(rays[i++ & 4095], hits);
    benchmark::DoNotOptimize(hits.data());
  }
  state.SetItemsProcessed(int64_t(state.iterations()));
}
BENCHMARK(BM_MeshVolumeAllHitsOnly)->Arg(2)->Arg(4)->Arg(6)->Arg(kDuck);

}  // namespace
}  // namespace caligo
