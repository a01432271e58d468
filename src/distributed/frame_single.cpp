// render_frame in a build without MPI: a launcher that started one process gets the plain
// render; more than one would each write the whole frame, so that is an error.
#include <string>

#include "core/error.h"
#include "distributed/frame.h"

namespace caligo::distributed {

bool built_with_mpi() { return false; }

std::optional<RenderResult> render_frame(const Scene& scene, const RenderSettings& frame, Split,
                                         Progress::Style progress, uint64_t /*frame_key: one process agrees*/) {
  const int processes = launcher_world_size().value_or(1);
  if (processes > 1)
    throw EnvironmentError("this caligo was built without MPI (libopenmpi-dev was not found when it was "
                           "configured), but a launcher started " + std::to_string(processes) +
                           " processes of it; install libopenmpi-dev and rebuild, or run it without mpirun/srun");
  return render(scene, frame, progress);
}

}  // namespace caligo::distributed
