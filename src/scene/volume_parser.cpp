#include "scene/volume_parser.h"

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "grids/generated_volume_grid.h"
#include "grids/grid_io.h"
#include "scene/mesh_loader.h"
#include "scene/shared_readers.h"
#include "scene/transform_parser.h"
#include "volumes/mesh_volume.h"

namespace caligo {
namespace {

// Henyey-Greenstein style asymmetry: |g| = 1 is a delta distribution, which no phase
// function here can represent or sample.
const Range kAsymmetry = Range::open(-1, 1);

PhaseFunction parse_phase(const JsonCursor& c) {
  ObjectReader r(c, "a phase function");
  const std::string type = r.choice("type", {"isotropic", "hg", "schlick", "double_hg"});
  r.set_what("a " + type + " phase function");
  PhaseFunction phase;
  if (type == "isotropic") {
    r.allow({"type"});
  } else if (type == "hg") {
    r.allow({"type", "g"});
    phase = HenyeyGreensteinPhase{r.number("g", kAsymmetry)};
  } else if (type == "schlick") {
    r.allow({"type", "g", "k"});
    const auto [which, value] = r.exactly_one("g", "k");
    const float x = value.number(kAsymmetry);
    phase = which == 0 ? SchlickPhase::from_g(x) : SchlickPhase{x};
  } else {
    r.allow({"type", "g1", "g2", "w"});
    phase = DoubleHenyeyGreensteinPhase{r.number("g1", kAsymmetry), r.number("g2", kAsymmetry),
                                        r.number("w", Range::closed(0, 1))};
  }
  r.finish();
  return phase;
}

// Lattice cells per metre: beyond these the pattern is finer than a float position resolves
// over a scene, or coarser than any scene.
const Range kNoiseScale = Range::closed(1e-6, 1e6);

NoiseModulation parse_noise(const JsonCursor& c) {
  ObjectReader r(c, "a density noise");
  r.allow({"scale", "amplitude", "wind"});
  NoiseModulation n;
  n.scale = r.number_or("scale", n.scale, kNoiseScale);
  n.amplitude = r.number_or("amplitude", n.amplitude, Range::closed(0, 1));
  if (auto w = r.optional_vec3("wind")) n.wind = *w;
  r.finish();
  return n;
}

BlackbodyEmission parse_blackbody(const JsonCursor& c) {
  ObjectReader r(c, "a blackbody emission");
  r.allow({"intensity", "scale", "offset"});
  BlackbodyEmission b;
  b.intensity = r.number_or("intensity", b.intensity, Range::non_negative());
  b.temperature_scale = r.number_or("scale", b.temperature_scale, Range::non_negative());
  b.temperature_offset = r.number_or("offset", b.temperature_offset, Range::closed(-1e6, 1e6));
  r.finish();
  return b;
}

FlameEmission parse_flame(const JsonCursor& c) {
  ObjectReader r(c, "a flame emission");
  r.allow({"color", "intensity"});
  FlameEmission f;
  f.color = r.rgb_or("color", f.color);
  f.intensity = r.number_or("intensity", f.intensity, Range::non_negative());
  r.finish();
  return f;
}

VolumeShader parse_medium(const JsonCursor& c) {
  ObjectReader r(c, "a medium");
  r.allow({"sigma_a", "sigma_s", "albedo", "extinction", "emission", "density", "phase", "falloff", "height_falloff", "noise",
           "step_size", "step_scale", "blackbody", "flame", "color_tint", "holdout"});
  VolumeShader s;
  if (r.has("albedo") || r.has("extinction")) {
    // The artist's form: how much light is lost per metre, and which fraction of it scatters.
    if (r.has("sigma_a") || r.has("sigma_s"))
      r.fail("give either sigma_a/sigma_s or albedo/extinction, not both");
    const RGB albedo = r.rgb("albedo", Range::closed(0, 1));
    const RGB extinction = r.rgb("extinction");
    s.sigma_s = albedo * extinction;
    s.sigma_a = (RGB(1.0f) - albedo) * extinction;
  } else {
    s.sigma_a = r.rgb_or("sigma_a", RGB(0.0f));
    s.sigma_s = r.rgb_or("sigma_s", RGB(0.0f));
  }
  s.emission = r.rgb_or("emission", RGB(0.0f));
  // Holdout extinction sigma_h (grey, 1/m at density 1): the medium hides what is behind it
  // and shows the background plate instead (VolumeShader::holdout).
  s.holdout = r.number_or("holdout", 0.0f, Range::non_negative());
  s.density = r.number_or("density", 1.0f, Range::non_negative());
  if (auto p = r.optional("phase")) s.phase = parse_phase(*p);
  if (auto f = r.optional("falloff")) {
    ObjectReader fr(*f, "a density falloff");
    fr.allow({"exponent"});
    s.field = RadialFalloffDensity{fr.number_or("exponent", 1.0f, Range::positive())};
    fr.finish();
  }
  if (auto h = r.optional("height_falloff")) {
    if (r.has("falloff")) r.fail("give either falloff or height_falloff, not both");
    ObjectReader hr(*h, "a height falloff");
    hr.allow({"base", "scale_height"});
    s.field = HeightFalloffDensity{hr.number_or("base", 0.0f), hr.number("scale_height", Range::positive())};
    hr.finish();
  }
  if (auto n = r.optional("noise")) s.noise = parse_noise(*n);
  s.step_size = r.number_or("step_size", 0.0f, Range::positive());
  s.step_scale = r.number_or("step_scale", 1.0f, Range::closed(1e-3, 1e3));
  if (auto b = r.optional("blackbody")) s.blackbody = parse_blackbody(*b);
  if (auto f = r.optional("flame")) s.flame = parse_flame(*f);
  s.tint_with_color_grid = r.boolean_or("color_tint", true);
  r.finish();
  return s;
}

VolumeShape parse_volume_shape(ObjectReader& r, const std::string& type, const Transform& placement) {
  if (type == "sphere") {
    const Vec3 center = r.vec3("center");
    return SphereVolumeShape{Sphere::make(center, r.number("radius", size_range()), placement)};
  }
  const BoxCorners box = read_box_corners(r);
  return BoxVolumeShape{placement, box.min, box.max};
}

// A closed mesh filled with the medium: loaded, placed and checked for closure now, so a
// broken mesh is an error at its place in the scene file.
VolumeShape parse_mesh_volume(ObjectReader& r, const Transform& placement, SceneFiles& files) {
  const JsonCursor file = r.required("file");
  const std::string path = files.resolve(file);
  const bool skip = r.boolean_or("skip_degenerate", false);
  const bool parity = r.has("open_edges") && r.choice("open_edges", {"error", "parity"}) == "parity";
  TriangleMesh mesh =
      load_mesh(path, file.where(), skip ? DegenerateTriangles::kRemove : DegenerateTriangles::kReject);
  transform_mesh(mesh, placement);
  if (parity) {
    if (const std::string problem = MeshVolume::closure_problem(mesh); !problem.empty())
      files.warnings.push_back(r.cursor().where().to_string() + ": the mesh is not closed (" + problem +
                               "); read by parity (\"open_edges\": \"parity\"): a ray through a hole loses its "
                               "last crossing, so the medium near the holes is approximate");
  }
  return MeshVolumeShape{MeshVolume::build(std::move(mesh), r.cursor().where(), !parity)};
}

GridFilter parse_filter(ObjectReader& r) {
  if (!r.has("filter")) return GridFilter::kTrilinear;
  return r.choice("filter", {"trilinear", "nearest"}) == "nearest" ? GridFilter::kNearest : GridFilter::kTrilinear;
}

GridChannels parse_channels(ObjectReader& volume) {
  GridChannels channels;
  const auto c = volume.optional("grids");
  if (!c) return channels;
  ObjectReader r(*c, "the grid names");
  r.allow({"density", "temperature", "flame", "color"});
  if (r.has("density")) channels.density = r.string("density");
  if (r.has("temperature")) channels.temperature = r.string("temperature");
  if (r.has("flame")) channels.flame = r.string("flame");
  if (r.has("color")) channels.color = r.string("color");
  r.finish();
  return channels;
}

std::shared_ptr<const VolumeGrid> parse_generated_grid(const JsonCursor& c) {
  ObjectReader r(c, "a generated grid");
  r.allow({"kind", "resolution", "seed"});
  const std::string kind = r.choice("kind", {"cloud", "smoke", "fire"});
  const int res = int(r.integer_or("resolution", 128, Range::closed(8, 1024)));
  const uint64_t seed = uint64_t(r.integer_or("seed", 1, Range::closed(0, 1e9)));
  r.finish();
  return generated_volume_grid({*parse_generated_volume(kind), res, seed});
}

// A grid volume: the grid from a VDB/NanoVDB file, a raw dense array or the generator, placed
// by the transform; its shape is the box of its bounds.
GridDensity parse_grid_field(ObjectReader& r, const std::string& type, const Transform& placement,
                             SceneFiles& files) {
  GridDensity field{nullptr, placement, parse_filter(r)};
  if (type == "vdb") {
    const auto [which, c] = r.exactly_one("file", "generate");
    if (which == 1) {
      field.grid = parse_generated_grid(c);
    } else {
      const std::string path = files.resolve(c);
      field.grid = load_grid_file(path, parse_channels(r), c.where());
    }
    return field;
  }
  const auto [from_values, source] = r.exactly_one("file", "values");
  const JsonCursor dims = r.required("dimensions");
  const auto elements = dims.elements("an array of three voxel counts");
  if (elements.size() != 3) dims.fail("expected an array of three voxel counts, got " + dims.describe());
  DenseGridLayout layout;
  for (int a = 0; a < 3; ++a) {
    const JsonCursor& n = elements[size_t(a)];
    const float count = n.number(Range::closed(1, 1 << 16));
    if (count != std::floor(count)) n.fail("expected a whole number of voxels, got " + n.describe());
    layout.dims[size_t(a)] = int(count);
  }
  layout.voxel_size = r.number("voxel_size", size_range());
  layout.origin = r.optional_vec3("origin").value_or(Vec3(0.0f));
  if (!from_values) {
    field.grid = load_dense_grid(files.resolve(source), layout, source.where());
    return field;
  }
  const uint64_t voxels = uint64_t(layout.dims[0]) * uint64_t(layout.dims[1]) * uint64_t(layout.dims[2]);
  const std::vector<JsonCursor> elements_in = source.elements("an array of voxel values, x fastest");
  if (elements_in.size() != voxels)
    source.fail("expected " + std::to_string(voxels) + " values (the dimensions' product), got " +
                std::to_string(elements_in.size()));
  std::vector<float> values;
  values.reserve(voxels);
  for (const JsonCursor& v : elements_in) values.push_back(v.number(Range::non_negative()));
  field.grid = dense_values_grid(values, layout, source.where());
  return field;
}

// A medium's emission and tint must find the channels they read in the grid.
void check_channels(const ObjectReader& r, const VolumeShader& shader) {
  const auto* grid = std::get_if<GridDensity>(&shader.field);
  if (!grid) {
    if (shader.blackbody || shader.flame)
      r.fail("the medium's blackbody or flame emission needs a grid volume (type vdb or dense)");
    return;
  }
  if (shader.blackbody && !grid->grid->has_temperature())
    r.fail("the medium has blackbody emission but the grid has no temperature channel");
  if (shader.flame && !grid->grid->has_flame())
    r.fail("the medium has flame emission but the grid has no flame channel");
}

}  // namespace

int find_medium(const JsonCursor& c, const std::vector<NamedMedium>& media) {
  std::vector<std::string> names;
  for (const NamedMedium& m : media) names.push_back(m.name);
  return int(find_definition(c, names, "medium", "media"));
}

std::vector<NamedMedium> parse_media(const JsonCursor& c) {
  std::vector<NamedMedium> media;
  for (const auto& [name, m] : named_definitions(c, "medium", "media"))
    media.push_back({name, parse_medium(m)});
  return media;
}

VolumePrimitive parse_volume(const JsonCursor& c, const std::vector<NamedMedium>& media, SceneFiles& files) {
  ObjectReader r(c, "a volume");
  const std::string type = r.choice("type", {"sphere", "box", "mesh", "vdb", "dense"});
  r.set_what("a " + type + " volume");
  if (type == "sphere")
    r.allow({"type", "center", "radius", "medium", "transform"});
  else if (type == "box")
    r.allow({"type", "min", "max", "medium", "transform"});
  else if (type == "mesh")
    r.allow({"type", "file", "skip_degenerate", "open_edges", "medium", "transform"});
  else if (type == "vdb")
    r.allow({"type", "file", "generate", "grids", "filter", "clip", "medium", "transform"});
  else
    r.allow({"type", "file", "values", "dimensions", "voxel_size", "origin", "clip", "filter", "medium", "transform"});
  Transform placement;
  if (auto t = r.optional("transform")) placement = parse_transform(*t);
  VolumePrimitive v;
  v.medium = find_medium(r.required("medium"), media);
  const VolumeShader& medium = media[size_t(v.medium)].shader;
  v.shader = medium;
  if (type == "mesh") {
    v.shape = parse_mesh_volume(r, placement, files);
  } else if (type == "vdb" || type == "dense") {
    if (!std::holds_alternative<ConstantDensity>(medium.field))
      r.fail("a grid volume takes its density from the grid: its medium may not have a falloff");
    GridDensity field = parse_grid_field(r, type, placement, files);
    Bounds3 b = field.grid->world_bounds();
    // "clip": {"min", "max"} (in the grid's own space): the medium ends at the box,
    // as pbrt-v4's grid media end at their bounds (trilinear lookups beyond the outer voxel
    // centres would otherwise fade out over half a voxel outside).
    if (const auto clip = r.optional("clip")) {
      ObjectReader cr(*clip, "the clip box");
      cr.allow({"min", "max"});
      const BoxCorners box = read_box_corners(cr);
      cr.finish();
      b = Bounds3{max(b.lo, box.min), min(b.hi, box.max)};
      if (!(b.lo.x < b.hi.x && b.lo.y < b.hi.y && b.lo.z < b.hi.z)) clip->fail("the clip box misses the grid");
    }
    v.shape = BoxVolumeShape{placement, b.lo, b.hi};
    v.shader.field = std::move(field);
  } else {
    v.shape = parse_volume_shape(r, type, placement);
  }
  check_channels(r, v.shader);
  r.finish();
  return v;
}

}  // namespace caligo
