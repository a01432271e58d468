// Running Wyman & Ramsey's Table 1 (wyman_table.h): the references, the variants' runs per
// scale, the step errors and the previews strip.
#include "experiments/wyman_table.h"

#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <memory>
#include <utility>
#include <variant>

#include "core/error.h"
#include "core/median.h"
#include "geometry/mesh_generate.h"
#include "image/tonemap.h"
#include "realtime/pipeline.h"
#include "render/render.h"
#include "scene/builtins.h"
#include "scene/scene.h"

namespace caligo {

namespace {

// The textured spotlight runs with the exact gobo (blur level 0, no per-interval blur): the path
// tracer computes single scattering through the sharp texture, and the blur is the paper's
// stand-in for multiple scattering, an approximation the error column would otherwise mostly
// measure.
TexturedSpotSettings bench_spot_settings(const WymanVariant& v) {
  TexturedSpotSettings s;
  s.blur_level = 0;
  s.blur_per_interval = false;
  if (v.spot_steps > 0) {
    s.min_steps = s.max_steps = v.spot_steps;
    s.lit_rate = 1.0f;
  }
  return s;
}

// Triangles of the generated occluders (from the generator's own sizing rule, without building
// them); mesh files count as unknown (0).
uint64_t generated_triangles(const SceneDesc& desc) {
  uint64_t total = 0;
  for (const ShapeDesc& shape : desc.shapes)
    if (const auto* g = std::get_if<GeneratedMeshShape>(&shape.geometry)) {
      if (g->kind == GeneratedMeshShape::Kind::kSphere) {
        total += 20ull << (2 * icosphere_subdivisions_for(g->triangles));
      } else {
        const TorusKnot k = torus_knot_for(g->triangles);
        total += 2ull * uint64_t(k.segments) * uint64_t(k.sides);
      }
    }
  return total;
}

SceneDesc black_surfaces(SceneDesc desc) {
  for (Material& m : desc.materials) {
    if (!m.emission.is_black())
      throw InputError(SourceLocation{desc.file, ""},
                       "bench-table: emissive materials would add light the volumetric methods do not model");
    m.bsdf = BlackBsdf{};
  }
  return desc;
}

Image rgb_average(const Image& a, const Image& b) {
  const auto ca = *a.rgb_indices(), cb = *b.rgb_indices();
  Image out(a.width(), a.height(), {"R", "G", "B"});
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x)
      for (int k = 0; k < 3; ++k)
        out.at(x, y, k) = 0.5f * (a.at(x, y, ca[size_t(k)]) + b.at(x, y, cb[size_t(k)]));
  return out;
}

struct Reference {
  Image image;
  double noise = 0;  // relative RMSE of `image` against the converged one, estimated
  int spp = 0;       // two equal halves: the requested spp rounded down to even, at least 2
};

Reference render_reference(const Scene& scene, int resolution, int spp) {
  RenderSettings rs = render_settings(scene.desc());
  rs.resolution = {resolution, resolution};
  rs.spp = std::max(1, spp / 2);
  rs.path.limits.max_bounces = 1;
  rs.path.limits.max_volume_bounces = 1;
  rs.seed = 1;
  const Image a = render(scene, rs, Progress::Style::kQuiet).image;
  rs.seed = 2;
  const Image b = render(scene, rs, Progress::Style::kQuiet).image;
  return {rgb_average(a, b), reference_error(a, b).relative_rmse / 2.0, 2 * rs.spp};
}

// One variant's frames on `pipeline`; `image` receives the last frame.
WymanRun run_variant(RealtimePipeline& pipeline, const WymanVariant& v, int frames, const Image& reference,
                     Image& image) {
  const int warmup = v.converged ? 0 : wyman::kWarmup;
  if (v.converged) frames = 1;
  HybridScatterer* scatterer = nullptr;
  if (v.method == VolumetricMethod::kMarch) {
    pipeline.set_scatterer(nullptr);
  } else {
    HybridSettings hs;
    hs.brute_samples = v.brute_samples;
    auto owned = std::make_unique<HybridScatterer>(pipeline.scene(), v.method, hs, bench_spot_settings(v));
    scatterer = owned.get();
    pipeline.set_scatterer(std::move(owned));
  }
  std::vector<double> total, volumetric;
  const RealtimeFrame* frame = nullptr;
  for (int i = 0; i < warmup + frames; ++i) {
    frame = &pipeline.render(0.0f, uint32_t(i));
    if (i >= warmup) {
      total.push_back(frame->times.total);
      volumetric.push_back(frame->times.volumetric());
    }
  }
  WymanRun run;
  run.ran = true;
  run.frame_us = median(total);
  run.volumetric_us = median(volumetric);
  image = to_image(frame->color);
  run.error = reference_error(image, reference);
  // Light 0: the Wyman scenes have one point light (other scenes: the first light decides the label).
  run.used = volumetric_method_name(scatterer ? scatterer->used(0) : VolumetricMethod::kMarch);
  return run;
}

// Previews side by side: one row per scale, methods then the reference.
Rgb8Image compose_strip(const std::vector<std::vector<const Image*>>& rows, float exposure) {
  const int w = rows[0][0]->width(), h = rows[0][0]->height(), gap = 4;
  size_t columns = 0;
  for (const auto& row : rows) columns = std::max(columns, row.size());
  Rgb8Image strip;
  strip.width = int(columns) * w + int(columns - 1) * gap;
  strip.height = int(rows.size()) * h + int(rows.size() - 1) * gap;
  strip.rgb.assign(size_t(strip.width) * size_t(strip.height) * 3, 255);
  for (size_t r = 0; r < rows.size(); ++r)
    for (size_t c = 0; c < rows[r].size(); ++c) {
      const std::vector<uint8_t> p = to_srgb8_preview(*rows[r][c], PreviewSettings{exposure, true});
      for (int y = 0; y < h; ++y) {
        const size_t dst =
            ((r * size_t(h + gap) + size_t(y)) * size_t(strip.width) + c * size_t(w + gap)) * 3;
        std::copy_n(p.begin() + ptrdiff_t(size_t(y) * size_t(w) * 3), size_t(w) * 3,
                    strip.rgb.begin() + ptrdiff_t(dst));
      }
    }
  return strip;
}

// One scene's references (the point light's and, with a twin, the spot's) and what runs on it.
struct SceneWork {
  const WymanTableSettings& settings;
  const std::vector<WymanVariant>& variants;
  const WymanScene& scene;
  const WymanTableHooks& hooks;
  // Built once (surfaces black, still): the reference and every scale's pipeline share them.
  std::shared_ptr<const Scene> built, spot_built;
  Reference reference, spot_reference;

