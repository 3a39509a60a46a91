#include "estimate/track_estimator.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <future>
#include <limits>
#include <utility>

#include "core/error.h"
#include "core/rotation.h"
#include "core/statistics.h"
#include "estimate/axial_ambiguity.h"
#include "estimate/point_selection.h"
#include "estimate/smoothing.h"
#include "estimate/stage_timing.h"
#include "estimate/two_view_geometry.h"
#include "estimate/window_freedoms.h"

namespace hapcine {

void TrackEstimatorOptions::Check() const {
  if (!(prior_hfov_deg > 1 && prior_hfov_deg < 179)) throw UsageError("prior FOV must be in (1, 179) degrees");
  if (window_frames < 10) throw UsageError("window must be at least 10 frames");
  if (max_points < 20) throw UsageError("max points must be at least 20");
  if (!(spread_points_factor >= 1 && spread_points_factor <= 10))
    throw UsageError("spread points factor must be in [1, 10]");
  if (point_grid_cells < 0) throw UsageError("point grid must be >= 0 cells");
  if (!(track_rms_cut_px > 0 && track_rms_cut_rotation_px > 0)) throw UsageError("track RMS cut must be > 0");
  if (window_lead_in_frames < 0 || window_lead_in_frames >= window_frames)
    throw UsageError("window lead-in must be in [0, window frames)");
  if (!(keyframe_motion > 0 && keyframe_motion < 0.5)) throw UsageError("keyframe motion must be in (0, 0.5)");
  if (!(keyframe_min_shared > 0 && keyframe_min_shared < 1)) throw UsageError("keyframe min shared must be in (0, 1)");
  if (keyframe_max_gap < 1) throw UsageError("keyframe max gap must be >= 1");
  if (min_tracks < 8) throw UsageError("min tracks must be >= 8");
  if (!(min_rotation_for_focal_deg >= 0)) throw UsageError("min rotation for focal must be >= 0");
  if (!(smooth_sigma_frames >= 0)) throw UsageError("smoothing sigma must be >= 0");
  if (ba_iterations < 1) throw UsageError("BA iterations must be >= 1");
  if (num_threads < 1) throw UsageError("threads must be >= 1");
  two_view.Check();
}

namespace {

// Angle between the optical axes (roll about the axis does not count: it
// does not tell the focal length).
double AxisAngleDeg(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  const Eigen::Vector3d za = a * Eigen::Vector3d::UnitZ(), zb = b * Eigen::Vector3d::UnitZ();
  return RadToDeg(std::acos(std::clamp(za.dot(zb), -1.0, 1.0)));
}

// OpenCV world/camera axes -> the file's OpenGL axes (flip Y and Z).
const Eigen::Matrix3d kFlip = Eigen::Vector3d(1, -1, -1).asDiagonal();

double Clamp01(double v) { return std::isfinite(v) ? std::clamp(v, 0.0, 1.0) : 0.0; }

}  // namespace

TrackCameraEstimator::TrackCameraEstimator(int width, int height,
                                           const TrackEstimatorOptions& options)
    : width_(width), height_(height), options_(options) {
  options_.Check();
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
  frames_.clear();
  buffer_start_ = 0;
  keyframes_.clear();
  raw_.clear();
  outlier_tracks_.clear();
  focal_samples_.clear();
  focal_observed_ = false;
  scale_set_ = false;
  scene_depth_ = 1;
}

void TrackCameraEstimator::AddFrame(const FrameTracks& tracks) {
  const bool new_shot = shot_ < 0 || tracks.shot != shot_ ||
                        tracks.boundary == ShotBoundary::kCut ||
                        tracks.boundary == ShotBoundary::kFade;
  if (new_shot) {
    if (shot_ >= 0) FinishShot();
    StartShot(shot_ < 0 ? tracks.shot : std::max(tracks.shot, shot_ + 1));
  }
  BufferedFrame f;
  f.tracks = tracks;
  f.tracks.points.clear();
  for (const auto& p : tracks.points) {
    if (p.px.allFinite()) f.u[p.track_id] = Normalise(p.px);
  }
  f.usable = !tracks.blank && static_cast<int>(f.u.size()) >= options_.min_tracks;
  const int pos = shot_frames_++;
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
  if (static_cast<int>(disp.size()) < options_.min_tracks) {
    // Tracking lost inside the shot: close what we have and restart the
    // chain here, holding the last pose (no link to measure the jump).
    AddKeyframe(pos, true);
    return;
  }
  const double shared = static_cast<double>(disp.size()) / std::max<size_t>(kf.u.size(), 1);
  if (Median(disp) > options_.keyframe_motion || shared < options_.keyframe_min_shared ||
      pos - last.pos >= options_.keyframe_max_gap) {
    AddKeyframe(pos, false);
  }
}

void TrackCameraEstimator::AddKeyframe(int pos, bool force_static) {
  Keyframe k;
  k.pos = pos;
  if (keyframes_.empty()) {
    // Start of the shot's chain: identity at the origin (or the last pose).
    k.cam.log_focal = prior_log_focal_;
    if (!raw_.empty()) k.cam = raw_.back().cam;
    k.cam.rotation_source = k.cam.center_source = k.cam.focal_source = -1;
    k.fixed = true;
    k.chain_start = true;
    keyframes_.push_back(k);
    return;
  }
  const Keyframe& a = keyframes_.back();
  if (force_static) {
    // Chain broken: solve what we have, then restart from here.
    ProcessWindow(true);
    keyframes_.clear();
    frames_.erase(frames_.begin(), frames_.begin() + (pos - buffer_start_));
    buffer_start_ = pos;
    k.cam = raw_.empty() ? BaCamera{} : raw_.back().cam;
    k.cam.rotation_source = k.cam.center_source = k.cam.focal_source = -1;
    k.fixed = true;
    k.fixed_focal = focal_observed_;
    k.chain_start = true;
    k.chain_start = true;
    keyframes_.push_back(k);
    return;
  }
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
  const TwoViewResult tv = SelectTwoViewModel(u1, u2, fa_norm, options_.two_view);
  k.cam = a.cam;
  k.cam.rotation_source = k.cam.center_source = k.cam.focal_source = -1;
  if (!tv.valid) {
    k.model = MotionModel::kStatic;
    k.inlier_ratio = 0;
    keyframes_.push_back(k);
    return;
  }
  for (size_t i = 0; i < ids.size(); ++i)
    if (!tv.inliers[i]) outlier_tracks_.insert(ids[i]);
  k.model = tv.model;
  k.inlier_ratio = tv.num_points ? static_cast<double>(tv.num_inliers) / tv.num_points : 0;
  const Eigen::Matrix3d R_ba = tv.cam2_from_cam1;
  const Eigen::Matrix3d R_wa = a.cam.world_from_cam.toRotationMatrix();
  k.cam.world_from_cam = Eigen::Quaterniond(R_wa * R_ba.transpose()).normalized();
  if (HasZoom(tv.model)) k.cam.log_focal = a.cam.log_focal + std::log(tv.f2 / tv.f1);
  if (tv.model == MotionModel::kRotation || tv.model == MotionModel::kRotationZoom) {
    if (AxisAngleDeg(Eigen::Quaterniond(R_ba), Eigen::Quaterniond::Identity()) >=
        options_.min_rotation_for_focal_deg)
      focal_samples_.push_back(std::log(tv.f1));
  }
  if (HasTranslation(tv.model)) {
    // Scale: triangulated median depth in view a matches the scene depth so far.
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
  }
  keyframes_.push_back(k);
  // The window's own frames start at its last held keyframe (the lead-in before it is decided).
  size_t held = 0;
  while (held + 1 < keyframes_.size() && keyframes_[held + 1].fixed) ++held;
  if (pos - keyframes_[held > 0 ? held - 1 : 0].pos >= options_.window_frames &&
      keyframes_.size() >= std::max<size_t>(4, held + 3)) {
    ProcessWindow(false);
  }
}

void TrackCameraEstimator::ProcessWindow(bool final) {
  if (keyframes_.empty()) return;
  const int n = static_cast<int>(keyframes_.size());
  LogStage("window: keyframes", n);
  WindowReport report;
  report.shot = shot_;
  report.keyframes = n;
  report.first_frame = At(keyframes_.front().pos).tracks.index;
  report.freedoms_dropped = std::exchange(freedoms_dropped_, false);

  // --- labels: promote short runs between two more general equal neighbours.
  for (int i = 1; i < n; ++i) {
    if (keyframes_[i].fixed) continue;
    for (int len = 1; len <= 2 && i + len < n; ++len) {
      const MotionModel left = keyframes_[i - 1].model, right = keyframes_[i + len].model;
      if (keyframes_[i - 1].chain_start) break;  // it has no interval of its own
      bool run_same = true;
      for (int j = i; j < i + len; ++j) run_same &= keyframes_[j].model == keyframes_[i].model;
      if (run_same && left == right && left != keyframes_[i].model &&
          IsAtLeastAsGeneral(left, keyframes_[i].model)) {
        for (int j = i; j < i + len; ++j) keyframes_[j].model = left;
        break;
      }
    }
  }

  // --- cameras with the models' sharing.
  auto build_cameras = [&](bool zoom_in_general) {
    std::vector<BaCamera> cams(n);
    for (int i = 0; i < n; ++i) {
      cams[i] = keyframes_[i].cam;
      cams[i].fixed = keyframes_[i].fixed;
      cams[i].fixed_focal = keyframes_[i].fixed_focal;
      cams[i].rotation_source = cams[i].center_source = cams[i].focal_source = -1;
      if (i == 0 || keyframes_[i].fixed) continue;
      MotionModel m = keyframes_[i].model;
      if (zoom_in_general && m == MotionModel::kGeneral) m = MotionModel::kGeneralZoom;
      if (!HasRotation(m)) cams[i].rotation_source = i - 1;
      if (!HasTranslation(m)) cams[i].center_source = i - 1;
      if (!HasZoom(m)) cams[i].focal_source = i - 1;
    }
    // Shared blocks start from the source's value.
    for (int i = 1; i < n; ++i) {
      if (cams[i].rotation_source >= 0) cams[i].world_from_cam = cams[i - 1].world_from_cam;
      if (cams[i].center_source >= 0) cams[i].center = cams[i - 1].center;
      if (cams[i].focal_source >= 0) cams[i].log_focal = cams[i - 1].log_focal;
    }
    return cams;
  };
  bool has_translation = false, has_general = false;
  for (int i = 1; i < n; ++i) {
    has_translation |= HasTranslation(keyframes_[i].model);
    has_general |= keyframes_[i].model == MotionModel::kGeneral && !keyframes_[i].fixed;
  }
  // Focal initialisation from rotation pairs that turned enough (first window only).
  if (!focal_observed_ && !focal_samples_.empty() && keyframes_[0].pos == 0 && !keyframes_[1 < n ? 1 : 0].fixed) {
    const double shift = Median(focal_samples_) - keyframes_[0].cam.log_focal;
    for (auto& k : keyframes_) k.cam.log_focal += shift;
  }
  double max_turn = 0;
  for (const auto& k : keyframes_)
    max_turn = std::max(max_turn, AxisAngleDeg(k.cam.world_from_cam, keyframes_[0].cam.world_from_cam));
  const bool focal_observable = focal_observed_ || max_turn >= options_.min_rotation_for_focal_deg;
  report.focal_observable = focal_observable;

  // --- points: tracks seen by >= 2 keyframes, spread over the image
  // (point_selection.h), longest first within an image cell.
  std::map<long, std::vector<int>> seen;  // track -> keyframes
  for (int i = 0; i < n; ++i)
    for (const auto& [id, u] : At(keyframes_[i].pos).u)
      if (!outlier_tracks_.count(id)) seen[id].push_back(i);
  std::vector<TrackCandidate> candidates;
  for (const auto& [id, kfs] : seen)
    if (kfs.size() >= 2)
      candidates.push_back({id, static_cast<int>(kfs.size()), At(keyframes_[kfs[kfs.size() / 2]].pos).u.at(id)});
  // Only where the camera translates, and not along the optical axis:
  // without parallax an occlusion edge does not slide (every track is rigid,
  // the longest are best), and along the axis the tracks in front of the
  // subject decide the dolly/zoom branch (see drop_bad_tracks below).
  std::vector<BaCamera> initial(n);
  for (int i = 0; i < n; ++i) initial[i] = keyframes_[i].cam;
  // The last held keyframe (the window's fixed lead-in): the motion before it
  // is decided, so the axial tests below look only after it.
  int held = 0;
  while (held + 1 < n && keyframes_[held + 1].fixed) ++held;
  const bool spread_points = has_translation && !IsAxialMotion(initial, held);
  std::vector<std::pair<int, long>> order;
  // Where the grid spreads the points, the whole-track cut below also drops
  // the occlusion-edge corners (a third or more of the tracks near
  // silhouettes) and the good tracks the first, bent solve puts far: take
  // more there, so that about `max_points` rigid ones remain.
  const int window_points =
      spread_points ? static_cast<int>(std::lround(options_.max_points * options_.spread_points_factor))
                    : options_.max_points;
  for (long id : SelectWindowTracks(std::move(candidates), window_points,
                                    spread_points ? options_.point_grid_cells : 0))
    order.push_back({-static_cast<int>(seen[id].size()), id});

  // Point k is the track order[k] in every candidate reconstruction.
  std::map<long, int> point_of_track;
  for (size_t k = 0; k < order.size(); ++k) point_of_track[order[k].second] = static_cast<int>(k);
  // Points from the cameras' initial poses: anchored at the first keyframe
  // that sees them, depth by midpoint triangulation with the most distant one.
  // Reads only (it runs on two threads at once in general windows, below).
  auto init_points = [&](const std::vector<BaCamera>& cams, std::vector<BaPoint>* points_out,
                         std::vector<BaObservation>* obs_out) {
    std::vector<BaPoint>& points = *points_out;
    std::vector<BaObservation>& obs = *obs_out;
    points.clear();
    obs.clear();
    for (const auto& [neg, id] : order) {
      const auto& kfs = seen.at(id);
      const BaCamera& ca = cams[kfs[0]];
      const Eigen::Vector2d ua = At(keyframes_[kfs[0]].pos).u.at(id);
      const double fa = std::exp(ca.log_focal);
      const Eigen::Vector3d ray_a = (ca.world_from_cam * Eigen::Vector3d(ua.x() / fa, ua.y() / fa, 1)).normalized();
      double rho = 0;
      if (has_translation) {
        // Midpoint triangulation with the most distant observing keyframe.
        int best = -1;
        double best_base = 0;
        for (int j : kfs) {
          const double base = (cams[j].center - ca.center).norm();
          if (base > best_base) {
            best_base = base;
            best = j;
          }
        }
        if (best >= 0) {
          const BaCamera& cb = cams[best];
          const Eigen::Vector2d ub = At(keyframes_[best].pos).u.at(id);
          const double fb = std::exp(cb.log_focal);
          const Eigen::Vector3d ray_b = (cb.world_from_cam * Eigen::Vector3d(ub.x() / fb, ub.y() / fb, 1)).normalized();
          const Eigen::Vector3d w = cb.center - ca.center;
          const double bb = ray_a.dot(ray_b), d1 = ray_a.dot(w), d2 = ray_b.dot(w);
          const double den = 1 - bb * bb;
          if (den > 1e-8) {
            const double lambda = (d1 - bb * d2) / den;
            if (lambda > 0 && std::isfinite(lambda)) rho = 1 / lambda;
          }
        }
        if (!(rho > 0)) rho = 0.2 / scene_depth_;
      }
      BaPoint p;
      p.anchor = ca.center;
      p.homogeneous = Eigen::Vector4d(ray_a.x(), ray_a.y(), ray_a.z(), rho).normalized();
      for (int j : kfs) obs.push_back({j, static_cast<int>(points.size()), At(keyframes_[j].pos).u.at(id)});
      points.push_back(p);
    }
  };
  std::vector<BaCamera> cams = build_cameras(false);
  std::vector<BaPoint> points;
  std::vector<BaObservation> obs;
  init_points(cams, &points, &obs);

  BaOptions ba;
  ba.huber_scale = 1.0 / 960;
  ba.focal_prior_log = prior_log_focal_;
  ba.fix_first_focal = !focal_observable;
  ba.use_depth = has_translation;
  ba.max_iterations = options_.ba_iterations;
  ba.num_threads = options_.num_threads;
  // Scale gauge: unless two fixed keyframes with distinct centres pin it.
  const bool scale_pinned = n >= 2 && keyframes_[0].fixed && keyframes_[1].fixed &&
                            (cams[1].center - cams[0].center).norm() > 1e-9;
  if (has_translation && !scale_pinned) {
    for (int i = 1; i < n; ++i) {
      if (HasTranslation(keyframes_[i].model)) {
        const double d = (cams[i].center - cams[i - 1].center).norm();
        if (d > 1e-9) {
          ba.scale_a = i - 1;
          ba.scale_b = i;
          ba.scale_distance = d;
        }
        break;
      }
    }
  }

  // Re-solves on a reduced set of observations, from the current (already
  // close) estimate with a third of the iterations; a success updates the
  // summary's RMS and observation count. Every cut below ends with it.
  auto polish_with = [](const BaOptions& opts, std::vector<BaCamera>* c, std::vector<BaPoint>* p,
                        const std::vector<BaObservation>& o, BaSummary* s) {
    BaOptions polish = opts;
    polish.max_iterations = std::max(5, opts.max_iterations / 3);
    const BaSummary s2 = SolveBundle(c, p, o, polish);
    if (s2.success) {
      s->rms_after = s2.rms_after;
      s->num_observations = s2.num_observations;
    }
  };
  auto polish_on = [&](std::vector<BaCamera>* c, std::vector<BaPoint>* p, const std::vector<BaObservation>& o,
                       BaSummary* s) { polish_with(ba, c, p, o, s); };
  auto solve_with = [&](const BaOptions& opts, std::vector<BaCamera>* c, std::vector<BaPoint>* p,
                        std::vector<BaObservation>* o) {
    // The first solve stops at a 1e-4 relative decrease of the cost: with the
    // outliers still in, its last iterations creep (~1e-5 a step, the Huber
    // loss's linear convergence; 40 iterations without converging on the
    // first window of the 1080p traveling) towards a fit the polish below
    // redoes without them. Without a polish it continues to the usual tolerance.
    BaOptions first = opts;
    first.function_tolerance = 1e-4;
    BaSummary s = SolveBundle(c, p, *o, first);
    if (!s.success) return s;
    // Drop outliers (beyond 1.5 Huber scales, ~1.5 px at 960 px) and
    // polish (the whole-track test below comes after the model choice).
    const auto errs = ObservationErrors(*c, *p, *o, opts.use_depth);
    std::vector<BaObservation> kept;
    for (size_t i = 0; i < o->size(); ++i)
      if (std::isfinite(errs[i]) && errs[i] < 1.5 * opts.huber_scale) kept.push_back((*o)[i]);
    const bool polish_follows = kept.size() < o->size() && kept.size() > 10;
    if (!polish_follows && first.function_tolerance != opts.function_tolerance) {
      BaOptions rest = opts;
      rest.max_iterations = std::max(1, opts.max_iterations - s.iterations + 1);
      const BaSummary s3 = SolveBundle(c, p, *o, rest);
      if (s3.success) s.rms_after = s3.rms_after;
    }
    if (polish_follows) {
      *o = kept;
      polish_with(opts, c, p, *o, &s);
    }
    return s;
  };
  auto solve = [&](std::vector<BaCamera>* c, std::vector<BaPoint>* p, std::vector<BaObservation>* o) {
    return solve_with(ba, c, p, o);
  };
  // The tight cut is for windows with parallax throughout: where a few
  // intervals among rotation read as general (the blur of a whip pan), the
  // tracks' RMS is mostly tracking noise, as without translation.
  int translating = 0, free_keyframes = 0;
  for (int i = 1; i < n; ++i) {
    if (keyframes_[i].fixed) continue;
    ++free_keyframes;
    translating += HasTranslation(keyframes_[i].model);
  }
  const bool mostly_translating = has_translation && 2 * translating >= free_keyframes;
  // Tracks between two depth layers (depth_layers.h) under the solution the
  // RMS cut left: corners sliding along a silhouette that fit a rigid point
  // at an in-between depth, which the RMS cannot see. The tracks the RMS cut
  // dropped are no one's neighbours (they are often such corners too).
  auto drop_between_layers = [&](std::vector<BaCamera>* c, std::vector<BaPoint>* p,
                                 std::vector<BaObservation>* o, BaSummary* s) {
    std::vector<char> kept_point(p->size(), 0);
    for (const auto& ob : *o) kept_point[ob.point] = 1;
    std::vector<long> track_of_point(p->size(), -1);
    std::set<long> dropped;
    for (const auto& [id, k] : point_of_track) {
      track_of_point[k] = id;
      if (!kept_point[k]) dropped.insert(id);
    }
    const std::set<long> between = TracksBetweenLayersOf(*c, dropped);
    std::vector<BaObservation> kept;
    for (const auto& ob : *o)
      if (!between.count(track_of_point[ob.point])) kept.push_back(ob);
    if (kept.size() == o->size() || kept.size() <= 10) return;
    *o = kept;
    polish_on(c, p, *o, s);
  };
  // After the model choice (the comparison needs the same tracks in every
  // candidate, and the tracks in front of a dolly-zoom subject are the cue).
  auto drop_bad_tracks = [&](std::vector<BaCamera>* c, std::vector<BaPoint>* p,
                             const std::vector<BaObservation>& all, std::vector<BaObservation>* o,
                             BaSummary* s) {
    // Drop whole tracks that no rigid point explains, and polish. About a
    // quarter of the KLT tracks on the synthetic clips are corners formed by
    // a silhouette against the background (occlusion edges): they move
    // smoothly, pass every frame-to-frame check and stay within a pixel or two
    // of *some* rigid point, and they are the longest tracks (the subject's
    // outline stays in view), so they make up half of the points a window
    // picks. Their shared bias bends the window along the rotation/translation
    // ambiguity (docs/estimate.md, "Where the rotation error comes from").
    // Residuals of a track are systematic, so a track's RMS is the test, not
    // single observations (all of the track's, also those cut above). The
    // threshold follows the noise: at least twice the lower quartile of the
    // tracks' RMS (about the noise of a good track). The cut tightens in four
    // rounds, 2.5x, 2x, 1.5x, then 1x, each after a polish: the first solution
    // is still bent by the bad tracks, and cutting tight at once also drops
    // good tracks the bend put far (crane_shot: 0.15 deg instead of 0.08).
    *o = all;
    for (double factor : {2.5, 2.0, 1.5, 1.0}) {
      const auto errs = ObservationErrors(*c, *p, *o, ba.use_depth);
      std::vector<double> sum_sq(p->size(), 0);
      std::vector<int> count(p->size(), 0);
      for (size_t i = 0; i < o->size(); ++i) {
        const int k = (*o)[i].point;
        sum_sq[k] += std::isfinite(errs[i]) ? errs[i] * errs[i] : std::numeric_limits<double>::infinity();
        ++count[k];
      }
      std::vector<double> rms(p->size(), 0), finite;
      for (size_t k = 0; k < p->size(); ++k) {
        if (!count[k]) continue;
        rms[k] = std::sqrt(sum_sq[k] / count[k]);
        if (std::isfinite(rms[k])) finite.push_back(rms[k]);
      }
      if (finite.empty()) break;
      std::nth_element(finite.begin(), finite.begin() + finite.size() / 4, finite.end());
      const double cut_px = mostly_translating ? options_.track_rms_cut_px : options_.track_rms_cut_rotation_px;
      const double cut = factor * std::max(cut_px / 960.0,  // normalised units
                                           2.0 * finite[finite.size() / 4]);
      std::vector<BaObservation> kept;
      for (const auto& ob : *o)
        if (rms[ob.point] < cut) kept.push_back(ob);
      if (kept.size() <= 10) break;
      *o = kept;
      polish_on(c, p, *o, s);
    }
    if (options_.depth_layer_cut && mostly_translating) drop_between_layers(c, p, o, s);
    // Diagnostic (docs/estimate.md, crane_shot): every point's RMS over all
    // its observations after the cut (and the options above), and whether it was kept.
    if (std::getenv("HAPCINE_TRACK_RMS_DEBUG")) {
      const auto errs = ObservationErrors(*c, *p, all, ba.use_depth);
      std::vector<double> sq(p->size(), 0);
      std::vector<int> cnt(p->size(), 0), kept_pt(p->size(), 0);
      for (size_t i = 0; i < all.size(); ++i) {
        sq[all[i].point] += errs[i] * errs[i];
        ++cnt[all[i].point];
      }
      for (const auto& ob : *o) kept_pt[ob.point] = 1;
      for (const auto& [id, k] : point_of_track)
        if (cnt[k])
          std::fprintf(stderr, "track_rms %d %ld %.4f %d\n", At(keyframes_.front().pos).tracks.index, id,
                       std::sqrt(sq[k] / cnt[k]) * 960, kept_pt[k]);
    }
  };

  struct Candidate {
    std::vector<BaCamera> cams;
    std::vector<BaPoint> pts;
    std::vector<BaObservation> ob;
    BaSummary summary;
  };
  auto solve_from = [&](std::vector<BaCamera> init) {
    Candidate c;
    c.cams = std::move(init);
    init_points(c.cams, &c.pts, &c.ob);
    c.summary = solve(&c.cams, &c.pts, &c.ob);
    return c;
  };
  // Few translating intervals among rotation: the window is also solved
  // without their translation (and without the zoom of zooming intervals, if
  // those are few too), on a second thread beside the solve below, and the
  // freedoms are kept only if they pay for themselves over the whole window
  // (window_freedoms.h). A pair of frames reads motion blur or a fade as
  // translation; one depth per point across the window does not fit it.
  // "Few" by frames, not keyframes: a fast whip makes a keyframe of every
  // frame, a still part one every keyframe_max_gap frames.
  int translating_frames = 0, free_frames = 0;
  for (int i = 1; i < n; ++i) {
    if (keyframes_[i].fixed) continue;
    const int span = keyframes_[i].pos - keyframes_[i - 1].pos;
    free_frames += span;
    if (HasTranslation(keyframes_[i].model)) translating_frames += span;
  }
  std::future<Candidate> without_freedoms;
  std::vector<char> drop_translation(n, 0), drop_zoom(n, 0);
  if (options_.freedom_test && has_translation && 2 * translating_frames < free_frames) {
    int zooming_frames = 0;
    for (int i = 1; i < n; ++i)
      if (!keyframes_[i].fixed && HasZoom(keyframes_[i].model)) zooming_frames += keyframes_[i].pos - keyframes_[i - 1].pos;
    const bool few_zooming = 2 * zooming_frames < free_frames;
    std::vector<MotionModel> labels(n);
    for (int i = 0; i < n; ++i) {
      labels[i] = keyframes_[i].model;
      if (keyframes_[i].fixed) continue;
      drop_translation[i] = HasTranslation(labels[i]);
      drop_zoom[i] = few_zooming && HasZoom(labels[i]);
      keyframes_[i].model = ReducedModel(labels[i], drop_translation[i], drop_zoom[i]);
    }
    std::vector<BaCamera> reduced = build_cameras(false);
    for (int i = 0; i < n; ++i) keyframes_[i].model = labels[i];
    without_freedoms = std::async(std::launch::async, [&, c = std::move(reduced)]() mutable {
      Candidate r;
      r.cams = std::move(c);
      r.pts = points;  // bearings: the solve ignores their inverse depth
      r.ob = obs;
      BaOptions bearings = ba;
      bearings.use_depth = false;
      bearings.scale_a = bearings.scale_b = -1;
      r.summary = solve_with(bearings, &r.cams, &r.pts, &r.ob);
      return r;
    });
  }
  // General windows: the per-keyframe-focal solve started from the two-view
  // chain does not depend on the constant-focal one, so it runs beside it on
  // a second thread (the same result as one after the other). After tracking
  // has ended the last window is the whole critical path, one core idle.
  const std::vector<BaCamera> zoom_cams = has_general ? build_cameras(true) : std::vector<BaCamera>{};
  std::future<Candidate> zoom_from_chain;
  if (has_general) zoom_from_chain = std::async(std::launch::async, solve_from, zoom_cams);
  std::vector<BaPoint> pts = points;
  std::vector<BaObservation> ob = obs;
  BaSummary summary = solve(&cams, &pts, &ob);
  LogStage("window: constant-focal solve");
  if (without_freedoms.valid()) {
    const Candidate r = without_freedoms.get();
    if (summary.success && r.summary.success) {
      const FreedomEvidence ev = CompareFreedoms(cams, pts, r.cams, r.pts, obs, drop_translation, drop_zoom,
                                                 options_.two_view.noise_floor);
      if (std::getenv("HAPCINE_FREEDOM_DEBUG"))
        std::fprintf(stderr,
                     "freedom_test frame %d: keyframes %d, dropping translation %d zoom %d, points %d: chi2 "
                     "with %.1f without %.1f, penalty %.1f, sigma %.3f px -> %s\n",
                     report.first_frame, n, ev.translation_dropped, ev.zoom_dropped, ev.informed_points,
                     ev.chi2_with, ev.chi2_without, ev.penalty, ev.sigma * 960, ev.PaysOff() ? "kept" : "dropped");
      LogStage("window: freedom test");
      if (!ev.PaysOff()) {
        if (zoom_from_chain.valid()) zoom_from_chain.get();  // wait, discard
        for (int i = 0; i < n; ++i)
          keyframes_[i].model = ReducedModel(keyframes_[i].model, drop_translation[i], drop_zoom[i]);
        freedoms_dropped_ = true;
        ProcessWindow(final);  // the window again, with the reduced models
        return;
      }
    }
  }
  bool branch_by_occlusion = false;
  if (zoom_from_chain.valid() && !summary.success) zoom_from_chain.get();  // wait, discard
  if (summary.success && has_general) {
    // BIC: does a per-keyframe focal in the general segments pay for itself?
    // Per-keyframe focal candidates: from the two-view initialisation and,
    // when the move is along the optical axis, from the other branch of the
    // axial dolly/zoom ambiguity (axial_ambiguity.h), whichever fits better.
    std::vector<Candidate> zoomed;
    auto try_zoom = [&](Candidate c) {
      if (c.summary.success) zoomed.push_back(std::move(c));
    };
    const int pivot = held;  // the branch before it is decided
    const bool axial = IsAxialMotion(cams, pivot);
    Candidate mirrored;  // solved here while the chain's candidate may still be solving
    if (axial) {
      std::vector<BaCamera> solved = zoom_cams;  // sharing of the zoom variant, values of the solve
      for (int i = 0; i < n; ++i) {
        solved[i].world_from_cam = cams[i].world_from_cam;
        solved[i].center = cams[i].center;
        solved[i].log_focal = cams[i].log_focal;
      }
      std::vector<std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>>> matches(n);
      for (int k = pivot + 1; k < n; ++k)
        for (const auto& [id, u] : At(keyframes_[k].pos).u) {
          auto it = At(keyframes_[k - 1].pos).u.find(id);
          if (it != At(keyframes_[k - 1].pos).u.end()) matches[k].push_back({it->second, u});
        }
      mirrored = solve_from(MirroredAxialBranch(solved, pivot, matches));
    }
    try_zoom(zoom_from_chain.get());
    if (axial) try_zoom(std::move(mirrored));
    LogStage("window: per-keyframe-focal solves");
    // Every candidate is scored on all observations (capped), with one sigma.
    const auto e0 = ObservationErrors(cams, pts, obs, true);
    std::vector<std::vector<double>> ez;
    std::vector<double> finite;
    for (const Candidate& c : zoomed) {
      ez.push_back(ObservationErrors(c.cams, c.pts, obs, true));
      for (double e : ez.back())
        if (std::isfinite(e)) finite.push_back(e);
    }
    const double sigma = std::max(Median(finite, 0.0) / 1.1774, options_.two_view.noise_floor);
    auto chi2 = [&](const std::vector<double>& e) {
      double sum = 0;
      for (double v : e) sum += std::isfinite(v) ? std::min(v * v / (sigma * sigma), 9.0) : 9.0;
      return sum;
    };
    // Along the optical axis the fit cannot tell the branches apart: the
    // occlusion order can (occlusion_order.h). A candidate it contradicts,
    // when another agrees with it, is out of the choice; [0]: constant focal.
    std::vector<char> ruled_out(zoomed.size() + 1, 0);
    if (axial) {
      std::vector<const std::vector<BaCamera>*> candidate_cams{&cams};
      for (const Candidate& c : zoomed) candidate_cams.push_back(&c.cams);
      ruled_out = ContradictedByOcclusion(OcclusionVotesOf(candidate_cams));
      for (char r : ruled_out) branch_by_occlusion |= r;
    }
    int best = -1;
    double best_chi2 = 0;
    for (size_t c = 0; c < zoomed.size(); ++c) {
      if (ruled_out[c + 1]) continue;
      const double x = chi2(ez[c]);
      if (best < 0 || x < best_chi2) {
        best = static_cast<int>(c);
        best_chi2 = x;
      }
    }
    if (best >= 0) {
      int extra = 0;
      for (int i = 1; i < n; ++i) extra += keyframes_[i].model == MotionModel::kGeneral && !keyframes_[i].fixed;
      const double m = 2.0 * obs.size();
      const double bic0 = chi2(e0), bic1 = best_chi2 + extra * std::log(std::max(m, 2.0));
      if (bic1 < bic0 || ruled_out[0]) {
        Candidate& c = zoomed[best];
        cams = c.cams;
        pts = c.pts;
        ob = c.ob;
        summary = c.summary;
        report.zoom_by_bic = true;
        for (int i = 1; i < n; ++i)
          if (keyframes_[i].model == MotionModel::kGeneral && !keyframes_[i].fixed)
            keyframes_[i].model = MotionModel::kGeneralZoom;
      }
    }
  }
  // Not along the optical axis: there the tracks in front of the subject are
  // the only cue between the two branches of the dolly/zoom ambiguity, and
  // the branch not taken leaves them with the largest residuals. Unless the
  // occlusion order chose the branch: then the residuals are not the cue.
  LogStage("window: model choice");
  if (summary.success && (branch_by_occlusion || !(has_translation && IsAxialMotion(cams, held))))
    drop_bad_tracks(&cams, &pts, obs, &ob, &summary);
  LogStage("window: track rejection");
  if (summary.success) {
    for (int i = 0; i < n; ++i) {
      keyframes_[i].cam.world_from_cam = cams[i].world_from_cam;
      keyframes_[i].cam.center = cams[i].center;
      keyframes_[i].cam.log_focal = cams[i].log_focal;
    }
    points = pts;
    if (focal_observable) focal_observed_ = true;
  }
  // Points whose track the BA kept (outlier tracks are dropped whole): the
  // only ones the in-between frames may use.
  std::vector<char> point_kept(points.size(), summary.success ? 0 : 1);
  if (summary.success)
    for (const auto& o : ob) point_kept[o.point] = 1;
  report.points = static_cast<int>(points.size());
  report.observations = summary.num_observations;
  report.rms_px = summary.rms_after * width_;

  // --- units: median depth seen from the first keyframe with depth.
  auto depths_from = [&](const BaCamera& cam) {
    std::vector<double> depths;
    for (const auto& p : points) {
      if (!(p.homogeneous(3) > 1e-12)) continue;
      const Eigen::Vector3d X = p.anchor + p.homogeneous.head<3>() / p.homogeneous(3);
      const double z = (cam.world_from_cam.conjugate() * (X - cam.center)).z();
      if (z > 0 && std::isfinite(z)) depths.push_back(z);
    }
    return depths;
  };
  if (has_translation && summary.success) {
    const BaCamera origin = keyframes_[0].cam;
    const double m = Median(depths_from(origin));
    if (!scale_set_ && m > 0) {
      const double k = 1 / m;  // scale about the first keyframe's centre
      for (auto& kf : keyframes_) kf.cam.center = origin.center + (kf.cam.center - origin.center) * k;
      for (auto& p : points) {
        p.anchor = origin.center + (p.anchor - origin.center) * k;
        p.homogeneous(3) /= k;
        p.homogeneous.normalize();
      }
      scale_set_ = true;
    }
    const double last = Median(depths_from(keyframes_.back().cam));
    if (last > 0) scene_depth_ = last;
  }

  // --- frames of the window: keyframes as solved, the others pose-only.
  const int emit_end = final ? buffer_start_ + static_cast<int>(frames_.size())
                             : keyframes_[n - 2].pos;  // exclusive
  const int emit_begin = raw_.empty() ? 0 : raw_.back().meta.index - frames_.front().tracks.index + buffer_start_ + 1;
  std::vector<BaPoint> rpoints = points;
  int ki = 0;
  for (int pos = emit_begin; pos < emit_end; ++pos) {
    const BufferedFrame& f = At(pos);
    RawPose out;
    out.meta = f.tracks;
    while (ki + 1 < n && keyframes_[ki + 1].pos <= pos) ++ki;
    if (pos < keyframes_[0].pos) {  // before the chain starts (blank lead-in)
      out.cam = keyframes_[0].cam;
      out.model = MotionModel::kStatic;
      out.confidence = 0.05;
      raw_.push_back(out);
      continue;
    }
    const Keyframe& a = keyframes_[ki];
    if (pos == a.pos) {
      out.cam = a.cam;
      out.model = ki == 0 && n > 1 ? keyframes_[1].model : a.model;
      if (a.fixed && ki == 0 && n > 1) out.model = keyframes_[1].model;
      out.confidence = Clamp01(a.inlier_ratio) * Clamp01(std::max(f.tracks.quality, 0.3)) *
                       std::exp(-0.5 * std::pow(report.rms_px * 960.0 / width_ / 2.0, 2)) *
                       (focal_observable ? 1.0 : 0.8);
      if (!summary.success) out.confidence *= 0.3;
      raw_.push_back(out);
      continue;
    }
    if (ki + 1 >= n || !f.usable) {
      // After the last keyframe (end of shot) or unusable: hold the previous pose.
      out.cam = raw_.empty() ? a.cam : raw_.back().cam;
      out.model = raw_.empty() ? a.model : raw_.back().model;
      out.confidence = 0.1;
      if (f.usable && ki + 1 >= n) {
        // Trailing frames with tracks: pose-only solve with the last model's freedoms.
        out.model = a.model;
      } else {
        raw_.push_back(out);
        continue;
      }
    }
    const Keyframe& b = ki + 1 < n ? keyframes_[ki + 1] : keyframes_[ki];
    const double t = b.pos > a.pos ? static_cast<double>(pos - a.pos) / (b.pos - a.pos) : 0;
    out.cam.world_from_cam = a.cam.world_from_cam.slerp(t, b.cam.world_from_cam);
    out.cam.center = (1 - t) * a.cam.center + t * b.cam.center;
    out.cam.log_focal = (1 - t) * a.cam.log_focal + t * b.cam.log_focal;
    out.cam.rotation_source = out.cam.center_source = out.cam.focal_source = -1;
    out.model = ki + 1 < n ? b.model : a.model;
    std::vector<BaObservation> fobs;
    for (const auto& [id, u] : f.u) {
      auto it = point_of_track.find(id);
      if (it != point_of_track.end() && point_kept[it->second]) fobs.push_back({0, it->second, u});
    }
    PoseFreedoms fr;
    fr.rotation = HasRotation(out.model);
    fr.center = HasTranslation(out.model);
    fr.focal = HasZoom(out.model);
    double rms_px = report.rms_px;
    if (static_cast<int>(fobs.size()) >= options_.min_tracks && summary.success &&
        (fr.rotation || fr.center || fr.focal)) {
      BaOptions po = ba;
      po.max_iterations = 10;
      BaCamera cam = out.cam;
      const BaSummary ps = SolvePose(&cam, fr, rpoints, fobs, po);
      if (ps.success && cam.world_from_cam.coeffs().allFinite() && cam.center.allFinite() &&
          std::isfinite(cam.log_focal)) {
        out.cam = cam;
        rms_px = ps.rms_after * width_;
      }
    }
    out.confidence = Clamp01(b.inlier_ratio) * Clamp01(std::max(f.tracks.quality, 0.3)) *
                     std::exp(-0.5 * std::pow(rms_px * 960.0 / width_ / 2.0, 2)) *
                     (focal_observable ? 1.0 : 0.8);
    if (!summary.success) out.confidence *= 0.3;
    raw_.push_back(out);
  }
  report.last_frame = raw_.empty() ? report.first_frame : raw_.back().meta.index;
  reports_.push_back(report);
  LogStage("window: in-between frames");
  if (final) return;

  // --- next window: overlap of two keyframes (or the last
  // window_lead_in_frames, track_estimator.h), held constant.
  int first_kept = n - 2;
  while (first_kept > 0 && keyframes_[n - 1].pos - keyframes_[first_kept - 1].pos <= options_.window_lead_in_frames)
    --first_kept;
  std::vector<Keyframe> lead_in(keyframes_.begin() + first_kept, keyframes_.end());
  for (Keyframe& k : lead_in) {
    k.fixed = k.fixed_focal = true;
    k.chain_start = false;
  }
  keyframes_ = std::move(lead_in);
  const int drop = keyframes_.front().pos - buffer_start_;
  frames_.erase(frames_.begin(), frames_.begin() + drop);
  buffer_start_ = keyframes_.front().pos;
  outlier_tracks_.clear();
}

void TrackCameraEstimator::FinishShot() {
  if (shot_ < 0) return;
  if (!keyframes_.empty()) {
    ProcessWindow(true);
  } else {
    // No usable frame in the whole shot: identity, prior focal, no confidence.
    for (const auto& f : frames_) {
      RawPose out;
      out.meta = f.tracks;
      out.cam.log_focal = prior_log_focal_;
      raw_.push_back(out);
    }
  }
  keyframes_.clear();
  frames_.clear();
  const int n = static_cast<int>(raw_.size());
  // Smoothing per segment, only on the freedoms the segment's model has.
  std::vector<Eigen::Quaterniond> q(n);
  std::vector<Eigen::Vector3d> c(n);
  std::vector<double> lf(n);
  for (int i = 0; i < n; ++i) {
    q[i] = raw_[i].cam.world_from_cam;
    c[i] = raw_[i].cam.center;
    lf[i] = raw_[i].cam.log_focal;
  }
  if (options_.smooth && options_.smooth_sigma_frames > 0) {
    for (int s = 0; s < n;) {
      int e = s;
      while (e + 1 < n && raw_[e + 1].model == raw_[s].model) ++e;
      const MotionModel m = raw_[s].model;
      // Include the neighbour frames so that segment ends stay continuous.
      const int lo = std::max(0, s - 1), hi = std::min(n - 1, e + 1);
      auto sub = [&](auto& v) { return std::vector<std::decay_t<decltype(v[0])>>(v.begin() + lo, v.begin() + hi + 1); };
      if (HasRotation(m)) {
        const auto sm = SmoothRotations(sub(q), options_.smooth_sigma_frames);
        for (int i = s; i <= e; ++i) q[i] = sm[i - lo];
      }
      if (HasTranslation(m)) {
        const auto sm = SmoothVectors(sub(c), options_.smooth_sigma_frames);
        for (int i = s; i <= e; ++i) c[i] = sm[i - lo];
      }
      if (HasZoom(m)) {
        const auto sm = SmoothScalars(sub(lf), options_.smooth_sigma_frames);
        for (int i = s; i <= e; ++i) lf[i] = sm[i - lo];
      }
      s = e + 1;
    }
  }
  for (int i = 0; i < n; ++i) {
    const RawPose& r = raw_[i];
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
    cf.model = MotionModelName(r.model);
    cf.confidence = Clamp01(r.confidence);
    path_.frames.push_back(cf);
  }
  raw_.clear();
}

CameraPath TrackCameraEstimator::Finish() {
  FinishShot();
  shot_ = -1;
  return path_;
}

}  // namespace hapcine
