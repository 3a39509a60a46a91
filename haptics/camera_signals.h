#pragma once
// The camera parameters of Equation 1, C = [x, y, z, phi, theta, psi, gamma],
// per frame and relative to the first frame of each shot, in the seat frame.
//
// The seat frame is the camera frame at the shot's first frame (camera +X
// right -> seat +X right, +Y up -> up, +Z backward -> backward), so a camera
// path in any world frame (ground truth) or in the estimator's frame (first
// frame at the origin) gives the same signals.
//   position_u   R_wc0^T (c - c0), in the path's units (metres for ground
//                truth, median scene depth of the shot's first frame for
//                estimated paths)
//   tilt/pan/roll_rad  phi (about X), theta (about Y), psi (about Z) of the
//                relative rotation R_wc0^T R_wc, decomposed as in
//                core/rotation.h and unwrapped over the shot (no +-2 pi jumps)
//   zoom_forward_u  gamma: the zoom as an "equivalent forward distance": the
//                distance the camera would have to move BACKWARD to cancel the
//                zoom's magnification of a subject at reference_depth,
//                  gamma = D * (tan(fov0/2) / tan(fov/2) - 1),
//                positive for a zoom-in (narrowing FOV). A dolly zoom that
//                keeps a subject at distance D the same size has
//                gamma(t) = -(forward travel)(t) exactly, which is what
//                makes the cinematic model produce no movement for Vertigo.

#include <optional>
#include <string>
#include <vector>

#include "core/camera_path.h"

namespace hapcine {

struct ShotRange {
  int shot = 0;      // value of the `shot` column (0 when absent)
  size_t first = 0;  // first frame index into CameraPath::frames
  size_t last = 0;   // last frame index (inclusive)
};

// Splits a path into runs of equal `shot` (frames without a shot value
// continue the previous run; a path without the column is one shot).
std::vector<ShotRange> SplitShots(const CameraPath& path);

struct CameraSignals {
  std::vector<double> time_s;
  std::vector<Eigen::Vector3d> position_u;
  std::vector<double> tilt_rad, pan_rad, roll_rad;
  std::vector<double> zoom_forward_u;
  std::vector<double> log_zoom;  // ln(tan(fov0/2)/tan(fov/2)), unit-free
  double reference_depth_u = 1;  // D used for zoom_forward_u
  size_t size() const { return time_s.size(); }
};

// Signals for frames [shot.first, shot.last] relative to shot.first.
CameraSignals ExtractShotSignals(const CameraPath& path, const ShotRange& shot,
                                 double reference_depth_u);

// Reference depth D used by gamma: the metadata key `subject_distance_m`
// (ground truth in metres) or `reference_depth` when present and positive,
// else `fallback` (1.0: estimated paths are in median-depth units).
double ReferenceDepthFor(const CameraPath& path, double fallback);

// Subject distance of a dolly zoom ("Vertigo"), in path units, from the
// motion alone. A camera that moves forward by d(t) while widening its field
// of view so that a subject at distance D keeps its size has
//   tan(fov0/2) / tan(fov(t)/2) = (D - d(t)) / D,  i.e.  1 - ratio(t) = d(t) / D.
// Least squares for 1/D over the shot (d = forward travel along the first
// frame's optical axis). nullopt unless the fit explains the zoom (rms
// residual <= 10 % of the rms of 1 - ratio), the magnification changes by at
// least 5 %, the travel reaches at least 5 % of D, and D > 0 (forward with a
// zoom-out, or backward with a zoom-in). Works in any units, so estimated
// paths (median-depth units) get their dolly zooms' D as well.
std::optional<double> DollyZoomSubjectDistance(const CameraPath& path, const ShotRange& shot);

// D for one shot: explicit_depth_u when > 0 (--reference-depth), else the
// dolly-zoom fit above, else ReferenceDepthFor(path, 1.0). A dolly zoom's own
// D makes its zoom cancel its travel exactly in the cinematic model, whatever
// a film-wide metadata value says.
double ShotReferenceDepth(const CameraPath& path, const ShotRange& shot, double explicit_depth_u);

// Lost frames (model `lost`, docs/formats.md) are no motion. Within each
// shot, the frames after a run of lost frames are moved rigidly (rotation,
// centre; the focal by the ratio of tan(fov/2)) so that the first placed
// frame after the run coincides with the run's placeholder pose: the pose
// gap, which nothing measured, is no jump, and the motion resumes from the
// next placed frame. nullopt when nothing moves (no lost frames, or every
// gap already closed), so a path is copied only when it must be.
std::optional<CameraPath> JoinAcrossLostFrames(const CameraPath& path);

// The actuators return to rest over lost frames: from the last placed frame
// before a lost run, the value it had is removed from `x` with the cut
// crossfade's smooth step over ramp_s (at once when ramp_s <= 0), and the
// motion after the run adds to that return (no jump; at rest by the end of
// a run longer than ramp_s). `lost[i]`: frame i is lost; x is per frame,
// relative to the shot start, on a path joined by JoinAcrossLostFrames.
void FadeToRestOverLostFrames(const std::vector<double>& time_s, const std::vector<bool>& lost,
                              double ramp_s, std::vector<double>* x);

// Checks beyond ReadCameraPath's: |position| <= 1e6, time gaps inside a shot
// <= max_gap_s, and what the gaps at shot changes skip beyond max_gap_s, summed,
// at most the time the frames cover (rows x median frame interval inside
// shots), so a track's length is bounded by its input's. Throws Error("<source>:<line>: frame N", reason) when
// `data_lines` gives the file line of every frame (CsvDataRowLines), else
// Error("<source>: frame N (data row R)", reason).
void ValidatePathForHaptics(const CameraPath& path, const std::string& source, double max_gap_s,
                            const std::vector<int>* data_lines = nullptr);

// The 1-based line number of every data row of a project CSV file (after the
// metadata lines and the header), for errors about rows the reader accepted.
// Stops at the first unreadable row; empty when the file cannot be read.
std::vector<int> CsvDataRowLines(const std::string& file);

}  // namespace hapcine
