#include "realtime/pipeline.h"

#include <chrono>

#include "core/parallel.h"
#include "realtime/directional_faces.h"
#include "realtime/froxel_fog.h"
#include "realtime/light_depth_volume.h"
#include "realtime/light_cores.h"
#include "realtime/scene_buffers.h"
#include "realtime/shadow_map.h"
#include "realtime/sky.h"
#include "realtime/surface_shading.h"
#include "scene/scene.h"
#include "volumes/volume_scene.h"

namespace caligo {
namespace {

using Clock = std::chrono::steady_clock;

double micros_since(Clock::time_point start) {
  return std::chrono::duration<double, std::micro>(Clock::now() - start).count();
}

}  // namespace

struct RealtimePipeline::CachedShadow {
  std::vector<float> key;
  int size = 0;
  std::optional<ShadowMap> map;
  std::optional<ShadowMap> cascades;  // a sun's, for surfaces
  // A sun's transmittance through the grid volumes, for the placement `media_key` of still media.
  std::optional<LightDepthVolume> media_depth;
  std::vector<float> media_key;
};

RealtimeSettings realtime_settings(const SceneDesc& desc) {
  RealtimeSettings s = desc.realtime;
  s.resolution = desc.camera.resolution;
  return s;
}

RealtimePipeline::RealtimePipeline(std::shared_ptr<const Scene> scene, const RealtimeSettings& settings)
    : settings_(settings), scene_(std::move(scene)) {
  const SceneDesc& desc = scene_->desc();
  // Thin-lens and orthographic cameras are path-traced only (the passes assume one eye point).
  const Camera camera(desc.camera, settings_.resolution);
  if (camera.projection() != CameraProjection::perspective)
    throw InputError({desc.file, "/camera/projection"},
                     "the real-time pipeline renders only perspective cameras, got an orthographic one; "
                     "use `caligo render`");
  if (camera.has_aperture())
    throw InputError({desc.file, "/camera"}, "the real-time pipeline renders only pinhole cameras, got a thin "
                                             "lens (\"aperture_radius\" or \"fstop\"); use `caligo render`");
  // Geometry never moves: its triangles are set up once.
  raster_ = std::make_unique<RasterScene>(RasterScene::build(*scene_));
  RasterScene glass = RasterScene::build(*scene_, RasterScene::Layer::glass);
  if (glass.triangle_count() > 0) {
    glass_raster_ = std::make_unique<RasterScene>(std::move(glass));
    camera_raster_ = std::make_unique<RasterScene>(RasterScene::build(*scene_, RasterScene::Layer::opaque));
  }
  gbuffer_ = std::make_unique<GBuffer>();
  shadows_.resize(desc.lights.size());
}

RealtimePipeline::~RealtimePipeline() = default;

namespace {

// The camera depths a frame's cascades cover: to the farthest corner of the surfaces and media
// (or the farthest surface where no sky shows), from 1/500 of that.
Vec2 cascade_depths(const View& view, const Bounds3& surfaces, const VolumeScene& volumes, const Plane& depth) {
  Bounds3 b = surfaces;
  for (const VolumePrimitive& p : volumes.primitives()) b.extend(volume_bounds(p.shape));
  float far = 1e-3f;
  for (int c = 0; c < 8 && !b.empty(); ++c) {
    far = std::max(far, dot(b.corner(c) - view.eye, view.forward));
  }
  float deepest = 0.0f;
  for (float d : depth.data) deepest = std::max(deepest, d);
  if (deepest < kSkyDepth) far = std::min(far, std::max(deepest, 1e-3f));
  return {far / 500.0f, far};
}

}  // namespace

// One of the suns an environment light is shaded by (light_stand_ins.h).
bool RealtimePipeline::is_sky_sun(const FrameLight& light) const {
  return std::holds_alternative<EnvironmentLight>(scene_->desc().lights[light.scene_light]);
}

// Maps are kept while their key holds: a still light keeps its map. A sun's cascades (for
// surfaces) keep each face until its snapped window moves (directional_faces.h).
void RealtimePipeline::update_shadow_maps(const std::vector<FrameLight>& lights, const VolumeScene& volumes,
                                          RealtimeFrame& frame) {
  const Bounds3 bounds = scene_->surfaces().bounds();
  frame.shadow_maps_rendered = 0;
  std::optional<Vec2> depths;
  for (const FrameLight& light : lights) {
    if (light.index >= shadows_.size()) shadows_.resize(light.index + 1);
    CachedShadow& cache = shadows_[light.index];
    if (!light.options.shadow) {
      cache.map.reset();
      cache.cascades.reset();
      continue;
    }
    const int size = light.options.shadow_map_size;
    std::vector<float> key = placement_key(light.light);
    const bool moved = cache.size != size || cache.key != key || cache.key.empty();
    if (moved) {
      cache.map = render_shadow_map(*raster_, light.light, size, bounds, light.skip_emitter);
      if (cache.map) cache.map->filter_surfaces = settings_.filter_surface_shadows;
      cache.key = std::move(key);
      cache.size = size;
      ++frame.shadow_maps_rendered;
    }
    // An environment's suns keep their one face: each is a sixteenth of a soft sky, and with
    // 16 of them a moving camera would redraw up to 16 cascades a frame.
    const auto* sun = std::get_if<DirectionalLight>(&light.light);
    if (!sun || is_sky_sun(light) || settings_.sun_cascades < 2 || !cache.map) {
      cache.cascades.reset();
      continue;
    }
    if (!depths) depths = cascade_depths(frame.view, bounds, volumes, gbuffer_->depth);
    // Each cascade at half the light's size: four of them cost two of the whole-scene map.
    CascadeFaces fit = fit_cascades(frame.view, depths->x, depths->y, sun->direction, bounds,
                                    settings_.sun_cascades, std::max(256, size / 2));
    end_with_whole_face(fit, cache.map->faces[0]);
    if (moved || !cache.cascades) cache.cascades.emplace();
    frame.shadow_maps_rendered +=
        update_cascaded_shadow_map(*raster_, fit, frame.view, light.skip_emitter, *cache.cascades, &*cache.map);
    cache.cascades->filter_surfaces = settings_.filter_surface_shadows;
  }
}

// Suns over grid volumes get their transmittance table (light_depth_volume.h), rebuilt when the
// light turns or the media move (then every frame: the media are the frame's own).
void RealtimePipeline::update_media_depths(const std::vector<FrameLight>& lights, const VolumeScene& volumes,
                                           bool media_move) {
  for (const FrameLight& light : lights) {
    if (light.index >= shadows_.size()) shadows_.resize(light.index + 1);
    CachedShadow& cache = shadows_[light.index];
    const auto* sun = std::get_if<DirectionalLight>(&light.light);
    if (!sun || settings_.light_depth_cells <= 0 || !light.options.volumetric) {
      cache.media_depth.reset();
      continue;
    }
    std::vector<float> key = placement_key(light.light);
    key.push_back(float(settings_.light_depth_cells));
    if (!media_move && cache.media_key == key) continue;
    // Across the light the cloud's self-shadow edges need the cells; along it a third will do
    // (measured on `cloud`: 192 x 64 within 1.2 % of the exact mean, 64 x 256 8 %). An
    // environment's suns, each a sixteenth of a soft sky, take half the columns (a quarter of
    // the build and the memory).
    const int columns = is_sky_sun(light) ? std::max(2, settings_.light_depth_cells / 2) : settings_.light_depth_cells;
    cache.media_depth = LightDepthVolume::build(*sun, volumes, columns, std::max(16, columns / 3));
    cache.media_key = std::move(key);
  }
}

namespace {

// Runs `stage` and adds its duration to `micros` (one timing helper for every pass).
template <typename Stage>
void timed(double& micros, Stage&& stage) {
  const auto start = Clock::now();
  stage();
  micros += micros_since(start);
}

}  // namespace

void RealtimePipeline::draw_scene_buffers(RealtimeFrame& next) {
  if (settings_.scene_buffers == SceneBufferMethod::embree) {
    *gbuffer_ = trace_gbuffer(*scene_, next.view);
    return;
  }
  rasterize_gbuffer(camera_raster_ ? *camera_raster_ : *raster_, next.view, *gbuffer_, settings_.simd);
  if (glass_raster_) glass_transmission_ = glass_transmission(*glass_raster_, *scene_, next.view, gbuffer_->depth);
}

// The camera side of the march is built on the first light that marches: when a scatterer takes
// every light, no frame pays for it. The scatterer's lights go to their own buffer: their
// noise-free result wants the small gather.
void RealtimePipeline::accumulate_lights(const std::vector<FrameLight>& lights, const VolumeScene& volumes,
                                         Vec2i low_res, uint32_t frame_index, RealtimeFrame& next,
                                         ColorPlanes& accum, bool* marched, bool* scattered) {
  PassTimes& times = next.times;
  next.low_depth = downsample_depth(gbuffer_->depth, settings_.scale, settings_.low_depth);
  accum = ColorPlanes(low_res.x, low_res.y);
  AccumulationSettings acc = settings_.accumulation;
  acc.frame_seed = frame_index;
  acc.simd = settings_.simd;
  times.per_light.assign(scene_->desc().lights.size(), 0.0);
  bool rays_built = false;
  if (scatterer_) {
    if (scatter_accum_.width() != low_res.x || scatter_accum_.height() != low_res.y)
      scatter_accum_ = ColorPlanes(low_res.x, low_res.y);
    else
      scatter_accum_.clear();
  }
  for (size_t i = 0; i < lights.size(); ++i) {
    if (!lights[i].options.volumetric) continue;
    const auto light_start = Clock::now();
    const double rays_before = times.rays;
    if (scatterer_ &&
        scatterer_->scatter(lights[i].index, lights[i], volumes, next.low_view, next.low_depth, scatter_accum_)) {
      *scattered = true;
    } else {
      *marched = true;
      if (!rays_built) {
        times.rays = 0.0;
        timed(times.rays, [&] { accumulation_rays_.build(volumes, next.low_view, next.low_depth, acc); });
        rays_built = true;
      }
      accumulate_light(lights[i], volumes, accumulation_rays_, acc, accum);
    }
    // rays reported apart
    times.per_light[lights[i].scene_light] += micros_since(light_start) - (times.rays - rays_before);
  }
}

ColorPlanes RealtimePipeline::gather(ColorPlanes& accum, bool marched, bool scattered, const RealtimeFrame& next) {
  const auto pass = [&](ColorPlanes& in, int radius) {
    return radius > 0 ? bilateral_gather(in, next.low_depth, radius, settings_.gather_depth_falloff, settings_.simd,
                                         settings_.gather_follow_slope)
                      : std::move(in);
  };
  ColorPlanes gathered = scattered && !marched ? pass(scatter_accum_, settings_.scatter_gather_radius)
                                               : pass(accum, settings_.gather_radius);
  if (scattered && marched) gathered.add(pass(scatter_accum_, settings_.scatter_gather_radius));
  return gathered;
}

// Temporal reprojection at accumulation resolution: the interleaving pattern and the flicker it
// fights live there, and it costs scale^2 times less than at full resolution.
void RealtimePipeline::reproject(ColorPlanes& gathered, RealtimeFrame& next) {
  if (settings_.temporal && has_history_)
    temporal_reproject(gathered, next.low_depth, next.low_view, previous_.low_volumetric, previous_.low_depth,
                       previous_.low_view, settings_.temporal_blend, next.low_volumetric, settings_.simd);
  else
    next.low_volumetric = std::move(gathered);
}

void RealtimePipeline::upsample(RealtimeFrame& next) {
  if (settings_.scale == 1)
    next.volumetric = next.low_volumetric;
  else
    upsample_nearest_depth(next.low_volumetric, next.low_depth, gbuffer_->depth, next.volumetric, 0.05f,
                           settings_.simd);
}

void RealtimePipeline::render_froxels(const std::vector<FrameLight>& lights, const VolumeScene& volumes,
                                      uint32_t frame_index, RealtimeFrame& next) {
  if (!froxels_) froxels_ = std::make_unique<FroxelFog>();
  FroxelFog::Times t;
  froxels_->render(lights, volumes, next.view, gbuffer_->depth, settings_, frame_index, scene_->desc().lights.size(),
                   next.volumetric, t);
  PassTimes& times = next.times;
  times.rays = t.columns;
  times.per_light = t.per_light;
  times.accumulation = t.columns + t.media;
  for (double l : t.per_light) times.accumulation += l;
  times.temporal = t.reproject;
  times.gather = t.integrate;
  times.upsample = t.lookup;
}

// Composite before tone mapping (the seed adds the upscaled buffer to the lit scene).
void RealtimePipeline::composite(RealtimeFrame& next) {
  if (next.color.width() != settings_.resolution.x || next.color.height() != settings_.resolution.y)
    next.color = ColorPlanes(settings_.resolution.x, settings_.resolution.y);
  parallel_for(settings_.resolution.y, [&](int y) {
    const auto add_row = [y](Plane& out, const Plane& a, const Plane& b) {
      float* o = out.row(y);
      const float *pa = a.row(y), *pb = b.row(y);
      for (int x = 0; x < out.width; ++x) o[x] = pa[x] + pb[x];
    };
    add_row(next.color.r, next.surfaces.r, next.volumetric.r);
    add_row(next.color.g, next.surfaces.g, next.volumetric.g);
    add_row(next.color.b, next.surfaces.b, next.volumetric.b);
    // Glass in front: what lies behind it, through its two interfaces.
    if (glass_transmission_.width == next.color.width() && glass_transmission_.height == next.color.height()) {
      const float* t = glass_transmission_.row(y);
      for (Plane* p : {&next.color.r, &next.color.g, &next.color.b}) {
        float* o = p->row(y);
        for (int x = 0; x < p->width; ++x) o[x] *= t[x];
      }
    }
  });
}

const RealtimeFrame& RealtimePipeline::render(float time, uint32_t frame_index) {
  const auto frame_start = Clock::now();
  const SceneDesc& desc = scene_->desc();
  std::swap(frame_, previous_);
  RealtimeFrame& next = frame_;
  PassTimes& times = next.times;
  times = {};
  const Camera camera(desc.camera_at(time), settings_.resolution);
  next.view = View::from_camera(camera, settings_.resolution);
  const int scale = settings_.scale;
  const Vec2i low_res{(settings_.resolution.x + scale - 1) / scale, (settings_.resolution.y + scale - 1) / scale};
  next.low_view = View::from_camera(camera, low_res);

  timed(times.depth, [&] { draw_scene_buffers(next); });
  // The lights the passes shade, posed at `time`; their shadow maps follow.
  std::vector<FrameLight> lights = frame_lights(desc, desc.lights_at(time), settings_.environment_lights);
  // Media in the wind are rebuilt at the frame's time; still ones are the scene's own.
  std::optional<VolumeScene> moved;
  if (desc.media_move()) moved.emplace(desc.volumes_at(time));
  const VolumeScene& volumes = moved ? *moved : scene_->volumes();
  timed(times.shadows, [&] {
    update_shadow_maps(lights, volumes, next);
    update_media_depths(lights, volumes, desc.media_move());
  });
  for (FrameLight& l : lights) {
    const CachedShadow& cache = shadows_[l.index];
    l.shadow = cache.map ? &*cache.map : nullptr;
    l.surface_shadow = cache.cascades ? &*cache.cascades : nullptr;
    l.media_depth = cache.media_depth ? &*cache.media_depth : nullptr;
  }
  if (settings_.froxel) {
    render_froxels(lights, volumes, frame_index, next);
  } else {
    ColorPlanes accum;
    bool marched = false, scattered = false;
    timed(times.accumulation,
          [&] { accumulate_lights(lights, volumes, low_res, frame_index, next, accum, &marched, &scattered); });
    ColorPlanes gathered;
    timed(times.gather, [&] { gathered = gather(accum, marched, scattered, next); });
    timed(times.temporal, [&] { reproject(gathered, next); });
    timed(times.upsample, [&] {
      upsample(next);
      // The cores need every light in the march (a scatterer's lights are not in it).
      if (settings_.resolve_light_cores && marched && !scattered)
        resolve_light_cores(lights, volumes, next.view, gbuffer_->depth, settings_.accumulation,
                            {kLightCoreRadius * float(settings_.scale), 4, 32}, next.volumetric);
    });
  }
  timed(times.surfaces, [&] {
    shade_surfaces(*gbuffer_, next.view, *scene_, lights, next.surfaces, settings_.simd);
    shade_sky(*gbuffer_, next.view, *scene_, next.surfaces);
  });
  timed(times.composite, [&] { composite(next); });
  times.total = micros_since(frame_start);
  has_history_ = true;
  return next;
}

}  // namespace caligo
