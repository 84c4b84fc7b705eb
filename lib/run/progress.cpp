#include "run/progress.h"

#include <unistd.h>

#include <cstdio>
#include <string>

namespace sdg {

Progress::Progress(uint64_t total, bool enabled)
    : total_(total), enabled_(enabled), start_(std::chrono::steady_clock::now()), lastDraw_(start_) {}

bool Progress::stderrIsTerminal() { return ::isatty(STDERR_FILENO) == 1; }

void Progress::update(uint64_t done) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (done < total_ && now - lastDraw_ < std::chrono::milliseconds(100)) return;
  lastDraw_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double rate = elapsed > 0 ? double(done) / elapsed : 0.0;
  const double eta = rate > 0 ? double(total_ - done) / rate : 0.0;
  constexpr int kWidth = 30;
  const int filled = total_ ? int(double(done) / double(total_) * kWidth) : kWidth;
  std::string bar(size_t(filled), '#');
  bar.append(size_t(kWidth - filled), '.');
  std::fprintf(stderr, "\r[%s] %llu/%llu frames  %.1f frames/s  ETA %.1f s ", bar.c_str(),
               static_cast<unsigned long long>(done), static_cast<unsigned long long>(total_), rate, eta);
  std::fflush(stderr);
}

void Progress::finish() {
  if (!enabled_) return;
  update(total_);
  std::fputc('\n', stderr);
}

}  // namespace sdg
