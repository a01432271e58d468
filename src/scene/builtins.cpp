#include "scene/builtins.h"

#include "scene/scene_parser.h"

namespace caligo {
namespace {

// A closed Cornell-style room, 4 m wide, 4 m high and 7 m deep, with all six walls facing
// inwards (the wall behind the camera included, so no light escapes). Kept identical to
// scenes/default.json.
constexpr const char* kDefault = R"json({
  "camera": {"position": [0, 1.7, 4.9], "look_at": [0, 1.3, -2], "fov": 48, "resolution": [640, 480]},
  "render": {"spp": 64, "max_depth": 8},
  "materials": {
    "white": {"type": "diffuse", "reflectance": 0.75},
    "red": {"type": "diffuse", "reflectance": [0.63, 0.065, 0.05]},
    "green": {"type": "diffuse", "reflectance": [0.14, 0.45, 0.091]},
    "glass": {"type": "dielectric", "ior": 1.5}
  },
  "media": {"fog": {"sigma_s": 0.03, "sigma_a": 0.003, "phase": {"type": "hg", "g": 0.4}}},
  "volumes": [{"type": "box", "min": [-2, 0, -2], "max": [2, 4, 5], "medium": "fog"}],
  "shapes": [
    {"type": "rectangle", "corner": [-2, 0, -2], "edge1": [0, 0, 7], "edge2": [4, 0, 0], "material": "white"},
    {"type": "rectangle", "corner": [-2, 4, -2], "edge1": [4, 0, 0], "edge2": [0, 0, 7], "material": "white"},
    {"type": "rectangle", "corner": [-2, 0, -2], "edge1": [4, 0, 0], "edge2": [0, 4, 0], "material": "white"},
    {"type": "rectangle", "corner": [-2, 0, 5], "edge1": [0, 4, 0], "edge2": [4, 0, 0], "material": "white"},
    {"type": "rectangle", "corner": [-2, 0, -2], "edge1": [0, 4, 0], "edge2": [0, 0, 7], "material": "red"},
    {"type": "rectangle", "corner": [2, 0, -2], "edge1": [0, 0, 7], "edge2": [0, 4, 0], "material": "green"},
    {"type": "sphere", "center": [-0.8, 0.7, 0.2], "radius": 0.7, "material": "glass"},
    {"type": "box", "min": [-0.6, 0, -0.6], "max": [0.6, 1.6, 0.6], "material": "white",
     "transform": [{"rotate": {"angle": 25, "axis": [0, 1, 0]}}, {"translate": [0.9, 0, -0.6]}]}
  ],
  "lights": [
    {"type": "quad", "corner": [-0.75, 3.99, -0.75], "edge1": [1.5, 0, 0], "edge2": [0, 0, 1.5],
     "color": [1, 0.85, 0.65], "radiance": 8},
    {"type": "point", "position": [1.4, 3.2, 2.2], "color": [1, 0.7, 0.4], "intensity": 2}
  ]
}
)json";

// Albedo-0.5 walls emitting 1 on both sides, seen from inside: L = E / (1 - a) = 2.
constexpr const char* kFurnace = R"json({
  "camera": {"position": [0, 0, 0], "look_at": [0, 0, 1], "fov": 60, "resolution": [32, 32]},
  "render": {"spp": 64, "max_depth": 1000},
  "materials": {
    "wall": {"type": "diffuse", "reflectance": 0.5, "emission": 1, "two_sided": true}
  },
  "shapes": [
    {"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "wall"}
  ]
}
)json";

// Irradiance on the wall E = I / r^2 = 1; the walls' radiance sums the bounces:
// L = (a / pi) E / (1 - a) = 1 / pi (the first bounce alone: a / pi = 0.159).
constexpr const char* kPointInSphere = R"json({
  "camera": {"position": [0, 0, 0], "look_at": [0, 0, 1], "fov": 60, "resolution": [32, 32]},
  "render": {"spp": 64, "max_depth": 1000},
  "materials": {
    "wall": {"type": "diffuse", "reflectance": 0.5}
  },
  "shapes": [
    {"type": "sphere", "center": [0, 0, 0], "radius": 2, "material": "wall"}
  ],
  "lights": [
    {"type": "point", "position": [0, 0, 0], "intensity": 4}
  ]
}
)json";

