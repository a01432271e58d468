#include "scene/builtins.h"

#include "scene/builtin_many_lamps.h"
#include "scene/scene_parser.h"

namespace caligo {
namespace {

// A closed Cornell-style room, 4 m wide, 4 m high and 7 m deep, with all six walls facing
// inwards (the wall behind the camera included, so no light escapes). Kept identical to
// scenes/default.json.
constexpr const char* kDefault = R"json({
  "camera": {"position": [0, 1.7, 4.9], "look_at": [0, 1.3, -2], "fov": 48, "resolution": [640, 480]},
  "render": {"spp": 64, "max_bounces": 8},
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
  "render": {"spp": 64, "max_bounces": 1000},
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
  "render": {"spp": 64, "max_bounces": 1000},
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
  "render": {"spp": 32, "max_bounces": 5},
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
  "render": {"spp": 64, "max_bounces": 1, "max_volume_bounces": 1},
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

// Depth of field in fog: the spot-shafts stage seen through a thin lens (10 cm aperture radius,
// far wider than a real lens so the blur shows at 320 x 240) focused 6.5 m away, on the
// occluding sphere in the middle of the shaft; a sphere in front and one behind are blurred.
constexpr const char* kDof = R"json({
  "camera": {"position": [0, 1.6, 6.5], "look_at": [0, 1.4, 0], "fov": 50, "resolution": [320, 240],
             "aperture_radius": 0.1, "focus_distance": 6.5},
  "render": {"spp": 128, "max_depth": 1, "max_volume_bounces": 1},
  "materials": {"ground": {"type": "diffuse", "reflectance": 0.5},
                "blocker": {"type": "diffuse", "reflectance": 0.3},
                "near": {"type": "diffuse", "reflectance": [0.7, 0.3, 0.2]},
                "far": {"type": "diffuse", "reflectance": [0.2, 0.4, 0.7]}},
  "media": {"haze": {"sigma_s": 0.25, "sigma_a": 0.02, "phase": {"type": "hg", "g": 0.5}}},
  "shapes": [
    {"type": "rectangle", "corner": [-4, 0, -4], "edge1": [0, 0, 8], "edge2": [8, 0, 0], "material": "ground"},
    {"type": "sphere", "center": [0.2, 2.2, 0], "radius": 0.45, "material": "blocker"},
    {"type": "sphere", "center": [-1.1, 0.45, 3.2], "radius": 0.45, "material": "near"},
    {"type": "sphere", "center": [1.7, 0.8, -3], "radius": 0.8, "material": "far"}
  ],
  "volumes": [{"type": "box", "min": [-3.5, 0, -3.5], "max": [3.5, 4, 3.5], "medium": "haze"}],
  "lights": [{"type": "spot", "position": [0, 3.9, 0], "look_at": [0, 0, 0], "inner_angle": 22,
              "outer_angle": 28, "color": [1, 0.9, 0.75], "intensity": 30},
             {"type": "environment", "radiance": 0.05}]
})json";

// An orthographic camera looking straight down (a window 6 m x 2 m, 1/16 m per pixel) through
// three boxes of a purely absorbing medium (sigma_a = 1 per metre, sigma_s = 0) that are 0.5,
// 1 and 2 m thick, under a uniform sky of radiance 1 and nothing else: a pixel over box k
// is exactly exp(-d_k) (0.60653, 0.36788, 0.13534), every other pixel exactly 1. Box edges
// fall on pixel edges (boxes over pixel columns 4-27, 36-59, 68-91 and rows 8-23), so with
// the box pixel filter no pixel mixes two values.
constexpr const char* kSlab = R"json({
  "camera": {"position": [0, 5, 0], "look_at": [0, 0, 0], "up": [0, 0, -1], "projection": "orthographic",
             "ortho_width": 6, "resolution": [96, 32]},
  "render": {"spp": 16},
  "media": {"ink": {"sigma_s": 0, "sigma_a": 1}},
  "volumes": [{"type": "box", "min": [-2.75, 0, -0.5], "max": [-1.25, 0.5, 0.5], "medium": "ink"},
              {"type": "box", "min": [-0.75, 0, -0.5], "max": [0.75, 1, 0.5], "medium": "ink"},
              {"type": "box", "min": [1.25, 0, -0.5], "max": [2.75, 2, 0.5], "medium": "ink"}],
  "lights": [{"type": "environment", "radiance": 1}]
})json";

