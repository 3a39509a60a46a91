#include "estimate/camera_estimator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <sstream>
#include <thread>

#include "core/diagnostics.h"
#include "core/error.h"
#include "estimate/colmap_backend.h"
#include "estimate/estimator_records.h"
#include "estimate/lens_bundle.h"
#include "estimate/lens_distortion.h"
#include "estimate/shot_quality.h"
#include "estimate/skipped_frames.h"
#include "estimate/stills_groups.h"
#include "extract/bounded_queue.h"
#include "extract/shot_detector.h"
#include "extract/threaded_frame_source.h"

namespace hapcine {

bool EstimatorOptions::MeasuresLensFromPairs() const {
  return lens_distortion && !lens_bundle && lens_k1 == 0;
}

void EstimatorOptions::Check() const {
  if (backend != "hapcine" && backend != "colmap")
    throw UsageError("backend must be 'hapcine' or 'colmap', not '" + backend + "'");
  frames.Check();
  tracker.Check();
  estimator.Check();
  if (!(std::abs(lens_k1) <= 0.5)) throw UsageError("lens k1 must be within [-0.5, 0.5]");
  // Each is a whole source of k1; two would undistort the tracks twice. The
  // pairs' measurement (the default) gives way to either (MeasuresLensFromPairs).
  if (lens_k1 != 0 && lens_bundle)
    throw UsageError("lens bundle and a known lens k1 exclude each other: choose one");
  if (lens_bundle_windows < 1 || lens_bundle_windows > 8) throw UsageError("lens windows must be within [1, 8]");
  if (colmap_binary.empty()) throw UsageError("colmap binary must not be empty");
  if (backend == "colmap" && frames.skip_nonref_frames)
    throw UsageError("skipping non-reference frames is for the hapcine backend only");
}

// Measured on the 17 synthetic clips (docs/estimate.md "Accuracy and
// speed"): ~0.6x the CPU of the defaults, less accurate (a crane move
// 0.32 deg, a telephoto pan's FOV 7.7 %, a whip pan 0.94 deg). Skipping the
// deblocking filter was left out here (3 % less CPU, but the crane move
// 0.086 -> 0.11 deg and the whip pan 0.45 -> 0.63 deg when measured);
// --draft adds it.
void ApplyFastPreset(EstimatorOptions* options) {
  options->frames.max_working_side = 640;
  options->tracker.max_tracks = 300;
  options->tracker.klt_window = 15;
  options->estimator.max_points = 200;
  // Not measured with more points in translating windows: as before that default.
  options->estimator.spread_points_factor = 1;
}

std::string FastPresetSummary() {
  EstimatorOptions o;
  ApplyFastPreset(&o);
  std::ostringstream s;
  s << "--max-side " << o.frames.max_working_side << " --tracks " << o.tracker.max_tracks
    << " --points " << o.estimator.max_points << " --spread-points-factor " << o.estimator.spread_points_factor
    << " --klt-window " << o.tracker.klt_window
    << (o.frames.skip_loop_filter ? ", no deblocking when decoding" : "");
  return s.str();
}

void ApplyDraftPreset(EstimatorOptions* options) {
  ApplyFastPreset(options);
  options->frames.skip_nonref_frames = true;
  options->frames.skip_loop_filter = true;
}

std::string DraftPresetSummary() {
  return "--fast, and decode only the frames others are predicted from (the others' poses "
         "interpolated) without deblocking";
}

namespace {

// Decoded frames allowed to wait for the tracker: enough to ride out one
// slow frame (a bundle-adjustment window closing), few enough to keep
// memory small (3 x 960x540 gray + thumbnails).
constexpr int kDecodeQueueFrames = 3;
// Tracked frames allowed to wait for the estimator: a window solve takes
// as long as tracking a few dozen frames, and FrameTracks are small (a few
// hundred points), so this is generous and still flat.
constexpr size_t kTrackQueueFrames = 48;
// Frames of the first shot the lens distortion is measured on: 6 s at
// 24 fps, enough for its frame pairs on any but the slowest move (memory:
// a few hundred points a frame, kept until the decision).
constexpr size_t kDistortionFrames = 144;

std::string Num(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

void AddMetadata(const FrameSource& source, const EstimatorOptions& options, CameraPath* path) {
  const VideoInfo& info = source.info();
  path->metadata["width"] = std::to_string(info.width);
  path->metadata["height"] = std::to_string(info.height);
  // Anamorphic video: width is the display width (stored width x this), the
  // pixels the path's focal_px and FOV are in.
  if (info.sample_aspect_num != info.sample_aspect_den)
    path->metadata["sample_aspect_ratio"] =
        std::to_string(info.sample_aspect_num) + ":" + std::to_string(info.sample_aspect_den);
  if (info.fps > 0) path->metadata["fps"] = Num(info.fps);
  path->metadata["source"] = info.path;
  path->metadata["estimator"] = "hapcine-" + options.backend;
  path->metadata["working_side"] = std::to_string(options.frames.max_working_side);
  if (options.backend == "hapcine") {
    path->metadata["tracks"] = std::to_string(options.tracker.max_tracks);
    path->metadata["window_frames"] = std::to_string(options.estimator.window_frames);
    path->metadata["prior_hfov_deg"] = Num(options.estimator.prior_hfov_deg);
    const bool smooth = options.estimator.smooth && !options.tracker.stills && !info.stills;
    path->metadata["smooth_sigma_frames"] = smooth ? Num(options.estimator.smooth_sigma_frames) : "0";
    // Readers of the path should know its in-between frames were not seen.
    if (options.frames.skip_nonref_frames) path->metadata["skip_nonref"] = "1";
  }
}

// Still images (a folder, a pattern, or --stills) are linked pair by pair
// by descriptors; their path is not smoothed: a Gaussian over frames would
// blur one view's pose into its neighbours', which are whole steps away.
TrackerOptions StillsAware(TrackerOptions tracker, const VideoInfo& info) {
  tracker.stills = tracker.stills || info.stills;
  return tracker;
}
TrackEstimatorOptions StillsAware(const EstimatorOptions& options, const VideoInfo& info) {
  TrackEstimatorOptions estimator = options.estimator;
  if (options.tracker.stills || info.stills) estimator.smooth = false;
  return estimator;
}

// The frames kept for a replay once a lens is decided: none where no k1 was
// kept, else every one undistorted by it. Returns whether to replay.
bool UndistortForReplay(double k1, int width, int height, std::vector<FrameTracks>* kept) {
  if (k1 == 0) kept->clear();
  for (FrameTracks& t : *kept) UndistortTracks(k1, width, height, &t);
  return k1 != 0;
}

// Measures k1 from frame pairs of the first shot's first frames
// (lens_distortion.h) while the estimator runs on them as they are. Where k1
// is kept, the caller starts a new estimator and replays every frame so far
// undistorted: the cost of a second start falls only on footage with a lens
// to correct, and the estimation overlaps tracking as without it.
class LensFromPairs {
 public:
  LensFromPairs(bool enabled, int width, int height, Diagnostics* diagnostics)
      : watching_(enabled), width_(width), height_(height), diagnostics_(diagnostics) {}

  // After `tracks` went to the estimator: true when k1 was found now (then
  // TakeFrames() holds every frame so far, undistorted). Decides once the
  // first shot has kDistortionFrames frames or another shot begins.
  bool Watch(const FrameTracks& tracks) {
    if (!watching_) return false;
    kept_.push_back(tracks);
    if (tracks.shot == kept_.front().shot && kept_.size() < kDistortionFrames) return false;
    return Decide();
  }

  // When the frames are in, or at the end with those seen by then.
  bool Decide() {
    if (!watching_) return false;
    watching_ = false;
    const auto first_shot_end = std::find_if(kept_.begin(), kept_.end(), [&](const FrameTracks& t) {
      return t.shot != kept_.front().shot;
    });
    // Not on stills: the pairs' measurement rests on KLT's sub-pixel steps,
    // and the tracks of stills are descriptor matches across whole viewpoint
    // changes, whose errors a homography does not absorb either.
    const bool stills =
        std::any_of(kept_.begin(), first_shot_end, [](const FrameTracks& t) { return t.still; });
    if (first_shot_end != kept_.begin() && !stills) Measure({kept_.begin(), first_shot_end});
    return UndistortForReplay(k1_, width_, height_, &kept_);
  }

  std::vector<FrameTracks> TakeFrames() { return std::move(kept_); }
  bool watching() const { return watching_; }
  double k1() const { return k1_; }

 private:
  void Measure(const std::vector<FrameTracks>& first_shot) {
    const RadialDistortionEstimate e = EstimateRadialDistortion(first_shot, width_, height_);
    k1_ = e.k1;
    Record(diagnostics_, "lens_distortion",
           {{"method", "pairs"},
            {"k1", e.k1},
            {"best_k1", e.best_k1},
            {"gric_gain", e.gric_gain},
            {"penalty", e.penalty},
            {"pairs", e.pairs},
            {"correspondences", e.correspondences}});
  }

  bool watching_;
  int width_, height_;
  Diagnostics* diagnostics_;
  std::vector<FrameTracks> kept_;
  double k1_ = 0;
};

// The first estimator's "window" records, held until the lens is decided:
// dropped when the estimation starts again undistorted (the report lists
// the run's own windows only), passed on otherwise. Estimation thread only.
class HeldWindowRecords : public Diagnostics {
 public:
  explicit HeldWindowRecords(Diagnostics* sink) : sink_(sink) {}
  bool Wants(const std::string& kind) const override { return hapcine::Wants(sink_, kind); }
  void Record(const std::string& kind, nlohmann::json fields) override {
    if (holding_ && kind == "window") held_.emplace_back(kind, std::move(fields));
    else hapcine::Record(sink_, kind, std::move(fields));
  }
  // pass_on: the records go to the sink; else they are dropped. Later ones pass.
  void Release(bool pass_on) {
    if (pass_on)
      for (auto& [kind, fields] : held_) hapcine::Record(sink_, kind, std::move(fields));
    held_.clear();
    holding_ = false;
  }

 private:
  Diagnostics* sink_;
  bool holding_ = true;
  std::vector<std::pair<std::string, nlohmann::json>> held_;
};

nlohmann::json LensBundleJson(const LensBundleEstimate& e) {
  return {{"k1", e.k1},
          {"best_k1", e.best_k1},
          {"chi2_gain", e.chi2_gain},
          {"penalty", e.penalty},
          {"sigma_k1", e.sigma_k1},
          {"track_sigma_k1", e.track_sigma_k1},
          {"noise_px", e.noise_px},
          {"observations", e.observations},
          {"points", e.points}};
}

// Keeps the frames until the estimator has solved the first shot's first
// windows (or the shot ended), then measures k1 on them (lens_bundle.h:
// one window alone, or several that must agree). Where k1 is kept the
// caller starts a new estimator and replays the kept frames undistorted:
// the cost of a second start falls only on footage with a lens to correct,
// and the estimation overlaps tracking as without it.
class LensFromWindows {
 public:
  LensFromWindows(bool enabled, int windows, int width, int height, Diagnostics* diagnostics)
      : watching_(enabled), windows_(windows), width_(width), height_(height), diagnostics_(diagnostics) {}

  // After `tracks` went to `estimator`: true when k1 was found now (then
  // TakeFrames() holds every frame so far, undistorted).
  bool Watch(const FrameTracks& tracks, const TrackCameraEstimator& estimator) {
    if (!watching_) return false;
    kept_.push_back(tracks);
    return estimator.solved_windows_complete() && Decide(estimator);
  }

  // When the windows are in, or at the end with those solved by then.
  bool Decide(const TrackCameraEstimator& estimator) {
    if (!watching_) return false;
    watching_ = false;
    const std::vector<SolvedWindow>& solved = estimator.solved_windows();
    if (!solved.empty()) Measure(solved);
    return UndistortForReplay(k1_, width_, height_, &kept_);
  }

  std::vector<FrameTracks> TakeFrames() { return std::move(kept_); }
  bool watching() const { return watching_; }
  double k1() const { return k1_; }
  bool focal_was_observable() const { return focal_was_observable_; }

 private:
  void Measure(const std::vector<SolvedWindow>& solved) {
    focal_was_observable_ = solved.front().focal_observable;
    nlohmann::json j = {{"method", "bundle"}, {"focal_observable", focal_was_observable_}};
    if (windows_ <= 1) {
      const LensBundleEstimate e = EstimateK1InWindow(solved.front(), width_, height_);
      j.update(LensBundleJson(e));
      k1_ = e.k1;
    } else {
      const LensAgreement a = EstimateK1InWindows(solved, width_, height_);
      j.update({{"k1", a.k1}, {"best_k1", a.pooled_k1}, {"sigma_k1", a.sigma}, {"spread_chi2", a.spread_chi2},
                {"spread_limit", a.spread_limit}, {"measuring_windows", a.measuring}, {"significant_windows", a.significant},
                {"same_sign", a.same_sign}});
      j["windows"] = nlohmann::json::array();
      for (const LensBundleEstimate& e : a.windows) j["windows"].push_back(LensBundleJson(e));
      k1_ = a.k1;
    }
    Record(diagnostics_, "lens_distortion", std::move(j));
  }

  bool watching_;
  int windows_;
  int width_, height_;
  Diagnostics* diagnostics_;
  std::vector<FrameTracks> kept_;
  double k1_ = 0;
  bool focal_was_observable_ = false;
};

// hold_focal: no window calibrates the focal (it stays at the prior).
// keep_windows: solved windows kept for the lens (lens_bundle.h).
std::unique_ptr<TrackCameraEstimator> NewEstimator(const EstimatorOptions& options, const VideoInfo& info,
                                                   bool hold_focal, int keep_windows, Diagnostics* diagnostics) {
  TrackEstimatorOptions o = StillsAware(options, info);
  if (hold_focal) o.min_rotation_for_focal_deg = std::numeric_limits<double>::infinity();
  o.keep_solved_windows = keep_windows;
  return std::make_unique<TrackCameraEstimator>(info.width, info.height, o, diagnostics);
}

// Tracking runs on its own thread, estimation (bundle-adjustment windows,
// which arrive in bursts) on this one, with a bounded queue of FrameTracks
// between them: on two cores the stages overlap instead of adding up. The
// frames are processed in the same order as in one thread, so the result
// is the same.
CameraPath TrackAndEstimate(FrameSource& source, const EstimatorOptions& options,
                            const ProgressFn& progress) {
  const VideoInfo& info = source.info();
  FeatureTracker tracker(StillsAware(options.tracker, info), options.diagnostics);
  // The estimator's records wait for the path's frame and shot numbers, and
  // the first estimator's window records for the lens decision.
  EstimatorRecords estimator_records(options.diagnostics);
  HeldWindowRecords first_run_records(&estimator_records);
  const bool measure_lens = options.lens_bundle || options.MeasuresLensFromPairs();
  std::unique_ptr<TrackCameraEstimator> estimator = NewEstimator(
      options, info, false, options.lens_bundle ? options.lens_bundle_windows : 0,
      measure_lens ? static_cast<Diagnostics*>(&first_run_records) : &estimator_records);
  // Which stage of the estimation thread is on the critical path after
  // tracking ends (docs/estimate.md "Speed").
  StageLog stages(options.diagnostics);
  BoundedQueue<FrameTracks> queue(kTrackQueueFrames);
  // --skip-nonref: the frames the decoder skipped (written by the tracking
  // thread, read after it ended), and the frame index of the estimator's
  // n-th frame: the estimator sees the decoded frames as consecutive.
  std::vector<SkippedFrame> skipped;
  std::vector<int> index_of_position;
  int last_index = -1;
  stages.Stage("tracking and estimation start");
  std::thread tracking([&] {
    try {
      Frame frame;
      while (source.Next(&frame)) {
        const int n = static_cast<int>(frame.skipped_before_s.size());
        for (int k = 0; k < n; ++k) skipped.push_back({frame.index - n + k, frame.skipped_before_s[k]});
        last_index = frame.index;
        if (!queue.Push(tracker.Process(frame))) return;  // the estimator gave up
      }
      for (double t : source.SkippedAtEnd()) skipped.push_back({++last_index, t});
      stages.Stage("tracking done");
      queue.Finish();
    } catch (...) {
      queue.Finish(std::current_exception());
    }
  });
  LensFromPairs lens_pairs(options.MeasuresLensFromPairs(), info.width, info.height,
                           options.diagnostics);
  LensFromWindows lens_bundle(options.lens_bundle, options.lens_bundle_windows, info.width, info.height,
                              options.diagnostics);
  // One source of k1 at most (EstimatorOptions::Check, MeasuresLensFromPairs).
  auto k1 = [&] { return options.lens_k1 + lens_pairs.k1() + lens_bundle.k1(); };
  // The estimation starts again on every frame so far, undistorted. hold_focal:
  // a focal the first window could not observe stays unobserved (undistorted,
  // a translating window's focal looks observable and is not, docs/estimate.md).
  auto replay = [&](std::vector<FrameTracks> frames, bool hold_focal) {
    first_run_records.Release(false);
    estimator = NewEstimator(options, info, hold_focal, 0, &estimator_records);
    for (const FrameTracks& t : frames) estimator->AddFrame(t);
  };
  auto estimate = [&](FrameTracks& tracks) {
    index_of_position.push_back(tracks.index);  // tracks.step keeps the gap
    tracks.index = static_cast<int>(index_of_position.size()) - 1;
    UndistortTracks(k1(), info.width, info.height, &tracks);
    estimator->AddFrame(tracks);
    if (lens_bundle.Watch(tracks, *estimator)) {
      replay(lens_bundle.TakeFrames(), !lens_bundle.focal_was_observable());
    } else if (lens_pairs.Watch(tracks)) {
      replay(lens_pairs.TakeFrames(), false);
    } else if (!lens_bundle.watching() && !lens_pairs.watching()) {
      first_run_records.Release(true);
    }
  };
  StillsRegrouper stills;  // stills shots linked across their splits: one shot (stills_groups.h)
  try {
    FrameTracks tracks;
    while (queue.Pop(&tracks)) {
      if (progress) progress(tracks.index + 1, info.frame_count);  // skipped frames count as done
      for (FrameTracks& ready : stills.Add(std::move(tracks))) estimate(ready);
    }
    for (FrameTracks& ready : stills.Finish()) estimate(ready);
    // A clip whose first shot is shorter than the pairs' frames: decided now,
    // before the last window is solved.
    if (lens_pairs.Decide()) replay(lens_pairs.TakeFrames(), false);
  } catch (...) {
    queue.Cancel();
    tracking.join();
    throw;
  }
  tracking.join();
  stages.Stage("all frames estimated, last window next");
  CameraPath path = estimator->Finish();
  if (lens_bundle.Decide(*estimator)) {  // a short clip: its windows closed only now
    replay(lens_bundle.TakeFrames(), !lens_bundle.focal_was_observable());
    path = estimator->Finish();
  }
  first_run_records.Release(true);  // no-op once released
  if (k1() != 0) path.metadata["k1"] = Num(k1());
  for (CameraFrame& f : path.frames) f.frame = index_of_position.at(f.frame);
  const std::map<int, int> shot_of_frame = ShotOfFrame(path);
  const std::vector<WindowReport> reports = stills.Restore(&path, estimator->reports());
  estimator_records.Release(index_of_position, ShotNumbers(shot_of_frame, ShotOfFrame(path)));
  InsertSkippedFrames(skipped, info.width, &path);
  WriteShotQuality(SummariseShots(path, reports, info.width), &path);
  stages.Stage("estimation done");
  return path;
}

}  // namespace

CameraPath EstimateCameraPath(FrameSource& source, const EstimatorOptions& options,
                              ProgressFn progress) {
  options.Check();
  const VideoInfo& info = source.info();
  if (info.width <= 0 || info.height <= 0) throw Error(info.path, "unknown frame size");
  CameraPath path;
  if (options.backend == "colmap") {
    path = EstimateWithColmap(source, options.colmap_binary, progress);
    WriteShotQuality(SummariseShots(path, {}, info.width), &path);
  } else {
    path = TrackAndEstimate(source, options, progress);
  }
  if (path.frames.empty()) throw Error(info.path, "no frames could be decoded");
  AddMetadata(source, options, &path);
  // Image sequences keep each image's number (docs/formats.md, `source_frame`).
  if (!info.source_frames.empty())
    for (const CameraFrame& f : path.frames)
      path.source_frames.push_back(f.frame >= 0 && f.frame < static_cast<int>(info.source_frames.size())
                                       ? OptionalInt(info.source_frames[f.frame])
                                       : OptionalInt());
  // Kept in the path's header, so the file itself says what the decoder lost.
  std::string warnings;
  for (const std::string& w : source.Warnings()) warnings += (warnings.empty() ? "" : "; ") + w;
  if (!warnings.empty()) path.metadata["warning"] = warnings;
  return path;
}

CameraPath EstimateCameraPathFromFile(const std::string& video, const EstimatorOptions& options,
                                      ProgressFn progress) {
  options.Check();
  FrameSourceOptions frames = options.frames;
  // Our backend looks at colour only through the shot detector's thumbnail
  // (COLMAP gets the working-size BGR images).
  if (options.backend == "hapcine" && frames.color_max_side == 0)
    frames.color_max_side = kShotThumbWidth;
  // Decoding and scaling overlap tracking and estimation (memory stays
  // flat: a few frames wait at most).
  ThreadedFrameSource source(OpenFrameSource(video, frames), kDecodeQueueFrames);
  return EstimateCameraPath(source, options, progress);
}

}  // namespace hapcine
