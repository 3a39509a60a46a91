#include "datasets/eval.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include "core/atomic_file.h"
#include "core/csv.h"
#include "core/error.h"
#include "core/rotation.h"
#include "core/statistics.h"
#include "datasets/umeyama.h"

namespace hapcine {
namespace {

struct MatchedPair {
  size_t gt = 0;   // index into gt.frames
  size_t est = 0;  // index into est.frames
  int shot = 0;
};

// Typical frame period of a path: 1/fps from the metadata, else the median
// time step; 0 when neither is known (a single frame without fps).
double FramePeriod(const CameraPath& p) {
  if (p.fps() > 0) return 1.0 / p.fps();
  if (p.frames.size() < 2) return 0;
  std::vector<double> dt;
  for (size_t i = 1; i < p.frames.size(); ++i) {
    dt.push_back(p.frames[i].time_s - p.frames[i - 1].time_s);
  }
  return Quantile(std::move(dt), 0.5);
}

std::vector<MatchedPair> MatchByIndex(const CameraPath& gt, const CameraPath& est) {
  std::map<int, size_t> gt_by_index;
  for (size_t i = 0; i < gt.frames.size(); ++i) gt_by_index[gt.frames[i].frame] = i;
  std::vector<MatchedPair> pairs;
  for (size_t j = 0; j < est.frames.size(); ++j) {
    auto it = gt_by_index.find(est.frames[j].frame);
    if (it != gt_by_index.end()) pairs.push_back({it->second, j, 0});
  }
  return pairs;
}

// Whether the same frame index is not the same instant in the two paths:
// their frame rates differ (a 25 fps encode against 24 fps ground truth) or
// the index pairs' times drift apart by over half a frame for more than a
// tenth of them. A constant offset (an export that starts later) is no drift.
bool IndexIsNotTime(const CameraPath& gt, const CameraPath& est,
                    const std::vector<MatchedPair>& pairs) {
  if (gt.fps() > 0 && est.fps() > 0 && std::abs(gt.fps() / est.fps() - 1) > 0.001) return true;
  double period = FramePeriod(gt);
  if (period <= 0) period = FramePeriod(est);
  if (period <= 0 || pairs.size() < 2) return false;
  std::vector<double> offset;
  for (const MatchedPair& p : pairs) offset.push_back(est.frames[p.est].time_s - gt.frames[p.gt].time_s);
  const double median = Quantile(offset, 0.5);
  const auto drifting = std::count_if(offset.begin(), offset.end(), [&](double o) {
    return std::abs(o - median) > 0.5 * period;
  });
  return 10 * static_cast<size_t>(drifting) > pairs.size();
}

// Nearest ground-truth time within half a frame; a GT frame claimed by two
// estimated frames keeps the closer one.
std::vector<MatchedPair> MatchByTime(const CameraPath& gt, const CameraPath& est) {
  double period = FramePeriod(gt);
  if (period <= 0) period = FramePeriod(est);
  const double tolerance_s = period > 0 ? 0.5 * period : 1e-6;
  std::vector<double> gt_times;
  for (const auto& f : gt.frames) gt_times.push_back(f.time_s);
  std::vector<long> best_est(gt.frames.size(), -1);
  std::vector<double> best_dt(gt.frames.size(), 0);
  for (size_t j = 0; j < est.frames.size(); ++j) {
    const double t = est.frames[j].time_s;
    auto it = std::lower_bound(gt_times.begin(), gt_times.end(), t);
    long cand = -1;
    double cand_dt = 0;
    for (auto k : {it - gt_times.begin() - 1, it - gt_times.begin()}) {
      if (k < 0 || k >= static_cast<long>(gt_times.size())) continue;
      const double dt = std::abs(gt_times[k] - t);
      if (cand < 0 || dt < cand_dt) {
        cand = k;
        cand_dt = dt;
      }
    }
    if (cand < 0 || cand_dt > tolerance_s) continue;
    if (best_est[cand] < 0 || cand_dt < best_dt[cand]) {
      best_est[cand] = static_cast<long>(j);
      best_dt[cand] = cand_dt;
    }
  }
  std::vector<MatchedPair> pairs;
  for (size_t i = 0; i < gt.frames.size(); ++i) {
    if (best_est[i] >= 0) pairs.push_back({i, static_cast<size_t>(best_est[i]), 0});
  }
  return pairs;
}

// f_t / f_0 of one path: from focal_px when both frames carry it, else from
// the FOV (the image width cancels: f_t / f_0 = tan(fov_0/2) / tan(fov_t/2)).
double FocalRatio(const CameraFrame& first, const CameraFrame& f) {
  if (first.focal_px && f.focal_px) return *f.focal_px / *first.focal_px;
  return std::tan(DegToRad(first.fov_deg) / 2) / std::tan(DegToRad(f.fov_deg) / 2);
}

double PathLength(const std::vector<Eigen::Vector3d>& c) {
  double len = 0;
  for (size_t i = 1; i < c.size(); ++i) len += (c[i] - c[i - 1]).norm();
  return len;
}

struct SegmentResult {
  SegmentReport report;
  std::vector<FrameError> frames;
  // Per-frame ATE divided by the segment's GT path length (empty when static).
  std::vector<double> ate_over_length;
  int model_equal = 0;
};

// The errors of one estimated frame `e` against its ground truth `g`, both
// relative to their segment's first frames; `c_est_aligned` is e's centre
// after the trajectory alignment.
FrameError FrameErrorAgainst(const CameraFrame& gt0, const CameraFrame& est0,
                             const CameraFrame& g, const CameraFrame& e,
                             const Eigen::Vector3d& c_gt, const Eigen::Vector3d& c_est_aligned) {
  FrameError fe;
  fe.gt_frame = g.frame;
  fe.est_frame = e.frame;
  fe.time_s = g.time_s;
  const Eigen::Quaterniond gt_rel = gt0.world_from_cam.conjugate() * g.world_from_cam;
  const Eigen::Quaterniond est_rel = est0.world_from_cam.conjugate() * e.world_from_cam;
  fe.rotation_deg = AngleBetweenDeg(gt_rel, est_rel);
  fe.fov_deg = std::abs(e.fov_deg - g.fov_deg);
  fe.fov_percent = 100.0 * fe.fov_deg / g.fov_deg;
  fe.zoom_ratio_percent = 100.0 * std::abs(FocalRatio(est0, e) / FocalRatio(gt0, g) - 1.0);
  fe.ate = (c_gt - c_est_aligned).norm();
  return fe;
}

// evo's RPE: E = (Q_i^-1 Q_j)^-1 (P_i^-1 P_j) with the estimate P aligned.
// The alignment rotation cancels in both parts; only its scale remains in
// the translation. `gt_step`/`est_step`: centre j minus centre i.
void AddRelativePoseError(const CameraFrame& g, const CameraFrame& e, const CameraFrame& g2,
                          const CameraFrame& e2, const Eigen::Vector3d& gt_step,
                          const Eigen::Vector3d& est_step, double scale, FrameError* fe) {
  const Eigen::Quaterniond gt_rot = g.world_from_cam.conjugate() * g2.world_from_cam;
  const Eigen::Quaterniond est_rot = e.world_from_cam.conjugate() * e2.world_from_cam;
  const Eigen::Vector3d t_gt = g.world_from_cam.conjugate() * gt_step;
  const Eigen::Vector3d t_est = scale * (e.world_from_cam.conjugate() * est_step);
  fe->rpe_rotation_deg = AngleBetweenDeg(gt_rot, est_rot);
  fe->rpe_translation = (t_est - t_gt).norm();
}

SegmentResult EvaluateSegment(const CameraPath& gt, const CameraPath& est,
                              const std::vector<MatchedPair>& pairs,
                              const EvalOptions& opt, std::optional<int> shot) {
  SegmentResult r;
  r.report.shot = shot;
  r.report.frames = static_cast<int>(pairs.size());
  if (pairs.empty()) return r;
  const CameraFrame& gt0 = gt.frames[pairs[0].gt];
  const CameraFrame& est0 = est.frames[pairs[0].est];

  std::vector<Eigen::Vector3d> c_gt, c_est;
  for (const auto& p : pairs) {
    c_gt.push_back(gt.frames[p.gt].center);
    c_est.push_back(est.frames[p.est].center);
  }
  Sim3 align;
  if (opt.align != TrajectoryAlignment::kNone) {
    align = AlignUmeyama(c_est, c_gt, opt.align == TrajectoryAlignment::kSim3);
  }
  r.report.align_scale = align.scale;
  r.report.gt_path_length = PathLength(c_gt);
  r.report.est_path_length = PathLength(c_est);
  r.report.gt_static = r.report.gt_path_length < opt.static_path_length;

  std::vector<double> rot, fov, fov_pct, zoom, ate, rpe_rot, rpe_trans;
  for (size_t k = 0; k < pairs.size(); ++k) {
    const CameraFrame& g = gt.frames[pairs[k].gt];
    const CameraFrame& e = est.frames[pairs[k].est];
    FrameError fe = FrameErrorAgainst(gt0, est0, g, e, c_gt[k], align.Apply(c_est[k]));
    fe.shot = pairs[k].shot;
    if (k + opt.rpe_delta < pairs.size()) {
      const size_t k2 = k + opt.rpe_delta;
      AddRelativePoseError(g, e, gt.frames[pairs[k2].gt], est.frames[pairs[k2].est],
                           c_gt[k2] - c_gt[k], c_est[k2] - c_est[k], align.scale, &fe);
      rpe_rot.push_back(*fe.rpe_rotation_deg);
      rpe_trans.push_back(*fe.rpe_translation);
    }
    if (g.model && e.model) {
      ++r.report.model_frames;
      if (*g.model == *e.model) ++r.model_equal;
    }
    if (!r.report.gt_static) r.ate_over_length.push_back(fe.ate / r.report.gt_path_length);
    rot.push_back(fe.rotation_deg);
    fov.push_back(fe.fov_deg);
    fov_pct.push_back(fe.fov_percent);
    zoom.push_back(fe.zoom_ratio_percent);
    ate.push_back(fe.ate);
    r.frames.push_back(fe);
  }
  r.report.rotation_deg = ComputeErrorStats(rot);
  r.report.fov_deg = ComputeErrorStats(fov);
  r.report.fov_percent = ComputeErrorStats(fov_pct);
  r.report.zoom_ratio_percent = ComputeErrorStats(zoom);
  r.report.ate = ComputeErrorStats(ate);
  r.report.rpe_rotation_deg = ComputeErrorStats(rpe_rot);
  r.report.rpe_translation = ComputeErrorStats(rpe_trans);
  if (!r.report.gt_static) {
    r.report.ate_percent = 100.0 * r.report.ate.rmse / r.report.gt_path_length;
  }
  if (r.report.model_frames > 0) {
    r.report.model_agreement = static_cast<double>(r.model_equal) / r.report.model_frames;
  }
  return r;
}

// Overall figures from per-shot results: per-frame errors pooled.
SegmentReport PoolSegments(const std::vector<SegmentResult>& segs) {
  SegmentReport all;
  std::vector<double> rot, fov, fov_pct, zoom, ate, rpe_rot, rpe_trans, ate_rel, scales;
  int model_equal = 0;
  bool any_moving = false;
  for (const auto& s : segs) {
    all.frames += s.report.frames;
    all.gt_path_length += s.report.gt_path_length;
    all.est_path_length += s.report.est_path_length;
    all.model_frames += s.report.model_frames;
    model_equal += s.model_equal;
    any_moving |= !s.report.gt_static;
    scales.push_back(s.report.align_scale);
    ate_rel.insert(ate_rel.end(), s.ate_over_length.begin(), s.ate_over_length.end());
    for (const auto& f : s.frames) {
      rot.push_back(f.rotation_deg);
      fov.push_back(f.fov_deg);
      fov_pct.push_back(f.fov_percent);
      zoom.push_back(f.zoom_ratio_percent);
      ate.push_back(f.ate);
      if (f.rpe_rotation_deg) rpe_rot.push_back(*f.rpe_rotation_deg);
      if (f.rpe_translation) rpe_trans.push_back(*f.rpe_translation);
    }
  }
  all.rotation_deg = ComputeErrorStats(rot);
  all.fov_deg = ComputeErrorStats(fov);
  all.fov_percent = ComputeErrorStats(fov_pct);
  all.zoom_ratio_percent = ComputeErrorStats(zoom);
  all.ate = ComputeErrorStats(ate);
  all.rpe_rotation_deg = ComputeErrorStats(rpe_rot);
  all.rpe_translation = ComputeErrorStats(rpe_trans);
  all.gt_static = !any_moving;
  // RMSE of ATE_i / L_shot(i): reduces to RMSE / L for a single shot.
  if (any_moving) all.ate_percent = 100.0 * ComputeErrorStats(ate_rel).rmse;
  all.align_scale = scales.empty() ? 1.0 : ComputeErrorStats(scales).median;
  if (all.model_frames > 0) {
    all.model_agreement = static_cast<double>(model_equal) / all.model_frames;
  }
  return all;
}

std::string Num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%11.5g", v);
  return buf;
}

std::string StatsRow(const std::string& name, const ErrorStats& s) {
  std::string row = name;
  row.resize(26, ' ');
  if (s.count == 0) return row + "        n/a\n";
  return row + Num(s.mean) + Num(s.median) + Num(s.max) + Num(s.rmse) + "\n";
}

std::string SegmentTable(const SegmentReport& s, int rpe_delta) {
  std::ostringstream o;
  o << "metric                           mean     median        max       rmse\n";
  o << StatsRow("rotation error (deg)", s.rotation_deg);
  o << StatsRow("fov error (deg)", s.fov_deg);
  o << StatsRow("fov error (%)", s.fov_percent);
  o << StatsRow("zoom ratio error (%)", s.zoom_ratio_percent);
  o << StatsRow("ATE (GT units)", s.ate);
  o << StatsRow("RPE rotation (deg)", s.rpe_rotation_deg);
  o << StatsRow("RPE translation (GT u)", s.rpe_translation);
  o << "ATE % of GT path length: "
    << (s.ate_percent ? Num(*s.ate_percent).substr(Num(*s.ate_percent).find_first_not_of(' ')) + " %"
                      : std::string("n/a (GT camera does not move)"))
    << "\n";
  o << "path length: GT " << FormatDouble(s.gt_path_length) << ", estimate "
    << FormatDouble(s.est_path_length) << " (estimate units, unaligned)";
  if (s.gt_static)
    o << (s.est_path_length > 0 ? "  <- spurious translation" : "  (none, as in the ground truth)");
  o << "\n";
  if (s.lost_frames > 0) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "lost: %d of %d matched frames (%.1f %%): not placed, left out of the errors above\n",
                  s.lost_frames, s.lost_frames + s.frames, 100.0 * s.lost_frames / (s.lost_frames + s.frames));
    o << buf;
  }
  if (s.model_agreement) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "model agreement: %.1f %% of %d frames\n",
                  100.0 * *s.model_agreement, s.model_frames);
    o << buf;
  }
  return o.str();
}