// Holdouts for compositing: a bank of fog over a plate whose real objects are held out. The
// ground, a torus knot that pokes out of the fog's front face and a sphere half out of its back
// face are holdouts (black in the beauty, transparent in alpha where the camera sees them, but
// they still cast shadows into the fog); the orange sphere inside the fog is the one CG object.
// The sky lights the fog but is invisible to the camera ("visible": false), so alpha is exactly
// the fog's and the CG sphere's coverage: 1 - e^(-sigma_t d) through clear fog (the fog bank is
// 3.5 m deep), lower in front of a holdout's hole by the fog between it and the camera.
constexpr const char* kHoldout = R"json({
  "camera": {"position": [0, 1.6, 7], "look_at": [0, 1.2, 0], "fov": 45, "resolution": [320, 240]},
  "render": {"spp": 64, "max_bounces": 4, "max_volume_bounces": 16, "aovs": ["default", "lights"]},
  "materials": {"plate": {"type": "diffuse", "reflectance": 0.4},
                "cg": {"type": "diffuse", "reflectance": [0.8, 0.45, 0.2]}},
  "media": {"fog": {"sigma_s": 0.3, "sigma_a": 0.01, "phase": {"type": "hg", "g": 0.3}}},
  "shapes": [
    {"type": "rectangle", "corner": [-8, 0, -8], "edge1": [0, 0, 16], "edge2": [16, 0, 0], "material": "plate",
     "holdout": true},
    {"type": "mesh", "generate": {"kind": "torus_knot", "triangles": 4608}, "material": "plate", "holdout": true,
     "transform": [{"scale": 0.6}, {"rotate": {"angle": 40, "axis": [0, 1, 0]}}, {"translate": [-1.3, 1.4, 1.5]}]},
    {"type": "sphere", "center": [1.3, 1.0, -2], "radius": 1.0, "material": "plate", "holdout": true},
    {"type": "sphere", "center": [0.2, 0.6, -0.2], "radius": 0.6, "material": "cg"}
  ],
  "volumes": [{"type": "box", "min": [-3.5, 0, -2], "max": [3.5, 3, 1.5], "medium": "fog"}],
  "lights": [{"type": "directional", "direction": [-0.5, -0.7, -0.35], "color": [1, 0.92, 0.8], "irradiance": 3},
             {"type": "environment", "color": [0.5, 0.65, 1], "radiance": 0.25, "visible": false}]
})json";

// Neon signs in fog: three emissive torus-knot tubes (closed generated meshes; an emissive
// material on a mesh makes one TriangleLight per triangle, 2,048 each, sampled by solid
// angle) over a dark wet-looking floor, in fog that glows around them. No other light.
constexpr const char* kNeon = R"json({
  "camera": {"position": [0, 1.4, 6.5], "look_at": [0, 1.3, 0], "fov": 45, "resolution": [480, 270]},
  "render": {"spp": 64, "max_bounces": 6, "max_volume_bounces": 8},
  "materials": {"floor": {"type": "diffuse", "reflectance": 0.25},
                "pink": {"type": "emissive", "color": [1, 0.15, 0.6], "radiance": 6},
                "cyan": {"type": "emissive", "color": [0.1, 0.8, 1], "radiance": 6},
                "amber": {"type": "emissive", "color": [1, 0.55, 0.1], "radiance": 6}},
  "media": {"fog": {"sigma_s": 0.12, "sigma_a": 0.01, "phase": {"type": "hg", "g": 0.3}}},
  "volumes": [{"type": "box", "min": [-5, 0, -4], "max": [5, 4, 4], "medium": "fog"}],
  "shapes": [
    {"type": "rectangle", "corner": [-8, 0, -8], "edge1": [0, 0, 16], "edge2": [16, 0, 0], "material": "floor"},
    {"type": "mesh", "generate": {"kind": "torus_knot", "triangles": 2000}, "material": "pink",
     "transform": [{"scale": 0.6}, {"rotate": {"angle": 90, "axis": [1, 0, 0]}}, {"translate": [-1.9, 1.5, -0.5]}]},
    {"type": "mesh", "generate": {"kind": "torus_knot", "triangles": 2000}, "material": "cyan",
     "transform": [{"scale": 0.5}, {"rotate": {"angle": 70, "axis": [1, 0, 0]}}, {"translate": [0.1, 2.1, -1]}]},
    {"type": "mesh", "generate": {"kind": "torus_knot", "triangles": 2000}, "material": "amber",
     "transform": [{"scale": 0.45}, {"rotate": {"angle": 100, "axis": [1, 0.3, 0]}}, {"translate": [1.9, 1.2, 0]}]}
  ]
})json";

