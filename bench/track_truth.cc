// hapcine_track_truth: separates track errors from solver errors on a
// synthetic clip (docs/estimate.md, "Where the rotation error comes from").
//
//   hapcine_track_truth PRESET CLIP_DIR [--mode klt|fit|ray|cut|dropbad] [--cut PX]
//                       [--noise PX] [--klt-window PX] [--klt-anchor-frames N] [--klt-anchor-min PX] [--klt-anchor-affine 1] [--points N] [--per-frame 1]
//                       [--est-out FILE] [--errors-out FILE] [--layers 1] [--stills 1]
//
// Tracks the clip with the real FeatureTracker, then casts the ray of every
// track's first observation into the synthetic scene (ground-truth camera) to
// find the 3-D point the track started on, and projects that point into every
// later frame with the ground-truth camera; also fits the rigid point that
// best explains each whole track with the ground-truth cameras (its largest
// residual says whether the track follows any 3-D point: occlusion-edge
// corners do not). Prints those statistics and the estimator's rotation
// error on
//   klt      the KLT tracks (what `hapcine estimate` sees)
//   fit      the same tracks (same ids, frames) moved onto their rigid fit
//   ray      the same tracks at the projection of their ray-cast point
//   cut      KLT, without observations off their rigid fit by > --cut px
//   dropbad  KLT, without tracks whose rigid fit is off by > --cut px
//   droplayers KLT, without tracks the depth-layer cue flags with GT depths
//   split    KLT, every track cut into pieces of --cut frames (new ids)
// (--noise adds Gaussian pixel noise to fit/ray positions).
// PRESET "real": CLIP_DIR is a real sequence of ../shared/realgt (video.mp4,
// gt.camera.csv, an off-centre principal point from its header): no scene,
// so only the rigid fits (no ray, no depth edges). --stills 1 tracks as
// image stills (descriptor linking from the first frame).
// --layers 1 prints how well the depth-layer cue (estimate/depth_layers.h)
// separates them, with the ground-truth depth of each track's rigid fit.
#include <Eigen/Geometry>
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "core/camera_path.h"
#include "core/rotation.h"
#include "core/statistics.h"
#include "datasets/eval.h"
#include "datasets/render.h"
#include "datasets/synth_clip.h"
#include "datasets/synth_presets.h"
#include "estimate/window/depth_layers.h"
#include "estimate/track_estimator.h"
#include "extract/feature_tracker.h"
#include "extract/frame_source.h"
#include <cstdlib>

using namespace hapcine;

