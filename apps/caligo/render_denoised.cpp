// caligo render --denoise: the frame as two films of disjoint sample halves ([0, n/2) and
// [n/2, n)), whose merge is bit for bit the film one render of n samples makes, so the beauty is
// unchanged; the halves go in the EXR as half_a and half_b (what the denoiser cross-filters and
// estimates its error from), and the denoised beauty as the layer "denoised", which the PNG
// preview shows. Albedo, normal, depth and variance are rendered whatever --aov says.
#include <cstdio>

#include "commands.h"
#include "core/error.h"
#include "denoise_image.h"
#include "render/render.h"
#include "render_denoised.h"

namespace caligo {
namespace {

void refuse_what_halves_cannot_do(const RenderOptions& o, const RenderSettings& s) {
  const auto refuse = [](const char* what) {
    throw InputError(kCommandLine, std::string("--denoise renders two fixed halves of the samples; ") + what +
                                       " cannot be combined with it (denoise a finished render with `caligo denoise`)");
  };
  if (o.checkpoint || o.resume || o.checkpoint_every) refuse("checkpoints");
  if (o.time_limit || o.target_rmse) refuse("a time limit or an error target");
  if (s.adaptive.threshold > 0.0f) refuse("adaptive sampling");
  if (guided(s)) refuse("path guiding");
  if (s.spp < 4) throw InputError(kCommandLine, "--denoise needs at least 4 samples per pixel (2 in each half)");
}

std::vector<RGB> beauty_of(const Image& image) {
  std::vector<RGB> out;
  out.reserve(image.pixel_count());
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) out.push_back(image.rgb(x, y, 0));
  return out;
}

}  // namespace

int run_render_denoised(const RenderOptions& o, const Scene& scene, RenderSettings settings,
                        const RenderOutputs& outputs, const HeaderOf& header_of, PreviewServer* preview) {
  refuse_what_halves_cannot_do(o, settings);
  settings.aovs = settings.aovs.with(Aov::kAlbedo).with(Aov::kNormal).with(Aov::kDepth).with(Aov::kVariance);
  RenderSettings first = settings, second = settings;
  first.first_sample = 0;
  first.spp = settings.spp / 2;
  second.first_sample = first.spp;
  second.spp = settings.spp - first.spp;
  const Progress::Style style = o.quiet ? Progress::Style::kQuiet : Progress::Style::kAuto;
  Film a(settings.resolution, settings.aovs), b(settings.resolution, settings.aovs);
  RenderStats stats = render_into(a, scene, first, style);
  const RenderStats second_stats = render_into(b, scene, second, style);
  stats += second_stats;
  stats.seconds += second_stats.seconds;
  Film full = a;
  full.merge(b);
  Image image = full.resolve();
  image = with_rgb_layer(image, "half_a", beauty_of(a.resolve()));
  image = with_rgb_layer(image, "half_b", beauty_of(b.resolve()));
  const DenoisedImage d = denoise_image(image, outputs.exr());
  ExrAttributes attributes = header_of({settings.spp, settings.spp}, stats.seconds);
  attributes.push_back({"caligo/denoiser", std::string("NFOR-style cross-filtered regression")});
  const Image preview_image = denoised_beauty(d.image);
  outputs.write_final(d.image, nullptr, 0, attributes, &preview_image);
  if (preview) {
    preview->publish({d.image, settings.spp, settings.spp, stats.seconds, true, {}});
    preview->linger(2.0);
  }
  if (!o.quiet) {
    std::fprintf(stderr, "caligo: rendered %d spp as two halves in %.2f s\n", settings.spp, stats.seconds);
    print_denoise_summary(d, outputs.exr());
  }
  return 0;
}

}  // namespace caligo
