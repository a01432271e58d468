// The markdown report of Wyman & Ramsey's Table 1 (wyman_table.h): Table 1 itself, the errors
// against the path tracer, the step errors and the equal-error speed-up.
#include <algorithm>
#include <cmath>
#include <iterator>

#include "experiments/markdown_table.h"
#include "experiments/wyman_table.h"

namespace caligo {

namespace {

using Align = MarkdownTable::Align;

// "20,480". Appending (GCC 12 warns falsely, -Wrestrict, on inserting into the digits).
std::string with_commas(uint64_t n) {
  const std::string digits = std::to_string(n);
  std::string s;
  for (size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) s += ',';
    s += digits[i];
  }
  return s;
}

std::string percent3(double fraction) { return percent(fraction, 3); }
std::string percent2(double fraction) { return percent(fraction, 2); }

// Index of the variant; vs.size() when none.
size_t find_variant(const std::vector<WymanVariant>& vs, VolumetricMethod method, int brute_samples = 150) {
  for (size_t i = 0; i < vs.size(); ++i)
    if (vs[i].method == method &&
        (method != VolumetricMethod::kBrute || vs[i].brute_samples == brute_samples))
      return i;
  return vs.size();
}

// The markdown the report's tables are written to.
struct Report {
  const WymanTableResults& results;
  std::string md;