constexpr const char* kLightsShowcase = R"json({
  "camera": {"position": [0, 2.5, 8], "look_at": [0, 0.8, 0], "fov": 40, "resolution": [640, 480]},
  "render": {"spp": 32, "max_depth": 5},
  "materials": {
    "ground": {"type": "diffuse", "reflectance": 0.5},
    "grey": {"type": "diffuse", "reflectance": 0.7},
    "rust": {"type": "diffuse", "reflectance": [0.7, 0.3, 0.15]},
    "slate": {"type": "diffuse", "reflectance": [0.2, 0.3, 0.6]}
  },
  "shapes": [
    {"type": "rectangle", "corner": [-20, 0, -20], "edge1": [0, 0, 40], "edge2": [40, 0, 0],
     "material": "ground"},
    {"type": "sphere", "center": [0, 1, 0], "radius": 1, "material": "grey"},
    {"type": "sphere", "center": [-2.5, 0.7, 0.5], "radius": 0.7, "material": "rust"},
    {"type": "sphere", "center": [2.2, 0.6, 1.2], "radius": 0.6, "material": "slate"}
  ],
  "lights": [
    {"type": "spot", "position": [-3, 5, 3], "look_at": [0, 1, 0], "inner_angle": 15, "outer_angle": 25,
     "color": [1, 0.9, 0.7], "power": 60},
    {"type": "sphere", "center": [2.5, 2.5, -1], "radius": 0.3, "color": [0.6, 0.8, 1], "power": 40},
    {"type": "point", "position": [0, 3.5, 2.5], "power": 60},
    {"type": "quad", "corner": [-1, 0.5, -4], "edge1": [2, 0, 0], "edge2": [0, 1.2, 0],
     "color": [1, 0.4, 0.2], "radiance": 3},
    {"type": "directional", "direction": [-0.4, -1, -0.3], "color": [1, 0.95, 0.85], "irradiance": 1.5,
     "angular_radius": 0.5},
    {"type": "environment", "color": [0.5, 0.7, 1], "radiance": 0.15}
  ]
}
)json";

// A 10 W/sr lamp inside a sphere of homogeneous fog, seen from outside: the equiangular
// sampling showcase (and its benchmark).
constexpr const char* kLampInFog = R"json({
  "camera": {"position": [0, 0, 6], "look_at": [0, 0, 0], "fov": 45, "resolution": [320, 240]},
  "render": {"spp": 64, "max_volume_bounces": 128},
  "media": {"fog": {"sigma_s": 0.4, "sigma_a": 0.02, "phase": {"type": "hg", "g": 0.3}}},
  "volumes": [{"type": "sphere", "center": [0, 0, 0], "radius": 2, "medium": "fog"}],
  "lights": [{"type": "point", "position": [0.4, 0.2, 0.3], "color": [1, 0.8, 0.55], "intensity": 10}]
})json";

// A spot light shining down through fog past a sphere: the shadow it casts is a dark shaft.
// Single scattering and direct light only (the real-time pipelines' reference); raise
// max_volume_bounces for multiple scattering, which a point-like light inside a medium makes
// noisy (the in-scattered radiance of rays passing at distance D from it grows as 1/D).
constexpr const char* kSpotShafts = R"json({
  "camera": {"position": [0, 1.6, 6.5], "look_at": [0, 1.4, 0], "fov": 50, "resolution": [320, 240]},
  "render": {"spp": 64, "max_depth": 1, "max_volume_bounces": 1},
  "materials": {"ground": {"type": "diffuse", "reflectance": 0.5},
                "blocker": {"type": "diffuse", "reflectance": 0.3}},
  "media": {"haze": {"sigma_s": 0.25, "sigma_a": 0.02, "phase": {"type": "hg", "g": 0.5}}},
  "shapes": [
    {"type": "rectangle", "corner": [-4, 0, -4], "edge1": [0, 0, 8], "edge2": [8, 0, 0], "material": "ground"},
    {"type": "sphere", "center": [0.2, 2.2, 0], "radius": 0.45, "material": "blocker"}
  ],
  "volumes": [{"type": "box", "min": [-3.5, 0, -3.5], "max": [3.5, 4, 3.5], "medium": "haze"}],
  "lights": [{"type": "spot", "position": [0, 3.9, 0], "look_at": [0, 0, 0], "inner_angle": 22,
              "outer_angle": 28, "color": [1, 0.9, 0.75], "intensity": 30}]
})json";

