// caligo bench-table wyman [--res N] [--scales 1,4] [--frames F] [--reference-spp S] [--scenes a,b] [-o DIR]
// Wyman & Ramsey's Table 1 (2008) on our built-in scenes: frames per second of the volumetric
// methods (none, brute 150, hybrid 50, textured spotlight up to 150, and the march for
// reference) with scattering at each accumulation scale, each frame's relative RMSE against the
// path tracer's single-scattering reference, and the hybrid's speed-up over brute force at
// equal error. The textured column runs on the scene's spot-light twin (built-in NAME-spot,
// same occluders, a spot with a stained-glass gobo at the point light's place) against that
// scene's own reference; scenes without a twin show "–" there.
//
// What is measured. The scene's surfaces are made black (BlackBsdf) for the whole benchmark, so
// that both the real-time frame and the reference hold in-scattered light only: the error is
// the volumetric method's, not the simple surface shading's. Temporal reprojection is off
// (each frame stands alone, as in the paper, and one pipeline per scale can switch methods
// without a history from another method); the gather and upsampling stay on. Times are the
// median of the whole frame (PassTimes::total) over the timed frames after kWarmup frames.
//
// The reference is rendered once per scene as two halves of S/2 spp with different seeds and
// averaged. Their relative RMSE against each other is sqrt(2) x one half's noise, and the
// average's noise is one half's / sqrt(2): the reference's own noise is about rRMSE(A, B) / 2.
// It adds in quadrature to every method's error alike; the table reports it and the raw errors.
//
// Equal error: against the path tracer, every method carries the same errors of the real-time
// pipeline (shadow-map resolution, low-resolution scattering, upsampling) and the reference's
// noise, which at affordable spp hide the step error that separates brute force from the
// hybrid. Both methods integrate lit stretches in closed form and differ only in where they read
// visibility, so their error is measured against brute force with kConvergedSteps steps in the
// same pipeline (the "step error"). Brute force runs again with 25 to 600 steps (kBruteSweep);
// the match is the FEWEST steps whose step error is at most (1 + kMatchTolerance) x the
// hybrid's, and the speed-up is that brute run's frame time over the hybrid's. When no count
// matches, the speed-up against the most steps is a lower bound and is shown as ">=".
#include <CLI/CLI.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "commands.h"
#include "core/atomic_file.h"
#include "geometry/mesh_generate.h"
#include "hybrid/hybrid_pipeline.h"
#include "image/png_io.h"
#include "image/tonemap.h"
#include "realtime/pipeline.h"
#include "realtime/reference_compare.h"
#include "render/render.h"
#include "scene/builtins.h"
#include "scene/scene.h"

namespace caligo {

void add_bench_table_command(CLI::App& app, BenchTableOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "bench-table",
      "Reproduce a paper's table on the built-in scenes (wyman: Wyman & Ramsey 2008, Table 1)");
  cmd->add_option("table", o.table, "Which table: wyman");
  cmd->add_option("--res", o.resolution, "Square output resolution N (NxN)");
  cmd->add_option("--scales", o.scales, "Accumulation scales, comma separated (1: full resolution, 4: 1/4)");
  cmd->add_option("--frames", o.frames, "Timed frames per method after the warm-up");
  cmd->add_option("--reference-spp", o.reference_spp, "Samples per pixel of the path-traced reference");
  cmd->add_option("--scenes", o.scenes, "Scenes, comma separated (default: the four wyman-* built-ins)");
  cmd->add_option("-o,--output", o.output, "A folder for table.md and one PNG per scene");
  cmd->add_option("--exposure", o.exposure, "Exposure of the PNGs, in stops");
}