nlohmann::json StatsJson(const ErrorStats& s) {
  nlohmann::json j;
  j["count"] = s.count;
  if (s.count == 0) {
    j["mean"] = j["median"] = j["max"] = j["rmse"] = nullptr;
  } else {
    j["mean"] = s.mean;
    j["median"] = s.median;
    j["max"] = s.max;
    j["rmse"] = s.rmse;
  }
  return j;
}

nlohmann::json SegmentJson(const SegmentReport& s) {
  nlohmann::json j;
  j["shot"] = s.shot ? nlohmann::json(*s.shot) : nlohmann::json(nullptr);
  j["frames"] = s.frames;
  j["lost_frames"] = s.lost_frames;
  j["lost_share"] = s.frames + s.lost_frames > 0
                        ? nlohmann::json(static_cast<double>(s.lost_frames) / (s.frames + s.lost_frames))
                        : nlohmann::json(nullptr);
  j["rotation_deg"] = StatsJson(s.rotation_deg);
  j["fov_deg"] = StatsJson(s.fov_deg);
  j["fov_percent"] = StatsJson(s.fov_percent);
  j["zoom_ratio_percent"] = StatsJson(s.zoom_ratio_percent);
  j["ate"] = StatsJson(s.ate);
  j["ate_percent"] = s.ate_percent ? nlohmann::json(*s.ate_percent) : nlohmann::json(nullptr);
  j["gt_path_length"] = s.gt_path_length;
  j["est_path_length"] = s.est_path_length;
  j["gt_static"] = s.gt_static;
  j["spurious_translation"] =
      s.gt_static ? nlohmann::json(s.est_path_length) : nlohmann::json(nullptr);
  j["align_scale"] = s.align_scale;
  j["rpe_rotation_deg"] = StatsJson(s.rpe_rotation_deg);
  j["rpe_translation"] = StatsJson(s.rpe_translation);
  j["model_agreement"] =
      s.model_agreement ? nlohmann::json(*s.model_agreement) : nlohmann::json(nullptr);
  j["model_frames"] = s.model_frames;
  return j;
}

}  // namespace

