// One real-time frame, pass by pass (the seed's pipeline, DESIGN.md "A frame in the
// real-time pipeline"): scene buffers -> shadow maps (cached while a light stands still) ->
// per-light accumulation at low resolution (or a LightScatterer's analytic pass for the lights
// it takes) -> bilateral gather -> temporal reprojection (at low resolution: see
// docs/techniques.md) -> nearest-depth upsampling -> composite over the simply lit surfaces.
// Each pass is a pure function (passes.h, scene_buffers.h, shadow_map.h, surface_shading.h);
// this class shares the built scene and owns what lives across frames (its triangles set up
// for the rasteriser, cached shadow maps, reused buffers, the history) and times every pass.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "realtime/accumulation_rays.h"
#include "realtime/passes.h"
#include "realtime/plane.h"
#include "realtime/view.h"
#include "scene/scene_desc.h"

namespace caligo {

class Scene;
class RasterScene;
class FroxelFog;
class VolumeScene;
struct FrameLight;
struct GBuffer;
struct ShadowMap;

// A replacement for accumulate_light on the lights it accepts: the Wyman & Ramsey hybrid of
// src/hybrid (hybrid/hybrid_pipeline.h) plugs in here. It is an interface rather than a
// settings enum because caligo::hybrid is built on caligo::realtime (views, shadow maps,
// the rasteriser), so the pipeline cannot call it directly without a dependency cycle.
class LightScatterer {
 public:
  virtual ~LightScatterer() = default;
  // Adds light `index`'s in-scattered radiance at low_view's resolution into `accum` and
  // returns true, or returns false without touching `accum` to leave the light to the march.
  // `low_depth` is the linear depth at low_view's resolution (kSkyDepth where nothing).
  virtual bool scatter(size_t index, const FrameLight& light, const VolumeScene& volumes, const View& low_view,
                       const Plane& low_depth, ColorPlanes& accum) = 0;
};

// The scene's `realtime` object at the camera's resolution.
RealtimeSettings realtime_settings(const SceneDesc& desc);

// Microseconds spent in each pass of one frame.
struct PassTimes {
  double depth = 0, shadows = 0, rays = 0, accumulation = 0, gather = 0, upsample = 0, temporal = 0, surfaces = 0,
         composite = 0, total = 0;
  // Accumulation of each of the scene's lights, by scene index (0 for non-volumetric lights
  // and for lights the passes do not shade).
  std::vector<double> per_light;
  // accumulation includes `rays`: the camera side shared by all lights (rays, media intervals,
  // interleaved offsets), built once per frame.
  // The budget: accumulation + gather + upsample + temporal.
  double volumetric() const { return accumulation + gather + upsample + temporal; }
};

struct RealtimeFrame {
  View view;                   // full resolution
  ColorPlanes surfaces;        // directly lit surfaces, attenuated by the media in front of them
  ColorPlanes volumetric;      // in-scattered light at full resolution
  ColorPlanes color;           // surfaces + volumetric, linear, before tone mapping
  View low_view;               // accumulation resolution
  Plane low_depth;             // linear depth at accumulation resolution
  ColorPlanes low_volumetric;  // gathered and temporally filtered: next frame's history
  PassTimes times;
  int shadow_maps_rendered = 0;
};

class RealtimePipeline {
 public:
  // The pipeline shares the built scene (surfaces, materials, still media) with whoever else
  // renders it; each frame poses only what moves (camera, lights, media in the wind).
  RealtimePipeline(std::shared_ptr<const Scene> scene, const RealtimeSettings& settings);
  ~RealtimePipeline();
  RealtimePipeline(const RealtimePipeline&) = delete;
  RealtimePipeline& operator=(const RealtimePipeline&) = delete;

  // Renders the scene at `time` seconds; frame_index seeds the interleaving pattern. The
  // previous call's frame is the temporal history.
  const RealtimeFrame& render(float time, uint32_t frame_index);

  // The built scene (geometry never moves): what a scatterer builds its occluders from.
  const Scene& scene() const { return *scene_; }
  // Lights the scatterer accepts skip accumulate_light; null (the default) marches all.
  void set_scatterer(std::unique_ptr<LightScatterer> scatterer) { scatterer_ = std::move(scatterer); }

 private:
  struct CachedShadow;

  void update_shadow_maps(const std::vector<FrameLight>& lights, const VolumeScene& volumes, RealtimeFrame& frame);
  bool is_sky_sun(const FrameLight& light) const;
  void update_media_depths(const std::vector<FrameLight>& lights, const VolumeScene& volumes, bool media_move);
  // The frame's stages, in order (render() times each).
  void draw_scene_buffers(RealtimeFrame& next);
  // Accumulation per light: the marched lights into `accum`, the scatterer's into
  // scatter_accum_; sets *marched and *scattered when any light went that way.
  void accumulate_lights(const std::vector<FrameLight>& lights, const VolumeScene& volumes, Vec2i low_res,
                         uint32_t frame_index, RealtimeFrame& next, ColorPlanes& accum, bool* marched,
                         bool* scattered);
  ColorPlanes gather(ColorPlanes& accum, bool marched, bool scattered, const RealtimeFrame& next);
  void reproject(ColorPlanes& gathered, RealtimeFrame& next);
  void upsample(RealtimeFrame& next);
  void composite(RealtimeFrame& next);
  // --method froxel: the grid's passes in place of accumulation, gather, temporal and upsample.
  void render_froxels(const std::vector<FrameLight>& lights, const VolumeScene& volumes, uint32_t frame_index,
                      RealtimeFrame& next);

  RealtimeSettings settings_;
  std::shared_ptr<const Scene> scene_;
  std::unique_ptr<RasterScene> raster_;  // every surface: the shadow maps
  // With glass in the scene: the camera's surfaces without it, the glass alone, and per pixel
  // the glass's transmission (1 where none; glass_transmission()).
  std::unique_ptr<RasterScene> camera_raster_, glass_raster_;
  Plane glass_transmission_;
  std::vector<CachedShadow> shadows_;
  AccumulationRays accumulation_rays_;  // per-frame camera side of accumulation, storage reused
  std::unique_ptr<GBuffer> gbuffer_;  // reused frame to frame (allocation costs as much as drawing it)
  RealtimeFrame frame_, previous_;   // swapped each frame so their buffers are reused
  bool has_history_ = false;
  std::unique_ptr<LightScatterer> scatterer_;
  ColorPlanes scatter_accum_;  // the scatterer's lights, reused frame to frame
  std::unique_ptr<FroxelFog> froxels_;  // --method froxel: the grid and its history
};

}  // namespace caligo