namespace {

double Percentile(std::vector<double> v, double p) { return v.empty() ? 0 : Quantile(std::move(v), p); }

synth::CameraView ViewOf(const CameraFrame& f, int w, int h) {
  synth::CameraView v;
  v.center = f.center;
  v.world_from_cam = f.world_from_cam;
  v.fov_deg = f.fov_deg;
  v.width = w;
  v.height = h;
  return v;
}

// A real sequence's principal point (cx_px, cy_px in the header) where it is
// off-centre: the shift that puts it at the centre the projection assumes
// (the tracks are shifted for the rigid fits only; the estimator is fed the
// tracks as seen).
Eigen::Vector2d PrincipalPointShift(const CameraPath& gt, int w, int h) {
  if (!gt.metadata.count("cx_px") || !gt.metadata.count("cy_px")) return {0, 0};
  return {0.5 * (w - 1) - std::stod(gt.metadata.at("cx_px")), 0.5 * (h - 1) - std::stod(gt.metadata.at("cy_px"))};
}

struct Args {
  std::string preset, dir, mode = "klt", est_out, errors_out;
  double noise = 0, cut = 1;
  int klt_anchor_frames = 0;
  double klt_anchor_min = 0.5;
  bool klt_anchor_affine = false;
  int klt_window = 0, points = 0, per_frame = 0, layers = 0, stills = 0;
};

// The command line into *a: -1, or the exit code of a bad one.
int ParseArgs(int argc, char** argv, Args* a) {
  if (argc < 3) {
    std::cerr << "usage: hapcine_track_truth PRESET CLIP_DIR [--mode klt|fit|ray|cut|dropbad]"
                 " [--cut PX] [--noise PX] [--klt-window PX] [--klt-anchor-frames N] [--klt-anchor-min PX] [--klt-anchor-affine 1] [--points N] [--per-frame 1]"
                 " [--est-out FILE] [--errors-out FILE]\n";
    return 2;
  }
  a->preset = argv[1];
  a->dir = argv[2];
  for (int i = 3; i + 1 < argc; i += 2) {
    const std::string o = argv[i];
    if (o == "--mode") a->mode = argv[i + 1];
    else if (o == "--noise") a->noise = std::stod(argv[i + 1]);
    else if (o == "--cut") a->cut = std::stod(argv[i + 1]);
    else if (o == "--klt-window") a->klt_window = std::stoi(argv[i + 1]);
    else if (o == "--klt-anchor-frames") a->klt_anchor_frames = std::stoi(argv[i + 1]);
    else if (o == "--klt-anchor-min") a->klt_anchor_min = std::stod(argv[i + 1]);
    else if (o == "--klt-anchor-affine") a->klt_anchor_affine = std::stoi(argv[i + 1]) != 0;
    else if (o == "--points") a->points = std::stoi(argv[i + 1]);
    else if (o == "--per-frame") a->per_frame = std::stoi(argv[i + 1]);
    else if (o == "--est-out") a->est_out = argv[i + 1];
    else if (o == "--errors-out") a->errors_out = argv[i + 1];
    else if (o == "--layers") a->layers = std::stoi(argv[i + 1]);
    else if (o == "--stills") a->stills = std::stoi(argv[i + 1]);
    else {
      std::cerr << "unknown option " << o << "\n";
      return 2;
    }
  }
  return -1;
}

// A clip with its ground truth, scene and KLT tracks.
struct Clip {
  CameraPath gt;
  std::shared_ptr<const synth::Scene> scene;  // none for a real sequence
  int W = 0, H = 0;
  std::vector<FrameTracks> frames;
  Eigen::Vector2d pp_shift{0, 0};
  std::vector<synth::CameraView> views;  // one per ground-truth frame
};

// PRESET "real": CLIP_DIR is a real sequence (video.mp4, gt.camera.csv;
// ../shared/realgt): no scene to cast rays into, only the rigid fits.
Clip LoadAndTrack(const Args& a) {
  const bool real = a.preset == "real";
  Clip c;
  c.gt = ReadCameraPathFile(real ? a.dir + "/gt.camera.csv" : a.dir + "/" + a.preset + ".camera.csv");
  c.scene = real ? nullptr : SynthScene(1, synth::FindSynthPreset(a.preset).scene, 1);
  auto source = OpenFrameSource(real ? a.dir + "/video.mp4" : a.dir + "/" + a.preset + ".mp4",
                                FrameSourceOptions{});
  c.W = source->info().width;
  c.H = source->info().height;
  TrackerOptions to;
  if (a.klt_window > 0) to.klt_window = a.klt_window;
  to.stills = a.stills != 0;
  to.klt_anchor_frames = a.klt_anchor_frames;
  to.klt_anchor_min_px = a.klt_anchor_min;
  to.klt_anchor_affine = a.klt_anchor_affine;
  FeatureTracker tracker{to};
  Frame frame;
  while (source->Next(&frame)) c.frames.push_back(tracker.Process(frame));
  if (real) c.pp_shift = PrincipalPointShift(c.gt, c.W, c.H);
  for (const CameraFrame& f : c.gt.frames) c.views.push_back(ViewOf(f, c.W, c.H));
  return c;
}

int GtFrames(const Clip& c) { return static_cast<int>(c.gt.frames.size()); }

// Pixel (OpenCV convention: pixel centres at integers) of X in view v.
bool ProjectPx(const synth::CameraView& v, const Eigen::Vector3d& X, Eigen::Vector2d* px) {
  Eigen::Vector2d xy;
  if (!synth::ProjectToImage(v, X, &xy)) return false;
  *px = xy - Eigen::Vector2d(0.5, 0.5);
  return true;
}

// World direction of the ray through pixel px of view v.
Eigen::Vector3d RayDirection(const synth::CameraView& v, const Eigen::Vector2d& px, int W, int H) {
  return v.world_from_cam * synth::CameraRayDirection(px.x() + 0.5, px.y() + 0.5, W, H, v.focal_px());
}

struct Obs {
  int frame;
  Eigen::Vector2d px;
};
using Observations = std::map<long, std::vector<Obs>>;  // per track, in frame order

Observations ObservationsPerTrack(const Clip& c) {
  Observations obs_of;
  for (const auto& ft : c.frames)
    if (ft.index < GtFrames(c))
      for (const auto& p : ft.points) obs_of[p.track_id].push_back({ft.index, p.px + c.pp_shift});
  return obs_of;
}

// (a) ray_point: the point a track *should* follow: the scene hit of its
// first observation's ray (ambiguous on silhouettes: the ray may pass the
// edge). (b) fit_point: the rigid point that best explains the track with the
// ground-truth cameras; fit_max, its largest residual (px), says whether the
// track is consistent with any 3-D point at all (occlusion-edge tracks and
// slides are not).
struct TrackFits {
  std::map<long, Eigen::Vector3d> ray_point, fit_point;
  std::map<long, double> fit_max;
};

// Linear: the nearest point to all the track's rays (X0 where they are
// near parallel).
Eigen::Vector3d NearestPointToRays(const Clip& c, const std::vector<Obs>& obs, const Eigen::Vector3d& X0) {
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero(), mean_dir = Eigen::Vector3d::Zero();
  double baseline = 0;
  for (const Obs& o : obs) {
    mean_dir += RayDirection(c.views[o.frame], o.px, c.W, c.H).normalized();
    baseline = std::max(baseline, (c.views[o.frame].center - c.views[obs[0].frame].center).norm());
  }
  // Rays from one centre (a rotation or zoom) meet there: any depth explains
  // them, so the point is put 10 units out along their mean direction.
  if (baseline < 1e-9) return c.views[obs[0].frame].center + 10 * mean_dir.normalized();
  for (const Obs& o : obs) {
    const synth::CameraView& v = c.views[o.frame];
    const Eigen::Vector3d d = RayDirection(v, o.px, c.W, c.H).normalized();
    const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - d * d.transpose();
    A += P;
    b += P * v.center;
  }
  return std::abs(A.determinant()) > 1e-9 ? Eigen::Vector3d(A.ldlt().solve(b)) : X0;
}

// Gauss-Newton on the pixel residuals (numeric Jacobian), up to 10 steps;
// stops where X leaves a view.
void RefineOnPixels(const Clip& c, const std::vector<Obs>& obs, Eigen::Vector3d* X) {
  for (int it = 0; it < 10; ++it) {
    Eigen::Matrix3d JtJ = Eigen::Matrix3d::Zero();
    Eigen::Vector3d Jtr = Eigen::Vector3d::Zero();
    for (const Obs& o : obs) {
      Eigen::Vector2d p0;
      if (!ProjectPx(c.views[o.frame], *X, &p0)) return;
      Eigen::Matrix<double, 2, 3> J;
      for (int a = 0; a < 3; ++a) {
        Eigen::Vector3d Xa = *X;
        Xa[a] += 1e-6;
        Eigen::Vector2d pa = p0;  // (ProjectPx fills it; initialised for the compiler)
        ProjectPx(c.views[o.frame], Xa, &pa);
        J.col(a) = (pa - p0) / 1e-6;
      }
      JtJ += J.transpose() * J;
      Jtr += J.transpose() * (p0 - o.px);
    }
    const Eigen::Vector3d step = (JtJ + 1e-6 * Eigen::Matrix3d::Identity()).ldlt().solve(Jtr);
    *X -= step;
    if (step.norm() < 1e-9) return;
  }
}

double LargestResidual(const Clip& c, const std::vector<Obs>& obs, const Eigen::Vector3d& X) {
  double mx = 0;
  for (const Obs& o : obs) {
    Eigen::Vector2d p;
    mx = std::max(mx, ProjectPx(c.views[o.frame], X, &p) ? (p - o.px).norm() : 1e9);
  }
  return mx;
}

TrackFits FitTracks(const Clip& c, const Observations& obs_of) {
  TrackFits f;
  for (const auto& [id, obs] : obs_of) {
    const synth::CameraView& v0 = c.views[obs[0].frame];
    synth::Hit hit;
    if (c.scene && c.scene->Trace(v0.center, RayDirection(v0, obs[0].px, c.W, c.H), &hit))
      f.ray_point[id] = hit.p;
    Eigen::Vector3d X = NearestPointToRays(
        c, obs, f.ray_point.count(id) ? f.ray_point[id] : Eigen::Vector3d(0, 1, -5));
    RefineOnPixels(c, obs, &X);
    f.fit_point[id] = X;
    f.fit_max[id] = LargestResidual(c, obs, X);
  }
  return f;
}

// Is a track born next to a depth edge (rays within +-r px of its first
// observation hit depths differing by > 5 %)?
bool NearDepthEdge(const Clip& c, const Obs& o, double r) {
  const synth::CameraView& v = c.views[o.frame];
  double lo = 1e18, hi = 0;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const Eigen::Vector3d d = v.world_from_cam * synth::CameraRayDirection(
          o.px.x() + 0.5 + dx * r, o.px.y() + 0.5 + dy * r, c.W, c.H, v.focal_px());
      synth::Hit hit;
      if (!c.scene || !c.scene->Trace(v.center, d, &hit)) continue;
      lo = std::min(lo, hit.t);
      hi = std::max(hi, hit.t);
    }
  return hi > 1.05 * lo;
}

