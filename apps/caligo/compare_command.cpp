// caligo compare A.exr B.exr [--max-rmse X]: error metrics of A against the reference B.
#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>

#include "commands.h"
#include "core/error.h"
#include "image/compare.h"
#include "image/exr_io.h"

namespace caligo {

void add_compare_command(CLI::App& app, CompareOptions& o) {
  CLI::App* cmd = app.add_subcommand("compare", "Compare an image with a reference (RGB channels)");
  cmd->add_option("image", o.a, "Image to measure (.exr)")->required();
  cmd->add_option("reference", o.b, "Reference image (.exr)")->required();
  cmd->add_option("--max-rmse", o.max_rmse, "Exit with status 1 when the RMSE exceeds this value");
}

int run_compare(const CompareOptions& o) {
  // A NaN limit would pass every comparison (rmse > NaN is false): refused like any bad number.
  if (o.max_rmse && !(std::isfinite(*o.max_rmse) && *o.max_rmse >= 0.0))
    throw InputError(kCommandLine, "--max-rmse: expected a finite number >= 0");
  const Image a = read_exr(o.a);
  const Image b = read_exr(o.b);
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
    return 1;
  }
  return 0;
}

}  // namespace caligo
