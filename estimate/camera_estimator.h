#pragma once
// The estimator's public entry point: video (or any FrameSource) in, camera
// path (docs/formats.md, "Camera path specification") out.
//
// Streaming: frames are decoded and tracked one at a time and handed to
// TrackCameraEstimator (track_estimator.h), which solves bundle-adjustment
// windows as they fill, so memory stays flat in video length. Three stages
// overlap on their own threads with small bounded queues between them:
// decoding (EstimateCameraPathFromFile), tracking, estimation (the caller's
// thread, which also runs the progress callback).
// Backends: "hapcine" (this pipeline) or "colmap" (colmap_backend.h).

#include <functional>
#include <string>

#include "core/camera_path.h"
#include "estimate/track_estimator.h"
#include "extract/feature_tracker.h"
#include "extract/frame_source.h"

namespace hapcine {

class Diagnostics;

struct EstimatorOptions {
  std::string backend = "hapcine";  // "hapcine" or "colmap"
  FrameSourceOptions frames;         // working resolution (max_working_side, default 960)
  TrackerOptions tracker;            // feature tracking (max_tracks, default 600)
  TrackEstimatorOptions estimator;   // models, bundle adjustment, smoothing
  std::string colmap_binary = "colmap";  // used by the colmap backend
  // Estimate one radial distortion coefficient from frame pairs of the first
  // shot's first frames (lens_distortion.h; kept only where it pays for
  // itself, the path's header then says k1=): where one is kept, the
  // estimation starts again from the first frame with every track
  // undistorted. Gives way to lens_bundle and lens_k1.
  bool lens_distortion = true;
  // Measure k1 in a bundle adjustment of the first window the estimator
  // solves (lens_bundle.h): where it pays for itself, the estimation starts
  // again from the first frame with the tracks undistorted (header k1=).
  // Not with lens_k1 (Check()).
  bool lens_bundle = false;
  // Windows of the first shot it measures k1 in: 1, that window's own test;
  // more, each window's k1 must agree with the others' (lens_bundle.h).
  int lens_bundle_windows = 3;
  // A known coefficient (lens_distortion.h's convention): every track is
  // undistorted with it, nothing is estimated; 0 = none.
  double lens_k1 = 0;
  // Where the run's diagnostics go (core/diagnostics.h): per-run "stage"
  // records, per-window "window" records, and the costlier ones it asks for.
  // Not owned; none by default.
  Diagnostics* diagnostics = nullptr;
  void Check() const;                // throws UsageError
  // lens_distortion, unless lens_bundle or lens_k1 is the source of k1.
  bool MeasuresLensFromPairs() const;
};

// The `--fast` preset: cheaper settings measured on the synthetic clips
// (docs/estimate.md "Speed"), applied over `options`.
void ApplyFastPreset(EstimatorOptions* options);
// One line naming what ApplyFastPreset() changes, for --help.
std::string FastPresetSummary();
// The decoding-speed draft (--draft): the fast preset, and the decoder
// skips the frames nothing is predicted from (their poses are interpolated)
// and H.264's deblocking. 1.4x the decoder's own wall time on 1080p H.264,
// less accurate (docs/estimate.md "Accuracy").
void ApplyDraftPreset(EstimatorOptions* options);
std::string DraftPresetSummary();

// Progress: frames done, total frames (0 when unknown).
using ProgressFn = std::function<void(long done, long total)>;

// Runs the chosen backend over `source`. Metadata written: width, height, fps
// (nominal), source, backend and the main estimator settings.
CameraPath EstimateCameraPath(FrameSource& source, const EstimatorOptions& options,
                              ProgressFn progress = {});

// Opens `video` (OpenFrameSource) and runs EstimateCameraPath. Throws
// hapcine::Error("<video>", reason) on unreadable input or when nothing could
// be estimated.
CameraPath EstimateCameraPathFromFile(const std::string& video, const EstimatorOptions& options,
                                      ProgressFn progress = {});

}  // namespace hapcine