  void line(const std::string& s) {
    md += s;
    md += '\n';
  }
  // The accumulation resolution at `scale`: "16²".
  std::string low(int scale) const {
    const int resolution = results.settings.resolution;
    std::string s = std::to_string((resolution + scale - 1) / scale);
    s += "²";
    return s;
  }
};

// Table 1 itself: frames per second of each main-table variant at each accumulation scale.
void fps_table(Report& rep) {
  const WymanTableSettings& o = rep.results.settings;
  const std::vector<WymanVariant>& vs = rep.results.variants;
  rep.line("Wyman & Ramsey 2008, Table 1, on Caligo's scenes: output " + std::to_string(o.resolution) +
           "², frames per second (median frame time of " + std::to_string(o.frames) + " frames after " +
           std::to_string(wyman::kWarmup) + " warm-up; temporal off, surfaces black).");
  rep.line("");
  MarkdownTable t;
  t.add_column("scene");
  t.add_column("triangles", Align::kRight);
  for (int s : o.scales)
    for (const WymanVariant& v : vs)
      if (v.in_main_table) t.add_column(v.label + " @" + rep.low(s), Align::kRight);
  for (const WymanSceneResult& r : rep.results.scenes) {
    std::vector<std::string> row = {r.name, r.triangles ? with_commas(r.triangles) : "?"};
    for (size_t si = 0; si < o.scales.size(); ++si)
      for (size_t vi = 0; vi < vs.size(); ++vi)
        if (vs[vi].in_main_table)
          row.push_back(r.runs[si][vi].ran ? format_number("%.1f", 1e6 / r.runs[si][vi].frame_us) : "–");
    t.add_row(std::move(row));
  }
  rep.md += t.str();
}

// One error per run and variant; `corrected`: also the error with the reference's noise taken
// out in quadrature, in parentheses.
template <typename Get, typename Format>
std::string error_cell(const WymanRun& run, const WymanVariant& v, Get get, Format format, bool corrected) {
  if (!run.ran) return "–";
  const double noise = run.reference_noise;
  std::string c = format(get(run));
  if (corrected) {
    c += " (" + format(std::sqrt(std::max(0.0, get(run) * get(run) - noise * noise))) + ")";
    if (v.spot) c += " [spot ref. noise " + percent2(noise) + "]";
  }
  // A hybrid that fell back to brute (open occluder) must not pass for the hybrid.
  if (run.used != volumetric_method_name(v.method)) c += " (ran " + run.used + ")";
  return c;
}

template <typename Get, typename Format>
void error_table(Report& rep, const std::string& title, Get get, Format format, bool corrected) {
  const std::vector<int>& scales = rep.results.settings.scales;
  const std::vector<WymanVariant>& vs = rep.results.variants;
  rep.line("");
  rep.line(title);
  rep.line("");
  MarkdownTable t;
  t.add_column("scene");
  t.add_column("scattering");
  if (corrected) t.add_column("ref. noise", Align::kRight);
  for (const WymanVariant& v : vs) t.add_column(v.label, Align::kRight);
  for (const WymanSceneResult& r : rep.results.scenes)
    for (size_t si = 0; si < scales.size(); ++si) {
      std::vector<std::string> row = {r.name, rep.low(scales[si])};
      if (corrected) row.push_back(percent2(r.reference_noise));
      for (size_t vi = 0; vi < vs.size(); ++vi)
        row.push_back(error_cell(r.runs[si][vi], vs[vi], get, format, corrected));
      t.add_row(std::move(row));
    }
  rep.md += t.str();
}

// One scene and scale of the speed-up table: the fewest brute steps that match the hybrid.
std::vector<std::string> speedup_row(const Report& rep, const WymanSceneResult& r, size_t si) {
  const std::vector<WymanVariant>& vs = rep.results.variants;
  const int most = wyman::kBruteSweep[std::size(wyman::kBruteSweep) - 1];
  const size_t hybrid = find_variant(vs, VolumetricMethod::kHybrid);
  const size_t most_steps = find_variant(vs, VolumetricMethod::kBrute, most);
  const auto& runs = r.runs[si];
  const double target = runs[hybrid].step_error * (1.0 + wyman::kMatchTolerance);
  size_t match = vs.size();
  for (int n : wyman::kBruteSweep) {
    const size_t vi = find_variant(vs, VolumetricMethod::kBrute, n);
    if (match == vs.size() && runs[vi].step_error <= target) match = vi;
  }
  const bool found = match != vs.size();
  const size_t b = found ? match : most_steps;
  const std::string bound = found ? "" : ">= ";
  return {r.name,
          rep.low(rep.results.settings.scales[si]),
          percent3(runs[hybrid].step_error),
          found ? std::to_string(vs[b].brute_samples) : "> " + std::to_string(most),
          percent3(runs[b].step_error),
          format_number("%.1f", 1e6 / runs[b].frame_us),
          format_number("%.1f", 1e6 / runs[hybrid].frame_us),
          bound + format_number("%.2fx", runs[b].frame_us / runs[hybrid].frame_us),
          bound + format_number("%.2fx", runs[b].volumetric_us / runs[hybrid].volumetric_us)};
}

// The speed-up of hybrid 50 over brute force at equal step error.
void speedup_table(Report& rep) {
  rep.line("");
  std::string sweep;
  for (int n : wyman::kBruteSweep) sweep += (sweep.empty() ? "" : ", ") + std::to_string(n);
  const int most = wyman::kBruteSweep[std::size(wyman::kBruteSweep) - 1];
  rep.line("Speed-up of hybrid 50 over brute force at equal step error: the fewest brute steps (of " + sweep +
           ") whose step error is at most " + format_number("%.0f", 100.0 + wyman::kMatchTolerance * 100) +
           " % of the hybrid's; ratio of median frame times (and of the volumetric passes alone). \">=\": no "
           "count "
           "matched, a lower bound against " +
           std::to_string(most) + " steps.");
  rep.line("");
  MarkdownTable t;
  t.add_column("scene");
  t.add_column("scattering");
  for (const char* h : {"hybrid step error", "brute steps", "brute step error", "brute fps", "hybrid fps",
                        "speed-up (frame)", "speed-up (volumetric)"})
    t.add_column(h, Align::kRight);
  for (const WymanSceneResult& r : rep.results.scenes)
    for (size_t si = 0; si < rep.results.settings.scales.size(); ++si) t.add_row(speedup_row(rep, r, si));
  rep.md += t.str();
}

}  // namespace

std::string wyman_markdown(const WymanTableResults& results) {
  Report rep{results, {}};
  fps_table(rep);
  error_table(
      rep,
      "Relative RMSE against the path-traced single-scattering reference (" +
          std::to_string(results.scenes.empty() ? 0 : results.scenes[0].reference_spp) +
          " spp, two halves of different seeds; ref. noise: the average's own, half the halves' difference; "
          "in parentheses: the error with that noise "
          "removed in quadrature, sqrt(e² - noise²)):",
      [](const WymanRun& r) { return r.error.relative_rmse; }, percent2, true);
  error_table(
      rep,
      "Step error: relative RMSE against the same pipeline (same shadow map, gather and upsampling; no "
      "reference noise) with " +
          std::to_string(wyman::kConvergedSteps) +
          " steps: brute force for the point-light columns, the textured pass for the spot:",
      [](const WymanRun& r) { return r.step_error; }, percent3, false);
  speedup_table(rep);
  return rep.md;
}

}  // namespace caligo