// A real mesh on a stage: the Wuson from Debian's assimp-testmodels (OBJ, 3,732 triangles,
// 3.2 m long, turned side-on) on a floor, under a narrow, bright spot in haze, with a dim
// blue sky. Most of the image is lit indirectly (haze -> lit floor -> eye).
constexpr const char* kStage = R"json({
  "camera": {"position": [0, 1.5, 5.6], "look_at": [0, 0.8, 0], "fov": 40, "resolution": [480, 270]},
  "render": {"spp": 64, "max_bounces": 6, "max_volume_bounces": 8},
  "materials": {"floor": {"type": "diffuse", "reflectance": 0.5},
                "wuson": {"type": "diffuse", "reflectance": [0.8, 0.72, 0.6]}},
  "media": {"haze": {"sigma_s": 0.08, "sigma_a": 0.005, "phase": {"type": "hg", "g": 0.4}}},
  "volumes": [{"type": "box", "min": [-6, 0, -6], "max": [6, 6, 6], "medium": "haze"}],
  "shapes": [
    {"type": "rectangle", "corner": [-10, 0, -10], "edge1": [0, 0, 20], "edge2": [20, 0, 0], "material": "floor"},
    {"type": "mesh", "file": "/usr/share/assimp/models/OBJ/WusonOBJ.obj", "material": "wuson",
     "transform": [{"rotate": {"angle": 90, "axis": [0, 1, 0]}}]}
  ],
  "lights": [{"type": "spot", "position": [0.6, 5.2, 1.2], "look_at": [0, 0.6, 0], "inner_angle": 12,
              "outer_angle": 17, "color": [1, 0.92, 0.8], "intensity": 400},
             {"type": "environment", "color": [0.45, 0.55, 1], "radiance": 0.03}]
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


// A cumulus from the grid generator lit as production cloud renders are: a low sun from the upper
// left and a little behind it, so the lit side, the self-shadowed base and right flank and the
// bright forward-scattering rim along the silhouette all show, under a blue sky that fills the
// shadows. A dense, bright medium (albedo 0.99, optical depth ~30 through the middle) whose look
// is multiple scattering, so paths may scatter hundreds of times. The grid is generated when the
// scene is loaded. `cloud-dense` is the same cumulus at 40 per metre (optical depth ~100).
std::string cloud_scene(const char* extinction) {
  return std::string(R"json({
  "camera": {"position": [0, 1.0, 5.2], "look_at": [0, 1.35, 0], "fov": 40, "resolution": [480, 270]},
  "render": {"spp": 64, "max_bounces": 64, "max_volume_bounces": 512},
  "media": {"cloud": {"albedo": 0.99, "extinction": )json") +
         extinction + R"json(, "phase": {"type": "hg", "g": 0.7}}},
  "volumes": [{"type": "vdb", "generate": {"kind": "cloud", "resolution": 128, "seed": 7}, "medium": "cloud"}],
  "lights": [{"type": "directional", "direction": [0.6, -0.45, 0.65], "angular_radius": 0.27,
              "color": [1, 0.93, 0.82], "irradiance": 6},
             {"type": "environment", "color": [0.35, 0.55, 1.0], "radiance": 0.35}]
})json";
}

// A smoke plume from the grid generator over a ground, lit by a warm sun from the side and a
// grey sky: grey, moderately absorbing smoke (albedo 0.8) in which shadows and multiple
// scattering both show.
constexpr const char* kSmoke = R"json({
  "camera": {"position": [0, 1.5, 6.5], "look_at": [0, 1.5, 0], "fov": 42, "resolution": [360, 400]},
  "render": {"spp": 64, "max_bounces": 16, "max_volume_bounces": 64},
  "materials": {"ground": {"type": "diffuse", "reflectance": 0.4}},
  "media": {"smoke": {"albedo": 0.8, "extinction": 24, "phase": {"type": "hg", "g": 0.3}}},
  "shapes": [{"type": "rectangle", "corner": [-6, 0, -6], "edge1": [0, 0, 12], "edge2": [12, 0, 0],
              "material": "ground"}],
  "volumes": [{"type": "vdb", "generate": {"kind": "smoke", "resolution": 112, "seed": 3}, "medium": "smoke"}],
  "lights": [{"type": "directional", "direction": [-0.7, -0.55, -0.45], "angular_radius": 0.5,
              "color": [1, 0.9, 0.75], "irradiance": 4},
             {"type": "environment", "radiance": 0.25}]
})json";