void PrintDepthEdgeShares(const Clip& c, const Observations& obs_of, const TrackFits& f) {
  int bad = 0, bad_edge = 0, good = 0, good_edge = 0;
  for (const auto& [id, obs] : obs_of) {
    const bool e = NearDepthEdge(c, obs[0], 8);  // half the KLT window at 960 px, in decoded px ~ 14
    const double m = f.fit_max.at(id);
    if (m > 2) { ++bad; bad_edge += e; } else if (m < 1) { ++good; good_edge += e; }
  }
  std::printf("tracks born within 8 px of a depth edge: %.1f %% of bad (> 2 px, %d), %.1f %% of good (< 1 px, %d)\n",
              100.0 * bad_edge / std::max(bad, 1), bad, 100.0 * good_edge / std::max(good, 1), good);
}

// Every 6th frame (about the keyframes): each track's inverse depth from its
// rigid fit, as the depth-layer cue takes it.
std::vector<std::vector<DepthSample>> GtDepthSamples(const Clip& c, const Observations& obs_of,
                                                     const TrackFits& f) {
  std::vector<std::vector<DepthSample>> samples;
  for (const auto& ft : c.frames) {
    if (ft.index >= GtFrames(c) || ft.index % 6 != 0) continue;
    samples.emplace_back();
    for (const auto& p : ft.points) {
      if (obs_of.at(p.track_id).size() < 2) continue;
      const double range = (f.fit_point.at(p.track_id) - c.views[ft.index].center).norm();
      const Eigen::Vector2d u((p.px.x() - 0.5 * (c.W - 1)) / c.W, (p.px.y() - 0.5 * (c.H - 1)) / c.W);
      samples.back().push_back({p.track_id, u, 1.0 / range});
    }
  }
  return samples;
}

