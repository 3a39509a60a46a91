#include "datasets/plot_tracks.h"

#include <cmath>
#include <limits>
#include <map>

#include "core/csv.h"
#include "core/error.h"
#include "core/rotation.h"
#include "haptics/effect_classifier.h"

namespace hapcine {
namespace {

struct PathSeries {
  std::vector<double> t, pan, tilt, roll, x, y, z, fov;
};

PathSeries Extract(const CameraPath& p, bool relative, double scale) {
  PathSeries s;
  if (p.frames.empty()) return s;
  const Eigen::Quaterniond q0_inv = p.frames[0].world_from_cam.conjugate();
  const Eigen::Vector3d c0 = p.frames[0].center;
  for (const auto& f : p.frames) {
    Eigen::Quaterniond q = f.world_from_cam;
    Eigen::Vector3d c = f.center;
    if (relative) {
      q = q0_inv * q;
      c = q0_inv * (c - c0);
    }
    c *= scale;
    const PanTiltRoll a = PanTiltRollFromQuaternion(q);
    s.t.push_back(f.time_s);
    s.pan.push_back(a.pan_deg);
    s.tilt.push_back(a.tilt_deg);
    s.roll.push_back(a.roll_deg);
    s.x.push_back(c.x());
    s.y.push_back(c.y());
    s.z.push_back(c.z());
    s.fov.push_back(f.fov_deg);
  }
  return s;
}

// Least-squares s minimising sum |g_t - s e_t|^2 over frames with equal
// indices (relative positions); 1 when undefined (no motion).
double EstimateScale(const CameraPath& gt, const CameraPath& est) {
  std::map<int, Eigen::Vector3d> g;
  const Eigen::Quaterniond g0 = gt.frames[0].world_from_cam.conjugate();
  for (const auto& f : gt.frames) g[f.frame] = g0 * (f.center - gt.frames[0].center);
  const Eigen::Quaterniond e0 = est.frames[0].world_from_cam.conjugate();
  double num = 0, den = 0;
  for (const auto& f : est.frames) {
    auto it = g.find(f.frame);
    if (it == g.end()) continue;
    const Eigen::Vector3d e = e0 * (f.center - est.frames[0].center);
    num += it->second.dot(e);
    den += e.squaredNorm();
  }
  const double s = den > 1e-300 ? num / den : 1.0;
  return std::isfinite(s) && s > 0 ? s : 1.0;
}

double FramePeriod(const CameraPath& p) {
  const size_t n = p.frames.size();
  return n > 1 ? (p.frames[n - 1].time_s - p.frames[0].time_s) / (n - 1) : 0.0;
}

// "traveling left", "zoom_in out", ...: the effect and the direction its
// intensity's sign gives (effect_classifier.h).
std::string LabelWithDirection(const EffectSegment& seg) {
  const bool neg = seg.intensity < 0;
  const char* dir = "";
  switch (seg.effect) {
    case CameraEffect::kCraneShot:
    case CameraEffect::kTilting:
      dir = neg ? " down" : " up";
      break;
    case CameraEffect::kDutchAngle:
      dir = neg ? " cw" : " ccw";
      break;
    case CameraEffect::kTraveling:
      dir = neg ? " left" : " right";
      break;
    case CameraEffect::kZoomIn:
      dir = neg ? " (out)" : "";
      break;
    case CameraEffect::kVertigo:
      dir = neg ? " backward" : "";
      break;
    default:
      break;
  }
  return std::string(EffectName(seg.effect)) + dir;
}

// "none" is light grey; every other label gets the next palette colour the
// first time it is seen (shared across the time lines of one figure).
PlotColor BandColor(const std::string& label, std::map<std::string, int>* colors) {
  if (label == "none") return PlotColor{235, 235, 235};
  const int index = colors->emplace(label, static_cast<int>(colors->size())).first->second;
  return PaletteColor(index + 1);
}

PlotPanel BandPanel(const std::string& title) {
  PlotPanel line;
  line.title = title;
  line.show_y_axis = false;
  line.height_weight = 0.45;
  return line;
}

// The classifier's segments of a path as bands, "none" between them and to
// the ends; two segments that touch (e.g. at a cut) stay two bands.
PlotPanel ClassifiedTimeline(const std::string& title, const CameraPath& p,
                             std::map<std::string, int>* colors) {
  PlotPanel line = BandPanel(title);
  auto add = [&](double begin, double end, const std::string& label) {
    PlotBand b;
    b.x_begin = begin;
    b.x_end = end;
    b.label = label;
    b.color = BandColor(label, colors);
    line.bands.push_back(b);
  };
  const double t1 = p.frames.back().time_s + FramePeriod(p);
  double at = p.frames.front().time_s;
  for (const EffectSegment& seg : ClassifyEffects(p, ClassifierOptions{})) {
    if (seg.start_s > at) add(at, seg.start_s, "none");
    add(seg.start_s, seg.end_s, LabelWithDirection(seg));
    at = seg.end_s;
  }
  if (at < t1) add(at, t1, "none");
  return line;
}

void AddSeries(PlotPanel* panel, const std::string& name, const std::vector<double>& t,
               const std::vector<double>& v, int color, bool dashed) {
  PlotSeries s;
  s.name = name;
  s.x = t;
  s.y = v;
  s.color = PaletteColor(color);
  s.dashed = dashed;
  panel->series.push_back(std::move(s));
}

}  // namespace

void CameraPlotOptions::Check() const {
  if (scale_estimate && !relative_to_first) {
    throw UsageError("scaling the estimate needs positions relative to the first frame");
  }
}

Figure CameraPathFigure(const CameraPath& gt, const CameraPath* est,
                        const CameraPlotOptions& options) {
  options.Check();
  if (gt.frames.empty()) throw UsageError("camera path has no frames");
  if (est && est->frames.empty()) throw UsageError("estimated camera path has no frames");
  Figure fig;
  fig.title = options.title;
  fig.panels.resize(3);
  PlotPanel& rot = fig.panels[0];
  PlotPanel& pos = fig.panels[1];
  PlotPanel& fov = fig.panels[2];
  rot.title = "rotation (pan, tilt, roll)";
  rot.y_label = "deg";
  pos.title = "camera centre";
  pos.y_label = "units";
  fov.title = "horizontal field of view";
  fov.y_label = "deg";
  fov.height_weight = 0.8;

  struct Source {
    const CameraPath* path;
    std::string suffix;
    std::string position_suffix;  // notes the estimate's scale factor
    bool dashed;
    double scale;
  };
  const std::string gt_suffix = est ? " (GT)" : "";
  std::vector<Source> sources = {{&gt, gt_suffix, gt_suffix, false, 1.0}};
  if (est) {
    const double s =
        options.relative_to_first && options.scale_estimate ? EstimateScale(gt, *est) : 1.0;
    std::string position_suffix = " (est)";
    if (s != 1.0) position_suffix = " (est x" + FormatDouble(std::round(s * 1000) / 1000) + ")";
    sources.push_back({est, " (est)", position_suffix, true, s});
  }
  for (const auto& src : sources) {
    const PathSeries s = Extract(*src.path, options.relative_to_first, src.scale);
    AddSeries(&rot, "pan" + src.suffix, s.t, s.pan, 0, src.dashed);
    AddSeries(&rot, "tilt" + src.suffix, s.t, s.tilt, 1, src.dashed);
    AddSeries(&rot, "roll" + src.suffix, s.t, s.roll, 2, src.dashed);
    AddSeries(&pos, "x" + src.position_suffix, s.t, s.x, 3, src.dashed);
    AddSeries(&pos, "y" + src.position_suffix, s.t, s.y, 4, src.dashed);
    AddSeries(&pos, "z" + src.position_suffix, s.t, s.z, 5, src.dashed);
    AddSeries(&fov, "fov" + src.suffix, s.t, s.fov, 0, src.dashed);
  }
  if (options.cuts) fig.cut_x = ShotCutTimes(gt);
  if (options.confidence) {
    std::optional<PlotPanel> conf;
    if (est) conf = ConfidencePanel(*est, "estimate confidence");
    if (!conf) conf = ConfidencePanel(gt, "estimate confidence");
    if (conf) fig.panels.push_back(std::move(*conf));
  }
  if (options.effect_labels) {
    std::map<std::string, int> colors;
    for (const auto& src : sources) {
      fig.panels.push_back(
          ClassifiedTimeline("effects found by the classifier" + src.suffix, *src.path, &colors));
    }
  }
  return fig;
}

std::vector<double> ShotCutTimes(const CameraPath& path) {
  std::vector<double> cuts;
  for (size_t i = 1; i < path.frames.size(); ++i) {
    const auto& before = path.frames[i - 1].shot;
    const auto& now = path.frames[i].shot;
    if (before && now && *before != *now) cuts.push_back(path.frames[i].time_s);
  }
  return cuts;
}

std::vector<double> ShotCutTimes(const HapticTrack& track) {
  std::vector<double> cuts;
  for (size_t i = 1; i < track.samples.size(); ++i) {
    const auto& before = track.samples[i - 1].shot;
    const auto& now = track.samples[i].shot;
    if (before && now && *before != *now) cuts.push_back(track.samples[i].time_s);
  }
  return cuts;
}

std::optional<PlotPanel> ConfidencePanel(const CameraPath& path, const std::string& title) {
  PlotSeries s;
  s.name = "confidence";
  s.color = PaletteColor(7);  // grey: under the curves, not one of them
  s.filled = true;
  bool any = false;
  for (const CameraFrame& f : path.frames) {
    any |= f.confidence.has_value();
    s.x.push_back(f.time_s);
    s.y.push_back(f.confidence.value_or(0.0));
  }
  if (!any) return std::nullopt;
  PlotPanel panel;
  panel.title = title;
  panel.y_label = "0..1";
  panel.height_weight = 0.6;
  panel.series.push_back(std::move(s));
  panel.y_min = 0;  // the same axis on every page and every film
  panel.y_max = 1;
  return panel;
}

PlotPanel EffectTimeline(const std::string& title, const std::vector<double>& t,
                         const std::vector<std::string>& labels, double last_period_s,
                         std::map<std::string, int>* colors) {
  PlotPanel line = BandPanel(title);
  for (size_t i = 0; i < labels.size();) {
    size_t j = i + 1;
    while (j < labels.size() && labels[j] == labels[i]) ++j;
    if (!labels[i].empty()) {
      PlotBand b;
      b.x_begin = t[i];
      // The run lasts until the next sample starts (or one period past the last).
      b.x_end = j < t.size() ? t[j] : t[j - 1] + last_period_s;
      b.label = labels[i];
      b.color = BandColor(labels[i], colors);
      line.bands.push_back(b);
    }
    i = j;
  }
  return line;
}

Figure HapticTracksFigure(const std::vector<const HapticTrack*>& tracks, const std::string& title,
                          const std::vector<std::string>& names) {
  if (tracks.empty()) throw UsageError("no haptic track to plot");
  for (const HapticTrack* track : tracks) {
    if (!track || track->samples.empty()) throw UsageError("haptic track has no samples");
  }
  Figure fig;
  fig.title = title;
  const char* kTitles[kNumActuators] = {"head (H)", "left hand (LA)", "right hand (RA)"};
  const char* axis[3] = {"x", "y", "z"};
  fig.panels.resize(kNumActuators);
  for (int a = 0; a < kNumActuators; ++a) {
    fig.panels[a].title = kTitles[a];
    fig.panels[a].y_label = "mm";
  }
  std::map<std::string, int> colors;
  std::vector<PlotPanel> timelines;
  for (size_t n = 0; n < tracks.size(); ++n) {
    const HapticTrack& track = *tracks[n];
    const std::string name = n < names.size() ? names[n] : track.model;
    const std::string suffix = tracks.size() > 1 ? " (" + name + ")" : "";
    std::vector<double> t;
    for (const auto& s : track.samples) t.push_back(s.time_s);
    for (int a = 0; a < kNumActuators; ++a) {
      for (int k = 0; k < 3; ++k) {
        std::vector<double> v;
        for (const auto& s : track.samples) v.push_back(1000.0 * s.pos_m[a](k));
        AddSeries(&fig.panels[a], axis[k] + suffix, t, v, k, n > 0);
      }
    }
    std::vector<std::string> labels;
    bool any = false;
    for (const auto& s : track.samples) {
      labels.push_back(s.effect ? *s.effect : "");
      any |= s.effect.has_value() && !s.effect->empty();
    }
    if (any) {
      const double period = track.rate_hz > 0 ? 1.0 / track.rate_hz : 0.0;
      timelines.push_back(EffectTimeline("effect" + suffix, t, labels, period, &colors));
    }
  }
  for (auto& line : timelines) fig.panels.push_back(std::move(line));
  fig.cut_x = ShotCutTimes(*tracks.front());
  return fig;
}

Figure HapticTrackFigure(const HapticTrack& track, const std::string& title) {
  return HapticTracksFigure({&track}, title);
}

}  // namespace hapcine
