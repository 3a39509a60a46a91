// TrackCameraEstimator::ProcessWindow: one window's bundle adjustment, from
// the keyframes' two-view labels to the solved keyframes and points (model
// choice, track rejection); its frames and units follow in
// track_estimator_frames.cc. docs/estimate.md, "Algorithm", step 4.

#include "estimate/track_estimator.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <future>
#include <limits>
#include <utility>

#include "core/rotation.h"
#include "core/statistics.h"
#include "estimate/axial_ambiguity.h"
#include "estimate/window_points.h"
#include "estimate/robust_bundle.h"
#include "estimate/stage_timing.h"
#include "estimate/two_view_geometry.h"
#include "estimate/window_freedoms.h"

namespace hapcine {

void TrackCameraEstimator::PromoteShortRuns() {
  const int n = static_cast<int>(keyframes_.size());
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
}

// The window's cameras from the keyframes, with the blocks each interval's
// model shares with the previous keyframe (no rotation, translation or zoom
// of its own). `labels`: models to use instead of the keyframes' own
// (candidate solves); `zoom_in_general`: general intervals get a zoom too.
// `free_lead_in_focal`: the held lead-in's focal is solved (its first
// calibration, ProcessWindow).
std::vector<BaCamera> TrackCameraEstimator::WindowCameras(bool zoom_in_general, bool free_lead_in_focal,
                                                          const std::vector<MotionModel>* labels) const {
  const int n = static_cast<int>(keyframes_.size());
  std::vector<BaCamera> cams(n);
  for (int i = 0; i < n; ++i) {
    cams[i] = keyframes_[i].cam;
    cams[i].fixed = keyframes_[i].fixed;
    cams[i].fixed_focal = keyframes_[i].fixed_focal && !free_lead_in_focal;
    cams[i].rotation_source = cams[i].center_source = cams[i].focal_source = -1;
    if (i == 0 || keyframes_[i].fixed) continue;
    MotionModel m = labels ? (*labels)[i] : keyframes_[i].model;
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
}

void TrackCameraEstimator::ProcessWindow(bool final) {
  if (keyframes_.empty()) return;
  const int n = static_cast<int>(keyframes_.size());
  LogStage("window: keyframes", n);
  WindowReport report;
  report.shot = shot_;
  report.keyframes = n;
  report.first_frame = At(keyframes_.front().pos).tracks.index;
  // A re-run without the freedoms that did not pay off is not tested again
  // (the lead-in's labels, held, may still have them).
  const bool rerun = std::exchange(labels_revised_, false);
  report.labels_revised = rerun;

  PromoteShortRuns();

  bool has_translation = false, has_general = false;
  for (int i = 1; i < n; ++i) {
    has_translation |= HasTranslation(keyframes_[i].model);
    has_general |= keyframes_[i].model == MotionModel::kGeneral && !keyframes_[i].fixed;
  }
  double max_turn = 0;
  for (const auto& k : keyframes_)
    max_turn = std::max(max_turn, OpticalAxisAngleDeg(k.cam.world_from_cam, keyframes_[0].cam.world_from_cam));
  const bool focal_observable = focal_observed_ || max_turn >= options_.min_rotation_for_focal_deg;
  report.focal_observable = focal_observable;
  // The shot's focal observable for the first time after frames that could
  // not observe it (a dolly, then a pan; or a chain restarted after lost
  // tracking): the focal the window starts from is still the prior, so the
  // held lead-in's is freed here and calibrated with the window, and the
  // frames already estimated take the same change (below). Held, a pan at
  // the prior's focal was off by ~3 deg in 15 (TravelingThenPanInTheNextWindow).
  const bool recalibrate_lead_in = focal_observable && !focal_observed_ && !raw_.empty();
  const double lead_in_log_focal = keyframes_[0].cam.log_focal;
  // Focal initialisation from rotation pairs that turned enough.
  if (!focal_observed_ && !focal_samples_.empty() &&
      ((keyframes_[0].pos == 0 && !keyframes_[1 < n ? 1 : 0].fixed) || recalibrate_lead_in)) {
    const double shift = Median(focal_samples_) - keyframes_[0].cam.log_focal;
    for (auto& k : keyframes_) k.cam.log_focal += shift;
  }

  // `labels`: the keyframes' models to use instead of theirs (candidates).
  auto build_cameras = [&](bool zoom_in_general, const std::vector<MotionModel>* labels = nullptr) {
    return WindowCameras(zoom_in_general, recalibrate_lead_in, labels);
  };

  // --- points: tracks seen by >= 2 keyframes, spread over the image
  // (window_points.h, point_selection.h), longest first within an image cell.
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
  // Where the grid spreads the points, the whole-track cut below also drops
  // the occlusion-edge corners (a third or more of the tracks near
  // silhouettes) and the good tracks the first, bent solve puts far: take
  // more there, so that about `max_points` rigid ones remain.
  const int window_points =
      spread_points ? static_cast<int>(std::lround(options_.max_points * options_.spread_points_factor))
                    : options_.max_points;
  std::vector<const KeyframeTracks*> tracks_at(n);
  for (int i = 0; i < n; ++i) tracks_at[i] = &At(keyframes_[i].pos).u;
  WindowTracks window_tracks = SelectWindowPoints(tracks_at, outlier_tracks_, window_points,
                                                  spread_points ? options_.point_grid_cells : 0);
  const std::map<long, int>& point_of_track = window_tracks.point_of_track;
  // Point k is the track order[k] in every candidate reconstruction.
  auto init_points = [&](const std::vector<BaCamera>& c, std::vector<BaPoint>* p, std::vector<BaObservation>* o) {
    InitWindowPoints(c, window_tracks, tracks_at, has_translation, 0.2 / scene_depth_, p, o);
  };
  std::vector<BaCamera> cams = build_cameras(false);
  std::vector<BaPoint> points;
  std::vector<BaObservation> obs;
  init_points(cams, &points, &obs);

  BaOptions ba;
  ba.huber_scale = 1.0 / kReferenceWidthPx;
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

  // Every solve drops what the fit cannot explain and polishes
  // (robust_bundle.h); the whole-track test comes after the model choice.
  auto solve = [&](std::vector<BaCamera>* c, std::vector<BaPoint>* p, std::vector<BaObservation>* o) {
    return SolveDroppingOutliers(ba, c, p, o);
  };
  // The tight cut is for windows with parallax throughout: where a few
  // intervals among rotation read as general (the blur of a whip pan), the
  // tracks' RMS is mostly tracking noise, as without translation.
  // Also counted in frames, for the window-level label tests below: a fast
  // whip makes a keyframe of every frame, a still part one every
  // keyframe_max_gap frames.
  int translating = 0, free_keyframes = 0, translating_frames = 0, zooming_frames = 0, free_frames = 0;
  for (int i = 1; i < n; ++i) {
    if (keyframes_[i].fixed) continue;
    ++free_keyframes;
    translating += HasTranslation(keyframes_[i].model);
    const int span = keyframes_[i].pos - keyframes_[i - 1].pos;
    free_frames += span;
    if (HasTranslation(keyframes_[i].model)) translating_frames += span;
    if (HasZoom(keyframes_[i].model)) zooming_frames += span;
  }
  const bool mostly_translating = has_translation && 2 * translating >= free_keyframes;
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
    // single observations (all of the track's, also those cut above); the
    // cut tightens in rounds (cutting tight at once on the first, still bent
    // solution also drops good tracks: a crane move 0.15 deg instead of 0.08).
    const double cut_px = mostly_translating ? options_.track_rms_cut_px : options_.track_rms_cut_rotation_px;
    DropInconsistentTracks(ba, cut_px / kReferenceWidthPx, c, p, all, o, s);  // normalised units
    // Diagnostic (docs/estimate.md, "Diagnostics"): every point's RMS over all
    // its observations after the cut, and whether it was kept.
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
                       std::sqrt(sq[k] / cnt[k]) * kReferenceWidthPx, kept_pt[k]);
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
  // The same for a few zooming intervals in a window without translation (a
  // tilt read as a zoom in a pair of frames). "Few": by frames.
  const bool few_translating = has_translation && 2 * translating_frames < free_frames;
  const bool few_zooming = zooming_frames > 0 && 2 * zooming_frames < free_frames;
  std::future<Candidate> without_freedoms;
  std::vector<char> drop_translation(n, 0), drop_zoom(n, 0);
  std::vector<MotionModel> reduced_labels(n);
  bool anything_to_drop = false;
  if (options_.freedom_test && !rerun && (few_translating || (!has_translation && few_zooming))) {
    for (int i = 0; i < n; ++i) {
      if (keyframes_[i].fixed) continue;
      drop_translation[i] = HasTranslation(keyframes_[i].model);
      drop_zoom[i] = few_zooming && HasZoom(keyframes_[i].model);
      anything_to_drop |= drop_translation[i] || drop_zoom[i];
    }
  }
  if (anything_to_drop) {
    for (int i = 0; i < n; ++i)
      reduced_labels[i] = ReducedModel(keyframes_[i].model, drop_translation[i], drop_zoom[i]);
    std::vector<BaCamera> reduced = build_cameras(false, &reduced_labels);
    without_freedoms = std::async(std::launch::async, [&, c = std::move(reduced)]() mutable {
      Candidate r;
      r.cams = std::move(c);
      r.pts = points;  // bearings: the solve ignores their inverse depth
      r.ob = obs;
      BaOptions bearings = ba;
      bearings.use_depth = false;
      bearings.scale_a = bearings.scale_b = -1;
      r.summary = SolveDroppingOutliers(bearings, &r.cams, &r.pts, &r.ob);
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
  auto blur_sigmas = [&] {
    std::vector<int> frame_of_camera(n);
    for (int i = 0; i < n; ++i) frame_of_camera[i] = keyframes_[i].pos;
    return BlurSigmas(obs, frame_of_camera, options_.blur_noise_per_speed);
  };
  // The window again from the start with revised labels (once: the re-run
  // is not tested again).
  auto rerun_with = [&](const std::vector<MotionModel>& labels) {
    if (zoom_from_chain.valid()) zoom_from_chain.get();  // wait, discard
    for (int i = 0; i < n; ++i) keyframes_[i].model = labels[i];
    labels_revised_ = true;
    ProcessWindow(final);
  };
  if (without_freedoms.valid()) {
    const Candidate r = without_freedoms.get();
    if (summary.success && r.summary.success) {
      const FreedomEvidence ev = CompareFreedoms(cams, pts, r.cams, r.pts, obs, drop_translation, drop_zoom,
                                                 options_.two_view.noise_floor, blur_sigmas());
      if (std::getenv("HAPCINE_FREEDOM_DEBUG"))
        std::fprintf(stderr,
                     "freedom_test frame %d: keyframes %d, dropping translation %d zoom %d (|d ln f| %.2g), "
                     "points %d: chi2 with %.1f without %.1f, penalty %.1f, sigma %.3f px -> %s\n",
                     report.first_frame, n, ev.translation_dropped, ev.zoom_dropped, ev.zoom_change,
                     ev.informed_points, ev.chi2_with, ev.chi2_without, ev.penalty, ev.sigma * kReferenceWidthPx,
                     ev.PaysOff() ? "kept" : "dropped");
      LogStage("window: freedom test");
      if (!ev.PaysOff()) {
        rerun_with(reduced_labels);
        return;
      }
    }
  }
  // The other way (window_freedoms.h): intervals labelled as a zoom without
  // translation in a window with translation (the slow start of a forward
  // dolly read as a zoom by a pair of frames) become general if that pays
  // for itself over the window. Not `rotation` ones: next to a whip pan's
  // blur read as translation they would take that translation too (one
  // whip pan went from 11 to 18 `general` frames).
  if (options_.freedom_test && !rerun && has_translation && summary.success) {
    std::vector<MotionModel> promoted_labels(n);
    int promoted = 0;
    for (int i = 0; i < n; ++i) {
      const MotionModel m = keyframes_[i].model;
      const bool promote = i > 0 && !keyframes_[i].fixed && HasZoom(m) && !HasTranslation(m);
      promoted_labels[i] = promote ? MotionModel::kGeneral : m;
      promoted += promote;
    }
    if (promoted > 0) {
      const Candidate p = solve_from(build_cameras(false, &promoted_labels));
      if (p.summary.success) {
        const PromotionEvidence ev =
            ComparePromotion(p.cams, p.pts, cams, pts, obs, promoted, options_.two_view.noise_floor,
                             blur_sigmas());
        if (std::getenv("HAPCINE_FREEDOM_DEBUG"))
          std::fprintf(stderr,
                       "promotion_test frame %d: keyframes %d, promoting %d: chi2 current %.1f promoted %.1f, "
                       "penalty %.1f, sigma %.3f px -> %s\n",
                       report.first_frame, n, ev.promoted, ev.chi2_current, ev.chi2_promoted, ev.penalty,
                       ev.sigma * kReferenceWidthPx, ev.PaysOff() ? "promoted" : "kept");
        LogStage("window: promotion test");
        if (ev.PaysOff()) {
          rerun_with(promoted_labels);
          return;
        }
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
    // Along the optical axis the fit cannot tell the branches apart: the
    // occlusion order can (occlusion_order.h). A candidate it contradicts,
    // when another agrees with it, is out of the choice; [0]: constant focal.
    std::vector<char> ruled_out(zoomed.size() + 1, 0);
    if (axial) {
      std::vector<const std::vector<BaCamera>*> candidate_cams{&cams};
      for (const Candidate& c : zoomed) candidate_cams.push_back(&c.cams);
      ruled_out = ContradictedByOcclusion(OcclusionVotesOf(candidate_cams));
      for (char r : ruled_out) branch_by_occlusion |= r;
      // Without occlusion events, the floor (plane_prior.h): on the wrong
      // branch it cannot be parallel to the move.
      // The whole-track rejection below stays off then (it bends such a
      // window away from the plane: 0.43 -> 0.71 of zoom in
      // DollyZoomOverAFloorRecoversTheZoom).
      if (!branch_by_occlusion && options_.motion_plane_prior)
        ruled_out = ContradictedByPlane(PlaneSupportOf(ba, held, candidate_cams));
    }
    // Every candidate is scored on all observations (capped), with one sigma.
    std::vector<std::vector<double>> ez;
    for (const Candidate& c : zoomed) ez.push_back(ObservationErrors(c.cams, c.pts, obs, true));
    int extra = 0;
    for (int i = 1; i < n; ++i) extra += keyframes_[i].model == MotionModel::kGeneral && !keyframes_[i].fixed;
    const int best = ChooseFocalCandidate(ObservationErrors(cams, pts, obs, true), ez, ruled_out, extra,
                                          options_.two_view.noise_floor);
    if (best >= 0) {
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
  // Not along the optical axis: there the tracks in front of the subject are
  // the only cue between the two branches of the dolly/zoom ambiguity, and
  // the branch not taken leaves them with the largest residuals. Unless the
  // occlusion order chose the branch: then the residuals are not the cue.
  LogStage("window: model choice");
  if (summary.success && (branch_by_occlusion || !(has_translation && IsAxialMotion(cams, held))))
    drop_bad_tracks(&cams, &pts, obs, &ob, &summary);
  LogStage("window: track rejection");
  // Along the axis the fit leaves every inverse depth open by one shift
  // (axial_ambiguity.h) unless the lead-in's own move pins the depths: take
  // the shift that makes a floor or wall parallel to the move. After every
  // other polish: the focal smoothness prior, the only term that is not flat
  // along the shift, would pull the solve back towards where it started.
  if (summary.success && report.zoom_by_bic && !scale_pinned && options_.motion_plane_prior &&
      IsAxialMotion(cams, held))
    ApplyPlanePriorToWindow(ba, held, report.first_frame, &cams, &pts, ob, &summary, &report.plane_prior);
  if (summary.success) {
    if (recalibrate_lead_in) {
      const double shift = cams[0].log_focal - lead_in_log_focal;
      for (RawPose& r : raw_) r.cam.log_focal += shift;
    }
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

  if (has_translation && summary.success) SetUnits(&points);

  WindowSolution solution;
  solution.points = std::move(points);
  solution.point_of_track = std::move(window_tracks.point_of_track);
  solution.point_kept = std::move(point_kept);
  solution.pose_options = ba;
  solution.success = summary.success;
  solution.rms_px = report.rms_px;
  solution.focal_observable = focal_observable;
  EmitWindowFrames(solution, final);
  report.last_frame = raw_.empty() ? report.first_frame : raw_.back().meta.index;
  reports_.push_back(report);
  LogStage("window: in-between frames");
  if (final) return;

  StartNextWindow();
}

}  // namespace hapcine
