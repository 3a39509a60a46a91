#include "bench/revisit_loops.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <map>

namespace hapcine {

namespace {

constexpr double kDegToRad = M_PI / 180;

Eigen::Vector3d OpticalAxis(const Eigen::Quaterniond& world_from_cam) {
  return world_from_cam * Eigen::Vector3d::UnitZ();
}

double AngleRad(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

// The rotation angle (rad) of q.
double RotationAngle(const Eigen::Quaterniond& q) {
  return 2 * std::atan2(q.vec().norm(), std::abs(q.w()));
}

// Residual of a measured relative rotation: the small-angle vector of
// measured^-1 * (world_from_a^-1 * world_from_b), over its sigma.
struct RelativeRotationCost {
  RelativeRotationCost(const Eigen::Quaterniond& a_from_b, double sigma)
      : b_from_a_measured(a_from_b.conjugate()), inv_sigma(1 / sigma) {}
  template <typename T>
  bool operator()(const T* qa, const T* qb, T* residual) const {
    Eigen::Map<const Eigen::Quaternion<T>> world_from_a(qa), world_from_b(qb);
    const Eigen::Quaternion<T> error =
        b_from_a_measured.cast<T>() * world_from_a.conjugate() * world_from_b;
    const T sign = error.w() < T(0) ? T(-1) : T(1);
    for (int k = 0; k < 3; ++k) residual[k] = T(2) * sign * error.vec()[k] * T(inv_sigma);
    return true;
  }
  Eigen::Quaterniond b_from_a_measured;
  double inv_sigma;
};

void AddRelative(ceres::Problem* problem, std::vector<Eigen::Quaterniond>* q, int a, int b,
                 const Eigen::Quaterniond& a_from_b, double sigma) {
  problem->AddResidualBlock(new ceres::AutoDiffCostFunction<RelativeRotationCost, 3, 4, 4>(
                                new RelativeRotationCost(a_from_b, sigma)),
                            nullptr, (*q)[a].coeffs().data(), (*q)[b].coeffs().data());
}

// The links that agree with the solved path within the drift its steps can
// have accumulated (LoopClosureOptions::link_gate_sigmas).
std::vector<RevisitLink> GatedLinks(const std::vector<Eigen::Quaterniond>& world_from_cam,
                                    const std::vector<RevisitLink>& links, const LoopClosureOptions& o) {
  const int n = static_cast<int>(world_from_cam.size());
  std::vector<RevisitLink> kept;
  for (const RevisitLink& l : links) {
    if (l.i < 0 || l.j < 0 || l.i >= n || l.j >= n || l.i == l.j || !(l.sigma_rad > 0)) continue;
    const Eigen::Quaterniond solved = world_from_cam[l.i].conjugate() * world_from_cam[l.j];
    const double disagreement = RotationAngle(l.i_from_j.conjugate() * solved);
    const double steps = std::abs(l.j - l.i);
    const double sigma = o.step_sigma_rad * steps + l.sigma_rad;
    if (std::isfinite(disagreement) && disagreement <= o.link_gate_sigmas * sigma) kept.push_back(l);
  }
  return kept;
}

}  // namespace

std::vector<RevisitPair> RevisitCandidates(const std::vector<Eigen::Quaterniond>& world_from_cam,
                                           double overlap_deg, double left_deg, int max_per_view) {
  const int n = static_cast<int>(world_from_cam.size());
  std::vector<Eigen::Vector3d> axis(n);
  for (int k = 0; k < n; ++k) axis[k] = OpticalAxis(world_from_cam[k]);
  std::map<int, std::vector<RevisitPair>> by_later;
  for (int i = 0; i < n; ++i) {
    bool left = false;
    for (int j = i + 1; j < n; ++j) {
      const double angle = AngleRad(axis[i], axis[j]);
      if (left && angle < overlap_deg * kDegToRad) by_later[j].push_back({i, j, angle / kDegToRad});
      left = left || angle > left_deg * kDegToRad;
    }
  }
  std::vector<RevisitPair> out;
  for (auto& [j, pairs] : by_later) {
    const int keep = std::min<int>(std::max(max_per_view, 0), static_cast<int>(pairs.size()));
    out.insert(out.end(), pairs.begin(), pairs.begin() + keep);
  }
  return out;
}

LoopClosure CloseRevisitLoops(const std::vector<Eigen::Quaterniond>& world_from_cam,
                              const std::vector<RevisitLink>& links, const LoopClosureOptions& options) {
  LoopClosure out;
  out.world_from_cam = world_from_cam;
  const std::vector<RevisitLink> kept = GatedLinks(world_from_cam, links, options);
  out.links_used = static_cast<int>(kept.size());
  out.links_rejected = static_cast<int>(links.size() - kept.size());
  if (kept.empty()) return out;  // nothing measured across the loop: the path as solved
  std::vector<Eigen::Quaterniond> q = world_from_cam;
  for (auto& r : q) r.normalize();
  ceres::Problem problem;
  for (size_t k = 0; k + 1 < q.size(); ++k)
    AddRelative(&problem, &q, k, k + 1, q[k].conjugate() * q[k + 1], options.step_sigma_rad);
  for (const RevisitLink& l : kept) AddRelative(&problem, &q, l.i, l.j, l.i_from_j.normalized(), l.sigma_rad);
  for (auto& r : q) {
    if (problem.HasParameterBlock(r.coeffs().data()))
      problem.SetManifold(r.coeffs().data(), new ceres::EigenQuaternionManifold);
  }
  problem.SetParameterBlockConstant(q[0].coeffs().data());  // the gauge: the shot's first view
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  solver.max_num_iterations = options.max_iterations;
  solver.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  if (!summary.IsSolutionUsable()) return out;
  for (auto& r : q) r.normalize();
  out.world_from_cam = q;
  out.changed = true;
  return out;
}

std::vector<Eigen::Vector3d> CarryCentres(const std::vector<Eigen::Quaterniond>& before,
                                          const std::vector<Eigen::Quaterniond>& after,
                                          const std::vector<Eigen::Vector3d>& centres) {
  std::vector<Eigen::Vector3d> out = centres;
  for (size_t k = 0; k + 1 < centres.size() && k + 1 < before.size() && k < after.size(); ++k) {
    const Eigen::Quaterniond turn = after[k] * before[k].conjugate();
    out[k + 1] = out[k] + turn * (centres[k + 1] - centres[k]);
  }
  return out;
}

}  // namespace hapcine
