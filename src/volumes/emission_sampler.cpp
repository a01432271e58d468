#include "volumes/emission_sampler.h"

#include <algorithm>
#include <cmath>

#include "core/ray_solids.h"
#include "grids/grid_blocks.h"
#include "grids/grid_dda.h"
#include "grids/grid_traversal.h"

namespace caligo {
namespace {

// Points per cell axis of the power estimate (a grid block's voxel centres 1, 3, 5, 7), and 2
// for fields of more than kManyCells cells, whose build would otherwise take seconds (64 shader
// calls per block of a 1000^3 explosion).
constexpr int kEstimatePoints = 4;
constexpr size_t kManyCells = size_t(1) << 16;
constexpr int kAnalyticCells = 4;   // per axis of an analytic primitive's bounds
constexpr double kCoverageFloor = 1e-3;

using Field = EmissionSampler::Field;

// A field's cells before normalisation: the cell and its estimated power.
struct CellWeight {
  uint32_t cell;
  double power;
};

// An occupied cell and the part of it where anything can be non-zero, in cell units ([0, 1]^3
// for analytic cells; a grid block's tight box, grids/grid_blocks.h).
struct OccupiedCell {
  int32_t cell;
  Vec3 lo{0.0f}, hi{1.0f};
};

// The estimated power of `primitive` in cell c: the mean emission (channel average) at
// points^3 stratified points of its non-zero part, times that part's world volume. The
// tight box matters: the shell of blocks a trilinear footprint adds around data emits only in its
// last voxel layer, which points spread over the whole block would miss.
double cell_power(const VolumePrimitive& primitive, const Field& field, const OccupiedCell& oc, int points,
                  VolumeContext& context) {
  const int32_t c[3] = {oc.cell % field.dims[0], oc.cell / field.dims[0] % field.dims[1],
                        oc.cell / (field.dims[0] * field.dims[1])};
  const Vec3 corner{float(c[0]), float(c[1]), float(c[2])}, extent = oc.hi - oc.lo;
  double sum = 0.0;
  for (int z = 0; z < points; ++z)
    for (int y = 0; y < points; ++y)
      for (int x = 0; x < points; ++x) {
        const float n = float(2 * points);
        const Vec3 at{oc.lo.x + extent.x * float(2 * x + 1) / n, oc.lo.y + extent.y * float(2 * y + 1) / n,
                      oc.lo.z + extent.z * float(2 * z + 1) / n};
        const Vec3 p = field.lattice_to_world.point(corner + at);
        sum += std::max(0.0f, shade_volume(primitive, p, context).emission.average());
      }
  const double power = sum / double(points * points * points) * field.cell_volume * extent.x *
                       extent.y * extent.z;
  return std::isfinite(power) ? power : 0.0;
}

size_t flat_cell(const Field& f, const int32_t* c) {
  return size_t(c[0]) + size_t(f.dims[0]) * (size_t(c[1]) + size_t(f.dims[1]) * size_t(c[2]));
}

// The affine map with these columns and origin, or nullopt when it is singular.
std::optional<Transform> affine(const Vec3 (&columns)[3], Vec3 origin) {
  Mat4 m = Mat4::identity();
  for (int r = 0; r < 3; ++r) {
    for (int a = 0; a < 3; ++a) m.m[size_t(r)][size_t(a)] = columns[a][r];
    m.m[size_t(r)][3] = origin[r];
  }
  return Transform::from_matrix(m);
}

// A grid's lattice: cell c is block lo + c, over the box of the occupied blocks.
std::optional<Field> grid_field(const GridDensity& g, std::vector<OccupiedCell>& occupied) {
  const GridBlocks& blocks = g.grid->blocks();
  Field f;
  int64_t cells = 1;
  for (int a = 0; a < 3; ++a) {
    f.dims[a] = blocks.block_hi[a] - blocks.block_lo[a] + 1;
    cells *= f.dims[a];
  }
  if (blocks.empty() || cells > kMaxEmissionCells) return std::nullopt;
  Vec3 columns[3];
  for (int a = 0; a < 3; ++a) {
    Vec3 e(0.0f);
    e[a] = float(kBlockEdge);
    columns[a] = g.grid_to_world.vector(g.grid->index_to_world_vector(e));
  }
  const Vec3 lo(float(blocks.block_lo[0]), float(blocks.block_lo[1]), float(blocks.block_lo[2]));
  const auto map = affine(columns, g.grid_to_world.point(g.grid->index_to_world(lo * float(kBlockEdge))));
  if (!map) return std::nullopt;
  f.lattice_to_world = *map;
  for_each_occupied_block(blocks, [&](const int32_t* b, const ParentCell& cell, int i) {
    const int32_t c[3] = {b[0] - blocks.block_lo[0], b[1] - blocks.block_lo[1], b[2] - blocks.block_lo[2]};
    const TightBox box = TightBox::unpack(cell.tight_box[size_t(i)]);
    OccupiedCell oc{int32_t(flat_cell(f, c))};
    for (int a = 0; a < 3; ++a) {
      oc.lo[a] = float(box.lo[size_t(a)]) / float(kBlockEdge);
      oc.hi[a] = float(box.hi[size_t(a)]) / float(kBlockEdge);
    }
    occupied.push_back(oc);
  });
  return f;
}

// An analytic primitive's lattice: kAnalyticCells^3 over its world bounds.
std::optional<Field> bounds_field(const VolumePrimitive& primitive, std::vector<OccupiedCell>& occupied) {
  const Bounds3 b = volume_bounds(primitive.shape);
  const Vec3 extent = b.hi - b.lo;
  if (!is_finite(b.lo) || !is_finite(b.hi) || !(extent.x > 0.0f && extent.y > 0.0f && extent.z > 0.0f))
    return std::nullopt;
  Field f;
  f.dims = {kAnalyticCells, kAnalyticCells, kAnalyticCells};
  const Vec3 columns[3] = {Vec3(extent.x / kAnalyticCells, 0, 0), Vec3(0, extent.y / kAnalyticCells, 0),
                           Vec3(0, 0, extent.z / kAnalyticCells)};
  const auto map = affine(columns, b.lo);
  if (!map) return std::nullopt;
  f.lattice_to_world = *map;
  for (int32_t i = 0; i < kAnalyticCells * kAnalyticCells * kAnalyticCells; ++i) occupied.push_back({i});
  return f;
}

float cell_world_volume(const Field& f) {
  const Transform& m = f.lattice_to_world;
  const float v = std::abs(dot(m.vector({1, 0, 0}), cross(m.vector({0, 1, 0}), m.vector({0, 0, 1}))));
  return std::isfinite(v) ? v : 0.0f;
}

}  // namespace

EmissionSampler EmissionSampler::build(const VolumeScene& volumes, VolumeContext& context) {
  EmissionSampler s;
  std::vector<std::vector<CellWeight>> weights;
  double total = 0.0;
  size_t positive = 0;
  for (uint32_t id = 0; id < volumes.primitives().size(); ++id) {
    const VolumePrimitive& primitive = volumes.primitive(id);
    if (!emits(primitive.shader)) continue;
    std::vector<OccupiedCell> occupied;
    const auto* g = std::get_if<GridDensity>(&primitive.shader.field);
    std::optional<Field> f = g ? grid_field(*g, occupied) : bounds_field(primitive, occupied);
    if (f) f->cell_volume = cell_world_volume(*f);
    if (!f || !(f->cell_volume > 0.0f)) return {};  // an emitter left uncovered: no sampler
    std::vector<CellWeight>& w = weights.emplace_back();
    const int points = occupied.size() > kManyCells ? 2 : kEstimatePoints;
    for (const OccupiedCell& oc : occupied) {
      const double power = cell_power(primitive, *f, oc, points, context);
      w.push_back({uint32_t(oc.cell), power});
      total += power;
      positive += power > 0.0;
    }
    s.fields_.push_back(std::move(*f));
  }
  if (s.fields_.empty()) return {};
  // Every occupied cell keeps a share (see the header): the floor is a fraction of the mean.
  const double floor = positive > 0 ? kCoverageFloor * total / double(positive) : 1.0;
  double sum = 0.0;
  for (auto& field_weights : weights)
    for (CellWeight& cw : field_weights) sum += (cw.power = std::max(cw.power, floor));
  double running = 0.0;
  for (uint32_t fi = 0; fi < s.fields_.size(); ++fi) {
    Field& f = s.fields_[fi];
    f.density.assign(size_t(f.dims[0]) * size_t(f.dims[1]) * size_t(f.dims[2]), 0.0f);
    for (const CellWeight& cw : weights[fi]) {
      running += cw.power;
      s.entries_.push_back({fi, cw.cell});
      s.cdf_.push_back(float(running / sum));
      f.density[cw.cell] = float(cw.power / sum / double(f.cell_volume));
    }
  }
  if (s.cdf_.empty() || !(sum > 0.0) || !std::isfinite(sum)) return {};
  s.cdf_.back() = 1.0f;
  return s;
}

size_t EmissionSampler::memory_bytes() const {
  size_t bytes = sizeof(*this) + entries_.capacity() * sizeof(Entry) + cdf_.capacity() * sizeof(float);
  for (const Field& f : fields_) bytes += sizeof(Field) + f.density.capacity() * sizeof(float);
  return bytes;
}

std::optional<EmissionPoint> EmissionSampler::sample(float u_cell, Vec3 u) const {
  if (empty()) return std::nullopt;
  const size_t i =
      std::min(size_t(std::upper_bound(cdf_.begin(), cdf_.end(), u_cell) - cdf_.begin()), cdf_.size() - 1);
  const Field& f = fields_[entries_[i].field];
  const size_t cell = entries_[i].cell, row = size_t(f.dims[0]), slab = row * size_t(f.dims[1]);
  const Vec3 c(float(cell % row), float(cell % slab / row), float(cell / slab));
  const Vec3 p = f.lattice_to_world.point(c + u);
  // The density where the point landed, every primitive's share (rounding may put a point on a
  // neighbour's face: it is then weighed by the density that neighbour gives it).
  const float density = pdf(p);
  if (!(density > 0.0f)) return std::nullopt;
  return EmissionPoint{p, density};
}

float EmissionSampler::pdf(Vec3 p) const {
  float sum = 0.0f;
  for (const Field& f : fields_) {
    const Vec3 l = f.lattice_to_world.inverse_point(p);
    int32_t c[3];
    bool inside = true;
    for (int a = 0; a < 3; ++a) {
      const float cell = std::floor(l[a]);
      inside = inside && cell >= 0.0f && cell < float(f.dims[a]);
      c[a] = inside ? int32_t(cell) : 0;
    }
    if (inside) sum += f.density[flat_cell(f, c)];
  }
  return sum;
}

float EmissionSampler::direction_pdf(Vec3 x, Vec3 w) const {
  double sum = 0.0;
  for (const Field& f : fields_) {
    // Affine maps keep the ray parameter: t is still the world distance along unit w.
    const Vec3 o = f.lattice_to_world.inverse_point(x), d = f.lattice_to_world.inverse_vector(w);
    if (!is_finite(o) || !is_finite(d) || length_squared(d) == 0.0f) continue;
    const auto range = ray_box(o, d, Vec3(0.0f), Vec3(float(f.dims[0]), float(f.dims[1]), float(f.dims[2])), 0.0f,
                               kInfinity);
    if (!range || !(range->t0 < range->t1)) continue;
    const float t0 = range->t0, t1 = range->t1;
    const int n[3] = {f.dims[0], f.dims[1], f.dims[2]};
    for_each_lattice_cell(o, d, t0, t1, n, [&](const int* c, float ta, float tb) {
      const float q = f.density[flat_cell(f, c)];
      // The integral of t^2 over [ta, tb], factored to keep its precision when ta ~ tb.
      if (q > 0.0f) sum += double(q) * double(tb - ta) * (double(tb) * tb + double(ta) * tb + double(ta) * ta) / 3.0;
    });
  }
  return float(sum);
}

RGB emission_at(const VolumeScene& volumes, Vec3 p, VolumeContext& context) {
  // The primitives covering p are those whose intervals cover the middle of a tiny probe ray
  // through it: the same test that decides which primitives a march shades there. One
  // primitive's intervals never overlap, so none is counted twice.
  const float eps = 1e-4f * (1.0f + std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)}));
  const Ray probe{p - Vec3(eps, 0.0f, 0.0f), Vec3(1.0f, 0.0f, 0.0f), 0.0f, 2.0f * eps};
  volumes.intervals(probe, context);
  RGB e;
  for (const VolumeInterval& iv : context.intervals)
    if (iv.t0 <= eps && eps < iv.t1 && emits(volumes.primitive(iv.primitive).shader))
      e += shade_volume(volumes.primitive(iv.primitive), p, context).emission;
  return e;
}

}  // namespace caligo
