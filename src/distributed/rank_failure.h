// Thrown on every rank of an MPI job that failed (distributed/frame.h), after rank 0 printed
// why: main exits with exit_code() and prints nothing, so the reason appears once, not once per
// rank. Its own header so that main need not include the renderer.
#pragma once

#include <exception>

namespace caligo::distributed {

class RankFailure : public std::exception {
 public:
  explicit RankFailure(int exit_code) : exit_code_(exit_code) {}
  int exit_code() const { return exit_code_; }
  const char* what() const noexcept override { return "the MPI job failed (rank 0 reported why)"; }

 private:
  int exit_code_;
};

}  // namespace caligo::distributed
