#include "datasets/preview.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>
#include <opencv2/imgproc.hpp>

#include "core/camera_path.h"
#include "core/error.h"
#include "core/haptic_track.h"
#include "core/output_files.h"
#include "datasets/preview_audio.h"
#include "datasets/preview_burn_in.h"
#include "datasets/preview_platform.h"
#include "datasets/video_writer.h"
#include "extract/frame_source.h"
#include "haptics/effect_classifier.h"
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

namespace {

// Everything drawn over the film, read before the first frame.
struct PreviewInputs {
  HapticTrack track, response;
  PlatformTrack platform, platform_sim;
  CameraPath camera;
  std::vector<EffectSegment> effects;
};

std::string Sibling(const std::string& video, const std::string& suffix) {
  const std::filesystem::path v(video);
  return (v.parent_path() / (v.stem().string() + suffix)).string();
}

PreviewInputs LoadInputs(const PreviewOptions& o) {
  PreviewInputs in;
  if (!o.platform_track.empty()) in.platform = ReadPlatformTrackFile(o.platform_track);
  if (o.simulate_platform) in.platform_sim = SimulatePlatform(in.platform);
  if (o.platform_track.empty()) {
    std::string track_path = o.track;
    if (track_path.empty()) {
      track_path = Sibling(o.video, ".haptic.csv");
      if (!std::filesystem::exists(track_path))
        throw Error(o.video, "no --track given and no " + track_path + " beside the video");
    }
    in.track = ReadHapticTrackFile(track_path);
    if (o.simulate) in.response = o.simulate(in.track);
  }
  if (!o.burn_in) return in;
  std::string camera = o.camera;
  if (camera.empty() && std::filesystem::exists(Sibling(o.video, ".camera.csv")))
    camera = Sibling(o.video, ".camera.csv");
  if (!camera.empty()) in.camera = ReadCameraPathFile(camera);
  const bool track_has_effects =
      std::any_of(in.track.samples.begin(), in.track.samples.end(),
                  [](const HapticSample& s) { return s.effect.has_value(); });
  if (!track_has_effects && in.camera.frames.size() > 1)
    in.effects = ClassifyEffects(in.camera, ClassifierOptions{});
  return in;
}

struct FrameRange {
  double from_s = 0;
  double to_s = std::numeric_limits<double>::infinity();
  bool Holds(double t) const { return t >= from_s - 1e-6 && t < to_s - 1e-6; }
};

FrameRange ResolveRange(const PreviewOptions& o, const VideoInfo& info) {
  const double fps = info.fps > 0 ? info.fps : 25.0;
  FrameRange r;
  if (!o.from.empty()) r.from_s = ParsePreviewTime(o.from, fps, "--from");
  if (!o.to.empty()) r.to_s = ParsePreviewTime(o.to, fps, "--to");
  if (!(r.from_s < r.to_s))
    throw UsageError("--from (" + o.from + ") must be before --to (" + o.to + ")");
  if (info.duration_s > 0 && r.from_s >= info.duration_s) {
    std::ostringstream msg;
    msg << "--from " << o.from << " is past the film's end (" << info.duration_s << " s)";
    throw UsageError(msg.str());
  }
  return r;
}

void DrawInsets(cv::Mat& img, const PreviewOptions& o, const PreviewInputs& in, double t) {
  const int w = img.cols, h = img.rows;
  const int inset_w = std::max(48, static_cast<int>(w * o.inset_fraction)) / 3 * 3;
  if (!o.platform_track.empty()) {
    const int inset_h = std::min(h, std::max(40, inset_w * 2 / 5));
    DrawPlatformInset(img, cv::Rect(w - inset_w, h - inset_h, inset_w, inset_h), in.platform, t,
                      o.simulate_platform ? &in.platform_sim : nullptr);
    return;
  }
  const int panel_w = inset_w / 3;
  const int panel_h = std::min(h, std::max(32, panel_w * 5 / 4));
  const int x0 = w - inset_w, y0 = h - panel_h;
  const char* names[kNumActuators] = {"head", "left", "right"};
  for (int a = 0; a < kNumActuators; ++a)
    DrawPanel(img, cv::Rect(x0 + a * panel_w, y0, panel_w, panel_h), names[a], in.track,
              o.simulate ? &in.response : nullptr, t, o.trail_s);
}

// The frame as an even-sized BGR image.
cv::Mat EvenBgr(const Frame& frame, const std::string& video) {
  cv::Mat img = frame.bgr;
  if (img.empty()) cv::cvtColor(frame.gray, img, cv::COLOR_GRAY2BGR);
  const int w = img.cols & ~1, h = img.rows & ~1;
  if (w < 16 || h < 16) throw Error(video, "frames too small for a preview");
  if (w != img.cols || h != img.rows) img = img(cv::Rect(0, 0, w, h)).clone();
  return img;
}

// What RenderFrames wrote: how many frames and the film times they span.
struct Rendered {
  int frames = 0;
  double first_s = 0, end_s = 0;  // end: the last frame's time plus one frame
};

Rendered RenderFrames(const PreviewOptions& o, const PreviewInputs& in, FrameSource& source,
                      const FrameRange& range, const std::string& path, bool atomic,
                      const std::function<void(int, int)>& progress) {
  const VideoInfo& info = source.info();
  const double fps = info.fps > 0 ? info.fps : 25.0;
  const BurnInLabels labels(in.camera, in.track, in.effects);
  long total = info.frame_count;  // 0: unknown (no ETA)
  if (std::isfinite(range.to_s)) {
    const long to_frames = std::lround(range.to_s * fps);
    total = total > 0 ? std::min(total, to_frames) : to_frames;
  }
  VideoWriter writer;
  VideoWriterOptions vo;
  vo.crf = o.crf;
  vo.atomic = atomic;
  Rendered r;
  Frame frame;
  for (int decoded = 1; source.Next(&frame); ++decoded) {
    if (progress && decoded % 10 == 0) progress(decoded, static_cast<int>(total));
    if (frame.time_s >= range.to_s - 1e-6) break;
    if (!range.Holds(frame.time_s)) continue;
    cv::Mat img = EvenBgr(frame, o.video);
    if (!writer.is_open()) writer.Open(path, img.cols, img.rows, fps, vo);
    DrawInsets(img, o, in, frame.time_s);
    if (o.burn_in) DrawBurnIn(img, labels.At(frame.time_s, fps));
    writer.Write(img);
    if (r.frames++ == 0) r.first_s = frame.time_s;
    r.end_s = frame.time_s + 1 / fps;
  }
  if (r.frames == 0) {
    if (o.from.empty() && o.to.empty()) throw Error(o.video, "no frames decoded");
    throw UsageError("no frame of " + o.video + " in --from " + o.from + " --to " + o.to);
  }
  writer.Close();
  return r;
}

}  // namespace

int RenderPreview(const PreviewOptions& o, const std::function<void(int, int)>& progress) {
  o.Check();
  const PreviewInputs inputs = LoadInputs(o);
  FrameSourceOptions fo;
  fo.max_working_side = o.max_side;
  fo.want_color = true;
  auto source = OpenFrameSource(o.video, fo);
  const FrameRange range = ResolveRange(o, source->info());
  if (!o.audio || !FilmHasAudio(o.video))
    return RenderFrames(o, inputs, *source, range, o.output, true, progress).frames;
  // Frames first into a temporary of our own, then muxed with the sound of
  // exactly the frames drawn into the output's temporary.
  TempOutput video_only(o.output), output(o.output);
  const Rendered r =
      RenderFrames(o, inputs, *source, range, video_only.write_path(), false, progress);
  MuxFilmAudio(video_only.write_path(), o.video, {r.first_s, r.end_s}, output.write_path(),
               o.output);
  output.Commit();
  return r.frames;
}

}  // namespace hapcine
