// hapcine_track_truth: separates track errors from solver errors on a
// synthetic clip (docs/estimate.md, "Where the rotation error comes from").
//
//   hapcine_track_truth PRESET CLIP_DIR [--mode klt|fit|ray|cut|dropbad] [--cut PX]
//                       [--noise PX] [--klt-window PX] [--klt-anchor-frames N] [--klt-anchor-min PX] [--points N] [--per-frame 1]
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

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::cerr << "usage: hapcine_track_truth PRESET CLIP_DIR [--mode klt|fit|ray|cut|dropbad]"
                 " [--cut PX] [--noise PX] [--klt-window PX] [--klt-anchor-frames N] [--klt-anchor-min PX] [--points N] [--per-frame 1]"
                 " [--est-out FILE] [--errors-out FILE]\n";
    return 2;
  }
  const std::string preset = argv[1], dir = argv[2];
  std::string mode = "klt", est_out, errors_out;
  double noise = 0, cut = 1;
  int klt_anchor_frames = 0;
  double klt_anchor_min = 0.5;
  bool klt_anchor_affine = false;
  int klt_window = 0, points = 0, per_frame = 0, layers = 0, stills = 0;
  for (int i = 3; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--mode") mode = argv[i + 1];
    else if (a == "--noise") noise = std::stod(argv[i + 1]);
    else if (a == "--cut") cut = std::stod(argv[i + 1]);
    else if (a == "--klt-window") klt_window = std::stoi(argv[i + 1]);
    else if (a == "--klt-anchor-frames") klt_anchor_frames = std::stoi(argv[i + 1]);
    else if (a == "--klt-anchor-min") klt_anchor_min = std::stod(argv[i + 1]);
    else if (a == "--klt-anchor-affine") klt_anchor_affine = std::stoi(argv[i + 1]) != 0;
    else if (a == "--points") points = std::stoi(argv[i + 1]);
    else if (a == "--per-frame") per_frame = std::stoi(argv[i + 1]);
    else if (a == "--est-out") est_out = argv[i + 1];
    else if (a == "--errors-out") errors_out = argv[i + 1];
    else if (a == "--layers") layers = std::stoi(argv[i + 1]);
    else if (a == "--stills") stills = std::stoi(argv[i + 1]);
    else {
      std::cerr << "unknown option " << a << "\n";
      return 2;
    }
  }
  // PRESET "real": CLIP_DIR is a real sequence (video.mp4, gt.camera.csv;
  // ../shared/realgt): no scene to cast rays into, only the rigid fits.
  const bool real = preset == "real";
  const CameraPath gt = ReadCameraPathFile(real ? dir + "/gt.camera.csv" : dir + "/" + preset + ".camera.csv");
  const auto scene = real ? nullptr : SynthScene(1, synth::FindSynthPreset(preset).scene, 1);

  auto source = OpenFrameSource(real ? dir + "/video.mp4" : dir + "/" + preset + ".mp4", FrameSourceOptions{});
  const int W = source->info().width, H = source->info().height;
  TrackerOptions to;
  if (klt_window > 0) to.klt_window = klt_window;
  to.stills = stills != 0;
  to.klt_anchor_frames = klt_anchor_frames;
  to.klt_anchor_min_px = klt_anchor_min;
  to.klt_anchor_affine = klt_anchor_affine;
  FeatureTracker tracker{to};
  std::vector<FrameTracks> frames;
  Frame frame;
  while (source->Next(&frame)) frames.push_back(tracker.Process(frame));
  const Eigen::Vector2d pp_shift = real ? PrincipalPointShift(gt, W, H) : Eigen::Vector2d(0, 0);

  const int n_gt = static_cast<int>(gt.frames.size());
  std::vector<synth::CameraView> views;
  for (int i = 0; i < n_gt; ++i) views.push_back(ViewOf(gt.frames[i], W, H));
  // Pixel (OpenCV convention: pixel centres at integers) of X in frame k.
  auto project = [&](int k, const Eigen::Vector3d& X, Eigen::Vector2d* px) {
    Eigen::Vector2d xy;
    if (!synth::ProjectToImage(views[k], X, &xy)) return false;
    *px = xy - Eigen::Vector2d(0.5, 0.5);
    return true;
  };

  // Observations per track.
  struct Obs {
    int frame;
    Eigen::Vector2d px;
  };
  std::map<long, std::vector<Obs>> obs_of;
  for (const auto& ft : frames)
    if (ft.index < n_gt)
      for (const auto& p : ft.points) obs_of[p.track_id].push_back({ft.index, p.px + pp_shift});

  // (a) The point a track *should* follow: the scene hit of its first
  // observation's ray (ambiguous on silhouettes: the ray may pass the edge).
  // (b) The rigid point that best explains the track with the ground-truth
  // cameras: its residuals say whether the track is consistent with any 3-D
  // point at all (occlusion-edge tracks and slides are not).
  std::map<long, Eigen::Vector3d> ray_point, fit_point;
  std::map<long, double> fit_max;  // largest residual of the fit, px
  for (const auto& [id, obs] : obs_of) {
    const synth::CameraView& v0 = views[obs[0].frame];
    const Eigen::Vector3d d0 = v0.world_from_cam * synth::CameraRayDirection(
                                   obs[0].px.x() + 0.5, obs[0].px.y() + 0.5, W, H, v0.focal_px());
    synth::Hit hit;
    if (scene && scene->Trace(v0.center, d0, &hit)) ray_point[id] = hit.p;
    // Linear: nearest point to all rays; then Gauss-Newton on pixels.
    Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
    Eigen::Vector3d b = Eigen::Vector3d::Zero();
    for (const Obs& o : obs) {
      const synth::CameraView& v = views[o.frame];
      const Eigen::Vector3d d = (v.world_from_cam * synth::CameraRayDirection(
                                     o.px.x() + 0.5, o.px.y() + 0.5, W, H, v.focal_px())).normalized();
      const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - d * d.transpose();
      A += P;
      b += P * v.center;
    }
    Eigen::Vector3d X = ray_point.count(id) ? ray_point[id] : Eigen::Vector3d(0, 1, -5);
    if (std::abs(A.determinant()) > 1e-9) X = A.ldlt().solve(b);
    for (int it = 0; it < 10; ++it) {
      Eigen::Matrix3d JtJ = Eigen::Matrix3d::Zero();
      Eigen::Vector3d Jtr = Eigen::Vector3d::Zero();
      bool ok = true;
      for (const Obs& o : obs) {
        Eigen::Vector2d p0;
        if (!project(o.frame, X, &p0)) { ok = false; break; }
        Eigen::Matrix<double, 2, 3> J;
        for (int a = 0; a < 3; ++a) {
          Eigen::Vector3d Xa = X;
          Xa[a] += 1e-6;
          Eigen::Vector2d pa = p0;  // (project fills it; initialised for the compiler)
          project(o.frame, Xa, &pa);
          J.col(a) = (pa - p0) / 1e-6;
        }
        JtJ += J.transpose() * J;
        Jtr += J.transpose() * (p0 - o.px);
      }
      if (!ok) break;
      const Eigen::Vector3d step = (JtJ + 1e-6 * Eigen::Matrix3d::Identity()).ldlt().solve(Jtr);
      X -= step;
      if (step.norm() < 1e-9) break;
    }
    fit_point[id] = X;
    double mx = 0;
    for (const Obs& o : obs) {
      Eigen::Vector2d p;
      mx = std::max(mx, project(o.frame, X, &p) ? (p - o.px).norm() : 1e9);
    }
    fit_max[id] = mx;
  }
  // Is a track born next to a depth edge (rays within +-R px of its first
  // observation hit depths differing by > 5 %)?
  auto near_edge = [&](const Obs& o, double r) {
    const synth::CameraView& v = views[o.frame];
    double lo = 1e18, hi = 0;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const Eigen::Vector3d d = v.world_from_cam * synth::CameraRayDirection(
            o.px.x() + 0.5 + dx * r, o.px.y() + 0.5 + dy * r, W, H, v.focal_px());
        synth::Hit hit;
        if (!scene || !scene->Trace(v.center, d, &hit)) continue;
        lo = std::min(lo, hit.t);
        hi = std::max(hi, hit.t);
      }
    return hi > 1.05 * lo;
  };
  {
    int bad = 0, bad_edge = 0, good = 0, good_edge = 0;
    for (const auto& [id, obs] : obs_of) {
      const bool e = near_edge(obs[0], 8);  // half the KLT window at 960 px, in decoded px ~ 14
      if (fit_max[id] > 2) { ++bad; bad_edge += e; } else if (fit_max[id] < 1) { ++good; good_edge += e; }
    }
    std::printf("tracks born within 8 px of a depth edge: %.1f %% of bad (> 2 px, %d), %.1f %% of good (< 1 px, %d)\n",
                100.0 * bad_edge / std::max(bad, 1), bad, 100.0 * good_edge / std::max(good, 1), good);
  }
  // Depth-layer cue (estimate/depth_layers.h) with the ground-truth depths of
  // each track's rigid fit, judged every 6th frame (about the keyframes).
  std::set<long> between;
  if (layers || mode == "droplayers") {
    std::vector<std::vector<DepthSample>> samples;
    for (const auto& ft : frames) {
      if (ft.index >= n_gt || ft.index % 6 != 0) continue;
      samples.emplace_back();
      for (const auto& p : ft.points) {
        if (obs_of.at(p.track_id).size() < 2) continue;
        const double range = (fit_point.at(p.track_id) - views[ft.index].center).norm();
        const Eigen::Vector2d u((p.px.x() - 0.5 * (W - 1)) / W, (p.px.y() - 0.5 * (H - 1)) / W);
        samples.back().push_back({p.track_id, u, 1.0 / range});
      }
    }
    between = TracksBetweenDepthLayers(samples);
    if (std::getenv("HAPCINE_LAYERS_DEBUG")) {  // per bad/good sample: position in the neighbours' range
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

  std::mt19937 rng(7);
  std::normal_distribution<double> gauss(0, 1);
  FILE* ef = errors_out.empty() ? nullptr : std::fopen(errors_out.c_str(), "w");
  if (ef) std::fprintf(ef, "frame,track,age,len,fit_dx,fit_dy,ray_dx,ray_dy,x,y\n");
  std::vector<double> fit_err;
  for (auto& ft : frames) {
    if (ft.index >= n_gt) break;
    std::vector<TrackPoint> kept;
    for (auto& p : ft.points) {
      const auto& obs = obs_of.at(p.track_id);
      Eigen::Vector2d fit_px, ray_px(1e9, 1e9);
      if (!project(ft.index, fit_point.at(p.track_id), &fit_px)) continue;
      const bool has_ray = ray_point.count(p.track_id) && project(ft.index, ray_point.at(p.track_id), &ray_px);
      fit_px -= pp_shift;  // back to the tracks' own pixels
      if (has_ray) ray_px -= pp_shift;
      const double e = (p.px - fit_px).norm();
      fit_err.push_back(e);
      if (ef)
        std::fprintf(ef, "%d,%ld,%d,%zu,%.4f,%.4f,%.4f,%.4f,%.2f,%.2f\n", ft.index, p.track_id,
                     ft.index - obs[0].frame, obs.size(), p.px.x() - fit_px.x(),
                     p.px.y() - fit_px.y(), p.px.x() - ray_px.x(), p.px.y() - ray_px.y(),
                     p.px.x(), p.px.y());
      TrackPoint q = p;
      if (mode == "klt") {
      } else if (mode == "split") {  // every track cut into pieces of --cut frames (new ids)
        const long piece = (ft.index - obs[0].frame) / std::max(1, static_cast<int>(cut));
        q.track_id = p.track_id * 1000 + piece;
      } else if (mode == "cut") {  // KLT observations off the rigid fit by more than --cut px dropped
        if (e > cut) continue;
      } else if (mode == "dropbad") {  // whole tracks whose fit is off by more than --cut px dropped
        if (fit_max.at(p.track_id) > cut) continue;
      } else if (mode == "droplayers") {  // tracks the depth-layer cue flags (GT depths) dropped
        if (between.count(p.track_id)) continue;
      } else if (mode == "fit") {  // every track moved onto its rigid fit
        q.px = fit_px + noise * Eigen::Vector2d(gauss(rng), gauss(rng));
      } else if (mode == "ray") {  // the ray-cast point (drops tracks that miss)
        if (!has_ray) continue;
        q.px = ray_px + noise * Eigen::Vector2d(gauss(rng), gauss(rng));
      } else {
        std::fprintf(stderr, "unknown mode %s\n", mode.c_str());
        return 2;
      }
      kept.push_back(q);
    }
    ft.points = kept;
  }
  if (ef) std::fclose(ef);
  std::printf("observation residual against the rigid fit, px: median %.3f p90 %.3f p99 %.3f\n",
              Percentile(fit_err, 0.5), Percentile(fit_err, 0.9), Percentile(fit_err, 0.99));

  TrackEstimatorOptions eo;
  if (points > 0) eo.max_points = points;
  TrackCameraEstimator est(W, H, eo);
  for (const auto& ft : frames) est.AddFrame(ft);
  CameraPath path = est.Finish();
  if (!est_out.empty()) WriteCameraPathFile(path, est_out);
  const EvalReport r = EvaluateCameraPaths(gt, path, EvalOptions{});
  std::printf("mode %s noise %.2f cut %.2f: rot mean %.4f max %.4f deg, fov err %.3f %%, ATE %.3f %%\n",
              mode.c_str(), noise, cut, r.overall.rotation_deg.mean, r.overall.rotation_deg.max,
              r.overall.fov_percent.mean, r.overall.ate_percent.value_or(-1));
  if (per_frame) {
    for (const FrameError& f : r.per_frame)
      if (f.gt_frame % 6 == 0) std::printf("%d:%.3f ", f.gt_frame, f.rotation_deg);
    std::printf("\n");
  }
  return 0;
}