// A fireball from the grid generator: blackbody emission from its temperature channel
// inside dark, absorbing smoke, over a ground it lights.
constexpr const char* kFire = R"json({
  "camera": {"position": [0, 1.6, 7.5], "look_at": [0, 1.6, 0], "fov": 42, "resolution": [400, 400]},
  "render": {"spp": 64, "max_bounces": 8, "max_volume_bounces": 32},
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
  "render": {"spp": 64, "max_bounces": 16, "max_volume_bounces": 64},
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
  "render": {"spp": 64, "max_bounces": 1, "max_volume_bounces": 1},
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

// ---- Nested dielectrics (media/medium_stack.h) ----

// Two overlapping boxes of absorbing media bounded by null surfaces with priorities: red is
// high (100), green normal (200), so the overlap is red. `caligo render priority-cubes
// --priority green=very_high` makes it green. The boxes float 1 cm above the ground so no
// boundary is coplanar with it.
constexpr const char* kPriorityCubes = R"json({
  "camera": {"position": [0.4, 2.0, 4.2], "look_at": [0, 0.55, 0], "fov": 38, "resolution": [256, 192]},
  "render": {"spp": 32, "max_bounces": 8, "max_volume_bounces": 8},
  "materials": {
    "ground": {"type": "diffuse", "reflectance": 0.8},
    "red": {"type": "null", "interior": "red", "priority": "high"},
    "green": {"type": "null", "interior": "green", "priority": "normal"}
  },
  "media": {"red": {"sigma_a": [0.2, 3, 3]},
            "green": {"sigma_a": [3, 0.2, 3]}},
  "shapes": [
    {"type": "rectangle", "corner": [-10, 0, 10], "edge1": [20, 0, 0], "edge2": [0, 0, -20], "material": "ground"},
    {"type": "box", "min": [-1.2, 0.01, -0.6], "max": [0.3, 1.2, 0.6], "material": "red"},
    {"type": "box", "min": [-0.3, 0.01, -0.6], "max": [1.2, 1.2, 0.6], "material": "green",
     "transform": [{"rotate": {"angle": 20, "axis": [0, 1, 0]}}, {"translate": [0, 0, -0.3]}]}
  ],
  "lights": [
    {"type": "quad", "corner": [-1, 3.5, -1], "edge1": [2, 0, 0], "edge2": [0, 0, 2], "radiance": 4},
    {"type": "environment", "color": [0.8, 0.9, 1], "radiance": 0.4}
  ]
})json";

