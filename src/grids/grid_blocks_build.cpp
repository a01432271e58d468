// Block records are computed over each block's footprint (see grid_blocks.h): the block's own
// voxels plus the first voxel layer of its +x/+y/+z neighbours. Rather than keep per-leaf
// summaries, each candidate block probes the (up to 8) nodes its footprint touches through a
// ReadAccessor: leaves are scanned, tiles and the background contribute their single value.
#include "grids/grid_blocks_build.h"

#include "grids/grid_tree_walk.h"

#include <algorithm>
#include <array>
#include <optional>
#include <tuple>
#include <string>
#include <vector>

namespace caligo {
namespace {

using Coord = nanovdb::Coord;

// Component-wise value range over a set of voxels.
template <class T>
struct Range {
  T lo{}, hi{};
  bool any = false;
};

inline float vmin(float a, float b) { return std::min(a, b); }
inline float vmax(float a, float b) { return std::max(a, b); }
inline nanovdb::Vec3f vmin(nanovdb::Vec3f a, const nanovdb::Vec3f& b) { return a.minComponent(b); }
inline nanovdb::Vec3f vmax(nanovdb::Vec3f a, const nanovdb::Vec3f& b) { return a.maxComponent(b); }
inline bool all_equal(const nanovdb::Vec3f& a, const nanovdb::Vec3f& b) {
  return a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
}

template <class T>
void add(Range<T>& r, const T& v) {
  if (!r.any) {
    r.lo = r.hi = v;
    r.any = true;
  } else {
    r.lo = vmin(r.lo, v);
    r.hi = vmax(r.hi, v);
  }
}

// Per axis, the offsets from the block origin (0..8) spanned by the footprint's non-zero voxels.
struct Span {
  int lo[3] = {kBlockEdge + 1, kBlockEdge + 1, kBlockEdge + 1}, hi[3] = {-1, -1, -1};

  void add(int x0, int x1, int y0, int y1, int z0, int z1) {
    const int l[3] = {x0, y0, z0}, h[3] = {x1, y1, z1};
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], l[a]);
      hi[a] = std::max(hi[a], h[a]);
    }
  }
  bool any() const { return hi[0] >= 0; }
  // The tight box (grids/grid_blocks.h): a trilinear lookup is non-zero only within one voxel of
  // a non-zero voxel.
  TightBox box() const {
    TightBox b;
    for (int a = 0; a < 3; ++a) {
      b.lo[a] = uint8_t(std::max(0, lo[a] - 1));
      b.hi[a] = uint8_t(std::min(kBlockEdge, hi[a] + 1));
    }
    return b;
  }
};

inline bool is_nonzero(float v) { return v != 0.0f; }
inline bool is_nonzero(const nanovdb::Vec3f&) { return false; }  // colour does not occupy blocks

// The range of a channel over the footprint of the block with voxel origin `o`; when `span` is
// given, also the extent of its non-zero voxels.
template <class T>
Range<T> footprint_range(const nanovdb::DefaultReadAccessor<T>& acc, Coord o, Span* span = nullptr) {
  Range<T> r;
  for (int dz = 0; dz < 2; ++dz) {
    for (int dy = 0; dy < 2; ++dy) {
      for (int dx = 0; dx < 2; ++dx) {
        const Coord q = o.offsetBy(dx * kBlockEdge, dy * kBlockEdge, dz * kBlockEdge);
        // Only the neighbour's first layer lies in the footprint along each axis we stepped.
        const int nx = dx ? 1 : kBlockEdge, ny = dy ? 1 : kBlockEdge, nz = dz ? 1 : kBlockEdge;
        const int ox = dx * kBlockEdge, oy = dy * kBlockEdge, oz = dz * kBlockEdge;
        const auto* leaf = acc.probeLeaf(q);
        if (!leaf) {
          const T v = acc.getValue(q);  // a tile or the background: constant over the whole block
          add(r, v);
          if (span && is_nonzero(v)) span->add(ox, ox + nx - 1, oy, oy + ny - 1, oz, oz + nz - 1);
          continue;
        }
        for (int x = 0; x < nx; ++x)
          for (int y = 0; y < ny; ++y)
            for (int z = 0; z < nz; ++z) {
              const T v = leaf->getValue(uint32_t((x << 6) | (y << 3) | z));
              add(r, v);
              if (span && is_nonzero(v)) span->add(ox + x, ox + x, oy + y, oy + y, oz + z, oz + z);
            }
      }
    }
  }
  return r;
}