namespace {

constexpr int kWarmup = 2;
constexpr double kMatchTolerance = 0.10;  // relative: brute matches at step error <= 1.1 x hybrid's
constexpr int kBruteSweep[] = {25, 50, 100, 150, 300, 600};  // ascending; 150 is the table's
constexpr int kConvergedSteps = 2000;

struct Variant {
  std::string label;
  VolumetricMethod method;
  int brute_samples = 150;
  bool in_main_table = true;
  bool converged = false;  // the step-error yardstick of its scene: one untimed frame
  bool spot = false;       // runs on the scene's textured-spotlight twin (NAME-spot)
  int spot_steps = 0;      // textured: min = max steps (0: the pass's own 16..150 rule)
};

// The textured spotlight runs with the exact gobo (blur level 0): the path tracer computes
// single scattering through the sharp texture, and the blur is the paper's stand-in for
// multiple scattering, an approximation the error column would otherwise mostly measure.
TexturedSpotSettings bench_spot_settings(const Variant& v) {
  TexturedSpotSettings s;
  s.blur_level = 0;
  if (v.spot_steps > 0) {
    s.min_steps = s.max_steps = v.spot_steps;
    s.lit_rate = 1.0f;
  }
  return s;
}

std::vector<Variant> variants() {
  std::vector<Variant> v = {{"none", VolumetricMethod::kNone},
                            {"brute 150", VolumetricMethod::kBrute, 150},
                            {"hybrid 50", VolumetricMethod::kHybrid},
                            {"textured ≤150", VolumetricMethod::kTextured, 150, true, false, true},
                            {"march", VolumetricMethod::kMarch}};
  for (int n : kBruteSweep)
    if (n != 150) v.push_back({"brute " + std::to_string(n), VolumetricMethod::kBrute, n, false});
  v.push_back({"textured " + std::to_string(kConvergedSteps), VolumetricMethod::kTextured, 150, false, true, true,
               kConvergedSteps});
  v.push_back(
      {"brute " + std::to_string(kConvergedSteps), VolumetricMethod::kBrute, kConvergedSteps, false, true});
  return v;
}

struct Run {
  bool ran = false;  // false: a spot variant on a scene without a textured-spotlight twin
  double frame_us = 0, volumetric_us = 0;
  double reference_noise = 0;  // of the reference the error is measured against
  ReferenceError error;   // against the path tracer
  double step_error = 0;  // relative RMSE against brute kConvergedSteps of the same pipeline
  std::string used;       // the method the light actually took (hybrid may fall back to brute)
  Image image;
};

std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> parts;
  size_t start = 0;
  while (true) {
    const size_t comma = text.find(',', start);
    parts.push_back(text.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (comma == std::string::npos) return parts;
    start = comma + 1;
  }
}

std::vector<int> parse_ints(const std::string& text, const char* option, int lo, int hi) {
  std::vector<int> values;
  for (const std::string& part : split(text)) {
    int v = 0;
    const auto [end, ec] = std::from_chars(part.data(), part.data() + part.size(), v);
    if (part.empty() || ec != std::errc() || end != part.data() + part.size() || v < lo || v > hi)
      throw InputError(kCommandLine, std::string(option) + ": expected comma-separated integers " +
                                         std::to_string(lo) + " to " + std::to_string(hi) + ", got \"" +
                                         text + "\"");
    values.push_back(v);
  }
  return values;
}

void check_range(int v, int lo, int hi, const char* option) {
  if (v < lo || v > hi)
    throw InputError(kCommandLine, std::string(option) + ": expected " + std::to_string(lo) + " to " +
                                       std::to_string(hi) + ", got " + std::to_string(v));
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

std::string with_commas(uint64_t n) {
  std::string s = std::to_string(n);
  for (int i = int(s.size()) - 3; i > 0; i -= 3) s.insert(size_t(i), ",");
  return s;
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

Reference render_reference(const SceneDesc& still, int resolution, int spp) {
  RenderSettings rs = render_settings(still);
  rs.resolution = {resolution, resolution};
  rs.spp = std::max(1, spp / 2);
  rs.path.limits.max_bounces = 1;
  rs.path.limits.max_volume_bounces = 1;
  const auto scene = Scene::build(still);
  rs.seed = 1;
  const Image a = render(*scene, rs, Progress::Style::kQuiet).image;
  rs.seed = 2;
  const Image b = render(*scene, rs, Progress::Style::kQuiet).image;
  return {rgb_average(a, b), reference_error(a, b).relative_rmse / 2.0, 2 * rs.spp};
}

Run run_variant(RealtimePipeline& pipeline, const Variant& v, int frames, const Image& reference) {
  const int warmup = v.converged ? 0 : kWarmup;
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
  Run run;
  run.ran = true;
  run.frame_us = median(total);
  run.volumetric_us = median(volumetric);
  run.image = to_image(frame->color);
  run.error = reference_error(run.image, reference);
  // Light 0: the Wyman scenes have one point light (other scenes: the first light decides the label).
  run.used = volumetric_method_name(scatterer ? scatterer->used(0) : VolumetricMethod::kMarch);
  return run;
}

// Previews side by side: one row per scale, methods then the reference.
void write_strip(const std::string& path, const std::vector<std::vector<const Image*>>& rows,
                 float exposure) {
  const int w = rows[0][0]->width(), h = rows[0][0]->height(), gap = 4;
  size_t columns = 0;
  for (const auto& row : rows) columns = std::max(columns, row.size());
  const int width = int(columns) * w + int(columns - 1) * gap;
  const int height = int(rows.size()) * h + int(rows.size() - 1) * gap;
  std::vector<uint8_t> rgb(size_t(width) * size_t(height) * 3, 255);
  for (size_t r = 0; r < rows.size(); ++r)
    for (size_t c = 0; c < rows[r].size(); ++c) {
      const std::vector<uint8_t> p = to_srgb8_preview(*rows[r][c], PreviewSettings{exposure, true});
      for (int y = 0; y < h; ++y) {
        const size_t dst = ((r * size_t(h + gap) + size_t(y)) * size_t(width) + c * size_t(w + gap)) * 3;
        std::copy_n(p.begin() + ptrdiff_t(size_t(y) * size_t(w) * 3), size_t(w) * 3,
                    rgb.begin() + ptrdiff_t(dst));
      }
    }
  write_png(path, width, height, rgb);
}

std::string fmt(const char* format, double value) {
  char s[64];
  std::snprintf(s, sizeof s, format, value);
  return s;
}

struct SceneResult {
  std::string name;
  uint64_t triangles = 0;
  double reference_noise = 0;
  int reference_spp = 0;
  std::vector<std::vector<Run>> runs;  // [scale][variant]
};

// " text |": one markdown cell (appending piecewise: GCC 12 warns falsely on chains of operator+).
std::string cell(const std::string& text) {
  std::string c = " ";
  c += text;
  c += " |";
  return c;
}

std::string percent(double fraction) { return fmt("%.2f %%", fraction * 100.0); }
std::string percent3(double fraction) { return fmt("%.3f %%", fraction * 100.0); }

// Index of the variant; vs.size() when none.
size_t find_variant(const std::vector<Variant>& vs, VolumetricMethod method, int brute_samples = 150) {
  for (size_t i = 0; i < vs.size(); ++i)
    if (vs[i].method == method &&
        (method != VolumetricMethod::kBrute || vs[i].brute_samples == brute_samples))
      return i;
  return vs.size();
}

// What the report's tables read, and the markdown they are written to.
struct Report {
  const BenchTableOptions& o;
  const std::vector<int>& scales;
  const std::vector<Variant>& vs;
  const std::vector<SceneResult>& results;
  std::string md;

  void line(const std::string& s) {
    md += s;
    md += '\n';
  }
  std::string low(int scale) const {
    std::string s = std::to_string((o.resolution + scale - 1) / scale);
    s += "²";
    return s;
  }
};

// Table 1 itself: frames per second of each main-table variant at each accumulation scale.
void fps_table(Report& rep) {
  const BenchTableOptions& o = rep.o;
  rep.line("Wyman & Ramsey 2008, Table 1, on Caligo's scenes: output " + std::to_string(o.resolution) +
           "², frames per second (median frame time of " + std::to_string(o.frames) + " frames after " +
           std::to_string(kWarmup) + " warm-up; temporal off, surfaces black).");
  rep.line("");
  std::string head = "| scene | triangles |", rule = "|---|---:|";
  for (int s : rep.scales)
    for (const Variant& v : rep.vs)
      if (v.in_main_table) {
        head += cell(v.label + " @" + rep.low(s));
        rule += "---:|";
      }
  rep.line(head);
  rep.line(rule);
  for (const SceneResult& r : rep.results) {
    std::string row = "|" + cell(r.name) + cell(r.triangles ? with_commas(r.triangles) : "?");
    for (size_t si = 0; si < rep.scales.size(); ++si)
      for (size_t vi = 0; vi < rep.vs.size(); ++vi)
        if (rep.vs[vi].in_main_table)
          row += cell(r.runs[si][vi].ran ? fmt("%.1f", 1e6 / r.runs[si][vi].frame_us) : "–");
    rep.line(row);
  }
}

// One error per run and variant; `corrected`: also the error with the reference's noise taken
// out in quadrature, in parentheses.
template <typename Get, typename Format>
void error_table(Report& rep, const std::string& title, Get get, Format format, bool corrected) {
  rep.line("");
  rep.line(title);
  rep.line("");
  std::string h = corrected ? "| scene | scattering | ref. noise |" : "| scene | scattering |";
  std::string ru = corrected ? "|---|---|---:|" : "|---|---|";
  for (const Variant& v : rep.vs) {
    h += cell(v.label);
    ru += "---:|";
  }
  rep.line(h);
  rep.line(ru);
  for (const SceneResult& r : rep.results)
    for (size_t si = 0; si < rep.scales.size(); ++si) {
      std::string row = "|" + cell(r.name) + cell(rep.low(rep.scales[si]));
      if (corrected) row += cell(percent(r.reference_noise));
      for (size_t vi = 0; vi < rep.vs.size(); ++vi) {
        const Run& run = r.runs[si][vi];
        if (!run.ran) {
          row += cell("–");
          continue;
        }
        const double noise = run.reference_noise;
        std::string c = format(get(run));
        if (corrected) {
          c += " (" + format(std::sqrt(std::max(0.0, get(run) * get(run) - noise * noise))) + ")";
          if (rep.vs[vi].spot) c += " [spot ref. noise " + percent(noise) + "]";
        }
        // A hybrid that fell back to brute (open occluder) must not pass for the hybrid.
        if (run.used != volumetric_method_name(rep.vs[vi].method)) c += " (ran " + run.used + ")";
        row += cell(c);
      }
      rep.line(row);
    }
}

// The speed-up of hybrid 50 over brute force at equal step error.
void speedup_table(Report& rep) {
  const std::vector<Variant>& vs = rep.vs;
  rep.line("");
  std::string sweep;
  for (int n : kBruteSweep) sweep += (sweep.empty() ? "" : ", ") + std::to_string(n);
  const int most = kBruteSweep[std::size(kBruteSweep) - 1];
  rep.line("Speed-up of hybrid 50 over brute force at equal step error: the fewest brute steps (of " + sweep +
           ") whose step error is at most " + fmt("%.0f", 100.0 + kMatchTolerance * 100) +
           " % of the hybrid's; ratio of median frame times (and of the volumetric passes alone). \">=\": no "
           "count "
           "matched, a lower bound against " +
           std::to_string(most) + " steps.");
  rep.line("");
  rep.line(
      "| scene | scattering | hybrid step error | brute steps | brute step error | brute fps | hybrid fps | "
      "speed-up (frame) | speed-up (volumetric) |");
  rep.line("|---|---|---:|---:|---:|---:|---:|---:|---:|");
  const size_t hybrid = find_variant(vs, VolumetricMethod::kHybrid);
  const size_t most_steps = find_variant(vs, VolumetricMethod::kBrute, most);
  for (const SceneResult& r : rep.results)
    for (size_t si = 0; si < rep.scales.size(); ++si) {
      const auto& runs = r.runs[si];
      const double target = runs[hybrid].step_error * (1.0 + kMatchTolerance);
      size_t match = vs.size();
      for (int n : kBruteSweep) {
        const size_t vi = find_variant(vs, VolumetricMethod::kBrute, n);
        if (match == vs.size() && runs[vi].step_error <= target) match = vi;
      }
      const bool found = match != vs.size();
      const size_t b = found ? match : most_steps;
      const std::string bound = found ? "" : ">= ";
      rep.line("|" + cell(r.name) + cell(rep.low(rep.scales[si])) + cell(percent3(runs[hybrid].step_error)) +
               cell(found ? std::to_string(vs[b].brute_samples) : "> " + std::to_string(most)) +
               cell(percent3(runs[b].step_error)) + cell(fmt("%.1f", 1e6 / runs[b].frame_us)) +
               cell(fmt("%.1f", 1e6 / runs[hybrid].frame_us)) +
               cell(bound + fmt("%.2fx", runs[b].frame_us / runs[hybrid].frame_us)) +
               cell(bound + fmt("%.2fx", runs[b].volumetric_us / runs[hybrid].volumetric_us)));
    }
}

std::string markdown(const BenchTableOptions& o, const std::vector<int>& scales,
                     const std::vector<Variant>& vs, const std::vector<SceneResult>& results) {
  Report rep{o, scales, vs, results, {}};
  fps_table(rep);
  error_table(
      rep,
      "Relative RMSE against the path-traced single-scattering reference (" +
          std::to_string(results.empty() ? 0 : results[0].reference_spp) +
          " spp, two halves of different seeds; ref. noise: the average's own, half the halves' difference; "
          "in parentheses: the error with that noise "
          "removed in quadrature, sqrt(e² - noise²)):",
      [](const Run& r) { return r.error.relative_rmse; }, percent, true);
  error_table(
      rep,
      "Step error: relative RMSE against the same pipeline (same shadow map, gather and upsampling; no "
      "reference noise) with " +
          std::to_string(kConvergedSteps) +
          " steps: brute force for the point-light columns, the textured pass for the spot:",
      [](const Run& r) { return r.step_error; }, percent3, false);
  speedup_table(rep);
  return rep.md;
}
}  // namespace

int run_bench_table(const BenchTableOptions& o) {
  if (o.table != "wyman")
    throw InputError(kCommandLine, "bench-table: expected a table name: wyman, got \"" + o.table + "\"");
  check_range(o.resolution, 8, 8192, "--res");
  check_range(o.frames, 1, 10000, "--frames");
  check_range(o.reference_spp, 1, 1'000'000, "--reference-spp");
  if (!std::isfinite(o.exposure)) throw InputError(kCommandLine, "--exposure: expected a finite number");
  const std::vector<int> scales = parse_ints(o.scales, "--scales", 1, 16);
  const std::vector<std::string> names =
      o.scenes.empty() ? std::vector<std::string>{"wyman-20k", "wyman-70k", "wyman-330k", "wyman-750k"}
                       : split(o.scenes);
  std::vector<SceneDesc> descs;
  for (const std::string& name : names)
    descs.push_back(black_surfaces(load_scene(name)));  // fail before work
  if (!o.output.empty()) {
    std::error_code ec;
    if (std::filesystem::exists(o.output, ec) && !std::filesystem::is_directory(o.output, ec))
      throw InputError(SourceLocation{o.output, ""}, "output exists and is not a folder");
    std::filesystem::create_directories(o.output, ec);
    if (ec)
      throw InputError(SourceLocation{o.output, ""}, "cannot create the output folder: " + ec.message());
  }

  const std::vector<Variant> vs = variants();
  std::vector<SceneResult> results;
  for (size_t i = 0; i < names.size(); ++i) {
    const SceneDesc& desc = descs[i];
    SceneResult r;
    r.name = names[i];
    r.triangles = generated_triangles(desc);
    std::fprintf(stderr, "bench-table: %s: reference %dx%d at %d spp...\n", names[i].c_str(), o.resolution,
                 o.resolution, o.reference_spp);
    const Reference reference = render_reference(desc.at_time(0.0f), o.resolution, o.reference_spp);
    r.reference_noise = reference.noise;
    r.reference_spp = reference.spp;
    // The textured column runs on the scene's spot-light twin, with its own reference.
    std::optional<SceneDesc> spot_desc;
    Reference spot_reference;
    if (find_builtin(names[i] + "-spot")) {
      spot_desc = black_surfaces(load_scene(names[i] + "-spot"));
      std::fprintf(stderr, "bench-table: %s-spot: reference...\n", names[i].c_str());
      spot_reference = render_reference(spot_desc->at_time(0.0f), o.resolution, o.reference_spp);
    }
    for (int scale : scales) {
      const auto make_pipeline = [&](const SceneDesc& d) {
        RealtimeSettings s = realtime_settings(d);
        s.resolution = {o.resolution, o.resolution};
        s.scale = scale;
        s.temporal = false;
        return std::make_unique<RealtimePipeline>(Scene::build(d), s);
      };
      const auto pipeline = make_pipeline(desc);
      const auto spot_pipeline = spot_desc ? make_pipeline(*spot_desc) : nullptr;
      std::vector<Run> runs;
      for (const Variant& v : vs) {
        if (v.spot && !spot_pipeline) {
          runs.emplace_back();
          continue;
        }
        const Reference& ref = v.spot ? spot_reference : reference;
        runs.push_back(run_variant(v.spot ? *spot_pipeline : *pipeline, v, o.frames, ref.image));
        runs.back().reference_noise = ref.noise;
        std::fprintf(stderr, "bench-table: %s scale %d %-13s %8.2f ms, rRMSE %.2f %%\n", names[i].c_str(),
                     scale, v.label.c_str(), runs.back().frame_us / 1000.0,
                     runs.back().error.relative_rmse * 100.0);
      }
      // Step errors against the converged run of the same scene (point: brute, spot: textured).
      for (size_t vi = 0; vi < vs.size(); ++vi) {
        if (!runs[vi].ran) continue;
        for (size_t ci = 0; ci < vs.size(); ++ci)
          if (vs[ci].converged && vs[ci].spot == vs[vi].spot)
            runs[vi].step_error = reference_error(runs[vi].image, runs[ci].image).relative_rmse;
      }
      r.runs.push_back(std::move(runs));
    }
    if (!o.output.empty()) {
      std::vector<std::vector<const Image*>> rows;
      for (const auto& runs : r.runs) {
        std::vector<const Image*> row;
        for (size_t vi = 0; vi < vs.size(); ++vi)
          if (vs[vi].in_main_table && runs[vi].ran) row.push_back(&runs[vi].image);
        row.push_back(&reference.image);
        if (spot_desc) row.push_back(&spot_reference.image);
        rows.push_back(row);
      }
      const std::string png =
          (std::filesystem::path(o.output) / (std::filesystem::path(names[i]).stem().string() + ".png"))
              .string();
      write_strip(png, rows, o.exposure);
    }
    // Only the images of the strip were needed; free them before the next scene.
    for (auto& runs : r.runs)
      for (Run& run : runs) run.image = Image();
    results.push_back(std::move(r));
  }

  const std::string md = markdown(o, scales, vs, results);
  std::fputs(md.c_str(), stdout);
  if (!o.output.empty()) {
    const std::string path = (std::filesystem::path(o.output) / "table.md").string();
    // Atomically, like every other output: an interrupted run leaves no half table.
    write_file_atomically(path, [&](const std::string& temp) {
      std::ofstream out(temp);
      out << md;
      out.close();
      if (!out) throw InputError(SourceLocation{path, ""}, "cannot write the table");
    });
    std::string pngs;
    for (const std::string& n : names) pngs += " " + std::filesystem::path(n).stem().string() + ".png";
    std::printf("-> %s, per scene (rows: scales; columns: none, brute 150, hybrid 50, textured, march, reference, spot reference):%s\n",
                path.c_str(), pngs.c_str());
  }
  return 0;
}

}  // namespace caligo
