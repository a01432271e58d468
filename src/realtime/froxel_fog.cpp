#include "realtime/froxel_fog.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <utility>

#include "core/parallel.h"
#include "realtime/accumulate_internal.h"
#include "realtime/light_volume.h"
#include "realtime/media.h"
#include "realtime/scene_buffers.h"
#include "volumes/volume_scene.h"

namespace caligo {

float FroxelGrid::edge(float i) const {
  if (i <= 1.0f) return near * std::max(i, 0.0f);
  return near * std::pow(far / near, (std::min(i, float(slices)) - 1.0f) / float(slices - 1));
}

float FroxelGrid::edge_coordinate(float z) const {
  if (z <= near) return std::max(z, 0.0f) / near;
  const float i = 1.0f + float(slices - 1) * std::log(z / near) / std::log(far / near);
  return std::min(i, float(slices));
}

std::vector<float> slice_edges(const FroxelGrid& grid) {
  std::vector<float> z(size_t(grid.slices) + 1);
  for (int i = 0; i <= grid.slices; ++i) z[size_t(i)] = grid.edge(float(i));
  return z;
}

FroxelGrid fit_froxel_grid(const View& view, const VolumeScene& volumes, const Plane& depth,
                           const FroxelSettings& settings) {
  FroxelGrid g;
  // Columns by the screen's size, and at least kMinColumns each way (or one per pixel) so a
  // small preview is not a handful of columns.
  constexpr int kMinColumns = 32;
  const int px = std::max(1, settings.column_pixels);
  auto columns_for = [&](int pixels) { return std::max((pixels + px - 1) / px, std::min(pixels, kMinColumns)); };
  g.width = settings.width > 0 ? settings.width : columns_for(view.resolution.x);
  g.height = settings.height > 0 ? settings.height : columns_for(view.resolution.y);
  g.slices = std::max(2, settings.slices);
  float far = 1e-3f;
  for (const VolumePrimitive& p : volumes.primitives()) {
    const Bounds3 b = volume_bounds(p.shape);
    for (int c = 0; c < 8; ++c) {
      const Vec3 corner = b.corner(c);
      far = std::max(far, dot(corner - view.eye, view.forward));
    }
  }
  // Nothing beyond the farthest surface is seen: where no sky shows, the grid ends there (a
  // room inside a fog volume the size of the level keeps its slices in the room).
  float deepest = 0.0f;
  for (float d : depth.data) deepest = std::max(deepest, d);
  g.far = deepest >= kSkyDepth ? far : std::min(far, std::max(deepest, 1e-3f));
  g.near = g.far / std::max(settings.near_ratio, 1.001f);
  return g;
}

void froxel_columns(const FroxelGrid& grid, const View& view, const VolumeScene& volumes, float jitter,
                    FroxelColumns& out) {
  out.columns.resize(grid.columns());
  out.t.resize(grid.cells());
  out.intervals.clear();
  std::vector<std::vector<VolumeInterval>> rows(size_t(grid.height));
  const std::vector<float> edges = slice_edges(grid);
  parallel_for(grid.height, [&](int y) {
    thread_local VolumeContext scratch;
    for (int x = 0; x < grid.width; ++x) {
      const size_t c = size_t(y) * size_t(grid.width) + size_t(x);
      FroxelColumns::Column& col = out.columns[c];
      const Ray ray = view.ray(grid.film(view, float(x), float(y)));
      col.origin = ray.origin;
      col.dir = ray.direction;
      col.t_per_depth = 1.0f / view.depth_per_t(ray.direction);
      float* t = out.t.data() + c * size_t(grid.slices);
      for (int s = 0; s < grid.slices; ++s) {
        const float z0 = edges[size_t(s)], z1 = edges[size_t(s) + 1];
        t[s] = (z0 + jitter * (z1 - z0)) * col.t_per_depth;
      }
      col.first = uint32_t(rows[size_t(y)].size());
      volumes.intervals(Ray{ray.origin, ray.direction, 0.0f, grid.far * col.t_per_depth}, scratch);
      rows[size_t(y)].insert(rows[size_t(y)].end(), scratch.intervals.begin(), scratch.intervals.end());
      col.count = uint32_t(rows[size_t(y)].size()) - col.first;
    }
  });
  // Rows' intervals joined into one list (column offsets shifted by the rows before).
  for (int y = 0; y < grid.height; ++y) {
    const uint32_t base = uint32_t(out.intervals.size());
    for (int x = 0; x < grid.width; ++x) out.columns[size_t(y) * size_t(grid.width) + size_t(x)].first += base;
    out.intervals.insert(out.intervals.end(), rows[size_t(y)].begin(), rows[size_t(y)].end());
  }
}

namespace {

std::span<const VolumeInterval> column_intervals(const FroxelColumns& columns, const FroxelColumns::Column& col) {
  return {columns.intervals.data() + col.first, col.count};
}

}  // namespace

void inject_media(const FroxelGrid& grid, const FroxelColumns& columns, const VolumeScene& volumes,
                  FroxelMedia& media) {
  media.reset(grid.cells());
  parallel_for(grid.height, [&](int y) {
    for (int x = 0; x < grid.width; ++x) {
      const size_t c = size_t(y) * size_t(grid.width) + size_t(x);
      const FroxelColumns::Column& col = columns.columns[c];
      const float* t = columns.t.data() + c * size_t(grid.slices);
      Froxel* cells = media.cells.data() + c * size_t(grid.slices);
      for (const VolumeInterval& iv : column_intervals(columns, col)) {
        const VolumePrimitive& prim = volumes.primitive(iv.primitive);
        const RGB sigma = prim.shader.sigma_a + prim.shader.sigma_s;
        // t grows with the slice: the interval covers one run of slices.
        const int s0 = int(std::lower_bound(t, t + grid.slices, iv.t0) - t);
        for (int s = s0; s < grid.slices && t[s] <= iv.t1; ++s)
          cells[s].sigma_t += sigma * medium_density(prim, col.origin + col.dir * t[s]);
      }
    }
  });
}

namespace {

// light_screen_bounds at the grid's resolution: the columns whose rays can meet the light.
PixelRect froxel_rect(const ShadedLight& light, const FroxelGrid& grid, const View& view) {
  View at_grid = view;
  at_grid.resolution = {grid.width, grid.height};
  const PixelRect r = light_screen_bounds(light, at_grid);
  return {std::max(r.x0, 0), std::max(r.y0, 0), std::min(r.x1, grid.width), std::min(r.y1, grid.height)};
}

// The run of slices [s0, s1) of column c whose samples the light's volume holds (t grows with
// the slice); s1 <= s0 when none.
std::pair<int, int> slices_in_reach(const ShadedLight& light, const FroxelGrid& grid, const FroxelColumns& columns,
                                    size_t c) {
  const FroxelColumns::Column& col = columns.columns[c];
  const float* t = columns.t.data() + c * size_t(grid.slices);
  const auto reach = light_volume_interval(light, col.origin, col.dir, 0.0f, t[grid.slices - 1]);
  if (!reach) return {0, 0};
  return {int(std::lower_bound(t, t + grid.slices, reach->t0) - t),
          int(std::upper_bound(t, t + grid.slices, reach->t1) - t)};
}

}  // namespace

void inject_light(const FrameLight& light, const FroxelGrid& grid, const View& view, const FroxelColumns& columns,
                  const VolumeScene& volumes, float multiple_scattering_floor, bool simd, FroxelMedia& media) {
  if (!light.options.volumetric || volumes.empty()) return;
  // Only the columns whose rays can meet the light's volume (a small lamp: a few).
  const PixelRect rect = froxel_rect(light.light, grid, view);
  if (rect.x0 >= rect.x1 || rect.y0 >= rect.y1) return;
  const float far = media_extent(volumes);
  const SimdMarcher marcher(light, volumes, multiple_scattering_floor, far);
  const bool use_simd = simd && marcher.supported();
  const RGB intensity(light.options.volumetric_intensity);
  parallel_for(rect.y1 - rect.y0, [&](int row) {
    const int y = rect.y0 + row;
    std::vector<RGB> in(size_t(grid.slices));
    for (int x = rect.x0; x < rect.x1; ++x) {
      const size_t c = size_t(y) * size_t(grid.width) + size_t(x);
      const FroxelColumns::Column& col = columns.columns[c];
      if (col.count == 0) continue;
      const float* t = columns.t.data() + c * size_t(grid.slices);
      const auto [s0, s1] = slices_in_reach(light.light, grid, columns, c);
      if (s1 <= s0) continue;
      PixelMarch march;
      march.origin = col.origin;
      march.dir = col.dir;
      march.intervals = column_intervals(columns, col);
      std::fill(in.begin(), in.begin() + (s1 - s0), RGB(0.0f));
      if (use_simd) {
        marcher.inscatter(march, {t + s0, size_t(s1 - s0)}, in.data());
      } else {
        for (int s = s0; s < s1; ++s)
          in[size_t(s - s0)] = inscatter_scalar(light, volumes, march, t[s], multiple_scattering_floor, far);
      }
      Froxel* cells = media.cells.data() + c * size_t(grid.slices);
      for (int s = s0; s < s1; ++s) cells[s].scatter += in[size_t(s - s0)] * intensity;
    }
  });
}

namespace {

// slices_in_reach, one more each way (the history's samples sat elsewhere in their slices).
std::pair<int, int> reached_slices(const ShadedLight& light, const FroxelGrid& grid, const FroxelColumns& columns,
                                   size_t c) {
  const auto [s0, s1] = slices_in_reach(light, grid, columns, c);
  if (s1 <= s0) return {0, 0};
  return {std::max(0, s0 - 1), std::min(grid.slices, s1 + 1)};
}

PixelRect united(PixelRect a, PixelRect b) {
  if (a.x0 >= a.x1 || a.y0 >= a.y1) return b;
  if (b.x0 >= b.x1 || b.y0 >= b.y1) return a;
  return {std::min(a.x0, b.x0), std::min(a.y0, b.y0), std::max(a.x1, b.x1), std::max(a.y1, b.y1)};
}

}  // namespace

void mark_moved_light(const ShadedLight* before, const ShadedLight& now, const FroxelGrid& grid, const View& view,
                      const FroxelColumns& columns, std::vector<uint8_t>& fresh) {
  PixelRect rect =
      before ? united(froxel_rect(*before, grid, view), froxel_rect(now, grid, view)) : froxel_rect(now, grid, view);
  if (rect.x0 >= rect.x1 || rect.y0 >= rect.y1) return;
  // The history is read trilinearly, so a froxel next to a stale one reads it too: each column
  // takes the runs of its 3x3 neighbourhood, found once per column first.
  rect = {std::max(rect.x0 - 1, 0), std::max(rect.y0 - 1, 0), std::min(rect.x1 + 1, grid.width),
          std::min(rect.y1 + 1, grid.height)};
  const int w = rect.x1 - rect.x0, h = rect.y1 - rect.y0;
  struct Runs {
    std::pair<int, int> now, before;
  };
  std::vector<Runs> runs(size_t(w) * size_t(h));
  parallel_for(h, [&](int row) {
    for (int col = 0; col < w; ++col) {
      const size_t c = size_t(rect.y0 + row) * size_t(grid.width) + size_t(rect.x0 + col);
      Runs& r = runs[size_t(row) * size_t(w) + size_t(col)];
      r.now = reached_slices(now, grid, columns, c);
      r.before = before ? reached_slices(*before, grid, columns, c) : std::pair<int, int>{0, 0};
    }
  });
  parallel_for(h, [&](int row) {
    for (int col = 0; col < w; ++col) {
      uint8_t* m = fresh.data() + (size_t(rect.y0 + row) * size_t(grid.width) + size_t(rect.x0 + col)) *
                                      size_t(grid.slices);
      for (int dy = std::max(row - 1, 0); dy <= std::min(row + 1, h - 1); ++dy) {
        for (int dx = std::max(col - 1, 0); dx <= std::min(col + 1, w - 1); ++dx) {
          const auto [a, b] = runs[size_t(dy) * size_t(w) + size_t(dx)];
          // The slices in exactly one of the two runs.
          for (int s = std::min(a.first, b.first); s < std::max(a.second, b.second); ++s)
            m[s] |= uint8_t((s >= a.first && s < a.second) != (s >= b.first && s < b.second));
        }
      }
    }
  });
}

bool same_pose(const ShadedLight& a, const ShadedLight& b) {
  if (placement_key(a) != placement_key(b)) return false;
  // The gobo moves the light's pattern without moving its shadow map.
  return std::visit(
      [&](const auto& l) {
        const auto& m = std::get<std::decay_t<decltype(l)>>(b);
        if constexpr (requires { l.gobo; })
          return l.gobo.offset.x == m.gobo.offset.x && l.gobo.offset.y == m.gobo.offset.y &&
                 l.gobo.rotation == m.gobo.rotation;
        return true;
      },
      a);
}

// A light that moved invalidates the history where it lit before and no longer does, and where
// it lights now and did not: no trail, no lag. Where it lit in both poses the history is kept
// (a slowly turning spot keeps its averaged beam).
bool FroxelFog::mark_moved_lights(const std::vector<FrameLight>& lights, const View& view,
                                  const FroxelColumns& columns) {
  fresh_.assign(grid_.cells(), 0);
  bool any = false;
  for (const FrameLight& light : lights) {
    const auto old = std::find_if(history_lights_.begin(), history_lights_.end(),
                                  [&](const FrameLight& h) { return h.index == light.index; });
    if (old != history_lights_.end() && same_pose(old->light, light.light)) continue;
    mark_moved_light(old != history_lights_.end() ? &old->light : nullptr, light.light, grid_, view, columns, fresh_);
    any = true;
  }
  return any;
}

void FroxelFog::render(const std::vector<FrameLight>& lights, const VolumeScene& volumes, const View& view,
                       const Plane& depth, const RealtimeSettings& settings, uint32_t frame_index,
                       size_t scene_lights, ColorPlanes& out, Times& times) {
  using Clock = std::chrono::steady_clock;
  auto since = [](Clock::time_point start) {
    return std::chrono::duration<double, std::micro>(Clock::now() - start).count();
  };
  times = {};
  times.per_light.assign(scene_lights, 0.0);
  auto start = Clock::now();
  grid_ = fit_froxel_grid(view, volumes, depth, settings.froxels);
  // With the history on, each frame samples its slices at another depth (the golden-ratio
  // sequence), and the blend averages them; without it, at the slices' middles.
  const bool temporal = settings.temporal;
  const float jitter = temporal ? std::fmod(0.5f + 0.6180340f * float(frame_index % 1024u), 1.0f) : 0.5f;
  froxel_columns(grid_, view, volumes, jitter, columns_);
  const FroxelColumns& columns = columns_;
  times.columns = since(start);
  start = Clock::now();
  inject_media(grid_, columns, volumes, media_);
  times.media = since(start);
  for (const FrameLight& light : lights) {
    start = Clock::now();
    inject_light(light, grid_, view, columns, volumes, settings.accumulation.multiple_scattering_floor,
                 settings.simd, media_);
    times.per_light[light.scene_light] += since(start);
  }
  start = Clock::now();
  if (temporal && has_history_) {
    const bool any = mark_moved_lights(lights, view, columns);
    reproject_froxels(grid_, view, history_, history_grid_, history_view_, settings.temporal_blend,
                      any ? std::span<const uint8_t>(fresh_) : std::span<const uint8_t>(), media_, settings.simd);
  }
  history_lights_ = lights;
  times.reproject = since(start);
  start = Clock::now();
  integrate_froxels(grid_, columns, media_, integrated_);
  times.integrate = since(start);
  start = Clock::now();
  lookup_froxels(grid_, integrated_, depth, out);
  times.lookup = since(start);
  std::swap(media_, history_);
  history_grid_ = grid_;
  history_view_ = view;
  has_history_ = true;
}

}  // namespace caligo