// HAPCINE_LAYERS_DEBUG: per bad/good sample, its position in the
// neighbours' range.
void PrintLayerNeighbourhoods(const std::vector<std::vector<DepthSample>>& samples,
                              const std::map<long, double>& fit_max) {
  for (const auto& fr : samples) {
    std::vector<double> all;
    for (const auto& x : fr) all.push_back(x.w);
    const double fs = Percentile(all, 0.98) - Percentile(all, 0.02);
    for (const auto& x : fr) {
      const double m = fit_max.at(x.track);
      if (!(m > 2 || m < 1)) continue;
      std::vector<double> nb;
      for (const auto& y : fr)
        if (y.track != x.track && (y.u - x.u).norm() <= 0.05) nb.push_back(y.w);
      if (nb.size() < 4) continue;
      const auto [lo, hi] = std::minmax_element(nb.begin(), nb.end());
      int sup = 0;
      for (double v : nb) sup += std::abs(v - x.w) <= 0.1 * (*hi - *lo);
      std::printf("L %d %.3f %.3f %d %zu\n", m > 2, (*hi - *lo) / fs, (x.w - *lo) / (*hi - *lo), sup, nb.size());
    }
  }
}

void PrintLayerCueShares(const std::map<long, double>& fit_max, const std::set<long>& between) {
  int bad = 0, bad_hit = 0, good = 0, good_hit = 0, mid = 0, mid_hit = 0;
  for (const auto& [id, m] : fit_max) {
    const bool hit = between.count(id);
    if (m > 2) { ++bad; bad_hit += hit; } else if (m < 1) { ++good; good_hit += hit; } else { ++mid; mid_hit += hit; }
  }
  std::printf("depth-layer cue (GT depths): flags %.1f %% of bad (> 2 px, %d), %.1f %% of 1-2 px (%d), "
              "%.1f %% of good (< 1 px, %d); precision (bad among flagged) %.1f %%\n",
              100.0 * bad_hit / std::max(bad, 1), bad, 100.0 * mid_hit / std::max(mid, 1), mid,
              100.0 * good_hit / std::max(good, 1), good,
              100.0 * bad_hit / std::max<size_t>(between.size(), 1));
}

