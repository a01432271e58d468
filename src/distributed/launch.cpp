// launcher_world_size(): compiled with and without MPI (it reads the environment only).
#include <cstdlib>
#include <string>

#include "distributed/frame.h"

namespace caligo::distributed {
namespace {

// A positive process count from the variable `name`; nullopt when unset or not a count.
std::optional<int> count_from(const char* name) {
  const char* text = std::getenv(name);
  if (!text || !*text) return std::nullopt;
  char* end = nullptr;
  const long n = std::strtol(text, &end, 10);
  if (*end != '\0' || n < 1 || n > 1'000'000) return std::nullopt;
  return int(n);
}

}  // namespace

std::optional<int> launcher_world_size() {
  if (const auto n = count_from("OMPI_COMM_WORLD_SIZE")) return n;
  if (const auto n = count_from("PMI_SIZE")) return n;
  if (std::getenv("PMIX_RANK")) {
    if (const auto n = count_from("SLURM_STEP_NUM_TASKS")) return n;
    if (const auto n = count_from("SLURM_NTASKS")) return n;
    return 1;  // a PMIx launcher that does not say how many: MPI_Comm_size will
  }
  return std::nullopt;
}

}  // namespace caligo::distributed