// A square glass (dielectric 1.5, priority high) on a table: a 5 mm bottom slab and four 4 mm
// walls, closed boxes of one material that merge (equal priorities) into one glass; they
// overlap rather than touch so that no two faces are coplanar. The water (1.33, priority
// normal, faintly blue-green) is a box overlapping the walls and the bottom by half a
// millimetre, so it refracts glass -> water with no air gap; an ice cube (1.31, priority very
// high, faintly cloudy) floats in it. Units: metres (the glass is 8 cm wide, 12 cm tall).
constexpr const char* kGlassOfWater = R"json({
  "camera": {"position": [0.05, 0.16, 0.36], "look_at": [0, 0.06, 0], "fov": 30, "resolution": [200, 256]},
  "render": {"spp": 64, "max_bounces": 32, "max_volume_bounces": 16, "priority_shadows": true},
  "materials": {
    "table": {"type": "diffuse", "reflectance": [0.75, 0.7, 0.6]},
    "wall": {"type": "diffuse", "reflectance": 0.6},
    "glass": {"type": "dielectric", "ior": 1.5, "priority": "high"},
    "water": {"type": "dielectric", "ior": 1.33, "priority": "normal", "interior": "water"},
    "ice": {"type": "dielectric", "ior": 1.31, "priority": "very_high", "interior": "ice"}
  },
  "media": {"water": {"sigma_a": [3, 0.8, 1.0], "sigma_s": 0.2},
            "ice": {"sigma_s": 25, "sigma_a": 0.2, "phase": {"type": "hg", "g": 0.6}}},
  "shapes": [
    {"type": "rectangle", "corner": [-1, -0.0005, 1], "edge1": [2, 0, 0], "edge2": [0, 0, -2], "material": "table"},
    {"type": "rectangle", "corner": [-1, -0.0005, -0.3], "edge1": [2, 0, 0], "edge2": [0, 1, 0], "material": "wall"},
    {"type": "box", "min": [-0.0398, 0, -0.0398], "max": [0.0398, 0.005, 0.0398], "material": "glass"},
    {"type": "box", "min": [-0.04, 0.0005, -0.04], "max": [-0.036, 0.12, 0.04], "material": "glass"},
    {"type": "box", "min": [0.036, 0.0005, -0.04], "max": [0.04, 0.12, 0.04], "material": "glass"},
    {"type": "box", "min": [-0.0365, 0.0005, -0.0399], "max": [0.0365, 0.1199, -0.036], "material": "glass"},
    {"type": "box", "min": [-0.0365, 0.0005, 0.036], "max": [0.0365, 0.1199, 0.0399], "material": "glass"},
    {"type": "box", "min": [-0.0364, 0.0045, -0.0364], "max": [0.0364, 0.09, 0.0364], "material": "water"},
    {"type": "box", "min": [-0.01, -0.01, -0.01], "max": [0.01, 0.01, 0.01], "material": "ice",
     "transform": [{"rotate": {"angle": 25, "axis": [0, 1, 0]}}, {"rotate": {"angle": 12, "axis": [1, 0, 0]}},
                   {"translate": [0.006, 0.085, 0.004]}]}
  ],
  "lights": [
    {"type": "quad", "corner": [-0.25, 0.45, -0.2], "edge1": [0.5, 0, 0], "edge2": [0, 0.15, 0.3], "radiance": 12},
    {"type": "environment", "color": [0.9, 0.95, 1], "radiance": 0.3}
  ]
})json";

// A pool: a 100 m water plane at y = 0 (open, normal up, so the water is below it) over a
// sandy floor 3 m down, with rocks on the floor and a half-submerged buoy; sun and sky.
// Shadow rays pass the water surface (priority_shadows), so the sun lights the floor.
// `camera` is the camera's JSON; `extra` adds shapes (the split view's clipping box).
std::string pool_scene(const char* camera, const char* extra) {
  return std::string(R"json({
  "camera": )json") + camera + R"json(,
  "render": {"spp": 32, "max_bounces": 12, "max_volume_bounces": 8, "priority_shadows": true},
  "materials": {
    "water": {"type": "dielectric", "ior": 1.33, "priority": "normal", "interior": "pool"},
    "clip": {"type": "null", "priority": "very_high"},
    "sand": {"type": "diffuse", "reflectance": [0.75, 0.65, 0.45]},
    "rock": {"type": "diffuse", "reflectance": [0.35, 0.33, 0.3]},
    "buoy": {"type": "diffuse", "reflectance": [0.9, 0.3, 0.05]}
  },
  "media": {"pool": {"sigma_a": [0.35, 0.06, 0.08], "sigma_s": 0.04}},
  "shapes": [
    {"type": "rectangle", "corner": [-50, 0, 50], "edge1": [100, 0, 0], "edge2": [0, 0, -100],
     "material": "water", "open": true},
    {"type": "rectangle", "corner": [-50, -3, 50], "edge1": [100, 0, 0], "edge2": [0, 0, -100], "material": "sand"},
    {"type": "sphere", "center": [-1.2, -2.6, -5], "radius": 0.7, "material": "rock"},
    {"type": "sphere", "center": [1.5, -2.8, -7], "radius": 0.9, "material": "rock"},
    {"type": "sphere", "center": [0.3, -2.9, -3], "radius": 0.3, "material": "rock"},
    {"type": "sphere", "center": [0.6, 0, -4], "radius": 0.4, "material": "buoy"})json" + extra + R"json(
  ],
  "lights": [
    {"type": "directional", "direction": [-0.3, -1, -0.5], "angular_radius": 0.27, "color": [1, 0.95, 0.85],
     "irradiance": 3},
    {"type": "environment", "color": [0.45, 0.65, 1], "radiance": 0.5}
  ]
})json";
}

