// render_frame over MPI: the only translation unit that includes <mpi.h>. Protocol, on a
// private duplicate of MPI_COMM_WORLD with MPI_ERRORS_RETURN (every call's code is checked):
//   1. every rank checks that all agree on the frame (a fingerprint of its settings);
//   2. every rank renders its share (share.h) into a film of its own, catching any exception;
//   3. all ranks exchange their outcome (MPI_Allgather of exit codes, then the failures'
//      messages gathered on rank 0): if one failed, all stop; rank 0 says which and why;
//   4. the statistics are summed on rank 0;
//   5. ranks 1..N-1 send their raw film bytes (Film::to_bytes, in pieces of at most 1 GiB, since
//      MPI counts are int) and rank 0 merges them in rank order (Film::merge, exact).
// Nothing collective follows step 5 but MPI_Finalize, so an error on rank 0 while merging
// cannot leave the other ranks waiting.
#include <mpi.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/message_text.h"
#include "core/rng.h"
#include "distributed/frame.h"
#include "guiding/guiding_schedule.h"

namespace caligo::distributed {

bool built_with_mpi() { return true; }

namespace {

constexpr int kTagSize = 1, kTagBytes = 2;
constexpr size_t kPiece = size_t(1) << 30;  // bytes per MPI_Send of a film
constexpr int kMessageBytes = 512;          // a failed rank's message, as gathered on rank 0

// The job cannot continue collectively (an MPI call failed, or rank 0 could not merge while
// other ranks may still be sending): render_frame prints the message and aborts the whole job.
class JobAbort : public std::runtime_error {
 public:
  JobAbort(int exit_code, const std::string& message) : std::runtime_error(message), exit_code_(exit_code) {}
  int exit_code() const { return exit_code_; }

 private:
  int exit_code_;
};

void check(int code, const char* call) {
  if (code == MPI_SUCCESS) return;
  char text[MPI_MAX_ERROR_STRING] = {};
  int length = 0;
  MPI_Error_string(code, text, &length);
  throw JobAbort(kExitEnvironmentError, std::string("MPI: ") + call + " failed: " + std::string(text, size_t(std::max(0, length))));
}

// MPI for one frame: initialised on construction with errors returned, not fatal, on a private
// communicator; finalised on destruction.
class Job {
 public:
  Job() {
    int initialized = 0;
    MPI_Initialized(&initialized);
    if (initialized) throw std::logic_error("render_frame: MPI is already initialised (one frame per process)");
    check(MPI_Init(nullptr, nullptr), "MPI_Init");
    check(MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN), "MPI_Comm_set_errhandler");
    check(MPI_Comm_dup(MPI_COMM_WORLD, &comm_), "MPI_Comm_dup");  // inherits MPI_ERRORS_RETURN
    check(MPI_Comm_rank(comm_, &rank_), "MPI_Comm_rank");
    check(MPI_Comm_size(comm_, &size_), "MPI_Comm_size");
  }
  ~Job() {
    MPI_Comm_free(&comm_);
    MPI_Finalize();
  }
  Job(const Job&) = delete;
  Job& operator=(const Job&) = delete;

  MPI_Comm comm() const { return comm_; }
  int rank() const { return rank_; }
  int size() const { return size_; }

