#pragma once
// Progress of a long study on standard error, only when it is a terminal (a log or a pipe
// gets nothing) and not --quiet. Standard output is never touched.
#include <unistd.h>

#include <cstdio>
#include <string>

#include <fmt/core.h>

namespace imunoise::cli {

class Progress {
 public:
  explicit Progress(bool quiet) : enabled_(!quiet && ::isatty(2) == 1) {}
  ~Progress() { done(); }
  void update(const std::string& what, double fraction) {
    if (!enabled_) return;
    fmt::print(stderr, "\r\033[K[{:3.0f}%] {}", 100.0 * fraction, what);
    std::fflush(stderr);
    shown_ = true;
  }
  void done() {
    if (enabled_ && shown_) fmt::print(stderr, "\r\033[K");
    shown_ = false;
  }

 private:
  bool enabled_;
  bool shown_ = false;
};

}  // namespace imunoise::cli
