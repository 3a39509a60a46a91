#include "datasets/preview.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <opencv2/imgproc.hpp>

#include "core/error.h"
#include "core/haptic_track.h"
#include "datasets/preview_platform.h"
#include "datasets/video_writer.h"
#include "extract/frame_source.h"
#include "platform/sim_platform.h"

namespace hapcine {
namespace {

constexpr double kHalfWorkspaceM = 0.05;

// One panel: top view of the workspace and a Y gauge.
void DrawPanel(cv::Mat& img, const cv::Rect& r, const char* name, const HapticTrack& track,
               const HapticTrack* response, double t, double trail_s) {
  cv::Mat roi = img(r);
  cv::Mat shade(roi.size(), roi.type(), cv::Scalar(30, 30, 30));
  cv::addWeighted(shade, 0.75, roi, 0.25, 0, roi);
  const int pad = std::max(4, r.height / 12);
  const int gauge_w = std::max(6, r.width / 10);
  const int side = std::min(r.width - 3 * pad - gauge_w, r.height - 3 * pad - r.height / 6);
  if (side < 8) return;
  const cv::Point origin(r.x + pad, r.y + pad + r.height / 6);
  const cv::Rect square(origin, cv::Size(side, side));
  cv::rectangle(img, square, cv::Scalar(120, 120, 120), 1, cv::LINE_AA);
  const cv::Point centre(square.x + side / 2, square.y + side / 2);
  cv::line(img, {centre.x - 4, centre.y}, {centre.x + 4, centre.y}, cv::Scalar(90, 90, 90));
  cv::line(img, {centre.x, centre.y - 4}, {centre.x, centre.y + 4}, cv::Scalar(90, 90, 90));
  const int a = name[0] == 'h' ? 0 : name[0] == 'l' ? 1 : 2;
  auto to_px = [&](const Eigen::Vector3d& p) {
    const double x = std::clamp(p.x() / kHalfWorkspaceM, -1.0, 1.0);
    const double z = std::clamp(p.z() / kHalfWorkspaceM, -1.0, 1.0);
    return cv::Point(centre.x + static_cast<int>(std::lround(x * side / 2)),
                     centre.y + static_cast<int>(std::lround(z * side / 2)));
  };
  Eigen::Vector3d pos[kNumActuators];
  size_t hint = 0;
  const int steps = 30;
  cv::Point prev;
  for (int i = 0; i <= steps; ++i) {
    const double ti = t - trail_s * (steps - i) / steps;
    track.Sample(ti, pos, &hint);
    const cv::Point p = to_px(pos[a]);
    if (i > 0) {
      const double w = static_cast<double>(i) / steps;
      cv::line(img, prev, p, cv::Scalar(60 + 140 * w, 120 + 80 * w, 60), 1, cv::LINE_AA);
    }
    prev = p;
  }
  track.Sample(t, pos);
  const int dot_r = std::max(3, side / 20);
  cv::circle(img, to_px(pos[a]), dot_r, cv::Scalar(40, 220, 255), -1, cv::LINE_AA);
  Eigen::Vector3d actual[kNumActuators];
  if (response) {
    response->Sample(t, actual);
    cv::circle(img, to_px(actual[a]), dot_r + 3, cv::Scalar(255, 200, 60), 2, cv::LINE_AA);
  }
  // Y gauge: up is up.
  const cv::Rect gauge(square.x + side + pad, square.y, gauge_w, side);
  cv::rectangle(img, gauge, cv::Scalar(120, 120, 120), 1);
  const double y = std::clamp(pos[a].y() / kHalfWorkspaceM, -1.0, 1.0);
  const int gy = gauge.y + side / 2 - static_cast<int>(std::lround(y * side / 2));
  cv::rectangle(img, cv::Point(gauge.x, std::min(gy, gauge.y + side / 2)),
                cv::Point(gauge.x + gauge_w, std::max(gy, gauge.y + side / 2)),
                cv::Scalar(40, 220, 255), -1);
  if (response) {
    const double ya = std::clamp(actual[a].y() / kHalfWorkspaceM, -1.0, 1.0);
    const int gya = gauge.y + side / 2 - static_cast<int>(std::lround(ya * side / 2));
    cv::line(img, {gauge.x - 3, gya}, {gauge.x + gauge_w + 3, gya}, cv::Scalar(255, 200, 60), 2);
  }
  const double font = std::max(0.3, r.height / 260.0);
  cv::putText(img, name, cv::Point(r.x + pad, r.y + pad + r.height / 9), cv::FONT_HERSHEY_SIMPLEX,
              font, cv::Scalar(230, 230, 230), 1, cv::LINE_AA);
}

}  // namespace

void PreviewOptions::Check() const {
  if (video.empty()) throw UsageError("preview needs VIDEO");
  if (output.empty()) throw UsageError("preview needs -o OUT.mp4");
  if (max_side != 0 && max_side < 64) throw UsageError("--max-side must be 0 or >= 64");
  if (!(inset_fraction >= 0.15 && inset_fraction <= 1))
    throw UsageError("--inset must be in [0.15, 1]");
  if (!(trail_s >= 0 && trail_s <= 10)) throw UsageError("--trail must be in [0, 10] s");
  if (crf < 0 || crf > 51) throw UsageError("--crf must be in [0, 51]");
}

int RenderPreview(const PreviewOptions& o, const std::function<void(int, int)>& progress) {
  o.Check();
  std::string track_path = o.track;
  PlatformTrack platform, platform_sim;
  if (!o.platform_track.empty()) platform = ReadPlatformTrackFile(o.platform_track);
  if (o.simulate_platform) platform_sim = SimulatePlatform(platform);
  if (track_path.empty() && o.platform_track.empty()) {
    const std::filesystem::path v(o.video);
    track_path = (v.parent_path() / (v.stem().string() + ".haptic.csv")).string();
    if (!std::filesystem::exists(track_path))
      throw Error(o.video, "no --track given and no " + track_path + " beside the video");
  }
  const HapticTrack track = o.platform_track.empty() ? ReadHapticTrackFile(track_path) : HapticTrack();
  HapticTrack response;
  if (o.simulate && o.platform_track.empty()) response = o.simulate(track);
  FrameSourceOptions fo;
  fo.max_working_side = o.max_side;
  fo.want_color = true;
  auto source = OpenFrameSource(o.video, fo);
  const VideoInfo& info = source->info();
  VideoWriter writer;
  VideoWriterOptions vo;
  vo.crf = o.crf;
  Frame frame;
  int n = 0;
  const int total = static_cast<int>(info.frame_count);
  while (source->Next(&frame)) {
    cv::Mat img = frame.bgr.empty() ? cv::Mat() : frame.bgr;
    if (img.empty()) cv::cvtColor(frame.gray, img, cv::COLOR_GRAY2BGR);
    const int w = img.cols & ~1, h = img.rows & ~1;
    if (w < 16 || h < 16) throw Error(o.video, "frames too small for a preview");
    if (w != img.cols || h != img.rows) img = img(cv::Rect(0, 0, w, h)).clone();
    if (!writer.is_open()) writer.Open(o.output, w, h, info.fps > 0 ? info.fps : 25.0, vo);
    const int inset_w = std::max(48, static_cast<int>(w * o.inset_fraction)) / 3 * 3;
    if (!o.platform_track.empty()) {
      const int inset_h = std::min(h, std::max(40, inset_w * 2 / 5));
      DrawPlatformInset(img, cv::Rect(w - inset_w, h - inset_h, inset_w, inset_h), platform,
                        frame.time_s, o.simulate_platform ? &platform_sim : nullptr);
      writer.Write(img);
      ++n;
      if (progress && n % 10 == 0) progress(n, total);
      continue;
    }
    const int panel_w = inset_w / 3;
    const int panel_h = std::min(h, std::max(32, panel_w * 5 / 4));
    const int x0 = w - inset_w, y0 = h - panel_h;
    const char* names[kNumActuators] = {"head", "left", "right"};
    for (int a = 0; a < kNumActuators; ++a)
      DrawPanel(img, cv::Rect(x0 + a * panel_w, y0, panel_w, panel_h), names[a], track,
                o.simulate ? &response : nullptr, frame.time_s, o.trail_s);
    writer.Write(img);
    ++n;
    if (progress && n % 10 == 0) progress(n, total);
  }
  if (n == 0) throw Error(o.video, "no frames decoded");
  writer.Close();
  return n;
}

}  // namespace hapcine