const char* TrajectoryAlignmentName(TrajectoryAlignment a) {
  switch (a) {
    case TrajectoryAlignment::kSim3: return "sim3";
    case TrajectoryAlignment::kSe3: return "se3";
    case TrajectoryAlignment::kNone: return "none";
  }
  return "?";
}

TrajectoryAlignment ParseTrajectoryAlignment(const std::string& name) {
  if (name == "sim3") return TrajectoryAlignment::kSim3;
  if (name == "se3") return TrajectoryAlignment::kSe3;
  if (name == "none") return TrajectoryAlignment::kNone;
  throw UsageError("unknown alignment '" + name + "' (use sim3, se3 or none)");
}

const char* FrameMatchingName(FrameMatching m) {
  switch (m) {
    case FrameMatching::kAuto: return "auto";
    case FrameMatching::kFrameIndex: return "frame";
    case FrameMatching::kTime: return "time";
  }
  return "?";
}

FrameMatching ParseFrameMatching(const std::string& name) {
  if (name == "auto") return FrameMatching::kAuto;
  if (name == "frame") return FrameMatching::kFrameIndex;
  if (name == "time") return FrameMatching::kTime;
  throw UsageError("unknown matching '" + name + "' (use auto, frame or time)");
}

void EvalOptions::Check() const {
  if (rpe_delta < 1) throw UsageError("RPE delta must be >= 1 frame");
  if (!(static_path_length >= 0) || !std::isfinite(static_path_length)) {
    throw UsageError("static path length must be a finite number >= 0");
  }
  if (shot_tolerance_frames < 0) throw UsageError("shot tolerance must be >= 0 frames");
}

