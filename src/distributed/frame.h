// One frame rendered by the processes of an MPI job (mpirun, srun): each rank renders its share
// (share.h), the raw films go to rank 0 as bytes (MPI has no 128-bit integer type) and are merged
// there exactly, in rank order; rank 0 alone resolves and writes. The result equals the
// single-process render bit for bit. This header includes no MPI header: only frame_mpi.cpp
// does, and a build without MPI compiles frame_single.cpp instead.
//
// Failures:
// - a rank that throws (bad input, a failed allocation, a bug) tells the others through a status
//   exchange after rendering. Rank 0 prints "caligo: error: rank R of N failed: MESSAGE" (the
//   first failing rank's message, and the list of failed ranks when several did), all ranks meet
//   in a barrier, then all throw RankFailure with the exit code of that rank's error (2 for an
//   InputError, 3 EnvironmentError, 1 other): main exits with it and prints nothing more.
// - ranks started with different options or scene files stop the same way before rendering,
//   exit code 2: they compare a fingerprint of the frame's settings (resolution, samples,
//   outputs, seed, crop, bounces) and of the caller's `frame_key`, which covers the rest.
// - an MPI call that fails is an EnvironmentError naming the call; it calls MPI_Abort, as
//   the job cannot continue collectively.
// - a rank that dies (killed, crashed) cannot tell anyone: Open MPI's mpirun notices the process
//   end and kills the whole job ("mpirun noticed that process rank 1 ... exited on signal 9"),
//   exit code non-zero, nothing written. Under Slurm, srun --kill-on-bad-exit does the same.
#pragma once

#include <cstdint>
#include <optional>

#include "distributed/rank_failure.h"
#include "distributed/share.h"
#include "render/render.h"

namespace caligo::distributed {

// How many processes a launcher started this one among, from the environment only (MPI is not
// initialised): Open MPI's mpirun (OMPI_COMM_WORLD_SIZE), PMI launchers such as MPICH's or
// srun --mpi=pmi2 (PMI_SIZE), or srun --mpi=pmix (PMIX_RANK with SLURM_STEP_NUM_TASKS).
// nullopt when started on its own, so single runs never pay for MPI_Init.
std::optional<int> launcher_world_size();

// Whether this binary was built with MPI (libopenmpi-dev found at configure time).
bool built_with_mpi();

// Renders `frame` as one rank of the job that launched this process: MPI_Init, this rank's
// share, the exact merge on rank 0, MPI_Finalize (once per process). Returns the frame on
// rank 0, nullopt on the other ranks, which must write nothing. Progress only on rank 0.
// Without MPI: the frame itself when launcher_world_size() is 1, an EnvironmentError when more
// processes were launched (each would write the whole frame).
// `frame_key`: a hash of everything else that must be the same on every rank for the merge to
// mean anything: the scene file's bytes, the filter, light sampler, distance sampling, deferred
// NEE, the time, --priority (caligo passes checkpoint_key(), apps/caligo/checkpoint.h). Ranks
// with different keys stop before rendering; 0 (the default) only agrees with 0.
// Test hook: CALIGO_TEST_MPI_FAIL=RANK:throw|input|kill makes that rank fail while rendering.
std::optional<RenderResult> render_frame(const Scene& scene, const RenderSettings& frame, Split split,
                                         Progress::Style progress, uint64_t frame_key = 0);

}  // namespace caligo::distributed