  // One printf-formatted line to hooks.progress.
  void progress(const char* format, ...) const __attribute__((format(printf, 2, 3)));
};

void SceneWork::progress(const char* format, ...) const {
  if (!hooks.progress) return;
  va_list args, again;
  va_start(args, format);
  va_copy(again, args);
  const int n = std::vsnprintf(nullptr, 0, format, args);  // scene paths have no length limit
  va_end(args);
  std::string line(size_t(std::max(n, 0)) + 1, '\0');
  std::vsnprintf(line.data(), line.size(), format, again);
  va_end(again);
  line.pop_back();
  hooks.progress(line);
}

std::unique_ptr<RealtimePipeline> make_pipeline(const std::shared_ptr<const Scene>& scene, int resolution, int scale) {
  RealtimeSettings s = realtime_settings(scene->desc());
  s.resolution = {resolution, resolution};
  s.scale = scale;
  s.temporal = false;
  return std::make_unique<RealtimePipeline>(scene, s);
}

// Every variant at one accumulation scale; `images` receives each run's last frame.
std::vector<WymanRun> run_scale(const SceneWork& work, int scale, std::vector<Image>& images) {
  const WymanScene& scene = work.scene;
  const std::vector<WymanVariant>& vs = work.variants;
  const auto pipeline = make_pipeline(work.built, work.settings.resolution, scale);
  const auto spot_pipeline = work.spot_built ? make_pipeline(work.spot_built, work.settings.resolution, scale) : nullptr;
  std::vector<WymanRun> runs;
  images.assign(vs.size(), Image());
  for (size_t vi = 0; vi < vs.size(); ++vi) {
    const WymanVariant& v = vs[vi];
    if (v.spot && !spot_pipeline) {
      runs.emplace_back();
      continue;
    }
    const Reference& ref = v.spot ? work.spot_reference : work.reference;
    runs.push_back(
        run_variant(v.spot ? *spot_pipeline : *pipeline, v, work.settings.frames, ref.image, images[vi]));
    runs.back().reference_noise = ref.noise;
    work.progress("%s scale %d %-13s %8.2f ms, rRMSE %.2f %%", scene.name.c_str(), scale, v.label.c_str(),
                  runs.back().frame_us / 1000.0, runs.back().error.relative_rmse * 100.0);
  }
  // Step errors against the converged run of the same scene (point: brute, spot: textured).
  for (size_t vi = 0; vi < vs.size(); ++vi) {
    if (!runs[vi].ran) continue;
    for (size_t ci = 0; ci < vs.size(); ++ci)
      if (vs[ci].converged && vs[ci].spot == vs[vi].spot)
        runs[vi].step_error = reference_error(images[vi], images[ci]).relative_rmse;
  }
  return runs;
}

// The strip's rows: per scale, the main table's runs, the reference and the spot reference.
Rgb8Image scene_strip(const SceneWork& work, const WymanSceneResult& r,
                      const std::vector<std::vector<Image>>& images) {
  std::vector<std::vector<const Image*>> rows;
  for (size_t si = 0; si < r.runs.size(); ++si) {
    std::vector<const Image*> row;
    for (size_t vi = 0; vi < work.variants.size(); ++vi)
      if (work.variants[vi].in_main_table && r.runs[si][vi].ran) row.push_back(&images[si][vi]);
    row.push_back(&work.reference.image);
    if (work.scene.spot) row.push_back(&work.spot_reference.image);
    rows.push_back(row);
  }
  return compose_strip(rows, work.settings.exposure);
}

WymanSceneResult run_scene(SceneWork& work) {
  const WymanTableSettings& o = work.settings;
  const WymanScene& scene = work.scene;
  WymanSceneResult r;
  r.name = scene.name;
  r.triangles = generated_triangles(scene.desc);
  work.progress("%s: reference %dx%d at %d spp...", scene.name.c_str(), o.resolution, o.resolution,
                o.reference_spp);
  work.built = Scene::build(scene.desc.at_time(0.0f));
  work.reference = render_reference(*work.built, o.resolution, o.reference_spp);
  r.reference_noise = work.reference.noise;
  r.reference_spp = work.reference.spp;
  // The textured column runs on the scene's spot-light twin, with its own reference.
  if (scene.spot) {
    work.progress("%s-spot: reference...", scene.name.c_str());
    work.spot_built = Scene::build(scene.spot->at_time(0.0f));
    work.spot_reference = render_reference(*work.spot_built, o.resolution, o.reference_spp);
  }
  // Only the images of the strip are needed; they go with this scene.
  std::vector<std::vector<Image>> images(o.scales.size());
  for (size_t si = 0; si < o.scales.size(); ++si) r.runs.push_back(run_scale(work, o.scales[si], images[si]));
  if (work.hooks.preview) work.hooks.preview(scene.name, scene_strip(work, r, images));
  return r;
}

}  // namespace

