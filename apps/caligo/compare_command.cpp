// caligo compare A.exr B.exr [--max-rmse X]: error metrics of A against the reference B.
#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <utility>

#include "commands.h"
#include "core/error.h"
#include "image/compare.h"
#include "image/exr_io.h"

namespace caligo {

void add_compare_command(CLI::App& app, CompareOptions& o) {
  CLI::App* cmd = app.add_subcommand("compare", "Compare an image with a reference (RGB channels)");
  cmd->add_option("image", o.a, "Image to measure (.exr)")->required();
  cmd->add_option("reference", o.b, "Reference image (.exr)")->required();
  cmd->add_option("--max-rmse", o.max_rmse, "Exit with status 4 when the RMSE exceeds this value");
}

int run_compare(const CompareOptions& o) {
  // A NaN limit would pass every comparison (rmse > NaN is false): refused like any bad number.
  if (o.max_rmse && !(std::isfinite(*o.max_rmse) && *o.max_rmse >= 0.0))
    throw InputError(kCommandLine, "--max-rmse: expected a finite number >= 0");
  const Image a = read_exr(o.a);
  const Image b = read_exr(o.b);
  // NaN or Inf would make every metric NaN, which compares false against any limit: reported,
  // and the comparison fails whatever the limit.
  int failed = 0;
  for (const auto& [image, path] : {std::pair{&a, &o.a}, std::pair{&b, &o.b}})
    if (const size_t n = non_finite_rgb(*image); n > 0) {
      std::fprintf(stderr, "caligo: %s holds %zu NaN or infinite R, G or B values: the comparison fails\n",
                   printable_for_message(*path).c_str(), n);
      failed = kExitCheckFailed;
    }
  if (failed) return failed;
  ImageMetrics m;
  try {
    m = compare_images(a, b);
  } catch (const std::invalid_argument& e) {
    throw InputError(SourceLocation{o.a, ""}, e.what());
  }
  std::printf("rmse %.9g\nrelative_mse %.9g\nmean_difference %.9g\nmax_abs_difference %.9g\npixels %zu\n",
              m.rmse, m.relative_mse, m.mean_difference, m.max_abs_difference, m.pixels);
  if (o.max_rmse && m.rmse > *o.max_rmse) {
    std::fprintf(stderr, "caligo: rmse %.6g exceeds --max-rmse %.6g\n", m.rmse, *o.max_rmse);
    return kExitCheckFailed;
  }
  return 0;
}

}  // namespace caligo