inline bool nonzero(const Range<float>& r) { return r.lo != 0.0f || r.hi != 0.0f; }

// Inclusive ranges of blocks that may be occupied, already dilated by one block towards -x/-y/-z
// (a block reads its + neighbours' first layer, so a non-zero voxel at block b also makes blocks
// b-1 occupied).
struct BlockRange {
  int64_t lo[3], hi[3];
};

void add_source(std::vector<BlockRange>& out, const Coord& voxel_origin, int64_t size_blocks) {
  BlockRange r;
  for (int a = 0; a < 3; ++a) {
    const int64_t b = floor_div(voxel_origin[a], kBlockEdge);
    r.lo[a] = b - 1;
    r.hi[a] = b + size_blocks - 1;
  }
  out.push_back(r);
}

// Every leaf and every non-zero tile (active or not: lookups read inactive values too).
void collect_sources(const nanovdb::FloatGrid& grid, std::vector<BlockRange>& out) {
  walk_tree(
      grid, [&](const auto&, Coord origin) { add_source(out, origin, 1); },
      [&](float value, bool, Coord origin, uint32_t dim) {
        if (value != 0.0f) add_source(out, origin, dim / kBlockEdge);
      });
}

using ParentKey = std::array<int32_t, 3>;

void sort_unique(std::vector<ParentKey>& keys) {
  std::sort(keys.begin(), keys.end(), [](const ParentKey& a, const ParentKey& b) {
    return std::tie(a[2], a[1], a[0]) < std::tie(b[2], b[1], b[0]);
  });
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
}

[[noreturn]] void too_large(size_t parents, const SourceLocation& where) {
  throw InputError(where, "grid too large: " + std::to_string(parents) +
                              " or more occupied parent cells of 64^3 voxels (at most " +
                              std::to_string(kMaxOccupiedParents) + ")");
}

// The distinct parents the ranges touch, sorted z-major; deduplicated as they accumulate so a
// tile covering a vast region is rejected before it is enumerated.
std::vector<ParentKey> candidate_parents(const std::vector<BlockRange>& ranges, const SourceLocation& where) {
  std::vector<ParentKey> keys;
  for (const BlockRange& r : ranges) {
    int32_t lo[3], hi[3];
    int64_t volume = 1;
    for (int a = 0; a < 3; ++a) {
      lo[a] = floor_div(int32_t(r.lo[a]), kParentBlocks);
      hi[a] = floor_div(int32_t(r.hi[a]), kParentBlocks);
      volume *= int64_t(hi[a]) - lo[a] + 1;
    }
    if (volume > kMaxOccupiedParents) too_large(size_t(volume), where);
    for (int32_t z = lo[2]; z <= hi[2]; ++z)
      for (int32_t y = lo[1]; y <= hi[1]; ++y)
        for (int32_t x = lo[0]; x <= hi[0]; ++x)
          if (keys.empty() || keys.back() != ParentKey{x, y, z}) keys.push_back({x, y, z});
    if (keys.size() > size_t(4 * kMaxOccupiedParents)) {
      sort_unique(keys);
      if (keys.size() > size_t(kMaxOccupiedParents)) too_large(keys.size(), where);
    }
  }
  sort_unique(keys);
  if (keys.size() > size_t(kMaxOccupiedParents)) too_large(keys.size(), where);
  return keys;
}

struct Accessors {
  nanovdb::DefaultReadAccessor<float> density;
  std::optional<nanovdb::DefaultReadAccessor<float>> temperature, flame;
  std::optional<nanovdb::DefaultReadAccessor<nanovdb::Vec3f>> color;
};