std::vector<WymanVariant> wyman_variants() {
  using wyman::kConvergedSteps;
  std::vector<WymanVariant> v = {{"none", VolumetricMethod::kNone},
                                 {"brute 150", VolumetricMethod::kBrute, 150},
                                 {"hybrid 50", VolumetricMethod::kHybrid},
                                 {"textured ≤150", VolumetricMethod::kTextured, 150, true, false, true},
                                 {"march", VolumetricMethod::kMarch}};
  for (int n : wyman::kBruteSweep)
    if (n != 150) v.push_back({"brute " + std::to_string(n), VolumetricMethod::kBrute, n, false});
  v.push_back({"textured " + std::to_string(kConvergedSteps), VolumetricMethod::kTextured, 150, false, true,
               true, kConvergedSteps});
  v.push_back(
      {"brute " + std::to_string(kConvergedSteps), VolumetricMethod::kBrute, kConvergedSteps, false, true});
  return v;
}

std::vector<WymanScene> load_wyman_scenes(const WymanTableSettings& settings, const SceneLoader& load) {
  std::vector<WymanScene> scenes;
  for (const std::string& name : settings.scenes) scenes.push_back({name, black_surfaces(load(name)), {}});
  for (WymanScene& s : scenes)
    if (find_builtin(s.name + "-spot")) s.spot = black_surfaces(load(s.name + "-spot"));
  return scenes;
}

WymanTableResults run_wyman_table(const WymanTableSettings& settings, const std::vector<WymanScene>& scenes,
                                  const WymanTableHooks& hooks) {
  WymanTableResults results{settings, wyman_variants(), {}};
  for (const WymanScene& scene : scenes) {
    SceneWork work{settings, results.variants, scene, hooks, {}, {}};
    results.scenes.push_back(run_scene(work));
  }
  return results;
}

}  // namespace caligo