 private:
  MPI_Comm comm_ = MPI_COMM_NULL;
  int rank_ = 0, size_ = 1;
};

// What rendering a share came to: exit code 0, or the error's code (core/error.h) and message.
struct Outcome {
  int exit_code = 0;
  std::string message;
};

// Ends a failed job on every rank: rank 0 prints `message` (as main prints errors), then all
// meet in a barrier before anyone leaves, since mpirun kills the job once one rank exits non-zero
// and rank 0's message would be lost if it printed later; then every rank throws RankFailure.
[[noreturn]] void fail_job(const Job& job, int exit_code, const std::string& message) {
  if (job.rank() == 0) {
    std::fprintf(stderr, "caligo: error: %s\n", printable_for_message(message, kMessageLineBytes).c_str());
    std::fflush(stderr);
  }
  check(MPI_Barrier(job.comm()), "MPI_Barrier");
  throw RankFailure(exit_code);
}

// CALIGO_TEST_MPI_FAIL=RANK:throw|input|kill (tests only): that rank fails while rendering.
void inject_test_failure(int rank) {
  const char* spec = std::getenv("CALIGO_TEST_MPI_FAIL");
  if (!spec) return;
  const std::string text = spec;
  const size_t colon = text.find(':');
  if (colon == std::string::npos || std::atoi(text.substr(0, colon).c_str()) != rank) return;
  const std::string how = text.substr(colon + 1);
  if (how == "kill") std::raise(SIGKILL);
  if (how == "input")
    throw InputError(SourceLocation{"CALIGO_TEST_MPI_FAIL", ""}, "a scene error injected on rank " + std::to_string(rank));
  throw std::runtime_error("a failure injected on rank " + std::to_string(rank) + " by CALIGO_TEST_MPI_FAIL");
}

Outcome render_share(std::optional<Film>& film, RenderStats& stats, const Scene& scene,
                     const RenderSettings& share, Progress::Style progress, int rank) {
  try {
    film.emplace(share.resolution, share.aovs);
    inject_test_failure(rank);
    stats = render_into(*film, scene, share, progress);
    return {};
  } catch (const JobAbort&) {
    throw;
  } catch (const InputError& e) {
    return {kExitInputError, e.what()};
  } catch (const EnvironmentError& e) {
    return {kExitEnvironmentError, e.what()};
  } catch (const std::exception& e) {
    return {kExitInternalError, std::string("internal: ") + e.what()};
  }
}

// Step 1: a rank started with another scene file or other options would merge garbage. The
// settings that shape the film are hashed here; `frame_key` covers the scene and the rest.
void check_same_frame(const Job& job, const RenderSettings& frame, uint64_t frame_key) {
  uint32_t crop[4];
  std::memcpy(crop, &frame.crop, sizeof crop);
  const uint64_t mine = hash_values(uint64_t(frame.resolution.x), frame.resolution.y, frame.aovs.bits(), frame.spp,
                                    frame.first_sample, frame.seed, crop[0], crop[1], crop[2], crop[3],
                                    frame.path.limits.max_bounces, frame.path.limits.max_volume_bounces, frame_key);
  uint64_t low = 0, high = 0;
  check(MPI_Allreduce(&mine, &low, 1, MPI_UINT64_T, MPI_MIN, job.comm()), "MPI_Allreduce");
  check(MPI_Allreduce(&mine, &high, 1, MPI_UINT64_T, MPI_MAX, job.comm()), "MPI_Allreduce");
  if (low == high) return;
  fail_job(job, kExitInputError,
           "the " + std::to_string(job.size()) + " ranks of the MPI job disagree on the frame (the scene file's "
           "contents, or options such as the resolution, samples, seed, filter or light sampler): are the scene "
           "files or options different on some nodes?");
}

// Step 3: returns when every rank succeeded; otherwise throws on every rank.
void agree_on_outcome(const Job& job, const Outcome& mine) {
  std::vector<int> codes(size_t(job.size()));
  check(MPI_Allgather(&mine.exit_code, 1, MPI_INT, codes.data(), 1, MPI_INT, job.comm()), "MPI_Allgather");
  const auto first = std::find_if(codes.begin(), codes.end(), [](int c) { return c != 0; });
  if (first == codes.end()) return;
  std::array<char, kMessageBytes> text{};
  const std::string printable = printable_for_message(mine.message, kMessageBytes - 1);
  std::memcpy(text.data(), printable.data(), std::min(printable.size(), text.size() - 1));
  std::vector<char> all(job.rank() == 0 ? size_t(job.size()) * kMessageBytes : 0);
  check(MPI_Gather(text.data(), kMessageBytes, MPI_CHAR, all.data(), kMessageBytes, MPI_CHAR, 0, job.comm()),
        "MPI_Gather");
  if (job.rank() != 0) fail_job(job, *first, "");
  const size_t failed_rank = size_t(first - codes.begin());
  std::string message = "rank " + std::to_string(failed_rank) + " of " + std::to_string(job.size()) +
                        " failed: " + std::string(&all[failed_rank * kMessageBytes]);
  std::vector<size_t> failed;
  for (size_t r = 0; r < codes.size(); ++r)
    if (codes[r] != 0) failed.push_back(r);
  if (failed.size() > 1) {
    message += " (" + std::to_string(failed.size()) + " ranks failed:";
    for (size_t i = 0; i < std::min<size_t>(failed.size(), 8); ++i) (message += ' ') += std::to_string(failed[i]);
    message += failed.size() > 8 ? " ...)" : ")";
  }
  fail_job(job, *first, message);
}

// Step 4: the paths, rays and steps of every rank, summed on rank 0.
void sum_stats(const Job& job, RenderStats& stats) {
  const uint64_t mine[5] = {stats.paths, stats.rays, stats.camera_march_steps, stats.march_steps,
                            stats.shader_evaluations};
  uint64_t total[5] = {};
  check(MPI_Reduce(mine, total, 5, MPI_UINT64_T, MPI_SUM, 0, job.comm()), "MPI_Reduce");
  stats.paths = total[0];
  stats.rays = total[1];
  stats.camera_march_steps = total[2];
  stats.march_steps = total[3];
  stats.shader_evaluations = total[4];
}

// Step 5, ranks 1..N-1.
void send_film(const Job& job, const Film& film) {
  const std::string bytes = film.to_bytes();
  const uint64_t size = bytes.size();
  check(MPI_Send(&size, 1, MPI_UINT64_T, 0, kTagSize, job.comm()), "MPI_Send");
  for (size_t at = 0; at < bytes.size(); at += kPiece)
    check(MPI_Send(bytes.data() + at, int(std::min(kPiece, bytes.size() - at)), MPI_BYTE, 0, kTagBytes, job.comm()),
          "MPI_Send");
}

// Step 5, rank 0: the film of rank `from`.
Film receive_film(const Job& job, int from) {
  uint64_t size = 0;
  check(MPI_Recv(&size, 1, MPI_UINT64_T, from, kTagSize, job.comm(), MPI_STATUS_IGNORE), "MPI_Recv");
  std::string bytes(size, '\0');
  for (size_t at = 0; at < bytes.size(); at += kPiece)
    check(MPI_Recv(bytes.data() + at, int(std::min(kPiece, bytes.size() - at)), MPI_BYTE, from, kTagBytes,
                   job.comm(), MPI_STATUS_IGNORE),
          "MPI_Recv");
  try {
    return Film::from_bytes(bytes, "the film of rank " + std::to_string(from));
  } catch (const InputError& e) {
    throw std::runtime_error(e.what());  // our own bytes: a bug, not the user's input
  }
}

// A guided frame (render.h: guided()): the training iterations are collective. Each iteration's
// samples [2^k - 1, 2^(k+1) - 1) are split over the ranks as the frame's are (share.h); then the
// ranks agree on their outcome, sum the field's statistics (32-bit limbs in 64-bit words, so
// MPI_SUM is exact) and every rank refines the same field. The samples after training are split
// once. Each sample is rendered once, with the field the single-process render gives it.
void render_guided_shares(const Job& job, std::optional<Film>& film, RenderStats& stats, const Scene& scene,
                          const RenderSettings& frame, Split split, Progress::Style progress) {
  GuidingField field(guiding_bounds(scene), guiding_config(frame));
  for (int first = 0; first < frame.spp;) {
    const bool train = field.training();
    const int end = train ? std::min(frame.spp, training_iteration_end(field.completed_iterations())) : frame.spp;
    RenderSettings part = frame;
    part.first_sample = first;
    part.spp = end - first;
    const RenderSettings share = settings_for_rank(part, split, job.rank(), job.size());
    Outcome outcome;
    try {
      if (!film) film.emplace(frame.resolution, frame.aovs);
      inject_test_failure(job.rank());
      stats += render_into(*film, scene, share, job.rank() == 0 ? progress : Progress::Style::kQuiet,
                           {&field, train});
    } catch (const InputError& e) {
      outcome = {kExitInputError, e.what()};
    } catch (const EnvironmentError& e) {
      outcome = {kExitEnvironmentError, e.what()};
    } catch (const std::exception& e) {
      outcome = {kExitInternalError, std::string("internal: ") + e.what()};
    }
    agree_on_outcome(job, outcome);
    if (train) {
      const std::vector<uint64_t> mine = field.statistics_words();
      std::vector<uint64_t> total(mine.size());
      check(MPI_Allreduce(mine.data(), total.data(), int(mine.size()), MPI_UINT64_T, MPI_SUM, job.comm()),
            "MPI_Allreduce");
      field.set_statistics_words(total);
      if (end == training_iteration_end(field.completed_iterations())) field.finish_iteration();
    }
    first = end;
  }
}

std::optional<RenderResult> render_frame_on(const Job& job, const Scene& scene, const RenderSettings& frame,
                                            Split split, Progress::Style progress, uint64_t frame_key) {
  const auto start = std::chrono::steady_clock::now();
  check_same_frame(job, frame, frame_key);
  std::optional<Film> film;
  RenderStats stats;
  if (guided(frame)) {
    render_guided_shares(job, film, stats, scene, frame, split, progress);
  } else {
    const RenderSettings share = settings_for_rank(frame, split, job.rank(), job.size());
    const Outcome outcome = render_share(film, stats, scene, share,
                                         job.rank() == 0 ? progress : Progress::Style::kQuiet, job.rank());
    agree_on_outcome(job, outcome);
  }
  sum_stats(job, stats);
  if (job.rank() != 0) {
    send_film(job, *film);
    return std::nullopt;
  }
  try {
    for (int r = 1; r < job.size(); ++r) film->merge(receive_film(job, r));
  } catch (const JobAbort&) {
    throw;
  } catch (const std::exception& e) {
    throw JobAbort(kExitInternalError, std::string("internal: merging the films of the ranks: ") + e.what());
  }
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return RenderResult{film->resolve(), stats};
}

}  // namespace

std::optional<RenderResult> render_frame(const Scene& scene, const RenderSettings& frame, Split split,
                                         Progress::Style progress, uint64_t frame_key) {
  std::optional<Job> job;
  try {
    job.emplace();
    return render_frame_on(*job, scene, frame, split, progress, frame_key);
  } catch (const JobAbort& e) {
    if (!job) throw EnvironmentError(e.what());  // MPI_Init failed: there is no job to abort
    // The other ranks may wait in a call that needs this one: end the whole job.
    std::fprintf(stderr, "caligo: error: rank %d of %d: %s\n", job->rank(), job->size(), e.what());
    std::fflush(stderr);
    MPI_Abort(MPI_COMM_WORLD, e.exit_code());
    std::_Exit(e.exit_code());
  }
}

}  // namespace caligo::distributed