ErrorStats ComputeErrorStats(std::vector<double> v) {
  ErrorStats s;
  s.count = static_cast<int>(v.size());
  if (v.empty()) return s;
  double sum = 0, sum_sq = 0;
  for (double x : v) {
    sum += x;
    sum_sq += x * x;
    s.max = std::max(s.max, x);
  }
  s.mean = sum / v.size();
  s.rmse = std::sqrt(sum_sq / v.size());
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  s.median = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
  return s;
}

namespace {

// Pairs of frames by the matching the options ask for; auto pairs by frame
// index unless under half the frames share an index or indices are not times.
std::vector<MatchedPair> MatchFrames(const CameraPath& gt, const CameraPath& est,
                                     FrameMatching matching, FrameMatching* used) {
  if (matching == FrameMatching::kTime) {
    *used = FrameMatching::kTime;
    return MatchByTime(gt, est);
  }
  std::vector<MatchedPair> pairs = MatchByIndex(gt, est);
  *used = FrameMatching::kFrameIndex;
  if (matching == FrameMatching::kFrameIndex) return pairs;
  const size_t shorter = std::min(gt.frames.size(), est.frames.size());
  if (2 * pairs.size() < shorter || IndexIsNotTime(gt, est, pairs)) {
    *used = FrameMatching::kTime;
    return MatchByTime(gt, est);
  }
  return pairs;
}

bool HasShots(const CameraPath& path) {
  for (const auto& f : path.frames)
    if (f.shot.has_value()) return true;
  return false;
}

ShotBoundaryScore ScoreBoundaries(const CameraPath& gt, const CameraPath& est,
                                    const std::vector<MatchedPair>& pairs,
                                    int tolerance_frames) {
  std::vector<ShotSample> samples;
  for (const auto& p : pairs)
    samples.push_back({gt.frames[p.gt].frame, gt.frames[p.gt].shot.value_or(-1),
                       est.frames[p.est].shot.value_or(-1)});
  std::stable_sort(samples.begin(), samples.end(),
                   [](const ShotSample& a, const ShotSample& b) { return a.frame < b.frame; });
  return ScoreShotBoundaries(samples, tolerance_frames);
}

// The matched pairs per shot (one group -1 when not per shot), without the
// estimate's lost frames, which are counted per group instead.
struct PairGroups {
  std::map<int, std::vector<MatchedPair>> pairs;
  std::map<int, int> lost;
  int lost_total = 0;
};

PairGroups GroupPairs(const CameraPath& gt, const CameraPath& est,
                      std::vector<MatchedPair> pairs, bool by_shot, bool gt_shots) {
  PairGroups g;
  for (auto& p : pairs) {
    if (by_shot) {
      const auto& s = gt_shots ? gt.frames[p.gt].shot : est.frames[p.est].shot;
      p.shot = s.value_or(-1);
    }
    if (IsLost(est.frames[p.est])) {
      ++g.lost[p.shot];
      ++g.lost_total;
      g.pairs[p.shot];  // a shot lost entirely is still listed
      continue;
    }
    g.pairs[p.shot].push_back(p);
  }
  if (g.lost_total == static_cast<int>(pairs.size())) {
    throw Error("eval", "every one of the " + std::to_string(g.lost_total) +
                            " matched frames of the estimate is lost: nothing to compare");
  }
  return g;
}

}  // namespace

