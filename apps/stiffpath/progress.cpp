// The progress bar on stderr: terminal only, after a short delay, throttled, cleared at the end.
#include "progress.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <unistd.h>

namespace stiffpath::cli {

Progress::Progress(std::string label, bool quiet)
    : label_(std::move(label)), enabled_(!quiet && ::isatty(2) != 0), start_(std::chrono::steady_clock::now()) {
  if (const char* delay = std::getenv("STIFFPATH_PROGRESS_DELAY_S")) {
    char* end = nullptr;
    const double value = std::strtod(delay, &end);
    if (end != delay && value >= 0.0) delay_s_ = value;
  }
}

Progress::~Progress() { finish(); }

void Progress::update(double fraction, std::string_view note) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (std::chrono::duration<double>(now - start_).count() < delay_s_) return;
  if (drawn_ && std::chrono::duration<double>(now - last_).count() < 0.1 && fraction < 1.0) return;
  last_ = now;
  drawn_ = true;
  const double f = std::clamp(fraction, 0.0, 1.0);
  constexpr int kWidth = 30;
  const int filled = static_cast<int>(f * kWidth);
  std::fprintf(stderr, "\r%s [%s%s] %3.0f%%  %.*s\033[K", label_.c_str(), std::string(static_cast<std::size_t>(filled), '#').c_str(),
               std::string(static_cast<std::size_t>(kWidth - filled), ' ').c_str(), f * 100, static_cast<int>(note.size()), note.data());
  std::fflush(stderr);
}

void Progress::finish() {
  if (!drawn_) return;
  std::fprintf(stderr, "\r\033[K");
  std::fflush(stderr);
  drawn_ = false;
}

std::function<void(double)> Progress::callback() {
  if (!enabled_) return {};
  return [this](double fraction) { update(fraction); };
}

}  // namespace stiffpath::cli
