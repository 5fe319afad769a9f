// The progress bar on stderr: terminal only, after a short delay, throttled, cleared at the end.
#include "progress.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fmt/format.h>
#include <fstream>
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

namespace {
int count_lines(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  int lines = 0;
  char buffer[1 << 16];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    for (std::streamsize i = 0; i < in.gcount(); ++i) lines += buffer[i] == '\n';
  }
  return lines;
}
}  // namespace

job::Progress job_progress(const std::string& gcode_file, Progress& bar) {
  if (!bar.enabled()) return {};
  const int total = std::max(count_lines(gcode_file), 1);
  return [total, &bar](std::uint64_t samples, int line) {
    bar.update(static_cast<double>(line) / total,
               fmt::format("line {}/{}  {:.1f} M samples", line, total, static_cast<double>(samples) / 1e6));
  };
}

std::function<void(double)> Progress::callback() {
  if (!enabled_) return {};
  return [this](double fraction) { update(fraction); };
}

}  // namespace stiffpath::cli