// Fills one parent's records; returns whether any block is occupied.
bool fill_parent(const ParentKey& p, Accessors& acc, ParentCell& cell) {
  cell.majorant.fill(-1.0f);
  cell.minimum.fill(0.0f);
  cell.constant_bits.fill(0);
  cell.tight_box.fill(kFullTightBox);
  bool any = false;
  for (int bz = 0; bz < kParentBlocks; ++bz) {
    for (int by = 0; by < kParentBlocks; ++by) {
      for (int bx = 0; bx < kParentBlocks; ++bx) {
        const Coord o((p[0] * kParentBlocks + bx) * kBlockEdge, (p[1] * kParentBlocks + by) * kBlockEdge,
                      (p[2] * kParentBlocks + bz) * kBlockEdge);
        Span span;
        const Range<float> density = footprint_range(acc.density, o, &span);
        bool occupied = nonzero(density), constant = density.lo == density.hi;
        for (auto* channel : {&acc.temperature, &acc.flame}) {
          if (!*channel) continue;
          const Range<float> r = footprint_range(**channel, o, &span);
          occupied = occupied || nonzero(r);
          constant = constant && r.lo == r.hi;
        }
        if (!occupied) continue;
        if (constant && acc.color) {
          const Range<nanovdb::Vec3f> r = footprint_range(*acc.color, o);
          constant = all_equal(r.lo, r.hi);
        }
        const int i = ParentCell::local_index(bx, by, bz);
        cell.majorant[i] = density.hi;
        cell.minimum[i] = std::max(0.0f, density.lo);
        // A constant occupied block has a non-zero channel everywhere: its span is full.
        if (constant) cell.constant_bits[i >> 6] |= uint64_t(1) << (i & 63);
        cell.tight_box[i] = span.box().pack();
        any = true;
      }
    }
  }
  return any;
}

void check_sparsity(const std::vector<ParentKey>& keys, GridBlocks& blocks, const SourceLocation& where) {
  int32_t lo[3] = {keys[0][0], keys[0][1], keys[0][2]}, hi[3] = {lo[0], lo[1], lo[2]};
  for (const ParentKey& k : keys)
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], k[a]);
      hi[a] = std::max(hi[a], k[a]);
    }
  int64_t cells = 1;
  for (int a = 0; a < 3; ++a) cells *= int64_t(hi[a]) - lo[a] + 1;
  const int64_t limit = std::max(kMinParentCells, kParentCellsPerOccupied * int64_t(keys.size()));
  if (cells > limit)
    throw InputError(where, "grid too large/sparse: " + std::to_string(cells) +
                                " parent cells of 64^3 voxels in its bounding box for " +
                                std::to_string(keys.size()) + " occupied (at most " + std::to_string(limit) +
                                ")");
  for (int a = 0; a < 3; ++a) {
    blocks.parent_lo[a] = lo[a];
    blocks.parent_dims[a] = hi[a] - lo[a] + 1;
  }
  blocks.parent_index.assign(size_t(cells), -1);
}

void finish_bounds_and_counts(GridBlocks& blocks) {
  for_each_occupied_block(blocks, [&](const int32_t* b, const ParentCell& cell, int i) {
    for (int a = 0; a < 3; ++a) {
      blocks.block_lo[a] = blocks.occupied_blocks == 0 ? b[a] : std::min(blocks.block_lo[a], b[a]);
      blocks.block_hi[a] = blocks.occupied_blocks == 0 ? b[a] : std::max(blocks.block_hi[a], b[a]);
    }
    ++blocks.occupied_blocks;
    blocks.constant_blocks += cell.constant(i);
    blocks.max_majorant = std::max(blocks.max_majorant, cell.majorant[i]);
  });
}

}  // namespace

GridBlocks build_grid_blocks(const BlockChannels& channels, const SourceLocation& where) {
  GridBlocks blocks;
  std::vector<BlockRange> ranges;
  for (const nanovdb::FloatGrid* grid : {channels.density, channels.temperature, channels.flame})
    if (grid) collect_sources(*grid, ranges);
  if (ranges.empty()) return blocks;
  const std::vector<ParentKey> keys = candidate_parents(ranges, where);
  ranges = {};
  check_sparsity(keys, blocks, where);

  Accessors acc{channels.density->getAccessor(), {}, {}, {}};
  if (channels.temperature) acc.temperature.emplace(channels.temperature->getAccessor());
  if (channels.flame) acc.flame.emplace(channels.flame->getAccessor());
  if (channels.color) acc.color.emplace(channels.color->getAccessor());
  ParentCell scratch;
  for (const ParentKey& k : keys) {
    if (!fill_parent(k, acc, scratch)) continue;
    const int64_t x = k[0] - blocks.parent_lo[0], y = k[1] - blocks.parent_lo[1],
                  z = k[2] - blocks.parent_lo[2];
    blocks.parent_index[blocks.slot(x, y, z)] =
        int32_t(blocks.parents.size());
    blocks.parents.push_back(scratch);
  }
  blocks.parents.shrink_to_fit();
  finish_bounds_and_counts(blocks);
  return blocks;
}

}  // namespace caligo
