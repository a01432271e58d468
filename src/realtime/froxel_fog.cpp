#include "realtime/froxel_fog.h"

#include <algorithm>
#include <chrono>
#include <cmath>

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
  g.width = std::max(1, settings.width);
  g.height = std::max(1, settings.height);
  g.slices = std::max(2, settings.slices);
  float far = 1e-3f;
  for (const VolumePrimitive& p : volumes.primitives()) {
    const Bounds3 b = volume_bounds(p.shape);
    for (int c = 0; c < 8; ++c) {
      const Vec3 corner((c & 1) ? b.hi.x : b.lo.x, (c & 2) ? b.hi.y : b.lo.y, (c & 4) ? b.hi.z : b.lo.z);
      far = std::max(far, dot(corner - view.eye, view.forward));
    }
  }
  // Nothing beyond the farthest surface is seen: where no sky shows, the grid ends there (a
  // room inside a fog volume the size of the level keeps its slices in the room).
  float deepest = 0.0f;
  for (float d : depth.data) deepest = std::max(deepest, d);
  g.far = deepest >= kSkyDepth ? far : std::min(far, std::max(deepest, 1e-3f));
  g.near = far / std::max(settings.near_ratio, 1.001f);
  return g;
}

FroxelColumns froxel_columns(const FroxelGrid& grid, const View& view, const VolumeScene& volumes, float jitter) {
  FroxelColumns out;
  out.columns.resize(grid.columns());
  out.t.resize(grid.cells());
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
  return out;
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
      RGB* sigma_t = media.sigma_t.data() + c * size_t(grid.slices);
      for (const VolumeInterval& iv : column_intervals(columns, col)) {
        const VolumePrimitive& prim = volumes.primitive(iv.primitive);
        const RGB sigma = prim.shader.sigma_a + prim.shader.sigma_s;
        // t grows with the slice: the interval covers one run of slices.
        const int s0 = int(std::lower_bound(t, t + grid.slices, iv.t0) - t);
        for (int s = s0; s < grid.slices && t[s] <= iv.t1; ++s)
          sigma_t[s] += sigma * medium_density(prim, col.origin + col.dir * t[s]);
      }
    }
  });
}

void inject_light(const FrameLight& light, const FroxelGrid& grid, const FroxelColumns& columns,
                  const VolumeScene& volumes, float multiple_scattering_floor, bool simd, FroxelMedia& media) {
  if (!light.options.volumetric || volumes.empty()) return;
  const float far = media_extent(volumes);
  const SimdMarcher marcher(light, volumes, multiple_scattering_floor, far);
  const bool use_simd = simd && marcher.supported();
  const RGB intensity(light.options.volumetric_intensity);
  parallel_for(grid.height, [&](int y) {
    std::vector<RGB> in(size_t(grid.slices));
    for (int x = 0; x < grid.width; ++x) {
      const size_t c = size_t(y) * size_t(grid.width) + size_t(x);
      const FroxelColumns::Column& col = columns.columns[c];
      if (col.count == 0) continue;
      const float* t = columns.t.data() + c * size_t(grid.slices);
      const auto reach = light_volume_interval(light.light, col.origin, col.dir, 0.0f, t[grid.slices - 1]);
      if (!reach) continue;
      // The run of slices whose samples the light's volume holds.
      const int s0 = int(std::lower_bound(t, t + grid.slices, reach->t0) - t);
      const int s1 = int(std::upper_bound(t, t + grid.slices, reach->t1) - t);
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
      RGB* scatter = media.scatter.data() + c * size_t(grid.slices);
      for (int s = s0; s < s1; ++s) scatter[s] += in[size_t(s - s0)] * intensity;
    }
  });
}

