// A driver for mpi_render_test: one rank of `mpirun -np 1 probe KEY : -np 1 probe KEY2`. Each
// renders an empty 8x8 scene through distributed::render_frame with its own frame_key and
// exits with the job's code: 0, or the RankFailure's (2 when the ranks disagree). It tests the
// key without the caligo command line, which derives the key from the scene and options.
#include <cstdio>
#include <cstdlib>
#include <string>

#include "distributed/frame.h"
#include "scene/scene.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: mpi_frame_key_probe FRAME_KEY\n");
    return 64;
  }
  using namespace caligo;
  const auto scene = Scene::build(SceneDesc{});
  RenderSettings settings;
  settings.resolution = {8, 8};
  settings.spp = 2;
  settings.threads = 1;
  try {
    const auto frame = distributed::render_frame(*scene, settings, distributed::Split::kSamples,
                                                 Progress::Style::kQuiet, std::strtoull(argv[1], nullptr, 10));
    return frame && frame->image.width() != 8 ? 1 : 0;
  } catch (const distributed::RankFailure& failure) {
    return failure.exit_code();
  }
}