// Two overlapping boxes of coloured media: in the overlap their coefficients add up.
constexpr const char* kOverlap = R"json({
  "camera": {"position": [0, 1, 5], "look_at": [0, 0.8, 0], "fov": 45, "resolution": [320, 240]},
  "render": {"spp": 64, "max_volume_bounces": 64},
  "media": {"red": {"sigma_s": [0.9, 0.15, 0.1], "sigma_a": 0.05},
            "blue": {"sigma_s": [0.1, 0.3, 1.0], "sigma_a": 0.05, "phase": {"type": "hg", "g": -0.2}}},
  "volumes": [{"type": "box", "min": [-1.5, 0, -1], "max": [0.4, 1.8, 1], "medium": "red"},
              {"type": "box", "min": [-0.4, 0, -1], "max": [1.5, 1.8, 1], "medium": "blue",
               "transform": [{"rotate": {"angle": 15, "axis": [0, 1, 0]}}]}],
  "lights": [{"type": "point", "position": [0, 3, 2], "intensity": 12},
             {"type": "environment", "radiance": 0.15}]
})json";


// A cumulus from the grid generator under a low sun and a blue sky: a dense, bright medium
// (albedo 0.99, optical depth ~30 through the middle) whose look is multiple scattering, so
// paths may scatter hundreds of times. The grid is generated when the scene is loaded.
constexpr const char* kCloud = R"json({
  "camera": {"position": [0, 1.0, 5.2], "look_at": [0, 1.35, 0], "fov": 40, "resolution": [480, 270]},
  "render": {"spp": 64, "max_depth": 64, "max_volume_bounces": 512},
  "media": {"cloud": {"albedo": 0.99, "extinction": 12, "phase": {"type": "hg", "g": 0.7}}},
  "volumes": [{"type": "vdb", "generate": {"kind": "cloud", "resolution": 128, "seed": 7}, "medium": "cloud"}],
  "lights": [{"type": "directional", "direction": [-0.55, -0.45, -0.7], "angular_radius": 0.27,
              "color": [1, 0.93, 0.82], "irradiance": 6},
             {"type": "environment", "color": [0.35, 0.55, 1.0], "radiance": 0.6}]
})json";

// A fireball from the grid generator: blackbody emission from its temperature channel
// inside dark, absorbing smoke, over a ground it lights.
constexpr const char* kFire = R"json({
  "camera": {"position": [0, 1.6, 7.5], "look_at": [0, 1.6, 0], "fov": 42, "resolution": [400, 400]},
  "render": {"spp": 64, "max_depth": 8, "max_volume_bounces": 32},
  "materials": {"ground": {"type": "diffuse", "reflectance": 0.35}},
  "media": {"fire": {"sigma_a": 1.2, "sigma_s": 0.6, "phase": {"type": "hg", "g": 0.2},
                     "blackbody": {"intensity": 2e-5, "scale": 1, "offset": 0}}},
  "shapes": [{"type": "rectangle", "corner": [-6, 0, -6], "edge1": [0, 0, 12], "edge2": [12, 0, 0],
              "material": "ground"}],
  "volumes": [{"type": "vdb", "generate": {"kind": "fire", "resolution": 96, "seed": 3}, "medium": "fire"}],
  "lights": [{"type": "environment", "radiance": 0.02}]
})json";