EvalReport EvaluateCameraPaths(const CameraPath& gt, const CameraPath& est,
                               const EvalOptions& options) {
  options.Check();
  EvalReport report;
  report.options = options;
  report.gt_frames = static_cast<int>(gt.frames.size());
  report.est_frames = static_cast<int>(est.frames.size());
  const std::vector<MatchedPair> pairs =
      MatchFrames(gt, est, options.matching, &report.matching_used);
  report.matched = static_cast<int>(pairs.size());
  report.unmatched_gt = report.gt_frames - report.matched;
  report.unmatched_est = report.est_frames - report.matched;
  if (pairs.empty()) {
    throw Error("eval", std::string("no frames in common between ground truth and estimate (by ") +
                            FrameMatchingName(report.matching_used) + ")");
  }
  // Shots: the ground truth's column if it has one, else the estimate's.
  const bool gt_shots = HasShots(gt), est_shots = HasShots(est);
  const bool by_shot = options.per_shot && (gt_shots || est_shots);
  if (gt_shots && est_shots)
    report.shot_boundaries = ScoreBoundaries(gt, est, pairs, options.shot_tolerance_frames);
  PairGroups groups = GroupPairs(gt, est, pairs, by_shot, gt_shots);

  std::vector<SegmentResult> segs;
  for (const auto& [shot, group] : groups.pairs) {
    segs.push_back(EvaluateSegment(gt, est, group, options,
                                   by_shot ? std::optional<int>(shot) : std::nullopt));
    segs.back().report.lost_frames = groups.lost[shot];
  }
  if (by_shot) {
    std::vector<SegmentResult> compared;  // shots with frames to compare
    for (const auto& s : segs)
      if (s.report.frames > 0) compared.push_back(s);
    report.overall = PoolSegments(compared);
    for (const auto& s : segs) report.shots.push_back(s.report);
  } else {
    report.overall = segs[0].report;
  }
  report.overall.lost_frames = groups.lost_total;
  for (const auto& s : segs) {
    report.per_frame.insert(report.per_frame.end(), s.frames.begin(), s.frames.end());
  }
  std::sort(report.per_frame.begin(), report.per_frame.end(),
            [](const FrameError& a, const FrameError& b) { return a.gt_frame < b.gt_frame; });
  return report;
}

