// Lookups and traversal of a built VolumeGrid. Lookups follow NanoVDB's index convention
// (voxel centres at integer index coordinates): trilinear reads the 2^3 voxels around the
// point, nearest the voxel whose centre is closest (floor(x + 0.5)).
#include "grids/volume_grid.h"

#include <cmath>

#include "grids/grid_accessor_cache.h"
#include "grids/grid_accessors.h"
#include "grids/grid_traversal.h"
#include "grids/volume_grid_data.h"

namespace caligo {
namespace {

using nanovdb::Coord;
using nanovdb::Vec3f;

// Index coordinates beyond this cannot be turned into int32 voxel coordinates (and are far
// outside any grid); lookups there read the background.
constexpr float kMaxIndex = float(1 << 30);

bool index_in_range(const Vec3f& x) {
  return std::abs(x[0]) < kMaxIndex && std::abs(x[1]) < kMaxIndex && std::abs(x[2]) < kMaxIndex;
}

template <class T>
T lerp(const T& a, const T& b, float w) {
  return a + (b - a) * w;
}

template <class Acc>
auto trilinear(const Acc& acc, const Vec3f& x) {
  const Vec3f f(std::floor(x[0]), std::floor(x[1]), std::floor(x[2]));
  const Coord ijk{int32_t(f[0]), int32_t(f[1]), int32_t(f[2])};
  const Vec3f w = x - f;
  using T = std::decay_t<decltype(acc.getValue(ijk))>;
  T v[2][2][2];  // [dx][dy][dz]
  // Two thirds of the points have all 8 voxels in one leaf: read them from it directly.
  const auto* leaf =
      ((ijk[0] & 7) < 7 && (ijk[1] & 7) < 7 && (ijk[2] & 7) < 7) ? acc.probeLeaf(ijk) : nullptr;
  if (leaf) {
    const uint32_t n = uint32_t(((ijk[0] & 7) << 6) | ((ijk[1] & 7) << 3) | (ijk[2] & 7));
    for (int dx = 0; dx < 2; ++dx)
      for (int dy = 0; dy < 2; ++dy)
        for (int dz = 0; dz < 2; ++dz)
          v[dx][dy][dz] = leaf->getValue(n + uint32_t((dx << 6) | (dy << 3) | dz));
  } else {
    for (int dx = 0; dx < 2; ++dx)
      for (int dy = 0; dy < 2; ++dy)
        for (int dz = 0; dz < 2; ++dz) v[dx][dy][dz] = acc.getValue(ijk.offsetBy(dx, dy, dz));
  }
  T yz[2][2];
  for (int dy = 0; dy < 2; ++dy)
    for (int dz = 0; dz < 2; ++dz) yz[dy][dz] = lerp<T>(v[0][dy][dz], v[1][dy][dz], w[0]);
  const T z0 = lerp<T>(yz[0][0], yz[1][0], w[1]);
  const T z1 = lerp<T>(yz[0][1], yz[1][1], w[1]);
  return lerp<T>(z0, z1, w[2]);
}

template <class Acc>
auto lookup(const Acc& acc, const Vec3f& x, GridFilter filter) {
  using T = std::decay_t<decltype(acc.getValue(Coord()))>;
  if (!index_in_range(x)) return T(acc.root().background());
  switch (filter) {
    case GridFilter::kTrilinear:
      return trilinear(acc, x);
    case GridFilter::kNearest:
      return acc.getValue(Coord(int32_t(std::floor(x[0] + 0.5f)), int32_t(std::floor(x[1] + 0.5f)),
                                int32_t(std::floor(x[2] + 0.5f))));
  }
  return T(acc.root().background());
}

Vec3f to_index(const nanovdb::GridData& grid, Vec3 p) { return grid.applyInverseMapF(Vec3f(p.x, p.y, p.z)); }

}  // namespace

VolumeGrid::VolumeGrid(std::unique_ptr<VolumeGridData> data) : data_(std::move(data)) {}
VolumeGrid::~VolumeGrid() = default;

Bounds3 VolumeGrid::world_bounds() const { return data_->world_bounds; }
float VolumeGrid::voxel_size() const { return data_->voxel_size; }
float VolumeGrid::max_density() const { return data_->blocks.max_majorant; }
bool VolumeGrid::has_temperature() const { return data_->temperature != nullptr; }
bool VolumeGrid::has_flame() const { return data_->flame != nullptr; }
bool VolumeGrid::has_color() const { return data_->color != nullptr; }
GridStatistics VolumeGrid::statistics() const { return data_->statistics; }

size_t VolumeGrid::nanovdb_bytes() const {
  const NanoGrids& h = data_->handles;
  return h.density.size() + (h.temperature ? h.temperature->size() : 0) + (h.flame ? h.flame->size() : 0) +
         (h.color ? h.color->size() : 0);
}

size_t VolumeGrid::memory_bytes() const {
  return sizeof(VolumeGrid) + sizeof(VolumeGridData) + nanovdb_bytes() + data_->blocks.memory_bytes() -
         sizeof(GridBlocks);
}

const GridBlocks& VolumeGrid::blocks() const { return data_->blocks; }

namespace {
Vec3 to_vec3(const Vec3f& v) { return {v[0], v[1], v[2]}; }
Vec3f to_vec3f(Vec3 v) { return {v.x, v.y, v.z}; }
}  // namespace

Vec3 VolumeGrid::index_to_world(Vec3 index) const { return to_vec3(data_->density->data()->applyMapF(to_vec3f(index))); }
Vec3 VolumeGrid::index_to_world_vector(Vec3 v) const {
  return to_vec3(data_->density->data()->applyJacobianF(to_vec3f(v)));
}
Vec3 VolumeGrid::world_to_index(Vec3 p) const { return to_vec3(to_index(*data_->density->data(), p)); }
Vec3 VolumeGrid::world_to_index_vector(Vec3 v) const {
  return to_vec3(data_->density->data()->applyInverseJacobianF(to_vec3f(v)));
}

void VolumeGrid::intervals(const Ray& ray, float t0, float t1, std::vector<GridInterval>& out,
                           float merge_tolerance) const {
  const nanovdb::GridData& grid = *data_->density->data();
  const Vec3f o = grid.applyInverseMapF(Vec3f(ray.origin.x, ray.origin.y, ray.origin.z));
  const Vec3f d = grid.applyInverseJacobianF(Vec3f(ray.direction.x, ray.direction.y, ray.direction.z));
  block_intervals(data_->blocks, Vec3(o[0], o[1], o[2]), Vec3(d[0], d[1], d[2]), t0, t1, merge_tolerance,
                  out);
}

float VolumeGrid::density(Vec3 p, GridFilter filter, GridAccessorCache& cache) const {
  GridAccessors& acc = cache.get(*data_);
  return lookup(acc.density, to_index(*data_->density->data(), p), filter);
}

GridValues VolumeGrid::values(Vec3 p, GridFilter filter, GridAccessorCache& cache) const {
  GridAccessors& acc = cache.get(*data_);
  const Vec3f x = to_index(*data_->density->data(), p);
  GridValues v;
  v.density = lookup(acc.density, x, filter);
  if (acc.temperature) v.temperature = lookup(*acc.temperature, x, filter);
  if (acc.flame) v.flame = lookup(*acc.flame, x, filter);
  if (acc.color) {
    const Vec3f xc = data_->color_shares_index_space ? x : to_index(*data_->color->data(), p);
    const Vec3f c = lookup(*acc.color, xc, filter);
    v.color = RGB(c[0], c[1], c[2]);
  }
  return v;
}

}  // namespace caligo
