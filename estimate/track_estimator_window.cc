// TrackCameraEstimator::ProcessWindow: the current window through
// SolveWindow (window_solver.h), its outcome into the keyframes, the frames
// already written and the shot's units, then its frames
// (track_estimator_frames.cc) and its report.

#include <algorithm>
#include <utility>

#include "core/diagnostics.h"
#include "estimate/track_estimator.h"

namespace hapcine {
namespace {

nlohmann::json BaJson(const BaSummary& s, int width) {
  return {{"success", s.success},
          {"iterations", s.iterations},
          {"initial_cost", s.initial_cost},
          {"final_cost", s.final_cost},
          {"termination", s.termination},
          {"observations", s.num_observations},
          {"rms_before_px", s.rms_before * width},
          {"rms_after_px", s.rms_after * width}};
}

nlohmann::json CandidateJson(const WindowCandidate& c, int width) {
  nlohmann::json j = {{"test", c.test},   {"name", c.name},     {"solved", c.solved},
                      {"score", c.score}, {"chosen", c.chosen}, {"ba", BaJson(c.ba, width)}};
  if (c.test == "focal") j["ruled_out"] = c.ruled_out;
  if (c.occlusion_agree >= 0) j["occlusion_votes"] = {{"agree", c.occlusion_agree}, {"disagree", c.occlusion_disagree}};
  if (c.plane_support >= 0) j["plane_support"] = c.plane_support;
  if (c.focal_first_px > 0) j["focal_px"] = {c.focal_first_px, c.focal_last_px};
  if (c.depth_relief >= 0) j["depth_relief"] = c.depth_relief;
  return j;
}

nlohmann::json ZoomDecisionJson(const ZoomDecision& d) {
  nlohmann::json j = {{"test", d.test},
                      {"zoom_taken", d.zoom_taken},
                      {"gain", d.gain},
                      {"penalty", d.penalty},
                      {"bic_margin", BicMargin(d)},
                      {"zoom_change", d.zoom_change},
                      {"decisiveness", Decisiveness(d)}};
  if (d.relief >= 0) j["relief_margin"] = ReliefMargin(d);
  if (d.decided_by_cue) j["decided_by_cue"] = true;
  if (d.test == "branch") j["fit_z"] = d.fit_z;
  return j;
}

const char* const kCandidateNames[kNumCandidates] = {"static", "zoom", "rotation", "rotation+zoom", "essential",
                                                     "homography"};

}  // namespace

WindowInput TrackCameraEstimator::WindowInputOf(bool labels_revised) const {
  WindowInput in;
  for (const Keyframe& k : keyframes_)
    in.keyframes.push_back(
        {k.pos, k.cam, k.model, k.fixed, k.fixed_focal, k.chain_start, &At(k.pos).u, At(k.pos).tracks.jump});
  for (int pos = keyframes_.front().pos; pos <= keyframes_.back().pos; ++pos) in.frames.push_back(&At(pos).u);
  in.outlier_tracks = outlier_tracks_;
  for (const auto& [id, n] : mover_intervals_)
    if (n.first > n.second) in.outlier_tracks.insert(id);
  in.shot = shot_;
  in.first_frame = At(keyframes_.front().pos).tracks.index;
  in.width = width_;
  in.height = height_;
  in.prior_log_focal = prior_log_focal_;
  in.focal_observed = focal_observed_;
  in.focal_samples = focal_samples_;
  in.frames_written = !raw_.empty();
  in.scene_depth = scene_depth_;
  in.labels_revised = labels_revised;
  in.stills = shot_of_stills_;
  return in;
}

void TrackCameraEstimator::UpdateKeyframes(const std::vector<BaCamera>& cams, const std::vector<MotionModel>& labels) {
  for (size_t i = 0; i < keyframes_.size(); ++i) {
    keyframes_[i].cam = cams[i];
    keyframes_[i].model = labels[i];
  }
}

void TrackCameraEstimator::ProcessWindow(bool final) {
  if (keyframes_.empty()) return;
  WindowOutcome w = SolveWindow(WindowInputOf(false), window_options_, diagnostics_);
  if (!w.revised_labels.empty()) {
    // The label tests revised the labels: the window again, once, with
    // them; the report keeps the tests' candidates.
    UpdateKeyframes(w.keyframe_cams, w.revised_labels);
    std::vector<WindowCandidate> tests = std::move(w.report.candidates);
    std::vector<ZoomDecision> decisions = std::move(w.report.zoom_decisions);
    w = SolveWindow(WindowInputOf(true), window_options_, diagnostics_);
    w.report.candidates.insert(w.report.candidates.begin(), tests.begin(), tests.end());
    w.report.zoom_decisions.insert(w.report.zoom_decisions.begin(), decisions.begin(), decisions.end());
  }
  UpdateKeyframes(w.keyframe_cams, w.labels);
  if (w.success) KeepSolvedWindow(w);
  if (w.written_log_focal_shift)
    for (RawPose& r : raw_) r.cam.log_focal += *w.written_log_focal_shift;
  if (w.focal_calibrated) focal_observed_ = true;
  if (w.translating && w.success) SetUnits(&w.points);
  if (options_.loop_bundle) KeepLoopKeyframes();
  StageClock clock;
  EmitWindowFrames(w, final);
  w.report.last_frame = raw_.empty() ? w.report.first_frame : raw_.back().meta.index;
  w.report.timings_s.emplace_back("in_between_frames", clock.Lap());
  Report(std::move(w.report));
  ++shot_windows_;
  if (!final) StartNextWindow();
}

// Each keyframe once, as the window that first solved it left it (in the
// shot's units); an overlap keyframe, held in the next window, records
// that it belongs to both.
void TrackCameraEstimator::KeepLoopKeyframes() {
  for (const Keyframe& k : keyframes_) {
    const int index = At(k.pos).tracks.index;
    const auto it = std::find_if(loop_keyframes_.begin(), loop_keyframes_.end(),
                                 [&](const LoopKeyframe& l) { return l.frame == index; });
    if (it != loop_keyframes_.end()) {
      it->last_window = shot_windows_;
      continue;
    }
    loop_keyframes_.push_back({index, k.cam, At(k.pos).u, shot_windows_, shot_windows_});
  }
}

// A translating shot's keyframes adjusted over the loops its tracks close
// (loop_bundle.h), then every frame of the shot moved with them.
void TrackCameraEstimator::AdjustShotLoop() {
  if (!scale_set_ || shot_windows_ < 2) return;
  LoopBundleOptions o;
  o.min_loop_tracks = options_.min_tracks;
  o.max_points =
      static_cast<int>(options_.max_points * options_.spread_points_factor) * shot_windows_;
  o.point_grid_cells = options_.point_grid_cells;
  o.track_rms_cut = options_.track_rms_cut_px / kReferenceWidthPx;
  o.ba_iterations = options_.ba_iterations;
  o.num_threads = options_.num_threads;
  StageClock clock;
  const LoopBundleResult r = AdjustLoop(loop_keyframes_, outlier_tracks_, true, o);
  if (Wants(diagnostics_, "loop_bundle"))
    diagnostics_->Record("loop_bundle", {{"shot", shot_},
                                         {"keyframes", loop_keyframes_.size()},
                                         {"loop_tracks", r.loop_tracks},
                                         {"adjusted", r.adjusted},
                                         {"points", r.points},
                                         {"points_kept", r.points_kept},
                                         {"observations", r.observations},
                                         {"rms_px", r.rms_after_px},
                                         {"seconds", clock.Lap()}});
  if (!r.adjusted) return;
  std::vector<int> raw_of_keyframe;
  size_t i = 0;
  for (const LoopKeyframe& k : loop_keyframes_) {
    while (i < raw_.size() && raw_[i].meta.index < k.frame) ++i;
    if (i == raw_.size() || raw_[i].meta.index != k.frame)
      return;  // not placed as a keyframe: leave the path
    raw_of_keyframe.push_back(static_cast<int>(i));
  }
  CorrectRawPoses(raw_of_keyframe, r.cameras);
}

// Each keyframe's correction is a rigid motion of the world (the adjusted
// pose from the solved one); a frame between two keyframes takes both
// corrections blended by its place between them, one outside takes the
// nearest keyframe's.
void TrackCameraEstimator::CorrectRawPoses(const std::vector<int>& raw_of_keyframe,
                                           const std::vector<BaCamera>& adjusted) {
  const auto moved = [&](size_t k, const BaCamera& cam) {
    const BaCamera& solved = loop_keyframes_[k].cam;
    const Eigen::Quaterniond d = adjusted[k].world_from_cam * solved.world_from_cam.conjugate();
    BaCamera out = cam;
    out.world_from_cam = (d * cam.world_from_cam).normalized();
    out.center = adjusted[k].center + d * (cam.center - solved.center);
    return out;
  };
  size_t b = 0;
  for (int i = 0; i < static_cast<int>(raw_.size()); ++i) {
    while (b < raw_of_keyframe.size() && raw_of_keyframe[b] < i) ++b;
    BaCamera& cam = raw_[i].cam;
    if (b == 0 || b == raw_of_keyframe.size() || raw_of_keyframe[b] == i) {
      cam = moved(b == raw_of_keyframe.size() ? b - 1 : b, cam);
      continue;
    }
    const double s =
        double(i - raw_of_keyframe[b - 1]) / (raw_of_keyframe[b] - raw_of_keyframe[b - 1]);
    const BaCamera before = moved(b - 1, cam), after = moved(b, cam);
    cam.world_from_cam = before.world_from_cam.slerp(s, after.world_from_cam).normalized();
    cam.center = (1 - s) * before.center + s * after.center;
  }
}

bool TrackCameraEstimator::solved_windows_complete() const {
  const int wanted = options_.keep_solved_windows;
  return static_cast<int>(solved_windows_.size()) >= wanted || (solved_windows_shot_ >= 0 && shot_ != solved_windows_shot_);
}

// Before SetUnits rescales the points: the window in the solve's own units.
// Only the first shot's (films change lenses at cuts), only when asked.
void TrackCameraEstimator::KeepSolvedWindow(const WindowOutcome& w) {
  if (solved_windows_complete()) return;
  solved_windows_shot_ = shot_;
  SolvedWindow s;
  s.cameras = w.keyframe_cams;
  s.points = w.points;
  s.use_depth = w.pose_options.use_depth;
  s.focal_observable = w.focal_observable;
  for (size_t i = 0; i < keyframes_.size(); ++i)
    for (const auto& [id, u] : At(keyframes_[i].pos).u) {
      const auto it = w.point_of_track.find(id);
      if (it == w.point_of_track.end() || !w.point_kept[it->second]) continue;
      s.observations.push_back({static_cast<int>(i), it->second, u});
    }
  solved_windows_.push_back(std::move(s));
}

// The window's report, with its keyframes' two-view model selection, to
// reports_ and the diagnostics ("window" record, docs/formats.md).
void TrackCameraEstimator::Report(WindowReport r) {
  for (const Keyframe& k : keyframes_) {
    if (k.chain_start || k.fixed) continue;
    r.inliers += k.inliers;
    r.correspondences += k.correspondences;
    r.border_support.push_back(k.border_support);
    r.border_still.push_back(k.border_still);
  }
  if (Wants(diagnostics_, "window")) {
    nlohmann::json keyframes = nlohmann::json::array();
    for (const Keyframe& k : keyframes_) {
      nlohmann::json j = {{"frame", At(k.pos).tracks.index},
                          {"held", k.fixed},
                          {"two_view_model", MotionModelName(k.two_view_model)},
                          {"model", MotionModelName(k.model)}};
      if (!k.chain_start && !k.fixed) {
        j["correspondences"] = k.correspondences;
        j["inliers"] = k.inliers;
        j["border_support"] = k.border_support;
        j["border_moved_by_turn"] = k.border_still.moved_by_turn;
        j["border_still"] = k.border_still.still;
        nlohmann::json gric;
        for (int c = 0; c < kNumCandidates; ++c) gric[kCandidateNames[c]] = k.gric[c];
        j["gric"] = gric;
      }
      keyframes.push_back(std::move(j));
    }
    nlohmann::json candidates = nlohmann::json::array();
    for (const WindowCandidate& c : r.candidates) candidates.push_back(CandidateJson(c, width_));
    nlohmann::json zoom_decisions = nlohmann::json::array();
    for (const ZoomDecision& d : r.zoom_decisions) zoom_decisions.push_back(ZoomDecisionJson(d));
    nlohmann::json timings = nlohmann::json::object();
    for (const auto& [step, s] : r.timings_s) timings[step] = s;
    diagnostics_->Record("window", {{"shot", r.shot},
                                    {"first_frame", r.first_frame},
                                    {"last_frame", r.last_frame},
                                    {"keyframes", std::move(keyframes)},
                                    {"model", r.model},
                                    {"zoom_by_bic", r.zoom_by_bic},
                                    {"labels_revised", r.labels_revised},
                                    {"branch_by_occlusion", r.branch_by_occlusion},
                                    {"plane_prior", r.plane_prior},
                                    {"focal_observable", r.focal_observable},
                                    {"chain_focal_shift", r.chain_focal_shift},
                                    {"points", r.points},
                                    {"points_kept", r.points_kept},
                                    {"observations", r.observations},
                                    {"rms_px", r.rms_px},
                                    {"candidates", std::move(candidates)},
                                    {"zoom_decisions", std::move(zoom_decisions)},
                                    {"zoom_confidence_factor", ZoomConfidenceFactor(r.zoom_decisions)},
                                    {"ba", BaJson(r.ba, width_)},
                                    {"timings_s", std::move(timings)}});
  }
  reports_.push_back(std::move(r));
}

}  // namespace hapcine
