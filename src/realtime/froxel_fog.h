// Froxel volumetric fog (`caligo realtime --method froxel`; Wronski 2014, "Volumetric fog",
// Hillaire 2015, "Physically based and unified volumetric rendering in Frostbite"): every
// volume primitive and every light the passes shade are injected into one camera-aligned grid of
// frustum voxels, width x height columns of `slices` exponentially spaced depth slices; the
// grid is blended with the previous frame's reprojected grid (the slice sample jittered per
// frame), integrated front to back per column, and read per output pixel at its depth. A
// light costs one evaluation per froxel its volume reaches, whatever its screen coverage, and
// the result is smooth at the grid's resolution: beams sharper than a froxel are the per-light
// march's (docs/techniques.md, "Froxel fog").
//
// Each stage is a pure function of the grid's buffers; FroxelFog holds the buffers and the
// history across frames. Its passes are timed as the pipeline's: columns + media + lights as
// "accumulation", the grid's reprojection as "temporal", the integration as "gather", the
// per-pixel lookup as "upsample".
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "core/rgb.h"
#include "realtime/frame_light.h"
#include "realtime/plane.h"
#include "realtime/view.h"
#include "settings/realtime_settings.h"
#include "volumes/interval.h"

namespace caligo {

class VolumeScene;

// The grid's placement: depth edges of the slices in the view's linear depth.
struct FroxelGrid {
  int width = 0, height = 0, slices = 0;
  float near = 0.0f, far = 0.0f;  // edge 1 and edge `slices`

