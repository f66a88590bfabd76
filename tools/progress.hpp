#pragma once
// A one-line progress bar on stderr with the rate and the time left, drawn
// only when stderr is a terminal (a log or a pipe gets nothing extra). Used
// by `headlight bench` and `headlight render`'s batches.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>

namespace headlight::cli {

class Progress {
 public:
  Progress(std::size_t total, bool enabled, const char* unit = "it")
      : total_(total), enabled_(enabled && isatty(2)), unit_(unit) {}
  void update(std::size_t done, const std::string& what) {
    if (!enabled_) return;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const double rate = elapsed > 0 ? double(done) / elapsed : 0.0;
    const double eta = done > 0 ? elapsed / double(done) * double(total_ - std::min(done, total_)) : 0.0;
    const int width = 30, filled = int(double(width) * double(done) / double(std::max<std::size_t>(total_, 1)));
    std::fprintf(stderr, "\r[%s%s] %zu/%zu %6.2f %s/s ETA %3d:%02d  %-40.40s",
                 std::string(std::size_t(filled), '#').c_str(), std::string(std::size_t(width - filled), ' ').c_str(),
                 done, total_, rate, unit_, int(eta) / 60, int(eta) % 60, what.c_str());
    std::fflush(stderr);
    drawn_ = true;
  }
  // Clears the bar so a message can be printed on a line of its own.
  void clear() {
    if (enabled_ && drawn_) std::fprintf(stderr, "\r%*s\r", 110, "");
  }
  void finish() {
    if (enabled_ && drawn_) std::fprintf(stderr, "\n");
    drawn_ = false;
  }

 private:
  std::size_t total_;
  bool enabled_;
  const char* unit_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace headlight::cli
