// The only translation unit with Ceres AutoDiff templates (slow to compile).
#include "estimate/bundle/bundle_adjustment.h"

#include <ceres/ceres.h>
#include <ceres/dynamic_autodiff_cost_function.h>
#include <ceres/manifold.h>
#include <ceres/product_manifold.h>
#include <ceres/sphere_manifold.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <thread>

#include "estimate/bundle/depth_cost.h"

namespace hapcine {
namespace {

// Point in camera coordinates: R_wc^T (d + rho (anchor - c)), up to scale.
template <typename T>
bool Project(const T* q, const T* c, const T* log_f, const T* d, const T& rho,
             const Eigen::Vector3d& anchor, T* u) {
  Eigen::Map<const Eigen::Quaternion<T>> world_from_cam(q);
  Eigen::Matrix<T, 3, 1> v(d[0], d[1], d[2]);
  if (c != nullptr) {
    if (rho < T(0)) return false;  // beyond infinity: behind every camera
    v += rho * (anchor.cast<T>() - Eigen::Matrix<T, 3, 1>(c[0], c[1], c[2]));
  }
  const Eigen::Matrix<T, 3, 1> p = world_from_cam.conjugate() * v;
  if (!(p.z() > T(1e-9) * ceres::sqrt(p.squaredNorm() + T(1e-300)))) return false;
  const T f = ceres::exp(log_f[0]);
  u[0] = f * p.x() / p.z();
  u[1] = f * p.y() / p.z();
  return true;
}

// Pose-only: the point is a constant.
struct PoseCost {
  PoseCost(const Eigen::Vector2d& u, const BaPoint& point, bool use_depth, double inv_scale)
      : u_(u), point_(point), use_depth_(use_depth), inv_scale_(inv_scale) {}
  template <typename T>
  bool operator()(const T* q, const T* c, const T* log_f, T* r) const {
    const T d[3] = {T(point_.homogeneous(0)), T(point_.homogeneous(1)), T(point_.homogeneous(2))};
    T p[2];
    if (!Project<T>(q, use_depth_ ? c : nullptr, log_f, d, T(point_.homogeneous(3)), point_.anchor, p))
      return false;
    r[0] = (p[0] - T(u_.x())) * inv_scale_;
    r[1] = (p[1] - T(u_.y())) * inv_scale_;
    return true;
  }
  static ceres::CostFunction* Create(const Eigen::Vector2d& u, const BaPoint& point, bool use_depth,
                                     double inv_scale) {
    return new ceres::AutoDiffCostFunction<PoseCost, 2, 4, 3, 1>(
        new PoseCost(u, point, use_depth, inv_scale));
  }
  Eigen::Vector2d u_;
  BaPoint point_;
  bool use_depth_;
  double inv_scale_;
};

// (log f_c - 2 log f_b + log f_a) / sigma: the zoom *rate* is smooth between
// neighbouring keyframes. A second difference does not pull a steady zoom
// towards "no zoom" (a first difference would shrink every zoom ratio).
// The log focals sit at `offset` of their blocks (7 in a merged rotation +
// centre + focal block, 0 in a focal block).
struct FocalStepCost {
  FocalStepCost(double inv_sigma, std::array<int, 3> offset) : inv_sigma_(inv_sigma), offset_(offset) {}
  template <typename T>
  bool operator()(T const* const* blocks, T* r) const {
    const T& a = blocks[0][offset_[0]];
    const T& b = blocks[1][offset_[1]];
    const T& c = blocks[2][offset_[2]];
    r[0] = (c - T(2) * b + a) * inv_sigma_;
    return true;
  }
  double inv_sigma_;
  std::array<int, 3> offset_;
};

struct FocalPriorCost {
  FocalPriorCost(double prior, double inv_sigma, int offset) : prior_(prior), inv_sigma_(inv_sigma), offset_(offset) {}
  template <typename T>
  bool operator()(T const* const* blocks, T* r) const {
    r[0] = (blocks[0][offset_] - T(prior_)) * inv_sigma_;
    return true;
  }
  double prior_, inv_sigma_;
  int offset_;
};

// The centres sit at `offset_a` / `offset_b` of their blocks (4 in a merged
// rotation + centre block, 0 in a centre block).
struct ScaleCost {
  ScaleCost(double distance, double inv_sigma, int offset_a, int offset_b)
      : distance_(distance), inv_sigma_(inv_sigma), offset_a_(offset_a), offset_b_(offset_b) {}
  template <typename T>
  bool operator()(T const* const* blocks, T* r) const {
    const T* a = blocks[0] + offset_a_;
    const T* b = blocks[1] + offset_b_;
    const T dx = b[0] - a[0], dy = b[1] - a[1], dz = b[2] - a[2];
    r[0] = (ceres::sqrt(dx * dx + dy * dy + dz * dz + T(1e-30)) - T(distance_)) * inv_sigma_;
    return true;
  }
  double distance_, inv_sigma_;
  int offset_a_, offset_b_;
};

struct Blocks {
  std::vector<std::array<double, 4>> q;  // Eigen order x, y, z, w
  std::vector<std::array<double, 3>> c;
  std::vector<double> lf;
  std::vector<int> rot, cen, foc;  // root block index per camera
  // Roots whose rotation and centre are one block (q then c): every camera
  // that uses either uses both.
  std::vector<char> merged;
  // Merged roots whose block also holds the log focal (at 7): every camera
  // that uses the pose uses the focal and the other way round.
  std::vector<char> merged_focal;
  std::vector<std::array<double, 8>> pose;
  double* CenterBlock(int camera) { return merged[cen[camera]] ? pose[cen[camera]].data() : c[cen[camera]].data(); }
  double* RotationBlock(int camera) { return merged[rot[camera]] ? pose[rot[camera]].data() : q[rot[camera]].data(); }
  double* FocalBlock(int camera) { return merged_focal[foc[camera]] ? pose[foc[camera]].data() : &lf[foc[camera]]; }
  int FocalOffset(int camera) const { return merged_focal[foc[camera]] ? 7 : 0; }
  int FocalBlockSize(int camera) const { return merged_focal[foc[camera]] ? 8 : 1; }
  int CenterOffset(int camera) const { return merged[cen[camera]] ? 4 : 0; }
  int CenterBlockSize(int camera) const { return merged[cen[camera]] ? (merged_focal[cen[camera]] ? 8 : 7) : 3; }
};

// Merges rotation and centre where the sharing allows: fewer, larger blocks
// for the Schur eliminator (with one thread it still locks a mutex per cell).
void MergePoses(Blocks* b) {
  const int n = static_cast<int>(b->q.size());  // MakeBlocks sized merged and pose
  for (int j = 0; j < n; ++j) b->merged[j] = b->rot[j] == j && b->cen[j] == j;
  for (int i = 0; i < n; ++i)
    if (b->rot[i] != b->cen[i]) b->merged[b->rot[i]] = b->merged[b->cen[i]] = 0;
  for (int j = 0; j < n; ++j) {
    if (!b->merged[j]) continue;
    std::copy(b->q[j].begin(), b->q[j].end(), b->pose[j].begin());
    std::copy(b->c[j].begin(), b->c[j].end(), b->pose[j].begin() + 4);
    b->pose[j][7] = b->lf[j];
  }
}

// Also the focal where the pose block is merged and the focal's sharing and
// constancy are the pose's (the per-keyframe focal of general+zoom segments).
void MergeFocals(Blocks* b, const std::vector<BaCamera>& cams, bool fix_first_focal) {
  const int n = static_cast<int>(b->q.size());
  std::vector<char> pose_const(n, 0), focal_const(n, 0);
  for (int j = 0; j < n; ++j) b->merged_focal[j] = b->merged[j] && b->foc[j] == j;
  for (int i = 0; i < n; ++i) {
    if (b->foc[i] != b->rot[i]) b->merged_focal[b->foc[i]] = b->merged_focal[b->rot[i]] = 0;
    if (cams[i].fixed) pose_const[b->rot[i]] = pose_const[b->cen[i]] = 1;
    if (cams[i].fixed_focal) focal_const[b->foc[i]] = 1;
  }
  if (fix_first_focal && n > 0) focal_const[b->foc[0]] = 1;
  for (int j = 0; j < n; ++j) {
    if (pose_const[j] != focal_const[j]) b->merged_focal[j] = 0;
    if (b->merged_focal[j]) b->pose[j][7] = b->lf[j];
  }
}

void SplitPoses(Blocks* b) {
  for (size_t j = 0; j < b->merged.size(); ++j) {
    if (!b->merged[j]) continue;
    std::copy(b->pose[j].begin(), b->pose[j].begin() + 4, b->q[j].begin());
    std::copy(b->pose[j].begin() + 4, b->pose[j].begin() + 7, b->c[j].begin());
    if (b->merged_focal[j]) b->lf[j] = b->pose[j][7];
  }
}

int Root(const std::vector<int>& roots, int src, int self) { return src < 0 ? self : roots[src]; }

Blocks MakeBlocks(const std::vector<BaCamera>& cams) {
  Blocks b;
  const int n = static_cast<int>(cams.size());
  b.q.resize(n);
  b.c.resize(n);
  b.lf.resize(n);
  b.rot.resize(n);
  b.cen.resize(n);
  b.foc.resize(n);
  b.merged.assign(n, 0);
  b.merged_focal.assign(n, 0);
  b.pose.resize(n);
  for (int i = 0; i < n; ++i) {
    const auto& cam = cams[i];
    const Eigen::Quaterniond q = cam.world_from_cam.normalized();
    b.q[i] = {q.x(), q.y(), q.z(), q.w()};
    b.c[i] = {cam.center.x(), cam.center.y(), cam.center.z()};
    b.lf[i] = cam.log_focal;
    b.rot[i] = Root(b.rot, cam.rotation_source, i);
    b.cen[i] = Root(b.cen, cam.center_source, i);
    b.foc[i] = Root(b.foc, cam.focal_source, i);
  }
  return b;
}

void ReadBack(const Blocks& b, std::vector<BaCamera>* cams) {
  for (size_t i = 0; i < cams->size(); ++i) {
    auto& cam = (*cams)[i];
    const auto& q = b.q[b.rot[i]];
    cam.world_from_cam = Eigen::Quaterniond(q[3], q[0], q[1], q[2]).normalized();
    const auto& c = b.c[b.cen[i]];
    cam.center = Eigen::Vector3d(c[0], c[1], c[2]);
    cam.log_focal = b.lf[b.foc[i]];
  }
}

bool ObservationError(const BaCamera& cam, const BaPoint& pt, const Eigen::Vector2d& u,
                      bool use_depth, double* err) {
  const Eigen::Quaterniond q = cam.world_from_cam.normalized();
  const double qa[4] = {q.x(), q.y(), q.z(), q.w()};
  const double p[3] = {cam.center.x(), cam.center.y(), cam.center.z()};
  double proj[2];
  if (!Project<double>(qa, use_depth ? p : nullptr, &cam.log_focal, pt.homogeneous.data(),
                       pt.homogeneous(3), pt.anchor, proj)) {
    *err = std::numeric_limits<double>::infinity();
    return false;
  }
  *err = (Eigen::Vector2d(proj[0], proj[1]) - u).norm();
  return true;
}

double Rms(const std::vector<double>& e) {
  double s = 0;
  int n = 0;
  for (double v : e)
    if (std::isfinite(v)) {
      s += v * v;
      ++n;
    }
  return n ? std::sqrt(s / n) : 0;
}

}  // namespace

std::vector<double> ObservationErrors(const std::vector<BaCamera>& cameras,
                                      const std::vector<BaPoint>& points,
                                      const std::vector<BaObservation>& observations,
                                      bool use_depth) {
  std::vector<double> errs(observations.size());
  for (size_t i = 0; i < observations.size(); ++i) {
    const auto& o = observations[i];
    ObservationError(cameras[o.camera], points[o.point], o.u, use_depth, &errs[i]);
  }
  return errs;
}

namespace {

// The manifolds of a window's parameter blocks, shared by every block (the
// problem does not own them; declared before it, they outlive it).
struct Manifolds {
  ceres::EigenQuaternionManifold quat;
  ceres::SphereManifold<4> sphere4;
  ceres::SphereManifold<3> sphere3;
  ceres::ProductManifold<ceres::EigenQuaternionManifold, ceres::EuclideanManifold<3>> pose;
  ceres::ProductManifold<ceres::EigenQuaternionManifold, ceres::EuclideanManifold<4>> pose_focal;
};

// One residual per observation whose point starts in front of its camera,
// with the cost function the camera's blocks call for. Returns how many;
// `point_used`: the points that got one.
int AddObservations(Blocks* b, const std::vector<BaPoint>& points,
                    const std::vector<BaObservation>& observations, const std::vector<double>& before,
                    const BaOptions& options, ceres::LossFunction* loss, std::vector<std::array<double, 4>>* X,
                    std::vector<char>* point_used, ceres::Problem* problem) {
  const double inv_huber_scale = 1.0 / options.huber_scale;
  int count = 0;
  for (size_t i = 0; i < observations.size(); ++i) {
    if (!std::isfinite(before[i])) continue;
    const auto& o = observations[i];
    const double inv_scale = inv_huber_scale / o.noise_scale;
    const int root = b->rot[o.camera];
    double* q = b->q[root].data();
    double* lf = &b->lf[b->foc[o.camera]];
    double* x = (*X)[o.point].data();
    if (options.use_depth && b->merged_focal[root]) {
      problem->AddResidualBlock(new PoseFocalDepthCostFunction(o.u, points[o.point].anchor, inv_scale), loss,
                                b->pose[root].data(), x);
    } else if (options.use_depth && b->merged[root]) {
      problem->AddResidualBlock(new PoseDepthCostFunction(o.u, points[o.point].anchor, inv_scale), loss,
                                b->pose[root].data(), lf, x);
    } else if (options.use_depth) {
      double* c = b->c[b->cen[o.camera]].data();
      problem->AddResidualBlock(new DepthCostFunction(o.u, points[o.point].anchor, inv_scale), loss, q, c, lf, x);
    } else {
      problem->AddResidualBlock(new BearingCostFunction(o.u, inv_scale), loss, q, lf, x);
    }
    (*point_used)[o.point] = 1;
    ++count;
  }
  return count;
}

void SetPointManifolds(std::vector<std::array<double, 4>>* X, const std::vector<char>& point_used, bool use_depth,
                       Manifolds* m, ceres::Problem* problem) {
  for (size_t i = 0; i < X->size(); ++i) {
    if (!point_used[i]) continue;
    double* x = (*X)[i].data();
    problem->SetManifold(x, use_depth ? static_cast<ceres::Manifold*>(&m->sphere4)
                                      : static_cast<ceres::Manifold*>(&m->sphere3));
    // Cheirality: rho < 0 would be a point "beyond infinity", i.e. behind
    // every camera, that still projects where it is seen (the homogeneous
    // projection does not see the sign). Without this bound a forward dolly
    // with a zoom out fits as a backward move at constant focal with the
    // near points flipped behind the cameras.
    if (use_depth) problem->SetParameterLowerBound(x, 3, 0.0);
  }
}

// Focal priors: between consecutive distinct focal blocks, and on the first
// (cameras whose focal block they are; the value may sit in a merged block).
void AddFocalPriors(Blocks* b, int n, const BaOptions& options, ceres::Problem* problem) {
  int prev_focal = -1, prev2_focal = -1;
  for (int i = 0; i < n; ++i) {
    const int f = b->foc[i];
    if (!problem->HasParameterBlock(b->FocalBlock(i)) || (prev_focal >= 0 && f == b->foc[prev_focal])) continue;
    if (prev2_focal >= 0) {
      auto* cost = new ceres::DynamicAutoDiffCostFunction<FocalStepCost>(new FocalStepCost(
          1.0 / options.focal_step_sigma,
          {b->FocalOffset(prev2_focal), b->FocalOffset(prev_focal), b->FocalOffset(i)}));
      for (int k : {prev2_focal, prev_focal, i}) cost->AddParameterBlock(b->FocalBlockSize(k));
      cost->SetNumResiduals(1);
      problem->AddResidualBlock(cost, nullptr, b->FocalBlock(prev2_focal), b->FocalBlock(prev_focal),
                                b->FocalBlock(i));
    }
    if (prev_focal < 0) {
      auto* cost = new ceres::DynamicAutoDiffCostFunction<FocalPriorCost>(new FocalPriorCost(
          options.focal_prior_log, 1.0 / options.focal_prior_sigma, b->FocalOffset(i)));
      cost->AddParameterBlock(b->FocalBlockSize(i));
      cost->SetNumResiduals(1);
      problem->AddResidualBlock(cost, nullptr, b->FocalBlock(i));
    }
    prev2_focal = prev_focal;
    prev_focal = i;
  }
}

void SetPoseManifolds(Blocks* b, int n, Manifolds* m, ceres::Problem* problem) {
  for (int i = 0; i < n; ++i) {
    if (problem->HasParameterBlock(b->q[i].data())) problem->SetManifold(b->q[i].data(), &m->quat);
    if (b->merged[i] && problem->HasParameterBlock(b->pose[i].data()))
      problem->SetManifold(b->pose[i].data(), b->merged_focal[i] ? static_cast<ceres::Manifold*>(&m->pose_focal)
                                                                 : static_cast<ceres::Manifold*>(&m->pose));
  }
}

// Gauge: fixed cameras' own blocks constant, the first focal where it is
// not observable, and the soft scale gauge.
void HoldGauge(Blocks* b, const std::vector<BaCamera>& cameras, const BaOptions& options, ceres::Problem* problem) {
  for (size_t i = 0; i < cameras.size(); ++i) {
    if (cameras[i].fixed_focal && problem->HasParameterBlock(b->FocalBlock(i)))
      problem->SetParameterBlockConstant(b->FocalBlock(i));
    if (!cameras[i].fixed) continue;
    if (problem->HasParameterBlock(b->RotationBlock(i))) problem->SetParameterBlockConstant(b->RotationBlock(i));
    if (options.use_depth && problem->HasParameterBlock(b->CenterBlock(i)))
      problem->SetParameterBlockConstant(b->CenterBlock(i));
  }
  if (options.fix_first_focal && problem->HasParameterBlock(b->FocalBlock(0)))
    problem->SetParameterBlockConstant(b->FocalBlock(0));
  if (!(options.use_depth && options.scale_a >= 0 && options.scale_b >= 0)) return;
  double* ca = b->CenterBlock(options.scale_a);
  double* cb = b->CenterBlock(options.scale_b);
  if (ca != cb && problem->HasParameterBlock(ca) && problem->HasParameterBlock(cb) &&
      !(problem->IsParameterBlockConstant(ca) && problem->IsParameterBlockConstant(cb))) {
    auto* cost = new ceres::DynamicAutoDiffCostFunction<ScaleCost>(
        new ScaleCost(options.scale_distance, options.scale_weight / options.scale_distance, b->CenterOffset(options.scale_a),
                      b->CenterOffset(options.scale_b)));
    cost->AddParameterBlock(b->CenterBlockSize(options.scale_a));
    cost->AddParameterBlock(b->CenterBlockSize(options.scale_b));
    cost->SetNumResiduals(1);
    problem->AddResidualBlock(cost, nullptr, ca, cb);
  }
}

ceres::Solver::Options SolverOptions(const BaOptions& options, int cameras) {
  ceres::Solver::Options so;
  so.linear_solver_type = cameras <= 80 ? ceres::DENSE_SCHUR : ceres::SPARSE_SCHUR;
  so.max_num_iterations = options.max_iterations;
  // Ceres bounds the threads to the cores itself, with a warning per solve.
  const int cores = static_cast<int>(std::thread::hardware_concurrency());
  so.num_threads = cores > 0 ? std::min(options.num_threads, cores) : options.num_threads;
  so.function_tolerance = options.function_tolerance;
  so.parameter_tolerance = 1e-9;
  // The cheirality bound makes the problem bounds-constrained, and Ceres then
  // runs a projected Armijo line search after every trust-region step: one
  // more residual-and-Jacobian evaluation per iteration, ~a fifth of the
  // bundle adjustment's CPU. Steps are projected onto the bound anyway
  // (ParameterBlock::Plus), and on the 17 synthetic clips the search changed
  // the printed accuracy of one clip only, a dolly zoom's, in the last digit.
  so.max_num_line_search_step_size_iterations = 0;
  so.logging_type = ceres::SILENT;
  return so;
}

}  // namespace

BaSummary SolveBundle(std::vector<BaCamera>* cameras, std::vector<BaPoint>* points,
                      const std::vector<BaObservation>& observations, const BaOptions& options) {
  BaSummary summary;
  if (cameras->empty()) return summary;
  Blocks b = MakeBlocks(*cameras);
  if (options.use_depth) {
    MergePoses(&b);
    MergeFocals(&b, *cameras, options.fix_first_focal);
  }
  std::vector<std::array<double, 4>> X(points->size());
  for (size_t i = 0; i < points->size(); ++i) {
    Eigen::Vector4d h = (*points)[i].homogeneous;
    if (!options.use_depth || h(3) < 0) h(3) = 0;  // bearing only / cheirality bound below
    h.normalize();
    X[i] = {h(0), h(1), h(2), h(3)};
  }
  const auto before = ObservationErrors(*cameras, *points, observations, options.use_depth);
  summary.rms_before = Rms(before);

  // One loss for every residual (declared before the problem, which must
  // not outlive it): no allocation per observation.
  ceres::HuberLoss huber(1.0);
  Manifolds manifolds;
  ceres::Problem::Options po;
  po.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  po.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(po);
  std::vector<char> point_used(points->size(), 0);
  summary.num_observations = AddObservations(&b, *points, observations, before, options, &huber, &X, &point_used,
                                             &problem);
  if (summary.num_observations == 0) return summary;
  SetPointManifolds(&X, point_used, options.use_depth, &manifolds, &problem);
  const int n = static_cast<int>(cameras->size());
  AddFocalPriors(&b, n, options, &problem);
  SetPoseManifolds(&b, n, &manifolds, &problem);
  HoldGauge(&b, *cameras, options, &problem);
  ceres::Solver::Summary cs;
  ceres::Solve(SolverOptions(options, n), &problem, &cs);
  summary.iterations = static_cast<int>(cs.iterations.size());
  summary.initial_cost = cs.initial_cost;
  summary.final_cost = cs.final_cost;
  summary.termination = ceres::TerminationTypeToString(cs.termination_type);
  summary.success = cs.IsSolutionUsable();
  if (!summary.success) return summary;
  SplitPoses(&b);
  ReadBack(b, cameras);
  for (size_t i = 0; i < points->size(); ++i) {
    (*points)[i].homogeneous = Eigen::Vector4d(X[i][0], X[i][1], X[i][2], X[i][3]);
  }
  summary.rms_after = Rms(ObservationErrors(*cameras, *points, observations, options.use_depth));
  return summary;
}

BaSummary SolvePose(BaCamera* camera, const PoseFreedoms& freedoms,
                    const std::vector<BaPoint>& points,
                    const std::vector<BaObservation>& observations, const BaOptions& options) {
  BaSummary summary;
  std::vector<BaCamera> cams = {*camera};
  cams[0].rotation_source = cams[0].center_source = cams[0].focal_source = -1;
  Blocks b = MakeBlocks(cams);
  ceres::HuberLoss huber(1.0);  // shared, as in SolveBundle
  ceres::Problem::Options po;
  po.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  po.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(po);
  ceres::EigenQuaternionManifold quat_manifold;
  const double inv_scale = 1.0 / options.huber_scale;
  std::vector<double> before;
  for (const auto& o : observations) {
    double e;
    if (!ObservationError(cams[0], points[o.point], o.u, options.use_depth, &e)) continue;
    before.push_back(e);
    problem.AddResidualBlock(PoseCost::Create(o.u, points[o.point], options.use_depth, inv_scale / o.noise_scale),
                             &huber, b.q[0].data(), b.c[0].data(), &b.lf[0]);
  }
  summary.num_observations = static_cast<int>(before.size());
  summary.rms_before = Rms(before);
  if (summary.num_observations < 3) return summary;
  problem.SetManifold(b.q[0].data(), &quat_manifold);
  if (!freedoms.rotation) problem.SetParameterBlockConstant(b.q[0].data());
  if (!freedoms.center || !options.use_depth) problem.SetParameterBlockConstant(b.c[0].data());
  if (!freedoms.focal) problem.SetParameterBlockConstant(&b.lf[0]);
  if (freedoms.rotation || (freedoms.center && options.use_depth) || freedoms.focal) {
    ceres::Solver::Options so;
    so.linear_solver_type = ceres::DENSE_QR;
    so.max_num_iterations = options.max_iterations;
    so.logging_type = ceres::SILENT;
    so.function_tolerance = 1e-8;
    ceres::Solver::Summary cs;
    ceres::Solve(so, &problem, &cs);
    summary.iterations = static_cast<int>(cs.iterations.size());
    if (!cs.IsSolutionUsable()) return summary;
  }
  summary.success = true;
  ReadBack(b, &cams);
  camera->world_from_cam = cams[0].world_from_cam;
  camera->center = cams[0].center;
  camera->log_focal = cams[0].log_focal;
  std::vector<double> after;
  for (const auto& o : observations) {
    double e;
    if (ObservationError(*camera, points[o.point], o.u, options.use_depth, &e)) after.push_back(e);
  }
  summary.rms_after = Rms(after);
  return summary;
}

}  // namespace hapcine
