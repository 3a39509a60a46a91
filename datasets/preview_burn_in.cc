#include "datasets/preview_burn_in.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "core/error.h"

namespace hapcine {
namespace {

int NominalRate(double fps) { return std::max(1, static_cast<int>(std::lround(fps))); }

// A non-negative whole number below `limit`, or -1.
long ParseField(const std::string& text, long limit) {
  if (text.empty() || text.size() > 9 ||
      !std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; }))
    return -1;
  const long v = std::stol(text);
  return v < limit ? v : -1;
}

// Seconds as a plain non-negative number below `limit`, or -1.
double ParseSeconds(const std::string& text, double limit) {
  if (text.empty() || text.find_first_not_of("0123456789.") != std::string::npos) return -1;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && std::isfinite(v) && v < limit ? v : -1;
}

std::vector<std::string> SplitColons(const std::string& text) {
  std::vector<std::string> parts;
  std::stringstream in(text);
  for (std::string part; std::getline(in, part, ':');) parts.push_back(part);
  if (!text.empty() && text.back() == ':') parts.push_back("");
  return parts;
}

}  // namespace

std::string Timecode(double t_s, double fps) {
  const int rate = NominalRate(fps);
  const long long n = std::max(0LL, std::llround(t_s * fps));
  const long long s = n / rate;
  char buf[48];
  std::snprintf(buf, sizeof(buf), "%02lld:%02lld:%02lld:%02lld", s / 3600, s / 60 % 60, s % 60,
                n % rate);
  return buf;
}

double ParsePreviewTime(const std::string& text, double fps, const std::string& option) {
  const std::string bad = option + ": '" + text +
                          "' is not a time: seconds (62.5) or a timecode HH:MM:SS:FF";
  const std::vector<std::string> parts = SplitColons(text);
  if (parts.size() == 1) {
    const double s = ParseSeconds(text, 1e9);
    if (s < 0) throw UsageError(bad);
    return s;
  }
  if (parts.size() == 4) {
    const int rate = NominalRate(fps);
    const long h = ParseField(parts[0], 1000000), m = ParseField(parts[1], 60),
               s = ParseField(parts[2], 60), f = ParseField(parts[3], rate);
    if (h < 0 || m < 0 || s < 0 || f < 0)
      throw UsageError(bad + " (MM, SS < 60; FF < " + std::to_string(rate) + ")");
    return (((h * 60 + m) * 60 + s) * static_cast<double>(rate) + f) / fps;
  }
  if (parts.size() == 2 || parts.size() == 3) {
    const long h = parts.size() == 3 ? ParseField(parts[0], 1000000) : 0;
    const long m = ParseField(parts[parts.size() - 2], parts.size() == 3 ? 60 : 1000000);
    const double s = ParseSeconds(parts.back(), 60);
    if (h < 0 || m < 0 || s < 0) throw UsageError(bad);
    return (h * 60 + m) * 60.0 + s;
  }
  throw UsageError(bad);
}

BurnInLabels::BurnInLabels(const CameraPath& path, const HapticTrack& track,
                           std::vector<EffectSegment> effects)
    : path_(path), track_(track), effects_(std::move(effects)) {
  track_has_effects_ = std::any_of(track.samples.begin(), track.samples.end(),
                                   [](const HapticSample& s) { return s.effect.has_value(); });
}

const CameraFrame* BurnInLabels::FrameAt(double t_s) const {
  const auto& f = path_.frames;
  // The frame on screen at t: the last one that started by then (half a
  // millisecond of slack for rounded times).
  auto it = std::upper_bound(f.begin(), f.end(), t_s + 5e-4,
                             [](double t, const CameraFrame& c) { return t < c.time_s; });
  return it == f.begin() ? nullptr : &*std::prev(it);
}

const HapticSample* BurnInLabels::SampleAt(double t_s) const {
  const auto& s = track_.samples;
  auto it = std::upper_bound(s.begin(), s.end(), t_s + 5e-4,
                             [](double t, const HapticSample& h) { return t < h.time_s; });
  return it == s.begin() ? nullptr : &*std::prev(it);
}

std::string BurnInLabels::EffectAt(double t_s) const {
  CameraEffect effect = CameraEffect::kNone;
  if (track_has_effects_) {
    const HapticSample* s = SampleAt(t_s);
    if (!s || !s->effect) return "";
    effect = EffectFromName(*s->effect).value_or(CameraEffect::kNone);
  } else {
    for (const EffectSegment& seg : effects_)
      if (t_s >= seg.start_s && t_s < seg.end_s) effect = seg.effect;
  }
  if (effect == CameraEffect::kNone) return "effect none";
  return std::string("effect ") + EffectName(effect) + " (" + MetaphorName(effect) + ")";
}

std::vector<std::string> BurnInLabels::At(double t_s, double fps) const {
  std::vector<std::string> lines = {Timecode(t_s, fps)};
  const CameraFrame* frame = FrameAt(t_s);
  const HapticSample* sample = SampleAt(t_s);
  std::string shot_line;
  if (frame && frame->shot) shot_line = "shot " + std::to_string(*frame->shot);
  else if (sample && sample->shot) shot_line = "shot " + std::to_string(*sample->shot);
  if (frame && frame->model)
    shot_line += (shot_line.empty() ? "" : "  ") + std::string("camera ") + *frame->model;
  if (!shot_line.empty()) lines.push_back(shot_line);
  const std::string effect = EffectAt(t_s);
  if (!effect.empty() && (track_has_effects_ || !path_.frames.empty())) lines.push_back(effect);
  return lines;
}

void DrawBurnIn(cv::Mat& bgr, const std::vector<std::string>& lines) {
  const int font = cv::FONT_HERSHEY_SIMPLEX;
  const double scale = std::max(0.35, bgr.rows / 720.0 * 0.75);
  const int thickness = std::max(1, static_cast<int>(std::lround(scale * 1.6)));
  int baseline = 0;
  const int text_h = cv::getTextSize("0:", font, scale, thickness, &baseline).height;
  const int step = text_h + std::max(5, text_h * 2 / 3);
  const int margin = std::max(4, bgr.rows / 60);
  int y = margin + text_h;
  for (const std::string& line : lines) {
    const cv::Point at(margin, y);
    // The outline first: dark strokes twice as wide keep white text legible
    // on a bright sky or a white wall.
    cv::putText(bgr, line, at, font, scale, cv::Scalar(0, 0, 0), thickness + 2 * std::max(1, thickness / 2 + 1),
                cv::LINE_AA);
    cv::putText(bgr, line, at, font, scale, cv::Scalar(255, 255, 255), thickness, cv::LINE_AA);
    y += step;
  }
}

}  // namespace hapcine
