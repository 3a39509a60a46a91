#pragma once
// Loop closure of a shot's rotations by revisit links, a measuring tool's
// model (docs/estimate.md, "Revisits: a rotation pose graph"; measured on
// lego_orbit, it cannot reach the target there even with exact links, so
// the estimator does not use it). An orbit, or a pan that turns away
// and comes back, sees the same side again long after its tracks ended;
// the windows' rotations drift in between (the KLT tracks' bias bends
// each window's structure, nothing spans far enough to hold it). A revisit
// link measures the rotation between two views directly (descriptor
// matches), and a rotation pose graph spreads the loop's disagreement over
// the steps between them.
//
//   RevisitCandidates: which view pairs can be revisits, from the solved
//     rotations alone (so no descriptor is computed on footage that never
//     comes back: no candidate, nothing changes).
//   CloseRevisitLoops: the pose graph; each consecutive step keeps its
//     solved relative rotation softly, each accepted link holds its
//     measured one; view 0 is the gauge.

#include <Eigen/Geometry>
#include <vector>

namespace hapcine {

// Views i < j that may see the same part of the scene after the camera
// left it: their optical axes within `overlap_deg` of each other, and some
// view between them turned more than `left_deg` away from view i (every
// view in between overlaps i otherwise: the tracks already link them, and
// a link adds nothing the windows did not have). `world_from_cam`: the
// solved rotations, one per view, in order. At most `max_per_view` pairs
// per later view j (the earliest i first: the longest loop holds most).
struct RevisitPair {
  int i = 0, j = 0;
  double axis_angle_deg = 0;  // angle between the optical axes
};
std::vector<RevisitPair> RevisitCandidates(const std::vector<Eigen::Quaterniond>& world_from_cam,
                                           double overlap_deg, double left_deg, int max_per_view);

// A measured relative rotation between views i and j (cam_i from cam_j, so
// that world_from_cam[j] = world_from_cam[i] * i_from_j) and its standard
// deviation per axis (rad).
struct RevisitLink {
  int i = 0, j = 0;
  Eigen::Quaterniond i_from_j = Eigen::Quaterniond::Identity();
  double sigma_rad = 0.002;
};

struct LoopClosureOptions {
  // Standard deviation (rad) of one consecutive step's solved relative
  // rotation: the windows' drift per view, which a loop spreads evenly.
  double step_sigma_rad = 0.002;
  // A link disagreeing with the solved path by more than this many times
  // the drift the steps between its views can accumulate (a bias, the same
  // way each step: step_sigma * steps) plus its own sigma is a wrong match
  // (repeated texture, a symmetric object): dropped.
  double link_gate_sigmas = 3;
  int max_iterations = 50;
};

struct LoopClosure {
  std::vector<Eigen::Quaterniond> world_from_cam;  // corrected (the input when nothing changed)
  int links_used = 0;
  int links_rejected = 0;
  bool changed = false;
};

LoopClosure CloseRevisitLoops(const std::vector<Eigen::Quaterniond>& world_from_cam,
                              const std::vector<RevisitLink>& links, const LoopClosureOptions& options);

// Centres after a rotation correction: every step's displacement turns with
// the rotation correction of the view it starts from (c'_{k+1} = c'_k +
// R'_k R_k^T (c_{k+1} - c_k)), view 0 stays.
std::vector<Eigen::Vector3d> CarryCentres(const std::vector<Eigen::Quaterniond>& before,
                                          const std::vector<Eigen::Quaterniond>& after,
                                          const std::vector<Eigen::Vector3d>& centres);

}  // namespace hapcine
