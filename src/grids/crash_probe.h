// Runs a body in a forked child process to learn whether it crashes, for third-party readers
// that corrupt memory on hostile input instead of throwing (OpenVDB reads an uncompressed
// chunk of whatever length the file states into a fixed buffer before checking the length).
// The caller then does the real work in-process only when the child survived.
//
// The child only runs `body` and leaves with _exit (no destructors, no atexit handlers). A
// lock held by another parent thread at fork time could block the child forever: after
// `timeout` the child is killed and the result is kUnknown.
#pragma once

#include <chrono>
#include <functional>

namespace caligo {

enum class ProbeResult { kSurvived, kThrew, kCrashed, kUnknown };

ProbeResult probe_in_child(const std::function<void()>& body, std::chrono::milliseconds timeout);

}  // namespace caligo
