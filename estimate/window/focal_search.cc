#include "estimate/window/focal_search.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "core/statistics.h"
#include "estimate/geometry/two_view_estimators.h"
#include "estimate/geometry/two_view_geometry.h"

namespace hapcine {
namespace {

// cam2_from_cam1 between two keyframes' cameras, and camera 2's centre in camera 1.
void RelativePose(const BaCamera& a, const BaCamera& b, Eigen::Matrix3d* R_ba, Eigen::Vector3d* centre_b_in_a) {
  const Eigen::Matrix3d R_wa = a.world_from_cam.toRotationMatrix();
  *R_ba = b.world_from_cam.toRotationMatrix().transpose() * R_wa;
  *centre_b_in_a = R_wa.transpose() * (b.center - a.center);
}

// The interval's relative pose at the given focal lengths, from its
// matches; false keeps the chain's.
bool FitInterval(MotionModel model, const std::vector<Eigen::Vector2d>& c1, const std::vector<Eigen::Vector2d>& c2,
                 double scene_depth, Eigen::Matrix3d* R_ba, Eigen::Vector3d* centre_b_in_a) {
  if (!HasRotation(model)) {
    R_ba->setIdentity();
    centre_b_in_a->setZero();
    return true;
  }
  if (!HasTranslation(model)) {
    centre_b_in_a->setZero();
    return FitRotation(c1, c2, R_ba);
  }
  const std::vector<Eigen::Matrix3d> E = EssentialEstimator::Estimate(c1, c2);
  Eigen::Vector3d t;
  if (E.empty() || !DecomposeEssential(E[0], c1, c2, R_ba, &t)) return false;
  std::vector<double> depths;
  for (size_t i = 0; i < c1.size(); ++i) {
    const double d = TriangulateDepth(c1[i], c2[i], *R_ba, t);
    if (d > 0 && std::isfinite(d)) depths.push_back(d);
  }
  if (depths.empty()) return false;
  *centre_b_in_a = -R_ba->transpose() * t * (scene_depth / Median(depths));
  return true;
}

}  // namespace

std::vector<BaCamera> ChainAtFocal(const std::vector<WindowKeyframe>& keyframes, double log_shift,
                                   const std::set<long>& outliers, double scene_depth) {
  const int n = static_cast<int>(keyframes.size());
  std::vector<BaCamera> cams(n);
  for (int i = 0; i < n; ++i) {
    cams[i] = keyframes[i].cam;
    cams[i].log_focal += log_shift;
  }
  for (int i = 1; i < n; ++i) {
    if (keyframes[i].fixed) continue;
    Eigen::Matrix3d R_ba;
    Eigen::Vector3d centre_b_in_a;
    RelativePose(keyframes[i - 1].cam, keyframes[i].cam, &R_ba, &centre_b_in_a);
    const double f1 = std::exp(cams[i - 1].log_focal), f2 = std::exp(cams[i].log_focal);
    std::vector<Eigen::Vector2d> c1, c2;
    for (const auto& [id, u] : *keyframes[i].tracks) {
      if (outliers.count(id)) continue;
      const auto it = keyframes[i - 1].tracks->find(id);
      if (it == keyframes[i - 1].tracks->end()) continue;
      c1.push_back(it->second / f1);
      c2.push_back(u / f2);
    }
    Eigen::Matrix3d R_fit;
    Eigen::Vector3d centre_fit;
    if (FitInterval(keyframes[i].model, c1, c2, scene_depth, &R_fit, &centre_fit)) {
      R_ba = R_fit;
      centre_b_in_a = centre_fit;
    }
    const Eigen::Matrix3d R_wa = cams[i - 1].world_from_cam.toRotationMatrix();
    cams[i].world_from_cam = Eigen::Quaterniond(R_wa * R_ba.transpose()).normalized();
    cams[i].center = cams[i - 1].center + R_wa * centre_b_in_a;
  }
  return cams;
}

std::vector<double> FocalStartShifts() {
  const double half_octave = 0.5 * std::log(2.0);
  return {0.0, -half_octave, half_octave};
}

int BestFocalStart(const std::vector<std::vector<double>>& errors, double noise_floor) {
  std::vector<double> finite;
  for (const auto& e : errors)
    for (double v : e)
      if (std::isfinite(v)) finite.push_back(v);
  if (errors.empty() || finite.empty()) return 0;
  const double sigma = std::max(Median(finite) / 1.1774, noise_floor);
  std::vector<double> chi2;
  for (const auto& e : errors) {
    double sum = 0;
    for (double v : e) sum += std::isfinite(v) ? std::min(v * v / (sigma * sigma), 9.0) : 9.0;
    chi2.push_back(sum);
  }
  const double penalty = std::log(std::max(2.0 * static_cast<double>(errors[0].size()), 2.0));
  int best = 0;
  for (size_t s = 1; s < chi2.size(); ++s)
    if (chi2[s] < chi2[0] - penalty && chi2[s] < chi2[best]) best = static_cast<int>(s);
  return best;
}

}  // namespace hapcine