const char* const kUnderwaterCamera =
    R"({"position": [0, -1.6, 1], "look_at": [0, 1, -3], "fov": 55, "resolution": [256, 192]})";
const char* const kAboveWaterCamera =
    R"({"position": [0, 2, 3], "look_at": [0, -1.5, -4], "fov": 50, "resolution": [256, 192]})";
// 2 cm below the water line, inside the clipping box: the box's front face is the "window".
const char* const kSplitCamera =
    R"({"position": [0, -0.02, 0.5], "look_at": [0, -0.02, -4], "fov": 55, "resolution": [256, 256]})";
const char* const kSplitBox =
    R"(,
    {"type": "box", "min": [-1, -1, -0.2], "max": [1, 1, 1], "material": "clip"})";

// Subsurface scattering as a dense medium inside a dielectric: the COLLADA duck (closed, about
// 1.6 m long) as a 1.4 dielectric around a waxy medium (albedo 0.9-0.99, extinction 25 per
// metre: a mean free path of 4 cm), lit from behind by a quad light so thin parts glow. Shadow
// rays pass the duck's surface (priority_shadows), so light reaches the medium by next-event
// estimation, not only by paths that happen to refract out onto the light.
constexpr const char* kSss = R"json({
  "camera": {"position": [0.9, 1.3, 3.4], "look_at": [0.1, 0.85, 0], "fov": 38, "resolution": [256, 192]},
  "render": {"spp": 32, "max_bounces": 64, "max_volume_bounces": 256, "priority_shadows": true},
  "materials": {
    "floor": {"type": "diffuse", "reflectance": 0.5},
    "wax": {"type": "dielectric", "ior": 1.4, "priority": "normal", "interior": "wax"}
  },
  "media": {"wax": {"albedo": [0.99, 0.96, 0.9], "extinction": 25, "phase": {"type": "hg", "g": 0.2}}},
  "shapes": [
    {"type": "rectangle", "corner": [-5, 0.09, -5], "edge1": [0, 0, 10], "edge2": [10, 0, 0], "material": "floor"},
    {"type": "mesh", "file": "/usr/share/assimp/models/Collada/duck.dae", "material": "wax"}
  ],
  "lights": [
    {"type": "quad", "corner": [-0.8, 0.3, -1.6], "edge1": [1.8, 0, 0], "edge2": [0, 1.6, 0.3], "radiance": 12},
    {"type": "environment", "radiance": 0.04}
  ]
})json";