namespace {

// Trilinear read of a froxel field at continuous cell coordinates (cell centres at integers);
// false outside the grid.
bool sample_field(const FroxelGrid& g, const std::vector<RGB>& field, float gx, float gy, float gs, RGB& out) {
  if (gx < -0.5f || gy < -0.5f || gs < -0.5f || gx > float(g.width) - 0.5f || gy > float(g.height) - 0.5f ||
      gs > float(g.slices) - 0.5f)
    return false;
  gx = std::clamp(gx, 0.0f, float(g.width - 1));
  gy = std::clamp(gy, 0.0f, float(g.height - 1));
  gs = std::clamp(gs, 0.0f, float(g.slices - 1));
  const int x0 = std::min(int(gx), std::max(0, g.width - 2)), y0 = std::min(int(gy), std::max(0, g.height - 2)),
            s0 = std::min(int(gs), g.slices - 2);
  const int x1 = std::min(x0 + 1, g.width - 1), y1 = std::min(y0 + 1, g.height - 1), s1 = s0 + 1;
  const float fx = gx - float(x0), fy = gy - float(y0), fs = gs - float(s0);
  auto at = [&](int x, int y, int s) { return field[(size_t(y) * size_t(g.width) + size_t(x)) * size_t(g.slices) + size_t(s)]; };
  auto lerp = [](RGB a, RGB b, float f) { return a + (b - a) * f; };
  const RGB a = lerp(lerp(at(x0, y0, s0), at(x1, y0, s0), fx), lerp(at(x0, y1, s0), at(x1, y1, s0), fx), fy);
  const RGB b = lerp(lerp(at(x0, y0, s1), at(x1, y0, s1), fx), lerp(at(x0, y1, s1), at(x1, y1, s1), fx), fy);
  out = lerp(a, b, fs);
  return true;
}

}  // namespace

void reproject_froxels(const FroxelGrid& grid, const View& view, const FroxelMedia& history,
                       const FroxelGrid& history_grid, const View& history_view, float blend, FroxelMedia& current) {
  const std::vector<float> edges = slice_edges(grid);
  parallel_for(grid.height, [&](int y) {
    for (int x = 0; x < grid.width; ++x) {
      const Vec2 film = grid.film(view, float(x), float(y));
      const size_t c = size_t(y) * size_t(grid.width) + size_t(x);
      for (int s = 0; s < grid.slices; ++s) {
        const float z = 0.5f * (edges[size_t(s)] + edges[size_t(s) + 1]);
        const Vec3 q = history_view.project(view.unproject(film, z));
        if (!(q.z > 0.0f)) continue;
        const float hx = q.x * float(history_grid.width) / float(history_view.resolution.x) - 0.5f;
        const float hy = q.y * float(history_grid.height) / float(history_view.resolution.y) - 0.5f;
        // Slice coordinate of the centre: the edge coordinate less half a slice.
        const float hs = history_grid.edge_coordinate(q.z) - 0.5f;
        RGB old_sigma, old_scatter;
        if (!sample_field(history_grid, history.sigma_t, hx, hy, hs, old_sigma)) continue;
        sample_field(history_grid, history.scatter, hx, hy, hs, old_scatter);
        const size_t i = c * size_t(grid.slices) + size_t(s);
        current.sigma_t[i] = old_sigma + (current.sigma_t[i] - old_sigma) * blend;
        current.scatter[i] = old_scatter + (current.scatter[i] - old_scatter) * blend;
      }
    }
  });
}

