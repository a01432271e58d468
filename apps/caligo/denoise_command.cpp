// caligo denoise IN.exr -o OUT.exr: the denoiser (src/denoise/denoise.h) on an EXR Caligo wrote
// with its half-sample layers (`caligo render --denoise`). OUT holds IN's layers and `denoised`;
// its PNG preview shows the denoised beauty. One output transaction; IN is never replaced.
#include <CLI/CLI.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "commands.h"
#include "denoise_image.h"
#include "core/error.h"
#include "core/output_transaction.h"
#include "denoise/denoise.h"
#include "image/compare.h"
#include "image/exr_io.h"
#include "image/png_io.h"
#include "image/tonemap.h"
#include "realtime/reference_compare.h"
#include "render_metadata.h"

namespace caligo {

void add_denoise_command(CLI::App& app, DenoiseOptions& o) {
  CLI::App* cmd = app.add_subcommand("denoise", "Denoise an EXR written by `caligo render --denoise`");
  cmd->add_option("input", o.input, "EXR with the half_a, half_b, variance, albedo, N and Z layers")->required();
  cmd->add_option("-o,--output", o.output, "The denoised EXR (a .png preview beside it)")->required();
  cmd->add_option("--radius", o.radius, "Regression window radius in pixels (1 to 15, default 4)");
  cmd->add_option("--exposure", o.exposure, "Exposure of the PNG preview, in stops");
  cmd->add_option("--view", o.view, "Tone curve of the PNG preview: filmic (default) or standard")
      ->check(CLI::IsMember({"filmic", "standard"}));
  cmd->add_option("--reference", o.reference,
                  "A converged render of the same frame: print the true MSE and relMSE of the noisy and denoised "
                  "beauty, and write OUT.strip.png (noisy | denoised | reference | error)");
  cmd->add_flag("-q,--quiet", o.quiet, "No summary line");
}

// The input's layers and the denoised one, its header with what was done; `preview_from`
// names the layer the PNG shows.
DenoisedImage denoise_image(const Image& image, const std::string& where, const DenoiseSettings& settings) {
  const auto start = std::chrono::steady_clock::now();
  const DenoiseResult r = denoise(denoise_layers(image, where), settings);
  DenoisedImage out{with_rgb_layer(image, "denoised", r.image), r, 0.0};
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

Image denoised_beauty(const Image& image) { return image.rgb_image(*image.rgb_indices("denoised.")); }

namespace {

// noisy | denoised | reference | error of the denoised (comparison_strip's heat map).
Rgb8Image four_panels(const Image& noisy, const Image& denoised, const Image& reference, float exposure) {
  const Rgb8Image three = comparison_strip(denoised, reference, exposure, 0.25f);
  const int w = noisy.width(), h = noisy.height();
  Rgb8Image out{three.width + w, three.height, std::vector<uint8_t>(size_t(three.width + w) * size_t(three.height) * 3, 0)};
  const std::vector<uint8_t> left = to_srgb8_preview(noisy, PreviewSettings{exposure, true});
  for (int y = 0; y < three.height; ++y) {
    uint8_t* row = &out.rgb[size_t(y) * size_t(out.width) * 3];
    if (y < h) std::copy_n(&left[size_t(y) * size_t(w) * 3], size_t(w) * 3, row);
    std::copy_n(&three.rgb[size_t(y) * size_t(three.width) * 3], size_t(three.width) * 3, row + size_t(w) * 3);
  }
  return out;
}

}  // namespace

void print_denoise_summary(const DenoisedImage& d, const std::string& output) {
  double share = 0;
  for (float s : d.result.filtered) share += s;
  share /= double(d.result.filtered.size());
  const double in = d.result.estimated_mse_input, out = d.result.estimated_mse_output;
  const std::string ratio = out > 0 ? "(" + std::to_string(int(std::lround(in / out))) + "x lower)" : "(below the estimate's noise)";
  std::fprintf(stderr, "caligo: denoised in %.2f s: estimated MSE %.3g -> %.3g %s, %.0f %% of pixels filtered -> %s\n",
               d.seconds, in, out, ratio.c_str(), 100 * share, output.c_str());
}

int run_denoise(const DenoiseOptions& o) {
  if (o.radius < 1 || o.radius > 15) throw InputError(kCommandLine, "--radius: expected 1 to 15");
  if (!(std::isfinite(o.exposure) && std::abs(o.exposure) <= 64.0f))
    throw InputError(kCommandLine, "--exposure: expected stops in [-64, 64]");
  if (std::filesystem::path(o.output).extension() != ".exr")
    throw InputError(SourceLocation{o.output, ""}, "output must be an .exr file");
  const std::string png = o.output.substr(0, o.output.size() - 4) + ".png";
  OutputTransaction tx;
  tx.protect(o.input, "input image");
  tx.add(o.output, "denoised image");
  tx.add(png, "preview");
  std::optional<Image> reference;
  std::string strip;
  if (o.reference) {
    tx.protect(*o.reference, "reference image");
    strip = o.output.substr(0, o.output.size() - 4) + ".strip.png";
    tx.add(strip, "comparison strip");
  }
  const Image image = read_exr(o.input);
  if (o.reference) {
    reference = read_exr(*o.reference);
    if (reference->width() != image.width() || reference->height() != image.height())
      throw InputError(SourceLocation{*o.reference, ""}, "the reference is " + std::to_string(reference->width()) + "x" +
                                                            std::to_string(reference->height()) + ", the image " +
                                                            std::to_string(image.width()) + "x" + std::to_string(image.height()));
    if (!reference->rgb_indices("")) throw InputError(SourceLocation{*o.reference, ""}, "the reference has no R, G, B");
  }
  ExrAttributes attributes = read_exr_attributes(o.input);
  DenoiseSettings settings;
  settings.radius = o.radius;
  const DenoisedImage d = denoise_image(image, o.input, settings);
  attributes.push_back({"caligo/denoiser", std::string("NFOR-style cross-filtered regression, radius ") +
                                               std::to_string(o.radius) + " (" + software_name() + ")"});
  const PreviewSettings preview{o.exposure, o.view == "filmic"};
  const Image beauty = denoised_beauty(d.image);
  std::vector<OutputTransaction::Writer> writers = {
      [&](const std::string& temp) { write_exr(temp, d.image, false, attributes); },
      [&](const std::string& temp) { write_png(temp, beauty.width(), beauty.height(), to_srgb8_preview(beauty, preview)); }};
  if (reference) {
    const Image noisy = image.rgb_image(*image.rgb_indices("")), ref = reference->rgb_image(*reference->rgb_indices(""));
    const ImageMetrics before = compare_images(noisy, ref), after = compare_images(beauty, ref);
    std::printf("mse_noisy %.6g\nmse_denoised %.6g\nrelmse_noisy %.6g\nrelmse_denoised %.6g\n", before.rmse * before.rmse,
                after.rmse * after.rmse, before.relative_mse, after.relative_mse);
    // A reference with its variance layer: its own noise adds its mean variance to every MSE
    // against it (independent noise), which this removes.
    if (const auto v = reference->rgb_indices("variance.")) {
      double mean = 0;
      for (int y = 0; y < reference->height(); ++y)
        for (int x = 0; x < reference->width(); ++x) mean += reference->rgb(x, y, *v).average();
      mean /= double(reference->pixel_count());
      std::printf("reference_variance %.6g\nmse_noisy_corrected %.6g\nmse_denoised_corrected %.6g\n", mean,
                  before.rmse * before.rmse - mean, after.rmse * after.rmse - mean);
    }
    writers.push_back([&, noisy, ref](const std::string& temp) {
      const Rgb8Image panels = four_panels(noisy, beauty, ref, o.exposure);
      write_png(temp, panels.width, panels.height, panels.rgb);
    });
  }
  tx.commit(writers);
  if (!o.quiet) print_denoise_summary(d, o.output);
  return 0;
}

}  // namespace caligo