// Image-based lighting in fog: a generated sky (lights/sky_generate.h) with a low sun ahead
// and to the right of the camera, a colonnade whose shadows stretch through haze towards the
// viewer, spheres of stone and glass on the ground. The sky is built in memory at load time,
// so the scene needs no file and runs from any directory.
constexpr const char* kHdriFog = R"json({
  "camera": {"position": [0, 1.6, 8], "look_at": [0, 1.8, -4], "fov": 50, "resolution": [320, 240]},
  "render": {"spp": 64, "max_bounces": 6},
  "materials": {
    "ground": {"type": "diffuse", "reflectance": [0.45, 0.42, 0.38]},
    "stone": {"type": "diffuse", "reflectance": 0.65},
    "rust": {"type": "diffuse", "reflectance": [0.6, 0.3, 0.15]},
    "glass": {"type": "dielectric", "ior": 1.5}
  },
  "media": {"haze": {"sigma_s": 0.03, "sigma_a": 0.003, "phase": {"type": "hg", "g": 0.6}}},
  "volumes": [{"type": "box", "min": [-20, 0, -30], "max": [20, 8, 10], "medium": "haze"}],
  "shapes": [
    {"type": "rectangle", "corner": [-30, 0, -40], "edge1": [0, 0, 52], "edge2": [60, 0, 0], "material": "ground"},
    {"type": "box", "min": [-2.8, 0, -2.3], "max": [-2.2, 4, -1.7], "material": "stone"},
    {"type": "box", "min": [2.2, 0, -2.3], "max": [2.8, 4, -1.7], "material": "stone"},
    {"type": "box", "min": [-2.8, 0, -6.3], "max": [-2.2, 4, -5.7], "material": "stone"},
    {"type": "box", "min": [2.2, 0, -6.3], "max": [2.8, 4, -5.7], "material": "stone"},
    {"type": "box", "min": [-2.8, 0, -10.3], "max": [-2.2, 4, -9.7], "material": "stone"},
    {"type": "box", "min": [2.2, 0, -10.3], "max": [2.8, 4, -9.7], "material": "stone"},
    {"type": "box", "min": [-2.8, 4, -10.3], "max": [2.8, 4.5, -1.7], "material": "stone"},
    {"type": "sphere", "center": [-0.6, 0.9, -4], "radius": 0.9, "material": "rust"},
    {"type": "sphere", "center": [1.1, 0.6, 0.5], "radius": 0.6, "material": "glass"}
  ],
  "lights": [
    {"type": "environment",
     "map": {"generate": {"kind": "sky", "resolution": 512, "sun_elevation": 14, "sun_azimuth": 35, "sun_size": 0.5}}}
  ]
})json";

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
      {"dof",
       "depth of field: the spot-shafts fog seen through a thin lens (aperture radius 0.1 m) focused 6.5 m "
       "away on the occluder in the shaft, with a blurred sphere in front and one behind",
       kDof},
      {"slab",
       "orthographic view straight down through three purely absorbing boxes (sigma_a 1/m) 0.5, 1 and 2 m "
       "thick under a uniform sky of radiance 1: pixels over them are exactly e^-0.5, e^-1, e^-2, others 1",
       kSlab},
      {"holdout",
       "compositing: a fog bank over held-out plate objects (ground, a torus knot poking out of the fog's front, "
       "a sphere half behind it) and one CG sphere, under an invisible sky: alpha is the fog's and the CG "
       "sphere's coverage, the holdouts are holes (black, transparent) that still shadow the fog",
       kHoldout},
      {"neon", "neon signs in fog: three emissive torus-knot tubes (6,144 triangle lights) over a dark floor",
       kNeon},
      {"stage",
       "the Wuson (assimp-testmodels OBJ) on a stage under a narrow, bright spot light in haze, with a dim sky",
       kStage},
      {"many-lamps",
       "a town at night in fog: 1,000 small point and spot lights (street lamps, windows) over streets of boxes "
       "(the light tree's benchmark: --light-sampler)",
       many_lamps_scene()},
      {"overlap", "two overlapping boxes of coloured media, whose coefficients add where they overlap",
       kOverlap},
      {"cloud",
       "a dense, bright cumulus (generated VDB grid) lit from the upper left and behind by a low sun, under a blue "
       "sky: self-shadowing, a darker base and a bright rim; 64+ bounces",
       cloud_scene("12")},
      {"cloud-dense", "the cumulus of `cloud` at 40 per metre (optical depth ~100 through the middle)",
       cloud_scene("40")},
      {"smoke", "a smoke plume (generated VDB grid, albedo 0.8) over a ground under a side sun and a grey sky",
       kSmoke},
      {"fire", "a fireball (generated VDB grid) glowing by blackbody emission from its temperature, in smoke",
       kFire},
      {"mesh-volume", "the COLLADA duck from assimp-testmodels filled with smoke (a closed-mesh volume, even/odd counting)",
       kMeshVolume},
      {"priority-cubes",
       "two overlapping boxes of red and green absorbing media bounded by null surfaces; red has the higher "
       "priority, so the overlap is red (--priority green=very_high makes it green)",
       kPriorityCubes},
      {"glass-of-water",
       "nested dielectrics: a square glass (five merged glass boxes, priority high) of slightly blue-green water "
       "(a box overlapping the walls, priority normal) with a floating ice cube (priority very high)",
       kGlassOfWater},
      {"underwater",
       "a pool seen from below the surface: an open water plane (priority normal, absorbing and scattering) over "
       "a sandy floor, sun and sky",
       pool_scene(kUnderwaterCamera, "")},
      {"underwater-above", "the underwater pool seen from above the surface", pool_scene(kAboveWaterCamera, "")},
      {"underwater-split",
       "the underwater pool seen from the water line: the camera sits in a clipping box (null, priority very "
       "high, vacuum) whose front face shows above and below the water at once",
       pool_scene(kSplitCamera, kSplitBox)},
      {"sss",
       "subsurface scattering: the COLLADA duck as a 1.4 dielectric around a dense waxy medium (albedo ~0.97, "
       "25 per metre), lit from behind",
       kSss},
      {"hdri-fog",
       "image-based lighting in haze: a generated sky with a low sun (an environment map, importance-sampled) "
       "behind a colonnade whose shadows stretch through the haze",
       kHdriFog},
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
