#include "volumes/mesh_volume.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <string>
#include <unordered_map>

#include "core/rng.h"

namespace caligo {
namespace {

// Perturbation of the retries, as a fraction of the box diagonal (origin) and of |direction|.
constexpr std::array<float, 3> kPerturbation = {1e-5f, 1e-4f, 1e-3f};
// The box is padded by more than the largest perturbation can move a ray's start, so the
// start is always outside the mesh.
constexpr float kPadding = 4e-3f;
// Hits closer than this fraction of the diagonal (in distance along the ray) are taken as one
// edge or vertex reported by several triangles. Float error at a shared edge is ~1e-7.
constexpr float kCoincident = 1e-6f;

// ---- Closedness ----------------------------------------------------------------------------

// Vertex ids after welding equal positions: files often split vertices at normal or UV seams,
// which leaves the surface closed although the index buffer is not.
std::vector<uint32_t> welded_ids(const TriangleMesh& mesh) {
  struct KeyHash {
    size_t operator()(const std::array<uint32_t, 3>& k) const {
      return size_t(hash_combine(hash_combine(k[0], k[1]), k[2]));
    }
  };
  std::unordered_map<std::array<uint32_t, 3>, uint32_t, KeyHash> first_with;
  std::vector<uint32_t> id(mesh.positions.size());
  for (size_t v = 0; v < mesh.positions.size(); ++v) {
    const Vec3 p = mesh.positions[v] + Vec3(0.0f);  // -0 + 0 = +0: one key for both zeros
    const std::array<uint32_t, 3> key = {std::bit_cast<uint32_t>(p.x), std::bit_cast<uint32_t>(p.y),
                                         std::bit_cast<uint32_t>(p.z)};
    id[v] = first_with.try_emplace(key, uint32_t(v)).first->second;
  }
  return id;
}

std::string plural(size_t n, const std::string& word) {
  return std::to_string(n) + " " + word + (n == 1 ? "" : "s");
}

// Empty when every edge is shared by exactly two triangles; otherwise names the first bad edge.
std::string open_or_non_manifold_edge(const TriangleMesh& mesh) {
  const std::vector<uint32_t> id = welded_ids(mesh);
  std::vector<uint64_t> edges;
  edges.reserve(mesh.indices.size());
  for (size_t t = 0; t < mesh.triangle_count(); ++t)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = id[mesh.indices[3 * t + size_t(k)]];
      const uint32_t b = id[mesh.indices[3 * t + size_t(k + 1) % 3]];
      edges.push_back(uint64_t(std::min(a, b)) << 32 | std::max(a, b));
    }
  std::sort(edges.begin(), edges.end());
  size_t bad = 0;
  uint64_t first_bad = 0;
  size_t first_bad_uses = 0;
  for (size_t i = 0; i < edges.size();) {
    size_t j = i;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    if (j - i != 2 && bad++ == 0) {
      first_bad = edges[i];
      first_bad_uses = j - i;
    }
    i = j;
  }
  if (bad == 0) return {};
  return "the edge between vertices " + std::to_string(first_bad >> 32) + " and " +
         std::to_string(first_bad & 0xffffffffu) + " is used by " + plural(first_bad_uses, "triangle") +
         (first_bad_uses == 1 ? " (an open boundary)" : " (non-manifold)") + "; " + plural(bad, "edge") +
         " of the mesh " + (bad == 1 ? "is" : "are") +
         " not shared by exactly two triangles, as a closed surface needs";
}

// ---- Ray set-up ----------------------------------------------------------------------------

// The parameter range over which the ray's whole line (t unbounded) is inside `box`; false
// when it misses. A zero direction component leaves that slab unbounded if the origin is in it.
// In double: the entry point is placed from it, and a camera far from a small mesh would
// otherwise put it off by more than the box's padding.
bool line_span(const Bounds3& box, const Ray& ray, double* t_enter, double* t_exit) {
  double t0 = -kInfinity, t1 = kInfinity;
  for (int a = 0; a < 3; ++a) {
    if (ray.direction[a] == 0.0f) {
      if (ray.origin[a] < box.lo[a] || ray.origin[a] > box.hi[a]) return false;
      continue;
    }
    const double inv = 1.0 / double(ray.direction[a]);
    double tn = (double(box.lo[a]) - ray.origin[a]) * inv;
    double tf = (double(box.hi[a]) - ray.origin[a]) * inv;
    if (tn > tf) std::swap(tn, tf);
    t0 = std::max(t0, tn);
    t1 = std::min(t1, tf);
  }
  *t_enter = t0;
  *t_exit = t1;
  return t0 <= t1 && std::isfinite(t0) && std::isfinite(t1);
}

Vec3 point_at(const Ray& ray, double t) {
  return {float(ray.origin.x + t * ray.direction.x), float(ray.origin.y + t * ray.direction.y),
          float(ray.origin.z + t * ray.direction.z)};
}

Vec3 random_offset(Pcg32& rng) {
  return {2.0f * rng.next_float() - 1.0f, 2.0f * rng.next_float() - 1.0f, 2.0f * rng.next_float() - 1.0f};
}

}  // namespace

