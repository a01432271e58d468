// How the real-time single-scattering pipeline (realtime/pipeline.h) renders a frame: plain
// data. A scene file's "realtime" object fills one (SceneDesc::realtime) and `caligo realtime`'s
// options override it.
#pragma once

#include <cstdint>

#include "core/vec.h"

namespace caligo {

// The per-light ray march of the accumulation pass (realtime/passes.h).
struct AccumulationSettings {
  int samples = 16;                        // march steps per pixel per light
  int tile_size = 8;                       // interleaved sampling tile side; 1 = no interleaving (midpoints)
  uint32_t frame_seed = 0;                 // randomises the offsets' order per tile and per frame
  float multiple_scattering_floor = 0.0f;  // shadow term never below this (faked multiple scattering)
  // Point and spot lights: steps uniform in the angle seen from the light (equiangular,
  // Kulla & Fajardo 2012) instead of the seed's uniform steps in distance. Resolves the
  // 1/d^2 peak of rays passing near a light; costs a tangent per step. Scene key "steps":
  // "equiangular".
  bool equiangular = false;
  bool simd = true;
};

// How the depth and surface buffers are made: rasterised triangles (the game's way) or Embree
// rays (kept for comparison).
enum class SceneBufferMethod { raster, embree };

// The camera-aligned froxel grid of `--method froxel` (realtime/froxel_fog.h; Wronski 2014,
// Hillaire 2015): columns across and down, slices in depth (exponentially spaced).
struct FroxelSettings {
  // Columns across and down; 0: one per column_pixels x column_pixels of the output (160 x 90
  // at 1920 x 1080, as Unreal's 16-pixel and HDRP's 8-pixel grids scale with the screen), at
  // least 32 each way (or one per pixel).
  int width = 0, height = 0, slices = 64;
  // Slice 1 starts at far / near_ratio (slice 0 covers the depths before it).
  float near_ratio = 256.0f;
  int column_pixels = 12;
};

// The depth of each low-resolution pixel, where its accumulation ray ends (passes.h):
// `centre`, the full-resolution pixel under its centre (point-sampled: a feature thinner than
// the block, a 4 cm cable or a slit in a fence, falls between centres and is lost or broken);
// `min_max`, the centre where it agrees with the neighbourhood, else the block's nearest or
// farthest depth, whichever the neighbouring centres do not already represent.
enum class LowResolutionDepth { centre, min_max };

struct RealtimeSettings {
  Vec2i resolution{640, 480};
  int scale = 4;  // accumulation at resolution / scale: 1, 2 (half) or 4 (quarter)
  AccumulationSettings accumulation;
  LowResolutionDepth low_depth = LowResolutionDepth::min_max;
  int gather_radius = 7;  // bilateral gather taps each side (2r + 1 per pass)
  // The gather of the lights a LightScatterer takes: their analytic result has no sampling
  // noise to blur, only low-resolution edges, so Wyman & Ramsey's 3x3 bilateral filter.
  int scatter_gather_radius = 1;
  float gather_depth_falloff = 1000.0f;  // weight exp(-falloff * |relative depth difference|)
  // The depth difference taken from the plane through the centre along the pass (a wall seen
  // edge-on keeps its taps: realtime/gather.cpp); false: the seed's weight on depth alone.
  // Opt-in: it removes the streaks along walls seen edge-on, but its one-sided slope weighs
  // the taps of curved depth (a floor's rows) unevenly, which moved the mean of the CLI's spot
  // scene from -1.7 % to -4.3 % against the path tracer (docs/techniques.md).
  bool gather_follow_slope = false;
  bool temporal = true;                  // temporal reprojection
  // Every light and medium into one camera-aligned froxel grid instead of a march per light
  // (realtime/froxel_fog.h); the cost does not grow with each light's screen coverage.
  bool froxel = false;
  FroxelSettings froxels;
  // Light cores (realtime/light_cores.h): the output pixels around on-screen point lights and
  // spot apexes re-marched at full resolution after the upsample, when every light marches. Off
  // by default: on `arena` at 1080p it costs ~108 ms a frame (docs/techniques.md).
  bool resolve_light_cores = false;
  float temporal_blend = 0.1f;           // weight of the current frame in the history blend
  // The suns an environment light is shaded by (median cut: realtime/light_stand_ins.h); each
  // costs what a directional light costs, shadow map included.
  int environment_lights = 16;
  // Cascaded shadow maps for directional lights on surfaces (realtime/directional_faces.h):
  // this many faces at half the light's shadow_map_size, each over one range of the camera's
  // depth; 1: the one face over the whole scene the march always uses (the former behaviour).
  int sun_cascades = 4;
  // Directional lights' transmittance through grid volumes tabulated in this many columns each
  // way across the light and a third as many cells along it (realtime/light_depth_volume.h),
  // built once while the light and media hold still; 0: integrated through the grid at every
  // march step (the former way).
  int light_depth_cells = 192;
  // Surface shadows through the 2 x 2 bilinear PCF (ShadowMap::filter_surfaces); false: one
  // tap, stair-stepped (the former behaviour, kept for comparison).
  bool filter_surface_shadows = true;
  bool simd = true;
  SceneBufferMethod scene_buffers = SceneBufferMethod::raster;
  // The animation `caligo realtime` renders: frame i is at time i / fps.
  float fps = 30.0f;
  int frames = 60;
};

}  // namespace caligo