// A closed mesh from Debian's assimp-testmodels (COLLADA's duck; the PLY Wuson there is open,
// 412 boundary edges, so it cannot bound a volume) filled with smoke, lit from above: its
// inside is found per ray by even/odd counting of all the mesh's crossings.
constexpr const char* kMeshVolume = R"json({
  "camera": {"position": [0.9, 1.3, 3.4], "look_at": [0.1, 0.85, 0], "fov": 38, "resolution": [400, 300]},
  "render": {"spp": 64, "max_depth": 16, "max_volume_bounces": 64},
  "materials": {"floor": {"type": "diffuse", "reflectance": 0.5}},
  "media": {"smoke": {"albedo": [0.95, 0.88, 0.6], "extinction": 6, "phase": {"type": "hg", "g": 0.3}}},
  "shapes": [{"type": "rectangle", "corner": [-5, 0.1, -5], "edge1": [0, 0, 10], "edge2": [10, 0, 0],
              "material": "floor"}],
  "volumes": [{"type": "mesh", "file": "/usr/share/assimp/models/Collada/duck.dae", "medium": "smoke"}],
  "lights": [{"type": "quad", "corner": [-0.5, 3, -0.5], "edge1": [1.5, 0, 0], "edge2": [0, 0, 1.2],
              "radiance": 8},
             {"type": "environment", "radiance": 0.1}]
})json";

// The Wyman & Ramsey (2008) test scenes: one light in homogeneous fog over a ground plane,
// above a closed occluder of a chosen size whose shadow volume cuts dark shafts into the
// airlight. Single scattering and direct light (the real-time methods' reference). The ground
// is a thin closed box rather than a rectangle so that it, too, can bound a shadow volume (the
// hybrid wants every occluder closed: hybrid/hybrid_pipeline.h). Sizes: Debian's
// assimp-testmodels has no closed mesh of 20k-750k triangles (its largest, the 110k-triangle
// 2CylinderEngine glTF, is open), so the occluders are generated. `light` is the one light's
// JSON: a point light (kWymanPoint) or the paper's textured spotlight (kWymanSpot).
std::string wyman_scene(const char* kind, int triangles, const char* transform, const char* light) {
  return std::string(R"json({
  "camera": {"position": [0, 2.2, 7.5], "look_at": [0, 1.1, 0], "fov": 45, "resolution": [512, 512]},
  "render": {"spp": 64, "max_depth": 1, "max_volume_bounces": 1},
  "materials": {"ground": {"type": "diffuse", "reflectance": 0.4},
                "occluder": {"type": "diffuse", "reflectance": 0.6}},
  "media": {"fog": {"sigma_s": 0.25, "sigma_a": 0.03}},
  "shapes": [
    {"type": "box", "min": [-8, -0.1, -8], "max": [8, 0, 8], "material": "ground"},
    {"type": "mesh", "generate": {"kind": ")json") + kind + R"json(", "triangles": )json" + std::to_string(triangles) +
         R"json(}, "material": "occluder", "transform": )json" + transform + R"json(}
  ],
  "volumes": [{"type": "box", "min": [-8, 0, -8], "max": [8, 6, 8], "medium": "fog"}],
  "lights": [)json" + light + R"json(]
})json";
}

const char* const kWymanSphere = R"([{"scale": 0.8}, {"translate": [0, 1.6, 0]}])";
const char* const kWymanKnot = R"([{"scale": 0.9}, {"translate": [0, 1.6, 0]}])";

const char* const kWymanPoint =
    R"({"type": "point", "position": [0.6, 4.2, -0.4], "color": [1, 0.92, 0.8], "intensity": 60})";
// The same position, aimed at the occluder's centre through a generated stained-glass gobo.
// Its intensity is the point light's 60 W/sr over the gobo's mean luminance (0.20: the panes
// are 0.3, the leading and the corners outside the window ~0), so the fog the cone lights is
// about as bright as under the point light (the panes a little brighter, the leading dark).
// Shadow map: the point light's default size.
const char* const kWymanSpot = R"({"type": "spot", "position": [0.6, 4.2, -0.4], "look_at": [0, 1.6, 0],
     "inner_angle": 26, "outer_angle": 32, "color": [1, 1, 1], "intensity": 300, "shadow_map_size": 1024,
     "gobo": {"generate": {"kind": "stained_glass", "resolution": 256, "seed": 1}}})";

