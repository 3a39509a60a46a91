#include "core/progress.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <utility>

namespace hapcine {
namespace {

constexpr int kBarWidth = 30;
constexpr double kBarInterval = 0.2;   // s between redraws of a bar
constexpr double kLineInterval = 5.0;  // s between plain lines

// HAPCINE_PROGRESS_INTERVAL (seconds, 0.1-60) overrides the lines' interval:
// `hapcine make` reads its steps' progress from their logs more often.
double LineInterval() {
  static const double interval = [] {
    const char* env = std::getenv("HAPCINE_PROGRESS_INTERVAL");
    const double v = env ? std::strtod(env, nullptr) : 0;
    return v >= 0.1 && v <= 60 ? v : kLineInterval;
  }();
  return interval;
}

// Counts as integers, fractional amounts (seconds played) with one decimal.
std::string Amount(double x) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), x == std::floor(x) ? "%.0f" : "%.1f", x);
  return buf;
}

std::string Rate(double per_s) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.1f/s", per_s);
  return buf;
}

std::string Count(const std::string& unit, const ProgressSnapshot& s) {
  std::string text = Amount(s.done);
  if (s.total > 0) text += "/" + Amount(s.total);
  return unit.empty() ? text : text + " " + unit;
}

}  // namespace

std::string FormatDuration(double seconds) {
  char buf[32];
  if (!(seconds >= 0) || !std::isfinite(seconds)) return "?";
  if (seconds < 60) {
    std::snprintf(buf, sizeof(buf), "%.1fs", seconds);
  } else if (seconds < 3600) {
    const int s = static_cast<int>(seconds + 0.5);
    std::snprintf(buf, sizeof(buf), "%dm%02ds", s / 60, s % 60);
  } else {
    const int m = static_cast<int>(seconds / 60 + 0.5);
    std::snprintf(buf, sizeof(buf), "%dh%02dm", m / 60, m % 60);
  }
  return buf;
}

ProgressMode ProgressModeFor(bool quiet) {
  if (quiet) return ProgressMode::kQuiet;
  return ::isatty(STDERR_FILENO) ? ProgressMode::kBar : ProgressMode::kLines;
}

Progress::Progress(std::ostream& out, ProgressMode mode, std::string label, std::string unit,
                   Clock clock)
    : out_(out), mode_(mode), label_(std::move(label)), unit_(std::move(unit)), clock_(std::move(clock)) {
  start_ = Now();
}

double Progress::Now() const {
  if (clock_) return clock_();
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

std::string Progress::BarText(const std::string& label, const std::string& unit,
                              const ProgressSnapshot& s) {
  std::string text = label;
  if (s.total > 0) {
    const int filled = static_cast<int>(std::clamp(s.done / s.total, 0.0, 1.0) * kBarWidth);
    text += " [" + std::string(filled, '#') + std::string(kBarWidth - filled, '.') + "]";
  }
  text += " " + Count(unit, s);
  if (!s.note.empty()) text += "  " + s.note;
  if (s.total > 0) text += "  ETA " + FormatDuration(s.eta_s);
  return text;
}

std::string Progress::LineText(const std::string& label, const std::string& unit,
                               const ProgressSnapshot& s) {
  std::string text = label + ": " + Count(unit, s);
  if (!s.note.empty()) text += ", " + s.note;
  if (s.total > 0) text += ", ETA " + FormatDuration(s.eta_s);
  return text;
}

void Progress::Update(double done, double total) {
  if (mode_ == ProgressMode::kQuiet) return;
  const double now = Now();
  if (now - last_draw_ < (mode_ == ProgressMode::kBar ? kBarInterval : LineInterval())) return;
  const double elapsed = now - start_;
  ProgressSnapshot s;
  s.done = done;
  s.total = total;
  if (elapsed > 0 && done > 0) {
    const double rate = done / elapsed;
    s.note = Rate(rate);
    if (total > 0) s.eta_s = std::max(0.0, total - done) / rate;
  }
  Show(s);
}

void Progress::Show(const ProgressSnapshot& snapshot) {
  last_draw_ = Now();
  if (mode_ == ProgressMode::kBar) {
    out_ << "\r\033[K" << BarText(label_, unit_, snapshot) << std::flush;
    bar_open_ = true;
  } else if (mode_ == ProgressMode::kLines) {
    out_ << LineText(label_, unit_, snapshot) << "\n" << std::flush;
  }
}

void Progress::Line(const std::string& text) {
  if (mode_ == ProgressMode::kQuiet) return;
  if (bar_open_) out_ << "\r\033[K";
  bar_open_ = false;
  out_ << text << "\n" << std::flush;
}

void Progress::Close() {
  if (bar_open_) out_ << "\n" << std::flush;
  bar_open_ = false;
}

void Progress::Finish(double done) {
  if (mode_ == ProgressMode::kQuiet) return;
  Close();
  const double elapsed = Now() - start_;
  out_ << label_ << ": " << Amount(done) << (unit_.empty() ? "" : " " + unit_) << " in "
       << FormatDuration(elapsed);
  if (elapsed > 0) out_ << " (" << Rate(done / elapsed) << ")";
  out_ << "\n" << std::flush;
}

}  // namespace hapcine