// Depth-layer cue (estimate/depth_layers.h) with the ground-truth depths of
// each track's rigid fit: the tracks it flags, and how they compare.
std::set<long> JudgeDepthLayerCue(const Clip& c, const Observations& obs_of, const TrackFits& f) {
  const std::vector<std::vector<DepthSample>> samples = GtDepthSamples(c, obs_of, f);
  const std::set<long> between = TracksBetweenDepthLayers(samples);
  if (std::getenv("HAPCINE_LAYERS_DEBUG")) PrintLayerNeighbourhoods(samples, f.fit_max);
  PrintLayerCueShares(f.fit_max, between);
  return between;
}

void PrintResidualShares(const std::string& preset, const std::map<long, double>& fit_max) {
  int n1 = 0, n2 = 0, n4 = 0;
  for (const auto& [id, m] : fit_max) {
    n1 += m > 1;
    n2 += m > 2;
    n4 += m > 4;
  }
  const double nt = std::max<size_t>(fit_max.size(), 1);
  std::printf("%s: %zu tracks; largest residual against the best rigid point (GT cameras): "
              "> 1 px %.1f %%, > 2 px %.1f %%, > 4 px %.1f %%\n",
              preset.c_str(), fit_max.size(), 100 * n1 / nt, 100 * n2 / nt, 100 * n4 / nt);
}

// One observation with the projections of its track's fitted and ray-cast
// points into its frame (in the tracks' own pixels).
struct Projected {
  Eigen::Vector2d fit_px, ray_px{1e9, 1e9};
  bool has_ray = false;
  double error = 0;  // |px - fit_px|
};

enum class ModeAnswer { kKeep, kDrop, kUnknownMode };

// What --mode does to observation p (moved, renumbered or dropped) into *q.
ModeAnswer ApplyMode(const Args& a, const TrackPoint& p, int frame, int first_frame, const Projected& j,
                     const TrackFits& f, const std::set<long>& between, std::mt19937& rng,
                     std::normal_distribution<double>& gauss, TrackPoint* q) {
  *q = p;
  if (a.mode == "klt") {
  } else if (a.mode == "split") {  // every track cut into pieces of --cut frames (new ids)
    const long piece = (frame - first_frame) / std::max(1, static_cast<int>(a.cut));
    q->track_id = p.track_id * 1000 + piece;
  } else if (a.mode == "cut") {  // KLT observations off the rigid fit by more than --cut px dropped
    if (j.error > a.cut) return ModeAnswer::kDrop;
  } else if (a.mode == "dropbad") {  // whole tracks whose fit is off by more than --cut px dropped
    if (f.fit_max.at(p.track_id) > a.cut) return ModeAnswer::kDrop;
  } else if (a.mode == "droplayers") {  // tracks the depth-layer cue flags (GT depths) dropped
    if (between.count(p.track_id)) return ModeAnswer::kDrop;
  } else if (a.mode == "fit") {  // every track moved onto its rigid fit
    q->px = j.fit_px + a.noise * Eigen::Vector2d(gauss(rng), gauss(rng));
  } else if (a.mode == "ray") {  // the ray-cast point (drops tracks that miss)
    if (!j.has_ray) return ModeAnswer::kDrop;
    q->px = j.ray_px + a.noise * Eigen::Vector2d(gauss(rng), gauss(rng));
  } else {
    return ModeAnswer::kUnknownMode;
  }
  return ModeAnswer::kKeep;
}

// p's track's fitted and ray-cast points projected into frame `frame`;
// false where the fitted point does not project.
bool ProjectTrackPoints(const Clip& c, const TrackFits& f, const TrackPoint& p, int frame, Projected* j) {
  const synth::CameraView& v = c.views[frame];
  if (!ProjectPx(v, f.fit_point.at(p.track_id), &j->fit_px)) return false;
  j->has_ray = f.ray_point.count(p.track_id) && ProjectPx(v, f.ray_point.at(p.track_id), &j->ray_px);
  j->fit_px -= c.pp_shift;  // back to the tracks' own pixels
  if (j->has_ray) j->ray_px -= c.pp_shift;
  j->error = (p.px - j->fit_px).norm();
  return true;
}