const std::vector<BuiltinScene>& all_builtins() {
  static const std::vector<BuiltinScene> scenes = {
      {"default",
       "a closed Cornell-style room in thin fog, with a glass sphere, a rotated box, a ceiling light and a "
       "lamp",
       kDefault},
      {"furnace", "camera inside a closed sphere of albedo 0.5 emitting 1: every pixel converges to 2",
       kFurnace},
      {"point-in-sphere",
       "camera inside an albedo-0.5 sphere of radius 2 lit by a 4 W/sr point light at its centre: "
       "every pixel converges to 1/pi",
       kPointInSphere},
      {"lights-showcase",
       "spheres on a ground plane lit by one light of each type: spot, sphere, point, quad, directional "
       "(0.5 degree sun) and environment",
       kLightsShowcase},
      {"lamp-in-fog", "a small point light inside a sphere of homogeneous scattering fog", kLampInFog},
      {"spot-shafts", "a spot light through fog past an occluding sphere: a volumetric shadow", kSpotShafts},
      {"overlap", "two overlapping boxes of coloured media, whose coefficients add where they overlap",
       kOverlap},
      {"cloud", "a dense, bright cumulus (generated VDB grid) under a low sun and a blue sky: 64+ bounces",
       kCloud},
      {"fire", "a fireball (generated VDB grid) glowing by blackbody emission from its temperature, in smoke",
       kFire},
      {"mesh-volume", "the COLLADA duck from assimp-testmodels filled with smoke (a closed-mesh volume, even/odd counting)",
       kMeshVolume},
      {"wyman-20k", "Wyman & Ramsey: a point light in fog over a ground plane, a 20,480-triangle sphere occluder",
       wyman_scene("sphere", 20000, kWymanSphere, kWymanPoint)},
      {"wyman-70k", "Wyman & Ramsey: a point light in fog, a 70,688-triangle torus-knot occluder",
       wyman_scene("torus_knot", 70000, kWymanKnot, kWymanPoint)},
      {"wyman-330k", "Wyman & Ramsey: a point light in fog, a 327,680-triangle sphere occluder",
       wyman_scene("sphere", 300000, kWymanSphere, kWymanPoint)},
      {"wyman-750k", "Wyman & Ramsey: a point light in fog, a 758,912-triangle torus-knot occluder",
       wyman_scene("torus_knot", 750000, kWymanKnot, kWymanPoint)},
      {"wyman-20k-spot",
       "Wyman & Ramsey: a textured spotlight (generated stained-glass gobo) in fog over a ground plane, a "
       "20,480-triangle sphere occluder",
       wyman_scene("sphere", 20000, kWymanSphere, kWymanSpot)},
      {"wyman-70k-spot",
       "Wyman & Ramsey: a textured spotlight (stained-glass gobo) in fog, a 70,688-triangle torus-knot "
       "occluder",
       wyman_scene("torus_knot", 70000, kWymanKnot, kWymanSpot)},
      {"wyman-330k-spot",
       "Wyman & Ramsey: a textured spotlight (stained-glass gobo) in fog, a 327,680-triangle sphere occluder",
       wyman_scene("sphere", 300000, kWymanSphere, kWymanSpot)},
      {"wyman-750k-spot",
       "Wyman & Ramsey: a textured spotlight (stained-glass gobo) in fog, a 758,912-triangle torus-knot "
       "occluder",
       wyman_scene("torus_knot", 750000, kWymanKnot, kWymanSpot)},
  };
  return scenes;
}

}  // namespace

std::vector<BuiltinScene> builtin_scenes() { return all_builtins(); }

const BuiltinScene* find_builtin(std::string_view name) {
  for (const BuiltinScene& scene : all_builtins())
    if (scene.name == name) return &scene;
  return nullptr;
}

SceneDesc parse_builtin(const BuiltinScene& scene) {
  return parse_scene_text(scene.json, "builtin:" + scene.name, "");
}

}  // namespace caligo
