#include "grids/grid_traversal.h"

#include <algorithm>
#include <cmath>

#include "core/ray_solids.h"
#include "grids/grid_dda.h"

namespace caligo {
namespace {

// Builds the merged interval list of one call.
class IntervalMerger {
 public:
  IntervalMerger(std::vector<GridInterval>& out, float tolerance) : out_(out), scale_(1.0f + tolerance) {}

  void add(float t0, float t1, float majorant, float minimum, bool constant) {
    if (!(t1 > t0)) return;  // zero-length crossings (grazed edges and corners) add nothing
    if (open_ && out_.back().t1 == t0) {
      GridInterval& last = out_.back();
      if (constant && last.constant && majorant == last.density_max) {
        last.t1 = t1;
        return;
      }
      const float hi = std::max(last.density_max, majorant), lo = std::min(open_min_, majorant);
      // The minima must agree too: merging a block whose minimum is far below would throw away
      // the control residual ratio tracking takes from the others (a shell block's is 0).
      const float min_hi = std::max(open_max_minimum_, minimum), min_lo = std::min(last.density_min, minimum);
      if (!constant && !last.constant && hi <= lo * scale_ && min_hi <= min_lo * scale_) {
        last.t1 = t1;
        last.density_max = hi;
        last.density_min = min_lo;
        open_min_ = lo;
        open_max_minimum_ = min_hi;
        return;
      }
    }
    out_.push_back({t0, t1, majorant, constant, minimum});
    open_ = true;
    open_min_ = majorant;
    open_max_minimum_ = minimum;
  }

 private:
  std::vector<GridInterval>& out_;
  float scale_;
  bool open_ = false;  // whether out_.back() was made by this merger
  float open_min_ = 0.0f;          // the smallest majorant merged into out_.back()
  float open_max_minimum_ = 0.0f;  // the largest minimum merged into it
};

// Clips [t0, t1], the ray's range inside the block with index-space corner `corner`, to the
// block's tight box. Only the box's inner faces are intersected: a face on the block's boundary
// keeps the DDA's t, which the neighbouring block shares, so full neighbours still merge. A ray
// parallel to an axis is in or out by its coordinate (closed bounds; the filtered values are
// zero on the tight box's inner faces anyway).
bool clip_to_tight_box(Vec3 o, Vec3 d, Vec3 corner, const TightBox& box, float& t0, float& t1) {
  for (int a = 0; a < 3; ++a) {
    const bool tight_lo = box.lo[a] > 0, tight_hi = box.hi[a] < kBlockEdge;
    if (!tight_lo && !tight_hi) continue;
    const float lo = corner[a] + float(box.lo[a]), hi = corner[a] + float(box.hi[a]);
    if (d[a] == 0.0f) {
      if (!(o[a] >= lo && o[a] <= hi)) return false;
      continue;
    }
    const float inv = 1.0f / d[a];
    // Moving towards +a the ray enters through lo and leaves through hi; towards -a the reverse.
    const bool enter_tight = d[a] > 0.0f ? tight_lo : tight_hi,
               exit_tight = d[a] > 0.0f ? tight_hi : tight_lo;
    if (enter_tight) t0 = std::max(t0, ((d[a] > 0.0f ? lo : hi) - o[a]) * inv);
    if (exit_tight) t1 = std::min(t1, ((d[a] > 0.0f ? hi : lo) - o[a]) * inv);
  }
  return t0 < t1;
}

}  // namespace

void block_intervals(const GridBlocks& blocks, Vec3 origin, Vec3 direction, float t0, float t1,
                     float merge_tolerance, std::vector<GridInterval>& out) {
  if (blocks.empty() || !is_finite(origin) || !is_finite(direction) || length_squared(direction) == 0.0f)
    return;
  if (!(t0 < t1)) return;  // also rejects NaN bounds
  const Vec3 box_lo(float(blocks.block_lo[0] * kBlockEdge), float(blocks.block_lo[1] * kBlockEdge),
                    float(blocks.block_lo[2] * kBlockEdge));
  const Vec3 box_hi(float((blocks.block_hi[0] + 1) * kBlockEdge),
                    float((blocks.block_hi[1] + 1) * kBlockEdge),
                    float((blocks.block_hi[2] + 1) * kBlockEdge));
  const auto clipped = ray_box(origin, direction, box_lo, box_hi, t0, t1);
  if (!clipped || !(clipped->t0 < clipped->t1)) return;
  t0 = clipped->t0;
  t1 = clipped->t1;

  IntervalMerger merger(out, merge_tolerance);
  const Vec3 parent_origin(float(blocks.parent_lo[0] * kParentVoxels),
                           float(blocks.parent_lo[1] * kParentVoxels),
                           float(blocks.parent_lo[2] * kParentVoxels));
  // Parent-level coordinates: one unit per parent, relative to the parent array's corner.
  const Vec3 po = (origin - parent_origin) / float(kParentVoxels);
  const Vec3 pd = direction / float(kParentVoxels);
  const Vec3 bd = direction / float(kBlockEdge);
  const int parent_n[3] = {blocks.parent_dims[0], blocks.parent_dims[1], blocks.parent_dims[2]};
  const int block_n[3] = {kParentBlocks, kParentBlocks, kParentBlocks};
  for_each_lattice_cell(po, pd, t0, t1, parent_n, [&](const int* p, float ta, float tb) {
    if (!(tb > ta)) return;
    const int32_t index = blocks.parent_index[blocks.slot(p[0], p[1], p[2])];
    if (index < 0) return;  // an empty parent: 64^3 voxels skipped in one step
    const ParentCell& cell = blocks.parents[size_t(index)];
    // Block-level coordinates local to this parent: one unit per block.
    const Vec3 corner = parent_origin + Vec3(float(p[0]), float(p[1]), float(p[2])) * float(kParentVoxels);
    const Vec3 bo = (origin - corner) / float(kBlockEdge);
    for_each_lattice_cell(bo, bd, ta, tb, block_n, [&](const int* b, float tc, float td) {
      const int i = ParentCell::local_index(b[0], b[1], b[2]);
      if (!cell.occupied(i)) return;
      const uint32_t packed = cell.tight_box[i];
      if (packed != kFullTightBox) {
        const Vec3 block_corner = corner + Vec3(float(b[0]), float(b[1]), float(b[2])) * float(kBlockEdge);
        if (!clip_to_tight_box(origin, direction, block_corner, TightBox::unpack(packed), tc, td)) return;
      }
      merger.add(tc, td, cell.majorant[i], cell.minimum[i], cell.constant(i));
    });
  });
}

}  // namespace caligo
