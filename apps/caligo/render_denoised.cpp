// caligo render --denoise: the frame as two films of disjoint sample halves ([0, n/2) and
// [n/2, n)), refined together in doubling passes (the preview gets the denoised frame after each),
// whose merge is bit for bit the film one render of n samples makes, so the beauty is unchanged; the halves go in the EXR as half_a and half_b (what the denoiser cross-filters and
// estimates its error from), and the denoised beauty as the layer "denoised", which the PNG
// preview shows. Albedo, normal, depth and variance are rendered whatever --aov says.
#include <chrono>
#include <cstdio>

#include "commands.h"
#include "core/error.h"
#include "denoise_image.h"
#include "interrupt.h"
#include "render/progressive.h"
#include "render/render.h"
#include "render_denoised.h"

namespace caligo {
namespace {

void refuse_what_halves_cannot_do(const RenderOptions& o, const RenderSettings& s) {
  const auto refuse = [](const char* what) {
    throw InputError(kCommandLine, std::string("--denoise renders two fixed halves of the samples; ") + what +
                                       " cannot be combined with it (denoise a finished render with `caligo denoise`)");
  };
  if (o.checkpoint || o.resume || o.checkpoint_every) refuse("checkpoints");  // two films, neither resumable alone
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

namespace {

struct Halves {
  Film a, b;
  RenderSettings first, second;
};

// The frame as it stands: the merged beauty and layers, the halves, and the denoised layer.
DenoisedImage frame_of(const Halves& h, const std::string& where) {
  Film full = h.a;
  full.merge(h.b);
  Image image = full.resolve();
  image = with_rgb_layer(image, "half_a", beauty_of(h.a.resolve()));
  image = with_rgb_layer(image, "half_b", beauty_of(h.b.resolve()));
  return denoise_image(image, where);
}

}  // namespace

int run_render_denoised(const RenderOptions& o, const Scene& scene, RenderSettings settings, const RenderOutputs& outputs,
                        const HeaderOf& header_of, PreviewServer* preview, const InterruptGuard& interrupt) {
  refuse_what_halves_cannot_do(o, settings);
  settings.aovs = settings.aovs.with(Aov::kAlbedo).with(Aov::kNormal).with(Aov::kDepth).with(Aov::kVariance);
  Halves h{Film(settings.resolution, settings.aovs), Film(settings.resolution, settings.aovs), settings, settings};
  h.first.first_sample = 0;
  h.second.first_sample = settings.spp / 2;
  const int half_a = settings.spp / 2, half_b = settings.spp - half_a;
  // Both halves refined together in doubling passes (1, 2, 4, ... each), so that a stop or the
  // preview finds two halves of equal counts; the halves' merge ends the plain render's film.
  const auto start = std::chrono::steady_clock::now();
  const auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  const PixelBounds window = settings.crop.pixels(settings.resolution);
  const uint64_t pixels = window.empty() ? 0 : uint64_t(window.width()) * uint64_t(window.height());
  Progress progress("render", pixels * uint64_t(settings.spp), o.quiet ? Progress::Style::kQuiet : Progress::Style::kAuto);
  RenderStats stats;
  for (int done = 0; done < half_b && !interrupt.stopped();) {
    done = o.single_pass ? half_b : std::min(half_b, std::max(1, 2 * done));
    stats += render_up_to(h.a, scene, h.first, std::min(done, half_a), &interrupt.stop(), Progress::Style::kQuiet, &progress);
    stats += render_up_to(h.b, scene, h.second, done, &interrupt.stop(), Progress::Style::kQuiet, &progress);
    if (preview && done < half_b && !interrupt.stopped()) {
      const DenoisedImage now = frame_of(h, outputs.exr());
      preview->publish({now.image, 2 * done, settings.spp, elapsed(), false, {}});
    }
  }
  progress.finish();
  stats.seconds = elapsed();
  const DenoisedImage d = frame_of(h, outputs.exr());
  const auto a_range = sample_range(h.a, h.first), b_range = sample_range(h.b, h.second);
  const std::pair<int, int> samples{a_range.first + b_range.first, a_range.second + b_range.second};
  ExrAttributes attributes = header_of(samples, stats.seconds);
  attributes.push_back({"caligo/denoiser", std::string("NFOR-style cross-filtered regression")});
  const Image preview_image = denoised_beauty(d.image);
  if (preview) {
    preview->publish({d.image, samples.first, settings.spp, stats.seconds, true, {}});
    preview->linger(2.0);
  }
  if (samples.first < settings.spp) {  // stopped: the partial image (the halves cannot be resumed)
    outputs.write_interrupted_images(d.image, attributes, &preview_image);
    std::fprintf(stderr, "caligo: interrupted with %d to %d of %d samples per pixel: wrote the denoised partial image %s "
                         "(%s, if it exists, is kept); no checkpoint (the two halves of --denoise cannot be resumed)\n",
                 samples.first, samples.second, settings.spp, outputs.partial_exr().c_str(), outputs.exr().c_str());
    return kExitInterruptedBase + (interrupt.signal_number() > 0 ? interrupt.signal_number() : 2);
  }
  outputs.write_final(d.image, nullptr, 0, attributes, &preview_image);
  if (!o.quiet) {
    std::fprintf(stderr, "caligo: rendered %d spp as two halves in %.2f s\n", settings.spp, stats.seconds);
    print_denoise_summary(d, outputs.exr());
  }
  return 0;
}

}  // namespace caligo