// The tracks as --mode makes them (observations whose fitted point does not
// project are dropped), with --errors-out written on the way; false on an
// unknown mode.
bool RewriteTracks(const Args& a, const Observations& obs_of, const TrackFits& f,
                   const std::set<long>& between, Clip* c) {
  std::mt19937 rng(7);
  std::normal_distribution<double> gauss(0, 1);
  FILE* ef = a.errors_out.empty() ? nullptr : std::fopen(a.errors_out.c_str(), "w");
  if (ef) std::fprintf(ef, "frame,track,age,len,fit_dx,fit_dy,ray_dx,ray_dy,x,y\n");
  std::vector<double> fit_err;
  for (auto& ft : c->frames) {
    if (ft.index >= GtFrames(*c)) break;
    std::vector<TrackPoint> kept;
    for (auto& p : ft.points) {
      const auto& obs = obs_of.at(p.track_id);
      Projected j;
      if (!ProjectTrackPoints(*c, f, p, ft.index, &j)) continue;
      fit_err.push_back(j.error);
      if (ef)
        std::fprintf(ef, "%d,%ld,%d,%zu,%.4f,%.4f,%.4f,%.4f,%.2f,%.2f\n", ft.index, p.track_id,
                     ft.index - obs[0].frame, obs.size(), p.px.x() - j.fit_px.x(),
                     p.px.y() - j.fit_px.y(), p.px.x() - j.ray_px.x(), p.px.y() - j.ray_px.y(),
                     p.px.x(), p.px.y());
      TrackPoint q;
      const ModeAnswer m = ApplyMode(a, p, ft.index, obs[0].frame, j, f, between, rng, gauss, &q);
      if (m == ModeAnswer::kUnknownMode) {
        std::fprintf(stderr, "unknown mode %s\n", a.mode.c_str());
        if (ef) std::fclose(ef);
        return false;
      }
      if (m == ModeAnswer::kKeep) kept.push_back(q);
    }
    ft.points = kept;
  }
  if (ef) std::fclose(ef);
  std::printf("observation residual against the rigid fit, px: median %.3f p90 %.3f p99 %.3f\n",
              Percentile(fit_err, 0.5), Percentile(fit_err, 0.9), Percentile(fit_err, 0.99));
  return true;
}

// The estimator on the (rewritten) tracks, against the ground truth.
void EstimateAndPrint(const Args& a, const Clip& c) {
  TrackEstimatorOptions eo;
  if (a.points > 0) eo.max_points = a.points;
  TrackCameraEstimator est(c.W, c.H, eo);
  for (const auto& ft : c.frames) est.AddFrame(ft);
  CameraPath path = est.Finish();
  if (!a.est_out.empty()) WriteCameraPathFile(path, a.est_out);
  const EvalReport r = EvaluateCameraPaths(c.gt, path, EvalOptions{});
  std::printf("mode %s noise %.2f cut %.2f: rot mean %.4f max %.4f deg, fov err %.3f %%, ATE %.3f %%\n",
              a.mode.c_str(), a.noise, a.cut, r.overall.rotation_deg.mean, r.overall.rotation_deg.max,
              r.overall.fov_percent.mean, r.overall.ate_percent.value_or(-1));
  if (a.per_frame) {
    for (const FrameError& f : r.per_frame)
      if (f.gt_frame % 6 == 0) std::printf("%d:%.3f ", f.gt_frame, f.rotation_deg);
    std::printf("\n");
  }
}

}  // namespace

int main(int argc, char** argv) {
  Args a;
  if (const int rc = ParseArgs(argc, argv, &a); rc >= 0) return rc;
  Clip clip = LoadAndTrack(a);
  const Observations obs_of = ObservationsPerTrack(clip);
  const TrackFits fits = FitTracks(clip, obs_of);
  PrintDepthEdgeShares(clip, obs_of, fits);
  std::set<long> between;
  if (a.layers || a.mode == "droplayers") between = JudgeDepthLayerCue(clip, obs_of, fits);
  PrintResidualShares(a.preset, fits.fit_max);
  if (!RewriteTracks(a, obs_of, fits, between, &clip)) return 2;
  EstimateAndPrint(a, clip);
  return 0;
}