std::string FormatEvalTable(const EvalReport& r) {
  std::ostringstream o;
  if (!r.gt_source.empty() || !r.est_source.empty()) {
    o << "ground truth: " << r.gt_source << "\nestimate:     " << r.est_source << "\n";
  }
  o << "frames: gt " << r.gt_frames << ", estimate " << r.est_frames << ", matched "
    << r.matched << " (by " << (r.matching_used == FrameMatching::kTime ? "time" : "frame index")
    << "), unmatched gt " << r.unmatched_gt << ", unmatched estimate " << r.unmatched_est
    << "\n";
  o << "alignment: " << TrajectoryAlignmentName(r.options.align) << " (scale "
    << FormatDouble(r.overall.align_scale) << (r.shots.size() > 1 ? ", median over shots" : "")
    << "), RPE delta " << r.options.rpe_delta << " frame(s)\n\n";
  o << SegmentTable(r.overall, r.options.rpe_delta);
  if (r.shot_boundaries) {
    const ShotBoundaryScore& b = *r.shot_boundaries;
    const auto frac = [](const std::optional<double>& v) {
      return v ? FormatDouble(*v) : std::string("n/a");
    };
    o << "shot boundaries (+-" << b.tolerance_frames << " frames): gt " << b.gt_boundaries.size()
      << ", estimate " << b.est_boundaries.size() << ", matched " << b.matched
      << ": precision " << frac(b.precision) << ", recall " << frac(b.recall) << "\n";
  }
  if (!r.shots.empty()) {
    o << "\nper shot (each aligned on its own first frame):\n";
    o << " shot frames   rot mean    rot max   fov mean  zoom mean   ATE rmse      ATE %"
         "  est path   lost\n";
    for (const auto& s : r.shots) {
      char buf[64];
      std::snprintf(buf, sizeof buf, "%5d %6d", s.shot.value_or(-1), s.frames);
      o << buf << Num(s.rotation_deg.mean) << Num(s.rotation_deg.max) << Num(s.fov_deg.mean)
        << Num(s.zoom_ratio_percent.mean) << Num(s.ate.rmse)
        << (s.ate_percent ? Num(*s.ate_percent) : std::string("        n/a"))
        << Num(s.est_path_length);
      std::snprintf(buf, sizeof buf, " %6d\n", s.lost_frames);
      o << buf;
    }
  }
  return o.str();
}

