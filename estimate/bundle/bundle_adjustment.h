#pragma once
// Bundle adjustment over one window of keyframes (Ceres), and the pose-only
// solve used for the frames between keyframes.
//
// Cameras (OpenCV axes inside: x right, y down, z forward):
//   world_from_cam  unit quaternion on EigenQuaternionManifold (no Euler angles)
//   center          camera centre in world units
//   log_focal       log of the focal length in normalised units (f_px / s)
// A camera may *share* a block with an earlier camera (rotation_source,
// center_source, focal_source): that is how a model without translation keeps
// the centre exactly constant, a model without zoom keeps the focal constant.
// Points are anchored inverse-depth points: X = anchor + d / rho with the
// anchor a constant world point (the centre of the keyframe that first saw
// the point) and (d, rho) a unit 4-vector on SphereManifold<4>; rho = 0 is a
// point at infinity and stays well conditioned. Windows without translation
// use only the bearing d (SphereManifold<3>): depth is unobservable there.
// Residuals are in normalised image units divided by `huber_scale` and go
// through a Huber loss. Focal: a smoothness prior on the second difference of
// log f over consecutive focal blocks and a weak prior on the first one.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "estimate/geometry/reference_width.h"

namespace hapcine {

struct BaCamera {
  Eigen::Quaterniond world_from_cam = Eigen::Quaterniond::Identity();
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double log_focal = 0;
  // Index (< own index) of the camera whose block is shared; -1 = own block.
  int rotation_source = -1, center_source = -1, focal_source = -1;
  bool fixed = false;        // rotation and centre held constant (gauge / overlap with the last window)
  bool fixed_focal = false;  // focal held constant (overlap with the previous window)
};

struct BaPoint {
  Eigen::Vector3d anchor = Eigen::Vector3d::Zero();      // constant world point
  Eigen::Vector4d homogeneous = Eigen::Vector4d(0, 0, 1, 0);  // (d, rho), normalised
  Eigen::Vector3d Direction() const { return homogeneous.head<3>(); }
};

struct BaObservation {
  int camera = 0;
  int point = 0;
  Eigen::Vector2d u = Eigen::Vector2d::Zero();  // normalised image coordinates
  // The observation's noise in units of the solve's (huber_scale): its
  // residual is divided by this (> 1: a noisier observation, e.g. a KLT
  // track's drift grown with its age, window/track_drift.h).
  double noise_scale = 1;
};

struct BaOptions {
  double huber_scale = 1.0 / kReferenceWidthPx;  // residual scale / Huber threshold, normalised units (~1 px)
  double focal_step_sigma = 0.01;     // prior sigma on the 2nd difference of log f over focal blocks
  double focal_prior_sigma = 0.7;     // prior sigma on the first focal around focal_prior_log
  double focal_prior_log = 0;         // log normalised focal of the prior
  bool fix_first_focal = false;       // focal not observable: hold the first focal block
  bool use_depth = true;              // false: bearings only (no translation in the window)
  // Soft scale gauge: |c[scale_b] - c[scale_a]| = scale_distance (skip if scale_a < 0),
  // with a sigma of scale_distance / scale_weight: tight by default (0.1 %);
  // loose, it only removes the gauge freedom and lets that interval's length
  // follow the rest of the window (shots of stills, window_solver.cc).
  int scale_a = -1, scale_b = -1;
  double scale_distance = 1;
  double scale_weight = 1e3;
  int max_iterations = 50;
  // Ceres' relative cost decrease at which the solve stops.
  double function_tolerance = 1e-7;
  int num_threads = 1;
};

struct BaSummary {
  bool success = false;
  int iterations = 0;
  int num_observations = 0;
  double rms_before = 0, rms_after = 0;  // unrobustified, normalised units
  // Ceres' robustified cost before and after, and why it stopped
  // (TerminationTypeToString: CONVERGENCE, NO_CONVERGENCE, ...). Diagnostics only.
  double initial_cost = 0, final_cost = 0;
  const char* termination = "";
};

// Optimises cameras and points in place. Observations whose point is behind
// the camera at the start are ignored.
BaSummary SolveBundle(std::vector<BaCamera>* cameras, std::vector<BaPoint>* points,
                      const std::vector<BaObservation>& observations, const BaOptions& options);

// Residual norms (normalised units) of each observation; +inf when the point
// is behind the camera.
std::vector<double> ObservationErrors(const std::vector<BaCamera>& cameras,
                                      const std::vector<BaPoint>& points,
                                      const std::vector<BaObservation>& observations,
                                      bool use_depth);

// Pose-only solve for one camera against fixed points (observations'
// `camera` field is ignored). Only the freedoms asked for move.
struct PoseFreedoms {
  bool rotation = true, center = false, focal = false;
};
BaSummary SolvePose(BaCamera* camera, const PoseFreedoms& freedoms,
                    const std::vector<BaPoint>& points,
                    const std::vector<BaObservation>& observations, const BaOptions& options);

}  // namespace hapcine
