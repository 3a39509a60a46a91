#include "haptics/camera_signals.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <string>
#include <utility>

#include "core/csv.h"
#include "core/error.h"
#include "core/input_file.h"
#include "core/rotation.h"
#include "haptics/washout.h"

namespace hapcine {
namespace {

constexpr double kAbsurdPosition = 1e6;

// Adds multiples of 2 pi so that consecutive samples differ by less than pi.
void Unwrap(std::vector<double>* v) {
  for (size_t i = 1; i < v->size(); ++i) {
    double d = (*v)[i] - (*v)[i - 1];
    while (d > kPi) {
      (*v)[i] -= 2 * kPi;
      d -= 2 * kPi;
    }
    while (d < -kPi) {
      (*v)[i] += 2 * kPi;
      d += 2 * kPi;
    }
  }
}

}  // namespace

std::vector<ShotRange> SplitShots(const CameraPath& path) {
  std::vector<ShotRange> shots;
  int current = 0;
  for (size_t i = 0; i < path.frames.size(); ++i) {
    const auto& f = path.frames[i];
    const int s = f.shot ? *f.shot : (shots.empty() ? 0 : current);
    if (shots.empty() || s != current) {
      shots.push_back(ShotRange{s, i, i});
      current = s;
    } else {
      shots.back().last = i;
    }
  }
  return shots;
}

CameraSignals ExtractShotSignals(const CameraPath& path, const ShotRange& shot,
                                 double reference_depth_u) {
  CameraSignals s;
  const auto& f0 = path.frames[shot.first];
  const Eigen::Matrix3d cam0_from_world = f0.world_from_cam.toRotationMatrix().transpose();
  const double tan0 = std::tan(DegToRad(f0.fov_deg) / 2);
  for (size_t i = shot.first; i <= shot.last; ++i) {
    const auto& f = path.frames[i];
    s.time_s.push_back(f.time_s);
    s.position_u.push_back(cam0_from_world * (f.center - f0.center));
    const Eigen::Quaterniond rel(cam0_from_world * f.world_from_cam.toRotationMatrix());
    const PanTiltRoll ptr = PanTiltRollFromQuaternion(rel);
    s.tilt_rad.push_back(DegToRad(ptr.tilt_deg));
    s.pan_rad.push_back(DegToRad(ptr.pan_deg));
    s.roll_rad.push_back(DegToRad(ptr.roll_deg));
    const double ratio = tan0 / std::tan(DegToRad(f.fov_deg) / 2);
    s.zoom_forward_u.push_back(reference_depth_u * (ratio - 1.0));
    s.log_zoom.push_back(std::log(ratio));
  }
  s.reference_depth_u = reference_depth_u;
  Unwrap(&s.pan_rad);
  Unwrap(&s.roll_rad);
  return s;
}

namespace {

// The rigid move (and focal ratio) applied to the frames after a lost run.
struct PoseCorrection {
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  double tan_ratio = 1;  // tan(fov/2) multiplier
  bool identity = true;
};

CameraFrame Corrected(const CameraFrame& f, const PoseCorrection& c) {
  if (c.identity) return f;
  CameraFrame out = f;
  out.world_from_cam = CanonicalQuaternion((c.rotation * f.world_from_cam).normalized());
  out.center = c.rotation * f.center + c.translation;
  const double half = std::atan(c.tan_ratio * std::tan(DegToRad(f.fov_deg) / 2));
  out.fov_deg = RadToDeg(2 * half);
  if (f.focal_px) *out.focal_px = *f.focal_px / c.tan_ratio;
  return out;
}

// The correction that puts `placed` (as read) on `target` (as corrected).
PoseCorrection CorrectionOnto(const CameraFrame& target, const CameraFrame& placed) {
  PoseCorrection c;
  c.rotation = (target.world_from_cam * placed.world_from_cam.conjugate()).normalized();
  c.translation = target.center - c.rotation * placed.center;
  c.tan_ratio = std::tan(DegToRad(target.fov_deg) / 2) / std::tan(DegToRad(placed.fov_deg) / 2);
  // Already joined (up to round-off): nothing to move.
  c.identity = AngleBetweenDeg(target.world_from_cam, placed.world_from_cam) < 1e-9 &&
               (target.center - placed.center).norm() <= 1e-12 * (1 + placed.center.norm()) &&
               std::abs(target.fov_deg - placed.fov_deg) < 1e-9;
  return c;
}

}  // namespace

std::optional<CameraPath> JoinAcrossLostFrames(const CameraPath& path) {
  std::optional<CameraPath> joined;
  PoseCorrection correction;
  for (size_t i = 1; i < path.frames.size(); ++i) {
    const CameraFrame& prev = path.frames[i - 1];
    const CameraFrame& f = path.frames[i];
    if (f.shot != prev.shot) correction = PoseCorrection();  // a new shot: its own origin
    if (IsLost(prev) && !IsLost(f) && f.shot == prev.shot) {
      const CameraFrame target = joined ? joined->frames[i - 1] : prev;
      correction = CorrectionOnto(target, f);
    }
    if (correction.identity) {
      if (joined) joined->frames[i] = f;
      continue;
    }
    if (!joined) joined = path;
    joined->frames[i] = Corrected(f, correction);
  }
  return joined;
}

void FadeToRestOverLostFrames(const std::vector<double>& time_s, const std::vector<bool>& lost,
                              double ramp_s, std::vector<double>* x) {
  double from = 0, to = 0, start_s = 0;  // the removed part goes from `from` to `to` from start_s
  auto removed = [&](double t) {
    const double w = ramp_s > 0 ? SmootherStep((t - start_s) / ramp_s) : 1.0;
    return from + (to - from) * w;
  };
  double last_removed = 0;
  for (size_t i = 0; i < x->size(); ++i) {
    if (i > 0 && lost[i] && !lost[i - 1]) {
      // A lost run starts: bring what frame i-1 shows back to rest.
      from = last_removed;
      to = (*x)[i - 1];
      start_s = time_s[i - 1];
    }
    last_removed = removed(time_s[i]);
    (*x)[i] -= last_removed;
  }
}

std::vector<int> CsvDataRowLines(const std::string& file) {
  std::vector<int> lines;
  if (!IsRegularFile(file)) return lines;  // the path's reader said why
  std::ifstream in(file);
  if (!in) return lines;
  try {
    CsvReader csv(in, file);
    csv.ReadPreamble();
    std::vector<std::string> fields;
    while (csv.NextRow(&fields)) lines.push_back(csv.line());
  } catch (const Error&) {
    // The reader reports bad rows itself; keep the lines read so far.
  }
  return lines;
}

double ReferenceDepthFor(const CameraPath& path, double fallback) {
  for (const char* key : {"subject_distance_m", "reference_depth"}) {
    auto it = path.metadata.find(key);
    if (it == path.metadata.end()) continue;
    char* end = nullptr;
    const double v = std::strtod(it->second.c_str(), &end);
    if (end != it->second.c_str() && std::isfinite(v) && v > 0) return v;
  }
  return fallback;
}

std::optional<double> DollyZoomSubjectDistance(const CameraPath& path, const ShotRange& shot) {
  const auto& f0 = path.frames[shot.first];
  const Eigen::Vector3d axis = f0.world_from_cam.toRotationMatrix().col(2);  // camera +Z (backward)
  const double tan0 = std::tan(DegToRad(f0.fov_deg) / 2);
  double sdd = 0, sdm = 0, smm = 0, max_m = 0, max_d = 0;
  std::vector<std::pair<double, double>> dm;  // (forward travel, 1 - ratio)
  for (size_t i = shot.first; i <= shot.last; ++i) {
    const auto& f = path.frames[i];
    const double d = -axis.dot(f.center - f0.center);
    const double m = 1.0 - tan0 / std::tan(DegToRad(f.fov_deg) / 2);
    dm.emplace_back(d, m);
    sdd += d * d;
    sdm += d * m;
    smm += m * m;
    max_m = std::max(max_m, std::abs(m));
    max_d = std::max(max_d, std::abs(d));
  }
  if (!(sdd > 0 && sdm > 0 && max_m >= 0.05)) return std::nullopt;
  const double inv_d = sdm / sdd;  // 1 / D
  double sr = 0;
  for (const auto& [d, m] : dm) sr += (m - d * inv_d) * (m - d * inv_d);
  if (!(sr <= 0.01 * smm) || !(max_d * inv_d >= 0.05)) return std::nullopt;
  const double depth = 1.0 / inv_d;
  return std::isfinite(depth) ? std::optional<double>(depth) : std::nullopt;
}

double ShotReferenceDepth(const CameraPath& path, const ShotRange& shot, double explicit_depth_u) {
  if (explicit_depth_u > 0) return explicit_depth_u;
  if (const auto d = DollyZoomSubjectDistance(path, shot)) return *d;
  return ReferenceDepthFor(path, 1.0);
}

namespace {

std::string Seconds(double s) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g s", s);
  return buf;
}

// Median time between consecutive frames of one shot; 0 when no shot has two.
double MedianFrameInterval(const CameraPath& path, const std::vector<ShotRange>& shots) {
  std::vector<double> dt;
  for (const ShotRange& r : shots) {
    for (size_t i = r.first + 1; i <= r.last; ++i)
      dt.push_back(path.frames[i].time_s - path.frames[i - 1].time_s);
  }
  if (dt.empty()) return 0;
  std::nth_element(dt.begin(), dt.begin() + dt.size() / 2, dt.end());
  return dt[dt.size() / 2];
}

// A shot change may skip time (an interlude cut out, shots of separate clips)
// and the track spans it, the film's clock being the player's. What a gap
// skips beyond max_gap_s is bounded by the time the path's own frames cover
// (rows x median frame interval), summed over all shot changes: the track is
// then at most about twice the path's length, whatever a time_s says.
void CheckGapsAtShotChanges(const CameraPath& path, const std::vector<ShotRange>& shots,
                            double max_gap_s, const std::function<std::string(size_t)>& where) {
  const double covered_s = path.frames.size() * MedianFrameInterval(path, shots);
  double skipped_s = 0;
  for (size_t k = 1; k < shots.size(); ++k) {
    const size_t i = shots[k].first;
    const double gap = path.frames[i].time_s - path.frames[i - 1].time_s;
    skipped_s += std::max(0.0, gap - max_gap_s);
    if (skipped_s > covered_s) {
      throw Error(where(i), "time gap of " + Seconds(gap) + " at the change to shot " +
                                std::to_string(shots[k].shot) + ": shot changes skip " +
                                Seconds(skipped_s) + " beyond --max-gap, more than the " +
                                Seconds(covered_s) + " the path's " +
                                std::to_string(path.frames.size()) +
                                " frames cover (a jump in time_s?)");
    }
  }
}

}  // namespace