nlohmann::json EvalReportToJson(const EvalReport& r) {
  nlohmann::json j;
  j["gt"] = r.gt_source;
  j["est"] = r.est_source;
  j["options"] = {{"align", TrajectoryAlignmentName(r.options.align)},
                  {"rpe_delta_frames", r.options.rpe_delta},
                  {"matching", FrameMatchingName(r.options.matching)},
                  {"per_shot", r.options.per_shot},
                  {"static_path_length", r.options.static_path_length},
                  {"shot_tolerance_frames", r.options.shot_tolerance_frames}};
  j["matching"] = FrameMatchingName(r.matching_used);
  j["frames"] = {{"gt", r.gt_frames},
                 {"est", r.est_frames},
                 {"matched", r.matched},
                 {"unmatched_gt", r.unmatched_gt},
                 {"unmatched_est", r.unmatched_est}};
  j["overall"] = SegmentJson(r.overall);
  j["shots"] = nlohmann::json::array();
  for (const auto& s : r.shots) j["shots"].push_back(SegmentJson(s));
  j["shot_boundaries"] = nullptr;
  if (r.shot_boundaries) {
    const ShotBoundaryScore& b = *r.shot_boundaries;
    const auto opt = [](const std::optional<double>& v) {
      return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
    };
    j["shot_boundaries"] = {{"tolerance_frames", b.tolerance_frames},
                            {"gt", b.gt_boundaries},
                            {"est", b.est_boundaries},
                            {"matched", b.matched},
                            {"precision", opt(b.precision)},
                            {"recall", opt(b.recall)}};
  }
  return j;
}

void WritePerFrameErrorsFile(const EvalReport& r, const std::string& file) {
  AtomicFile out(file);
  std::ostream& o = out.stream();
  o << "gt_frame,est_frame,time_s,shot,rotation_deg,fov_deg,fov_percent,zoom_ratio_percent,"
       "ate,rpe_rotation_deg,rpe_translation\n";
  for (const auto& f : r.per_frame) {
    o << f.gt_frame << ',' << f.est_frame << ',' << FormatFixed(f.time_s, 6) << ',' << f.shot
      << ',' << FormatDouble(f.rotation_deg) << ',' << FormatDouble(f.fov_deg) << ','
      << FormatDouble(f.fov_percent) << ',' << FormatDouble(f.zoom_ratio_percent) << ','
      << FormatDouble(f.ate) << ','
      << (f.rpe_rotation_deg ? FormatDouble(*f.rpe_rotation_deg) : "") << ','
      << (f.rpe_translation ? FormatDouble(*f.rpe_translation) : "") << '\n';
  }
  out.Commit();
}

}  // namespace hapcine
