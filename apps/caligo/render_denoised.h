// caligo render --denoise (render_denoised.cpp).
#pragma once

#include <functional>
#include <utility>

#include "commands.h"
#include "interrupt.h"
#include "image/exr_attributes.h"
#include "render/render.h"
#include "preview_server.h"
#include "render_outputs.h"

namespace caligo {

// The EXR header of the render, given the samples per pixel held and the seconds it took.
using HeaderOf = std::function<ExrAttributes(std::pair<int, int> samples, double seconds)>;

// `preview`, when given, gets the denoised frame after each pass; a stop (a signal, the page's
// button) ends the passes and writes the denoised partial image, without a checkpoint.
int run_render_denoised(const RenderOptions& o, const Scene& scene, RenderSettings settings,
                        const RenderOutputs& outputs, const HeaderOf& header_of, PreviewServer* preview,
                        const InterruptGuard& interrupt);

}  // namespace caligo