MeshVolume::MeshVolume(EmbreeScene scene, Bounds3 bounds) : scene_(std::move(scene)), bounds_(bounds) {
  diagonal_ = length(bounds_.diagonal());
  const float scale = std::max(max_component(max(-bounds_.lo, bounds_.hi)), diagonal_);
  const Vec3 pad(kPadding * diagonal_ + 1e-6f * scale);
  padded_ = {bounds_.lo - pad, bounds_.hi + pad};
}

std::string MeshVolume::closure_problem(const TriangleMesh& mesh) { return open_or_non_manifold_edge(mesh); }

std::shared_ptr<const MeshVolume> MeshVolume::build(TriangleMesh mesh, const SourceLocation& where,
                                                    bool require_closed) {
  std::string problem = validate_mesh(mesh);
  if (problem.empty() && require_closed) problem = open_or_non_manifold_edge(mesh);
  if (!problem.empty()) throw InputError(where, "the mesh cannot bound a volume: " + problem);
  Bounds3 bounds;
  for (Vec3 p : mesh.positions) bounds.extend(p);
  EmbreeScene scene;
  scene.add_mesh(std::move(mesh));
  scene.commit();
  return std::shared_ptr<const MeshVolume>(new MeshVolume(std::move(scene), bounds));
}

bool MeshVolume::query(const Ray& ray, double t_enter, int attempt, std::vector<SurfaceHit>& hits) const {
  Ray line{point_at(ray, t_enter), ray.direction, 0.0f, kInfinity};
  if (attempt > 0) {
    // Seeded by the ray itself, so answers do not depend on which thread asks or when.
    const uint64_t seed = hash_combine(
        hash_combine(std::bit_cast<uint32_t>(ray.origin.x), uint64_t(attempt)),
        hash_combine(std::bit_cast<uint32_t>(ray.origin.y), std::bit_cast<uint32_t>(ray.direction.z)));
    Pcg32 rng(seed, std::bit_cast<uint32_t>(ray.direction.x));
    const float s = kPerturbation[size_t(attempt - 1)];
    line.origin += random_offset(rng) * (s * diagonal_);
    line.direction += random_offset(rng) * (s * length(ray.direction));
  }
  scene_.all_hits(line, hits);
  // Checked in the line's own parameter, which starts at the box: far from the box, the ray's
  // parameter has too few bits left to tell an edge's two hits from two surfaces.
  bool plausible = hits.size() % 2 == 0;
  const float coincident = kCoincident * diagonal_ / length(line.direction);
  for (size_t i = 1; i < hits.size() && plausible; ++i) plausible = hits[i].t - hits[i - 1].t > coincident;
  for (SurfaceHit& h : hits) h.t = float(t_enter + double(h.t));
  return plausible;
}

int MeshVolume::crossings(const Ray& ray, std::vector<SurfaceHit>& hits) const {
  hits.clear();
  double t_enter = 0.0, t_exit = 0.0;
  if (!is_finite(ray.origin) || !is_finite(ray.direction) || !line_span(padded_, ray, &t_enter, &t_exit) ||
      t_exit < ray.tmin || t_enter > ray.tmax)
    return 0;
  const int attempts = int(kPerturbation.size()) + 1;
  for (int attempt = 0; attempt < attempts; ++attempt)
    if (query(ray, t_enter, attempt, hits)) return attempt + 1;
  // Still suspect after every perturbation (a self-intersecting or paper-thin mesh): keep
  // the pairs there are, so that one unmatched crossing cannot fill the rest of the ray.
  if (hits.size() % 2 != 0) hits.pop_back();
  return attempts;
}

void MeshVolume::intervals(const Ray& ray, std::vector<SurfaceHit>& hits,
                           std::vector<RayRange>& out) const {
  crossings(ray, hits);
  for (size_t i = 0; i + 1 < hits.size(); i += 2) {
    const float t0 = std::max(hits[i].t, ray.tmin);
    const float t1 = std::min(hits[i + 1].t, ray.tmax);
    if (t0 < t1) out.push_back({t0, t1});
  }
}

int MeshVolume::query_count(const Ray& ray, std::vector<SurfaceHit>& hits) const {
  return crossings(ray, hits);
}

}  // namespace caligo