std::vector<RGB> integrate_froxels(const FroxelGrid& grid, const FroxelColumns& columns, const FroxelMedia& media) {
  const size_t edges = size_t(grid.slices) + 1;
  const std::vector<float> z = slice_edges(grid);
  std::vector<RGB> out(grid.columns() * edges);
  parallel_for(grid.height, [&](int y) {
    for (int x = 0; x < grid.width; ++x) {
      const size_t c = size_t(y) * size_t(grid.width) + size_t(x);
      const float t_per_depth = columns.columns[c].t_per_depth;
      RGB sum(0.0f), transmittance(1.0f);
      RGB* o = out.data() + c * edges;
      o[0] = sum;
      for (int s = 0; s < grid.slices; ++s) {
        const size_t i = c * size_t(grid.slices) + size_t(s);
        const float dt = (z[size_t(s) + 1] - z[size_t(s)]) * t_per_depth;
        const RGB sigma = media.sigma_t[i], in = media.scatter[i];
        float step_t[3], step_l[3];
        for (int ch = 0; ch < 3; ++ch) {
          // (1 - e^(-x)) / sigma, by expm1 for a thin slice; in dt where there is no extinction.
          const float x = sigma[ch] * dt;
          step_t[ch] = std::exp(-x);
          step_l[ch] = in[ch] * (x > 1e-6f ? -std::expm1(-x) / sigma[ch] : dt);
        }
        sum += transmittance * RGB(step_l[0], step_l[1], step_l[2]);
        transmittance *= RGB(step_t[0], step_t[1], step_t[2]);
        o[s + 1] = sum;
      }
    }
  });
  return out;
}

void lookup_froxels(const FroxelGrid& grid, std::span<const RGB> integrated, const Plane& depth, ColorPlanes& out) {
  if (out.width() != depth.width || out.height() != depth.height) out = ColorPlanes(depth.width, depth.height);
  const size_t edges = size_t(grid.slices) + 1;
  const float sx = float(grid.width) / float(depth.width), sy = float(grid.height) / float(depth.height);
  parallel_for(depth.height, [&](int y) {
    const float gy = std::clamp((float(y) + 0.5f) * sy - 0.5f, 0.0f, float(grid.height - 1));
    const int y0 = int(gy), y1 = std::min(y0 + 1, grid.height - 1);
    const float fy = gy - float(y0);
    const float* d = depth.row(y);
    float *r = out.r.row(y), *g = out.g.row(y), *b = out.b.row(y);
    for (int x = 0; x < depth.width; ++x) {
      const float gx = std::clamp((float(x) + 0.5f) * sx - 0.5f, 0.0f, float(grid.width - 1));
      const int x0 = int(gx), x1 = std::min(x0 + 1, grid.width - 1);
      const float fx = gx - float(x0);
      const float e = grid.edge_coordinate(d[x] >= kSkyDepth ? grid.far : d[x]);
      const int e0 = std::min(int(e), grid.slices - 1);
      const float fe = e - float(e0);
      auto column = [&](int cx, int cy) {
        const RGB* o = integrated.data() + (size_t(cy) * size_t(grid.width) + size_t(cx)) * edges;
        return o[e0] + (o[e0 + 1] - o[e0]) * fe;
      };
      const RGB v = (column(x0, y0) * (1.0f - fx) + column(x1, y0) * fx) * (1.0f - fy) +
                    (column(x0, y1) * (1.0f - fx) + column(x1, y1) * fx) * fy;
      r[x] = v.r;
      g[x] = v.g;
      b[x] = v.b;
    }
  });
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
  const FroxelColumns columns = froxel_columns(grid_, view, volumes, jitter);
  times.columns = since(start);
  start = Clock::now();
  inject_media(grid_, columns, volumes, media_);
  times.media = since(start);
  for (const FrameLight& light : lights) {
    start = Clock::now();
    inject_light(light, grid_, columns, volumes, settings.accumulation.multiple_scattering_floor, settings.simd,
                 media_);
    times.per_light[light.index] = since(start);
  }
  start = Clock::now();
  if (temporal && has_history_)
    reproject_froxels(grid_, view, history_, history_grid_, history_view_, settings.temporal_blend, media_);
  times.reproject = since(start);
  start = Clock::now();
  const std::vector<RGB> integrated = integrate_froxels(grid_, columns, media_);
  times.integrate = since(start);
  start = Clock::now();
  lookup_froxels(grid_, integrated, depth, out);
  times.lookup = since(start);
  std::swap(media_, history_);
  history_grid_ = grid_;
  history_view_ = view;
  has_history_ = true;
}

}  // namespace caligo