void ValidatePathForHaptics(const CameraPath& path, const std::string& source, double max_gap_s,
                            const std::vector<int>* data_lines) {
  if (path.frames.empty()) throw Error(source, "camera path has no frames");
  const std::function<std::string(size_t)> where = [&](size_t i) {
    const std::string frame = "frame " + std::to_string(path.frames[i].frame);
    if (data_lines && i < data_lines->size()) {
      return source + ":" + std::to_string((*data_lines)[i]) + ": " + frame;
    }
    return source + ": " + frame + " (data row " + std::to_string(i + 1) + ")";
  };
  for (size_t i = 0; i < path.frames.size(); ++i) {
    const auto& f = path.frames[i];
    const std::string bad = ValidateCameraFrame(f);
    if (!bad.empty()) throw Error(where(i), bad);
    if (!(f.center.cwiseAbs().maxCoeff() <= kAbsurdPosition)) {
      throw Error(where(i), "camera position beyond 1e6 units (absurd)");
    }
    if (i > 0 && !(f.time_s > path.frames[i - 1].time_s)) {
      throw Error(where(i), "time_s is not increasing");
    }
  }
  const std::vector<ShotRange> shots = SplitShots(path);
  for (const ShotRange& r : shots) {
    for (size_t i = r.first + 1; i <= r.last; ++i) {
      const double gap = path.frames[i].time_s - path.frames[i - 1].time_s;
      if (gap > max_gap_s) {
        throw Error(where(i), "time gap of " + std::to_string(gap) + " s inside shot " +
                                  std::to_string(r.shot) + " (more than " +
                                  std::to_string(max_gap_s) + " s: missing frames?)");
      }
    }
  }
  CheckGapsAtShotChanges(path, shots, max_gap_s, where);
}

}  // namespace hapcine
