#include "estimate/track_estimator.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "core/error.h"
#include "core/rotation.h"
#include "core/statistics.h"
#include "estimate/geometry/border_support.h"
#include "estimate/geometry/smoothing.h"
#include "estimate/geometry/two_view_geometry.h"

namespace hapcine {

void TrackEstimatorOptions::Check() const {
  if (!(prior_hfov_deg > 1 && prior_hfov_deg < 179)) throw UsageError("prior FOV must be in (1, 179) degrees");
  if (window_frames < 10) throw UsageError("window must be at least 10 frames");
  if (!(blur_noise_per_speed >= 0 && blur_noise_per_speed <= 1))
    throw UsageError("blur noise must be in [0, 1] px per px/frame");
  if (max_points < 20) throw UsageError("max points must be at least 20");
  if (!(spread_points_factor >= 1 && spread_points_factor <= 10))
    throw UsageError("spread points factor must be in [1, 10]");
  if (point_grid_cells < 0) throw UsageError("point grid must be >= 0 cells");
  if (!(track_rms_cut_px > 0 && track_rms_cut_rotation_px > 0)) throw UsageError("track RMS cut must be > 0");
  if (!(keyframe_motion > 0 && keyframe_motion < 0.5)) throw UsageError("keyframe motion must be in (0, 0.5)");
  if (!(keyframe_min_shared > 0 && keyframe_min_shared < 1)) throw UsageError("keyframe min shared must be in (0, 1)");
  if (keyframe_max_gap < 1) throw UsageError("keyframe max gap must be >= 1");
  if (min_tracks < 8) throw UsageError("min tracks must be >= 8");
  if (!(min_rotation_for_focal_deg >= 0)) throw UsageError("min rotation for focal must be >= 0");
  if (!(smooth_sigma_frames >= 0 && smooth_sigma_frames <= 1000))
    throw UsageError("smoothing sigma must be in [0, 1000] frames");
  if (ba_iterations < 1) throw UsageError("BA iterations must be >= 1");
  if (num_threads < 1 || num_threads > 256) throw UsageError("threads must be in [1, 256]");
  two_view.Check();
  movers.Check();
}

namespace {

// OpenCV world/camera axes -> the file's OpenGL axes (flip Y and Z).
const Eigen::Matrix3d kFlip = Eigen::Vector3d(1, -1, -1).asDiagonal();

}  // namespace

namespace {

WindowOptions WindowOptionsOf(const TrackEstimatorOptions& o) {
  WindowOptions w;
  w.max_points = o.max_points;
  w.point_grid_cells = o.point_grid_cells;
  w.spread_points_factor = o.spread_points_factor;
  w.min_rotation_for_focal_deg = o.min_rotation_for_focal_deg;
  w.ba_iterations = o.ba_iterations;
  w.track_rms_cut_px = o.track_rms_cut_px;
  w.track_rms_cut_rotation_px = o.track_rms_cut_rotation_px;
  w.freedom_test = o.freedom_test;
  w.blur_noise_per_speed = o.blur_noise_per_speed;
  w.motion_plane_prior = o.motion_plane_prior;
  w.drift_weights = o.drift_weights;
  w.noise_floor = o.two_view.noise_floor;
  w.num_threads = o.num_threads;
  return w;
}

}  // namespace

TrackCameraEstimator::TrackCameraEstimator(int width, int height, const TrackEstimatorOptions& options,
                                           Diagnostics* diagnostics)
    : width_(width), height_(height), options_(options), diagnostics_(diagnostics) {
  options_.Check();
  window_options_ = WindowOptionsOf(options_);
  if (width <= 0 || height <= 0) throw UsageError("frame size must be positive");
  // Normalised focal = f_px / width.
  prior_log_focal_ = std::log(FocalPxFromFovDeg(options_.prior_hfov_deg, width) / width);
  path_.metadata["width"] = std::to_string(width);
  path_.metadata["height"] = std::to_string(height);
}

Eigen::Vector2d TrackCameraEstimator::Normalise(const Eigen::Vector2d& px) const {
  return (px - Eigen::Vector2d(0.5 * (width_ - 1), 0.5 * (height_ - 1))) / width_;
}

void TrackCameraEstimator::StartShot(int shot) {
  shot_ = shot;
  shot_frames_ = 0;
  shot_video_frames_ = 0;
  shot_of_stills_ = false;
  frames_.clear();
  buffer_start_ = 0;
  keyframes_.clear();
  raw_.clear();
  outlier_tracks_.clear();
  mover_intervals_.clear();
  focal_samples_.clear();
  focal_observed_ = false;
  scale_set_ = false;
  scene_depth_ = 1;
  split_log_focal_.reset();
  loop_keyframes_.clear();
  shot_windows_ = 0;
}

// The tracker started a new shot at `tracks` (another shot index, a cut or a fade).
bool TrackCameraEstimator::EndsTheShot(const FrameTracks& tracks) const {
  return tracks.shot != source_shot_ || tracks.boundary == ShotBoundary::kCut ||
         tracks.boundary == ShotBoundary::kFade;
}

void TrackCameraEstimator::AddFrame(const FrameTracks& tracks) {
  // A cut the tracker may yet withdraw (the picture continued) is held too.
  const bool cut = EndsTheShot(tracks);
  if (held_.empty() && !(tracks.bridging && cut && shot_ >= 0 && !keyframes_.empty())) {
    AddFrameNow(tracks);
  } else if (tracks.bridging) {
    held_.push_back(tracks);
  } else {
    ResolveHeld(&tracks);
  }
}

// The tracker bridged the break if `next` (none at the end) continues the
// last keyframe's tracks: the held frames placed nothing and are lost, the
// shot goes on. Otherwise they are added as they came: the shot splits
// where it broke, as it would have without the bridge.
void TrackCameraEstimator::ResolveHeld(const FrameTracks* next) {
  std::vector<FrameTracks> held = std::move(held_);
  held_.clear();
  if (next && ContinuesLastKeyframe(*next)) {
    for (FrameTracks& f : held) {
      f.points.clear();       // no usable tracks: lost
      f.shot = source_shot_;  // a cut held here was withdrawn: the same take
      f.boundary = ShotBoundary::kNone;
      AddFrameNow(f);
    }
  } else {
    replaying_held_ = true;
    for (const FrameTracks& f : held) AddFrameNow(f);
    replaying_held_ = false;
  }
  if (next) AddFrameNow(*next);
}

bool TrackCameraEstimator::ContinuesLastKeyframe(const FrameTracks& tracks) const {
  if (EndsTheShot(tracks) || tracks.blank || keyframes_.empty()) return false;
  KeyframeTracks u;
  for (const auto& p : tracks.points)
    if (p.px.allFinite()) u[p.track_id] = Normalise(p.px);
  return SharedWithLastKeyframe(u) >= options_.min_tracks;
}

void TrackCameraEstimator::AddFrameNow(const FrameTracks& tracks) {
  const bool new_shot = shot_ < 0 || EndsTheShot(tracks);
  if (new_shot) {
    const bool stills_split = SplitOfStills(tracks);
    if (shot_ >= 0) FinishShot();
    if (!stills_split) stills_log_focal_.reset();
    StartShot(shot_ < 0 ? tracks.shot : std::max(tracks.shot, shot_ + 1));
    source_shot_ = tracks.shot;
  }
  shot_of_stills_ = shot_of_stills_ || tracks.still;
  BufferedFrame f;
  f.tracks = tracks;
  f.tracks.points.clear();
  for (const auto& p : tracks.points) {
    if (p.px.allFinite()) f.u[p.track_id] = Normalise(p.px);
  }
  f.usable = !tracks.blank && static_cast<int>(f.u.size()) >= options_.min_tracks;
  if (f.usable && !keyframes_.empty() && SharedWithLastKeyframe(f.u) < options_.min_tracks) {
    if (tracks.bridging && !replaying_held_) {
      held_.push_back(tracks);  // the tracker may yet link a later frame across
      return;
    }
    if (keyframes_.size() > 1) {
      SplitShot(tracks);
      return;
    }
    RestartChain();
  }
  const int pos = shot_frames_++;
  // The keyframe gap and the window are counted in frames of the video, so a
  // decoder that skipped frames gives the same spacing in time.
  f.video_pos = pos == 0 ? 0 : shot_video_frames_ + std::max(tracks.step, 1);
  shot_video_frames_ = f.video_pos;
  frames_.push_back(std::move(f));
  const BufferedFrame& cur = frames_.back();
  if (!cur.usable) return;

  if (keyframes_.empty()) {
    AddKeyframe(pos, true);
    return;
  }
  const Keyframe& last = keyframes_.back();
  const BufferedFrame& kf = At(last.pos);
  std::vector<double> disp;
  for (const auto& [id, u] : cur.u) {
    auto it = kf.u.find(id);
    if (it != kf.u.end()) disp.push_back((u - it->second).norm());
  }
  const double shared = static_cast<double>(disp.size()) / std::max<size_t>(kf.u.size(), 1);
  if (Median(disp) > options_.keyframe_motion || shared < options_.keyframe_min_shared ||
      cur.video_pos - last.video_pos >= options_.keyframe_max_gap) {
    AddKeyframe(pos, false);
  }
}

int TrackCameraEstimator::SharedWithLastKeyframe(const KeyframeTracks& u) const {
  const BufferedFrame& kf = At(keyframes_.back().pos);
  int shared = 0;
  for (const auto& entry : u) shared += kf.u.count(entry.first) > 0;
  return shared;
}

// Nothing measures the motion from the last keyframe to this frame, so no
// pose after it can be put in the shot's frame: holding the last pose would
// say the camera stopped, continuing from it would hide a jump of unknown
// size. The frames in between are lost (EmitWindowFrames); this frame starts
// a new shot at the origin, as after a cut. The lens is the same (no cut was
// seen), so the new shot starts from the focal reached and keeps what was
// observed of it.
void TrackCameraEstimator::SplitShot(const FrameTracks& tracks) {
  const bool observed = focal_observed_;
  std::vector<double> samples = focal_samples_;
  FinishShot();
  StartShot(shot_ + 1);
  split_log_focal_ = last_log_focal_;
  focal_observed_ = observed && last_log_focal_.has_value();
  focal_samples_ = std::move(samples);
  AddFrame(tracks);
}

// The chain's first keyframe links to nothing after it: tracking broke again
// before any motion from it was measured (the blur of a handheld take, frame
// after frame). It placed nothing, so it does not make a shot of its own
// (a run of one-frame shots in a continuous take): its frames become the
// lost lead-in of a chain starting here, with the focal it started from.
void TrackCameraEstimator::RestartChain() {
  split_log_focal_ = keyframes_.front().cam.log_focal;
  keyframes_.clear();
}

void TrackCameraEstimator::AddKeyframe(int pos, bool first) {
  if (first) {
    // Start of the shot's chain: identity at the origin (after a split, at
    // the focal the previous shot reached).
    Keyframe k = ChainStart(pos);
    k.cam.log_focal = split_log_focal_.value_or(prior_log_focal_);
    k.cam.rotation_source = k.cam.center_source = k.cam.focal_source = -1;
    k.fixed_focal = split_log_focal_.has_value() && focal_observed_;
    split_log_focal_.reset();
    keyframes_.push_back(k);
    return;
  }
  keyframes_.push_back(LinkedKeyframe(keyframes_.back(), pos));
  // The window's own frames start at its last held keyframe (the lead-in before it is decided).
  size_t held = 0;
  while (held + 1 < keyframes_.size() && keyframes_[held + 1].fixed) ++held;
  if (keyframes_.back().video_pos - keyframes_[held > 0 ? held - 1 : 0].video_pos >= options_.window_frames &&
      keyframes_.size() >= std::max<size_t>(4, held + 3)) {
    ProcessWindow(false);
  }
}

TrackCameraEstimator::Keyframe TrackCameraEstimator::ChainStart(int pos) const {
  Keyframe k;
  k.pos = pos;
  k.video_pos = At(pos).video_pos;
  k.fixed = true;
  k.chain_start = true;
  return k;
}

// The keyframe at `pos` after `a`: the two-view model of the interval
// (model_selection.h) and the pose it gives; a translation is scaled so
// that the triangulated median depth in view a matches the scene depth so
// far. Its outlier tracks are kept out of the window's points.
TrackCameraEstimator::Keyframe TrackCameraEstimator::LinkedKeyframe(const Keyframe& a, int pos) {
  Keyframe k;
  k.pos = pos;
  k.video_pos = At(pos).video_pos;
  const BufferedFrame& fa = At(a.pos);
  const BufferedFrame& fb = At(pos);
  std::vector<long> ids;
  std::vector<Eigen::Vector2d> u1, u2;
  for (const auto& [id, u] : fb.u) {
    auto it = fa.u.find(id);
    if (it == fa.u.end()) continue;
    ids.push_back(id);
    u1.push_back(it->second);
    u2.push_back(u);
  }
  const double fa_norm = std::exp(a.cam.log_focal);
  const CameraMotion motion =
      SelectCameraMotion(u1, u2, fa_norm, 0.5 * height_ / width_, options_.two_view, options_.movers);
  const TwoViewResult& tv = motion.camera;
  k.cam = a.cam;
  k.cam.rotation_source = k.cam.center_source = k.cam.focal_source = -1;
  if (!tv.valid) {
    k.model = MotionModel::kStatic;
    k.inlier_ratio = 0;
    return k;
  }
  for (size_t i = 0; i < ids.size(); ++i) {
    if (motion.border_motion && motion.mover[i]) {
      ++mover_intervals_[ids[i]].first;
    } else if (!tv.inliers[i]) {
      outlier_tracks_.insert(ids[i]);
    } else {
      ++mover_intervals_[ids[i]].second;
    }
  }
  k.model = tv.model;
  // Movers are no sign of a poor fit: the ratio is over the tracks that are not theirs.
  const int candidates = tv.num_points - motion.movers;
  k.inlier_ratio = candidates > 0 ? static_cast<double>(tv.num_inliers) / candidates : 0;
  k.two_view_model = tv.model;
  k.correspondences = tv.num_points;
  k.inliers = tv.num_inliers;
  k.gric = tv.gric;
  if (tv.model != MotionModel::kStatic) {
    std::vector<Eigen::Vector2d> mid(u1.size());
    for (size_t i = 0; i < u1.size(); ++i) mid[i] = 0.5 * (u1[i] + u2[i]);
    k.border_support = BorderSupport(mid, tv.inliers, 0.5 * height_ / width_);
    k.border_still = StillBorderTracks(tv, u1, u2, TwoViewThreshold(tv, options_.two_view),
                                       0.5 * height_ / width_, options_.movers.border_radius);
  }
  const Eigen::Matrix3d R_ba = tv.cam2_from_cam1;
  const Eigen::Matrix3d R_wa = a.cam.world_from_cam.toRotationMatrix();
  k.cam.world_from_cam = Eigen::Quaterniond(R_wa * R_ba.transpose()).normalized();
  if (HasZoom(tv.model)) k.cam.log_focal = a.cam.log_focal + std::log(tv.f2 / tv.f1);
  if (tv.model == MotionModel::kRotation || tv.model == MotionModel::kRotationZoom) {
    if (OpticalAxisAngleDeg(Eigen::Quaterniond(R_ba), Eigen::Quaterniond::Identity()) >=
        options_.min_rotation_for_focal_deg)
      focal_samples_.push_back(std::log(tv.f1));
  }
  if (!HasTranslation(tv.model)) return k;
  std::vector<double> depths;
  for (size_t i = 0; i < u1.size(); ++i) {
    if (!tv.inliers[i]) continue;
    const double d = TriangulateDepth(u1[i] / fa_norm, u2[i] / fa_norm, R_ba, tv.translation);
    if (d > 0 && std::isfinite(d)) depths.push_back(d);
  }
  const double med = Median(depths);
  const double scale = med > 0 ? scene_depth_ / med : 0.05 * scene_depth_;
  const Eigen::Vector3d centre_b_in_a = -R_ba.transpose() * tv.translation;
  k.cam.center = a.cam.center + R_wa * centre_b_in_a * scale;
  return k;
}

TrackCameraEstimator::RawPose TrackCameraEstimator::LostPose(const FrameTracks& meta,
                                                             const BaCamera& placeholder) const {
  RawPose out;
  out.meta = meta;
  out.cam = placeholder;
  out.lost = true;
  out.confidence = 0;
  return out;
}

// Stills split where no view links (DecideBoundary leaves the stills' cuts to
// the descriptor link), not where the picture cut: the same footage.
bool TrackCameraEstimator::SplitOfStills(const FrameTracks& tracks) const {
  return shot_ >= 0 && shot_of_stills_ && tracks.still && tracks.boundary == ShotBoundary::kCut;
}

// A still linked to no other view (a shot of one view) has nothing to
// observe its focal with: the lens the stills before it calibrated (the
// same footage, no cut seen) is a better guess than the prior. Not for
// shots of several views: their start sits in their own basin (a focal
// carried into a short shot of stills moved it into a worse one,
// docs/estimate.md).
void TrackCameraEstimator::BorrowStillsFocal() {
  const bool one_view = shot_frames_ == 1 && keyframes_.size() == 1 && raw_.empty();
  if (one_view && shot_of_stills_ && stills_log_focal_) keyframes_.front().cam.log_focal = *stills_log_focal_;
}

// The focal stills footage calibrated, kept for the next stills shot.
void TrackCameraEstimator::KeepStillsFocal() {
  if (shot_of_stills_ && focal_observed_ && last_log_focal_) stills_log_focal_ = last_log_focal_;
}

void TrackCameraEstimator::FinishShot() {
  if (shot_ < 0) return;
  if (!keyframes_.empty()) {
    BorrowStillsFocal();
    ProcessWindow(true);
    if (options_.loop_bundle) AdjustShotLoop();
    if (options_.movers.enabled && BorderStaysStill()) HoldStillBeforeMover();
  } else {
    // No usable frame in the whole shot: nothing is placed; the placeholder
    // is the origin at the prior focal.
    BaCamera origin;
    origin.log_focal = prior_log_focal_;
    for (const auto& f : frames_) raw_.push_back(LostPose(f.tracks, origin));
  }
  keyframes_.clear();
  frames_.clear();
  const int n = static_cast<int>(raw_.size());
  std::vector<Eigen::Quaterniond> q(n);
  std::vector<Eigen::Vector3d> c(n);
  std::vector<double> lf(n);
  for (int i = 0; i < n; ++i) {
    q[i] = raw_[i].cam.world_from_cam;
    c[i] = raw_[i].cam.center;
    lf[i] = raw_[i].cam.log_focal;
  }
  // Stills are whole steps apart: a Gaussian over frames would blur one
  // view's pose into its neighbours'.
  if (options_.smooth && options_.smooth_sigma_frames > 0 && !shot_of_stills_) SmoothShot(&q, &c, &lf);
  HoldPlaceholders(&q, &c, &lf);
  last_log_focal_.reset();
  for (int i = 0; i < n; ++i) {
    const RawPose& r = raw_[i];
    if (!r.lost) last_log_focal_ = lf[i];
    CameraFrame cf;
    cf.frame = r.meta.index;
    cf.time_s = r.meta.time_s;
    const Eigen::Matrix3d R_cv = q[i].normalized().toRotationMatrix();
    cf.world_from_cam = CanonicalQuaternion(Eigen::Quaterniond(kFlip * R_cv * kFlip));
    cf.center = kFlip * c[i] + Eigen::Vector3d::Zero();  // + 0 turns -0 into 0
    cf.center = cf.center.unaryExpr([](double v) { return v == 0 ? 0.0 : v; });
    const double focal_px = std::exp(lf[i]) * width_;
    cf.focal_px = focal_px;
    cf.fov_deg = FovDegFromFocalPx(focal_px, width_);
    cf.shot = shot_;
    cf.model = r.lost ? kLostModel : MotionModelName(r.model);
    cf.confidence = r.lost ? 0.0 : Clamp01(r.confidence);
    path_.frames.push_back(cf);
  }
  raw_.clear();
  KeepStillsFocal();
}

// The still-border rule (StillBorderAroundMotion) over the keyframe
// intervals the shot's windows reported (the shot's reports are the last).
bool TrackCameraEstimator::BorderStaysStill() const {
  std::vector<double> support;
  std::vector<StillBorder> border;
  for (auto r = reports_.rbegin(); r != reports_.rend() && r->shot == shot_; ++r) {
    support.insert(support.end(), r->border_support.begin(), r->border_support.end());
    border.insert(border.end(), r->border_still.begin(), r->border_still.end());
  }
  return StillBorderAroundMotion(support, border);
}

// Why the origin: a still camera stays where the shot started, at the
// focal it started with (a subject's motion observes no focal either).
void TrackCameraEstimator::HoldStillBeforeMover() {
  const auto origin =
      std::find_if(raw_.begin(), raw_.end(), [](const RawPose& r) { return !r.lost; });
  if (origin == raw_.end()) return;
  const BaCamera still = origin->cam;
  for (RawPose& r : raw_) {
    if (r.lost) continue;
    r.cam = still;
    r.model = MotionModel::kStatic;
  }
  if (!reports_.empty() && reports_.back().shot == shot_) reports_.back().shot_held_still = true;
}

// A lost frame's pose is the last placed pose as written (after smoothing);
// before the first placed frame of the shot, that frame's (the origin).
void TrackCameraEstimator::HoldPlaceholders(std::vector<Eigen::Quaterniond>* q, std::vector<Eigen::Vector3d>* c,
                                            std::vector<double>* lf) const {
  const int n = static_cast<int>(raw_.size());
  int placed = -1;
  for (int i = 0; i < n && placed < 0; ++i)
    if (!raw_[i].lost) placed = i;
  if (placed < 0) return;
  for (int i = 0; i < n; ++i) {
    if (!raw_[i].lost) {
      placed = i;
      continue;
    }
    (*q)[i] = (*q)[placed];
    (*c)[i] = (*c)[placed];
    (*lf)[i] = (*lf)[placed];
  }
}

// Zero-phase smoothing per segment of equal model, only on the freedoms the
// segment's model has. Lost frames are neither smoothed nor used as a
// segment's neighbours: their placeholder pose is no measurement, and
// blending it in would pull placed frames towards the pose before the gap.
// A jump (FrameTracks::jump) ends a segment too, and its two sides are not
// each other's neighbours: the filter assumes a path continuous at the scale
// of a frame, and blurring a step spreads it over the frames either side.
void TrackCameraEstimator::SmoothShot(std::vector<Eigen::Quaterniond>* q, std::vector<Eigen::Vector3d>* c,
                                      std::vector<double>* lf) const {
  const int n = static_cast<int>(raw_.size());
  // The sigma is in frames of the video: where the decoder skipped frames
  // (FrameTracks::step) a sample stands for more than one, and a sigma in
  // samples would smooth over more time and lag the fast parts (with
  // every other frame, a sideways traveling's ATE was 0.12 % instead of
  // 0.06 %).
  double video_frames = 0;
  for (int i = 1; i < n; ++i) video_frames += std::max(raw_[i].meta.step, 1);
  const double sigma = n > 1 ? options_.smooth_sigma_frames / (video_frames / (n - 1))
                             : options_.smooth_sigma_frames;
  for (int s = 0; s < n;) {
    int e = s;
    while (e + 1 < n && raw_[e + 1].model == raw_[s].model && raw_[e + 1].lost == raw_[s].lost &&
           !raw_[e + 1].meta.jump)
      ++e;
    const MotionModel m = raw_[s].model;
    const bool lost = raw_[s].lost;
    // Include the neighbour frames so that segment ends stay continuous.
    const int lo = s > 0 && !raw_[s - 1].lost && !raw_[s].meta.jump ? s - 1 : s;
    const int hi = e + 1 < n && !raw_[e + 1].lost && !raw_[e + 1].meta.jump ? e + 1 : e;
    auto sub = [&](auto& v) { return std::vector<std::decay_t<decltype(v[0])>>(v.begin() + lo, v.begin() + hi + 1); };
    if (!lost && HasRotation(m)) {
      const auto sm = SmoothRotations(sub(*q), sigma);
      for (int i = s; i <= e; ++i) (*q)[i] = sm[i - lo];
    }
    if (!lost && HasTranslation(m)) {
      const auto sm = SmoothVectors(sub(*c), sigma);
      for (int i = s; i <= e; ++i) (*c)[i] = sm[i - lo];
    }
    if (!lost && HasZoom(m)) {
      const auto sm = SmoothScalars(sub(*lf), sigma);
      for (int i = s; i <= e; ++i) (*lf)[i] = sm[i - lo];
    }
    s = e + 1;
  }
}

CameraPath TrackCameraEstimator::Finish() {
  if (!held_.empty()) ResolveHeld(nullptr);
  FinishShot();
  shot_ = -1;
  return path_;
}

}  // namespace hapcine
