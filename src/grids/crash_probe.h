// Runs a body in a forked child process to learn whether it crashes, for third-party readers
// that corrupt memory on hostile input instead of throwing (OpenVDB reads an uncompressed
// chunk of whatever length the file states into a fixed buffer, and checks the length only
// afterwards). The caller does the real work in-process only when the child survived: after
// kThrew the parent's heap could already be corrupt had it run the body itself.
//
// The child only runs `body` and leaves with _exit (no destructors, no atexit handlers). A
// lock held by another parent thread at fork time could block the child forever: after
// `timeout` the child is killed and the result is kUnknown. `memory_allowance` (bytes; 0 for
// none) caps the child's address space at the parent's current size plus the allowance, so a
// corrupt length that makes the reader allocate and zero-fill gigabytes fails fast (kThrew)
// instead.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <string>

namespace caligo {

enum class ProbeResult { kSurvived, kThrew, kCrashed, kUnknown };

struct ProbeOutcome {
  ProbeResult result;
  std::string message;  // kThrew: the exception's what()
};

ProbeOutcome probe_in_child(const std::function<void()>& body, std::chrono::milliseconds timeout,
                            uint64_t memory_allowance = 0);

}  // namespace caligo