  // Linear depth of slice edge i in [0, slices]: 0, then near (far/near)^((i-1)/(slices-1)).
  float edge(float i) const;
  // The inverse: the continuous edge coordinate of depth z, clamped to [0, slices].
  float edge_coordinate(float z) const;
  size_t columns() const { return size_t(width) * size_t(height); }
  size_t cells() const { return columns() * size_t(slices); }
  // The film position (pixels of `view`) of column (x, y)'s centre.
  Vec2 film(const View& view, float x, float y) const {
    return {(x + 0.5f) * float(view.resolution.x) / float(width), (y + 0.5f) * float(view.resolution.y) / float(height)};
  }
};

// The depths of edges 0 .. slices (FroxelGrid::edge of each).
std::vector<float> slice_edges(const FroxelGrid& grid);

// The grid for `view`: columns as `settings` gives them or one per column_pixels^2 of the view
// (at least 32 each way, or one per pixel);
// far at the farthest linear depth of the media's bounds, or of `depth`'s
// surfaces where it is nearer and no pixel sees the sky (at least 1e-3); near = far / near_ratio.
FroxelGrid fit_froxel_grid(const View& view, const VolumeScene& volumes, const Plane& depth,
                           const FroxelSettings& settings);

// Per column: its ray, and the ray parameter of each slice's sample (at `jitter` in [0, 1)
// of the slice's depth span); the media intervals on the ray, flat.
struct FroxelColumns {
  struct Column {
    Vec3 origin, dir;
    float t_per_depth = 1.0f;  // 1 / View::depth_per_t
    uint32_t first = 0, count = 0;  // into intervals
  };
  std::vector<Column> columns;
  std::vector<float> t;  // cells(), column-major: column c's slices at c * slices
  std::vector<VolumeInterval> intervals;
};
void froxel_columns(const FroxelGrid& grid, const View& view, const VolumeScene& volumes, float jitter,
                    FroxelColumns& out);

// What the grid holds per froxel before integration: extinction and in-scattered radiance
// per unit length (towards the camera), both at the slice's sample; together, since the
// reprojection reads both at the same place.
struct Froxel {
  RGB sigma_t, scatter;
};
struct FroxelMedia {
  // FroxelColumns::t's order, and one padding froxel at the end (the reprojection's 8-lane
  // loads of a slice pair read 2 floats past the pair).
  std::vector<Froxel> cells;
  void reset(size_t n) { cells.assign(n + 1, Froxel{}); }
};

// sigma_t of every primitive at each froxel's sample (media.h's medium_density).
void inject_media(const FroxelGrid& grid, const FroxelColumns& columns, const VolumeScene& volumes,
                  FroxelMedia& media);
// Adds `light`'s single scattering at each froxel its volume reaches (the march's integrand:
// shadow map, the light's optical depth, phase; times the light's volumetric_intensity).
// Only the columns of light_screen_bounds (at the grid's resolution) are visited.
void inject_light(const FrameLight& light, const FroxelGrid& grid, const View& view, const FroxelColumns& columns,
                  const VolumeScene& volumes, float multiple_scattering_floor, bool simd, FroxelMedia& media);

// Sets to 1 the entries of `fresh` (cells() of them) whose froxel sample one pose of a moved
// light reaches and the other does not (`before` null: a new light, every froxel it reaches),
// each run one slice wider (the history's samples sat elsewhere in their slices) and one
// column wider each way (its trilinear taps): there the history is stale. Where both poses
// reach, the history is kept.
void mark_moved_light(const ShadedLight* before, const ShadedLight& now, const FroxelGrid& grid, const View& view,
                      const FroxelColumns& columns, std::vector<uint8_t>& fresh);
// Whether a light has the same pose as in the previous frame: its placement_key (position, aim,
// shape; frame_light.h) and its gobo's placement.
bool same_pose(const ShadedLight& a, const ShadedLight& b);

// Blends `current` with `history` (the previous frame's grid, of `history_grid` in
// `history_view`) sampled at each froxel's centre: current = history + blend (current - history).
// Froxels whose centre the previous grid did not hold, or that `fresh` marks (empty: none),
// keep the current value.
void reproject_froxels(const FroxelGrid& grid, const View& view, const FroxelMedia& history,
                       const FroxelGrid& history_grid, const View& history_view, float blend,
                       std::span<const uint8_t> fresh, FroxelMedia& current, bool simd = true);
// (simd: each history read as two 8-lane loads per slice pair; false: the scalar reference.)

// In-scattered radiance from the eye to each slice edge, per column ((slices + 1) per column,
// edge 0 is black): each slice integrated with its sample's sigma_t and scatter held constant,
// scatter (1 - e^(-sigma_t dt)) / sigma_t (Hillaire's energy-conserving step).
void integrate_froxels(const FroxelGrid& grid, const FroxelColumns& columns, const FroxelMedia& media,
                       std::vector<RGB>& out);

// The integrated grid read at each pixel of `depth` (linear, kSkyDepth for none; the view's
// resolution): bilinear across columns, linear between slice edges. `loads`: four 8-float
// loads a pixel; `gathers`: 24 AVX2 gathers per 8 pixels (the former lookup, for benchmarks).
enum class FroxelLookup { loads, gathers };
void lookup_froxels(const FroxelGrid& grid, std::span<const RGB> integrated, const Plane& depth, ColorPlanes& out,
                    FroxelLookup method = FroxelLookup::loads);

// The pass across frames: buffers and history.
class FroxelFog {
 public:
  struct Times {
    double columns = 0, media = 0, reproject = 0, integrate = 0, lookup = 0;
    std::vector<double> per_light;  // by scene index
  };
  // Renders the frame's in-scattered light at `depth`'s resolution into `out`.
  void render(const std::vector<FrameLight>& lights, const VolumeScene& volumes, const View& view, const Plane& depth,
              const RealtimeSettings& settings, uint32_t frame_index, size_t scene_lights, ColorPlanes& out,
              Times& times);

 private:
  // Marks fresh_ where lights that moved since the previous frame make the history stale;
  // false when none moved.
  bool mark_moved_lights(const std::vector<FrameLight>& lights, const View& view, const FroxelColumns& columns);

  FroxelGrid grid_, history_grid_;
  View history_view_;
  FroxelMedia media_, history_;
  FroxelColumns columns_;  // reused frame to frame
  std::vector<RGB> integrated_;
  std::vector<uint8_t> fresh_;
  std::vector<FrameLight> history_lights_;  // the previous frame's, for their poses
  bool has_history_ = false;
};

}  // namespace caligo
