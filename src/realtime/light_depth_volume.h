// A directional light's transmittance through the scene's grid volumes, tabulated once in the
// light's space (a deep shadow map: Lokovic & Veach 2000; the transmittance volumes of
// Frostbite's and Unreal's volumetric clouds): columns along the light over the grids' bounds,
// each holding the transmittance from where the light enters the bounds to each of its nodes
// (transmittance, not optical depth, is interpolated: docs/techniques.md gives both errors).
// A march step then reads the transmittance towards the light by one trilinear lookup instead
// of integrating through the cloud towards the sun (4-point Gauss-Legendre panels of two
// voxels at every step). Built when the light or the media change; its resolution blurs the
// cloud's self-shadowing by up to a cell (docs/techniques.md gives the error).
#pragma once

#include <optional>
#include <vector>

#include "core/rgb.h"
#include "core/vec.h"
#include "lights/light.h"
#include "volumes/volume_scene.h"

namespace caligo {

class LightDepthVolume {
 public:
  // nullopt when the scene has no grid volume (every other primitive has a closed form or a
  // single panel). `columns` cells each way across the light, `nodes` cells along it.
  static std::optional<LightDepthVolume> build(const DirectionalLight& light, const VolumeScene& volumes,
                                               int columns, int nodes);

  // The grids' transmittance (per channel, mean density) from p towards the light, from where
  // the light enters their bounds: trilinear between nodes, 1 outside the columns.
  RGB transmittance(Vec3 p) const;
  // Whether primitive i is one the table holds (its optical depth is not to be added again).
  bool holds(size_t primitive) const { return primitive < held_.size() && held_[primitive]; }

 private:
  Vec3 right_, up_, along_;   // light space: along_ is the light's direction of travel
  float u0_ = 0, v0_ = 0, w0_ = 0;
  float du_ = 1, dv_ = 1, dw_ = 1;  // cell sizes
  int nu_ = 0, nw_ = 0;             // nodes across (each way) and along: cells + 1
  // Transmittance from the entry to each node, [v][u][w][channel]: one channel when every
  // held grid's extinction is grey (clouds and smoke usually are), else three.
  int channels_ = 3;
  std::vector<float> t_;
  std::vector<bool> held_;
};

}  // namespace caligo
