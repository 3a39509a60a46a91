#include "estimate/geometry/two_view_estimators.h"

#include <Eigen/Dense>
#include <cmath>
#include <limits>

#include "core/statistics.h"

namespace hapcine {
namespace {

constexpr double kHuge = 1e30;  // residual of a point that cannot be projected

// A template: a fixed-size argument is not copied into a heap matrix.
template <typename Matrix>
bool AllFinite(const Matrix& m) {
  return m.allFinite();
}

Eigen::Vector3d Bearing(const Eigen::Vector2d& c) { return Eigen::Vector3d(c.x(), c.y(), 1).normalized(); }

// Kabsch: rotation R minimising sum |b2 - R b1|^2. Empty if the bearings do
// not span two directions (all the same ray).
bool KabschRotation(const std::vector<Eigen::Vector3d>& b1, const std::vector<Eigen::Vector3d>& b2,
                    Eigen::Matrix3d* R) {
  Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
  for (size_t i = 0; i < b1.size(); ++i) C += b2[i] * b1[i].transpose();
  if (!AllFinite(C)) return false;
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(C, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Vector3d s = svd.singularValues();
  if (!(s(0) > 0) || s(1) < 1e-10 * s(0)) return false;
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  D(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0 ? -1 : 1;
  *R = svd.matrixU() * D * svd.matrixV().transpose();
  return AllFinite(*R);
}

// Similarity that moves the centroid to 0 and the mean distance to sqrt(2).
bool HartleyNormalise(const std::vector<Eigen::Vector2d>& x, Eigen::Matrix3d* T) {
  Eigen::Vector2d c = Eigen::Vector2d::Zero();
  for (const auto& p : x) c += p;
  c /= static_cast<double>(x.size());
  double d = 0;
  for (const auto& p : x) d += (p - c).norm();
  d /= static_cast<double>(x.size());
  if (!(d > 0) || !std::isfinite(d)) return false;
  const double s = std::sqrt(2.0) / d;
  *T << s, 0, -s * c.x(), 0, s, -s * c.y(), 0, 0, 1;
  return true;
}

Eigen::Vector2d Apply(const Eigen::Matrix3d& T, const Eigen::Vector2d& p) {
  return (T * p.homogeneous()).hnormalized();
}

// Rows of the DLT systems below: 9 columns; 8 rows for the minimal samples
// of RANSAC (a fixed size, no heap in the SVD), any number for the re-fits.
using DltRows = Eigen::Matrix<double, Eigen::Dynamic, 9>;
using DltMinimal = Eigen::Matrix<double, 8, 9>;

// The right singular vector of the smallest singular value of A; false when
// the 8th singular value is also ~0 (degenerate sample: a 2-d null space).
template <typename Matrix>
bool NullVector(const Matrix& A, Eigen::Matrix<double, 9, 1>* v) {
  if (!A.allFinite()) return false;
  Eigen::JacobiSVD<Matrix> svd(A, Eigen::ComputeFullV);
  const auto& s = svd.singularValues();
  if (s.size() >= 8 && s(7) < 1e-10 * s(0)) return false;
  *v = svd.matrixV().col(8);
  return true;
}

// A minimal sample's 8 x 9 system always has a null vector: the direction
// orthogonal to its 8 rows, i.e. the last column of Q in A^T = Q R. One
// Householder QR costs a fraction of the SVD above (whose Jacobi sweeps were
// ~3 % of the estimator's CPU under perf). Column pivoting
// orders R's diagonal, so a small last entry flags the same degenerate
// samples (rank < 8: a 2-d null space, no unique model).
bool MinimalNullVector(const DltMinimal& A, Eigen::Matrix<double, 9, 1>* v) {
  if (!A.allFinite()) return false;
  const Eigen::ColPivHouseholderQR<Eigen::Matrix<double, 9, 8>> qr(A.transpose());
  const auto& R = qr.matrixQR();
  if (!(std::abs(R(7, 7)) >= 1e-10 * std::abs(R(0, 0)))) return false;
  *v = qr.householderQ() * Eigen::Matrix<double, 9, 1>::Unit(8);
  return true;
}

// The null vector of a DLT system of `rows` rows that `fill(&A)` writes:
// into a fixed-size matrix for a minimal sample (8 rows), else a dynamic one
// (the least-squares refit on the inliers: the SVD's smallest direction).
template <typename Fill>
bool DltNullVector(Eigen::Index rows, const Fill& fill, Eigen::Matrix<double, 9, 1>* v) {
  if (rows == 8) {
    DltMinimal A;
    fill(&A);
    return MinimalNullVector(A, v);
  }
  DltRows A(rows, 9);
  fill(&A);
  return NullVector(A, v);
}

template <typename Matrix>
void FillHomographyRows(const std::vector<Eigen::Vector2d>& x1, const std::vector<Eigen::Vector2d>& x2,
                        const Eigen::Matrix3d& T1, const Eigen::Matrix3d& T2, Matrix* A) {
  for (size_t i = 0; i < x1.size(); ++i) {
    const Eigen::Vector2d p = Apply(T1, x1[i]), q = Apply(T2, x2[i]);
    A->row(2 * i) << -p.x(), -p.y(), -1, 0, 0, 0, q.x() * p.x(), q.x() * p.y(), q.x();
    A->row(2 * i + 1) << 0, 0, 0, -p.x(), -p.y(), -1, q.y() * p.x(), q.y() * p.y(), q.y();
  }
}

template <typename Matrix>
void FillEssentialRows(const std::vector<Eigen::Vector2d>& x1, const std::vector<Eigen::Vector2d>& x2,
                       const Eigen::Matrix3d& T1, const Eigen::Matrix3d& T2, Matrix* A) {
  for (size_t i = 0; i < x1.size(); ++i) {
    const Eigen::Vector2d p = Apply(T1, x1[i]), q = Apply(T2, x2[i]);
    A->row(i) << q.x() * p.x(), q.x() * p.y(), q.x(), q.y() * p.x(), q.y() * p.y(), q.y(), p.x(),
        p.y(), 1;
  }
}

}  // namespace

// ---------------------------------------------------------------- zoom
std::vector<double> ZoomEstimator::Estimate(const std::vector<X_t>& x1, const std::vector<Y_t>& x2) {
  double num = 0, den = 0;
  for (size_t i = 0; i < x1.size(); ++i) {
    num += x1[i].dot(x2[i]);
    den += x1[i].squaredNorm();
  }
  // A point at the principal point does not tell the scale.
  if (!(den > 1e-12 * x1.size()) || !std::isfinite(num)) return {};
  const double s = num / den;
  if (!(s > 0) || !std::isfinite(s)) return {};
  return {s};
}

void ZoomEstimator::Residuals(const std::vector<X_t>& x1, const std::vector<Y_t>& x2, const M_t& s,
                              std::vector<double>* r) {
  r->resize(x1.size());
  for (size_t i = 0; i < x1.size(); ++i) (*r)[i] = (x2[i] - s * x1[i]).squaredNorm();
}

// ---------------------------------------------------------------- rotation
std::vector<Eigen::Matrix3d> RotationEstimator::Estimate(const std::vector<X_t>& c1,
                                                         const std::vector<Y_t>& c2) {
  std::vector<Eigen::Vector3d> b1, b2;
  for (size_t i = 0; i < c1.size(); ++i) {
    b1.push_back(Bearing(c1[i]));
    b2.push_back(Bearing(c2[i]));
  }
  Eigen::Matrix3d R;
  if (!KabschRotation(b1, b2, &R)) return {};
  return {R};
}

void RotationEstimator::Residuals(const std::vector<X_t>& c1, const std::vector<Y_t>& c2,
                                  const M_t& R, std::vector<double>* r) {
  r->resize(c1.size());
  for (size_t i = 0; i < c1.size(); ++i) {
    const Eigen::Vector3d p = R * c1[i].homogeneous();
    (*r)[i] = p.z() > 1e-9 ? (p.hnormalized() - c2[i]).squaredNorm() : kHuge;
  }
}

// ---------------------------------------------------------------- rotation + zoom
std::vector<RotationZoom> RotationZoomEstimator::Estimate(const std::vector<X_t>& c1,
                                                          const std::vector<Y_t>& u2) {
  std::vector<double> f2_candidates;
  const size_t n = c1.size();
  if (n < 2) return {};
  // Pairs (i, i + n/2): each gives up to two f2 from the preserved ray angle.
  const size_t half = n / 2;
  for (size_t i = 0; i < (n == 2 ? 1 : half); ++i) {
    const size_t j = n == 2 ? 1 : i + half;
    const double c = Bearing(c1[i]).dot(Bearing(c1[j]));
    const double p = u2[i].dot(u2[j]), a = u2[i].squaredNorm(), b = u2[j].squaredNorm();
    // (p + t)^2 = c^2 (a + t)(b + t), t = f2^2.
    const double A = 1 - c * c, B = 2 * p - c * c * (a + b), C = p * p - c * c * a * b;
    std::vector<double> ts;
    if (std::abs(A) < 1e-14) {
      if (std::abs(B) > 1e-300) ts.push_back(-C / B);
    } else {
      const double disc = B * B - 4 * A * C;
      if (disc >= 0) {
        const double sq = std::sqrt(disc);
        ts.push_back((-B + sq) / (2 * A));
        ts.push_back((-B - sq) / (2 * A));
      }
    }
    for (double t : ts) {
      if (!(t > 0) || !std::isfinite(t)) continue;
      if ((p + t) * c < 0) continue;  // squaring introduced the wrong-sign root
      f2_candidates.push_back(std::sqrt(t));
    }
  }
  if (f2_candidates.empty()) return {};
  std::vector<double> f2s;
  if (n == 2) {
    f2s = f2_candidates;
  } else {  // least squares: the median of the pair solutions, then Kabsch
    f2s.push_back(Quantile(f2_candidates, 0.5));
  }
  std::vector<RotationZoom> models;
  std::vector<Eigen::Vector3d> b1, b2;
  for (double f2 : f2s) {
    b1.clear();
    b2.clear();
    for (size_t i = 0; i < n; ++i) {
      b1.push_back(Bearing(c1[i]));
      b2.push_back(Bearing(u2[i] / f2));
    }
    RotationZoom m;
    m.f2 = f2;
    if (KabschRotation(b1, b2, &m.cam2_from_cam1)) models.push_back(m);
  }
  return models;
}

void RotationZoomEstimator::Residuals(const std::vector<X_t>& c1, const std::vector<Y_t>& u2,
                                      const M_t& m, std::vector<double>* r) {
  r->resize(c1.size());
  for (size_t i = 0; i < c1.size(); ++i) {
    const Eigen::Vector3d p = m.cam2_from_cam1 * c1[i].homogeneous();
    (*r)[i] = p.z() > 1e-9 ? (m.f2 * p.hnormalized() - u2[i]).squaredNorm() : kHuge;
  }
}

// ---------------------------------------------------------------- homography
std::vector<Eigen::Matrix3d> HomographyEstimator::Estimate(const std::vector<X_t>& x1,
                                                           const std::vector<Y_t>& x2) {
  const size_t n = x1.size();
  if (n < 4) return {};
  Eigen::Matrix3d T1, T2;
  if (!HartleyNormalise(x1, &T1) || !HartleyNormalise(x2, &T2)) return {};
  // Three collinear points (or repeated points) leave a 2-d null space.
  Eigen::Matrix<double, 9, 1> h;
  const auto fill = [&](auto* A) { FillHomographyRows(x1, x2, T1, T2, A); };
  if (!DltNullVector(static_cast<Eigen::Index>(2 * n), fill, &h)) return {};
  Eigen::Matrix3d Hn;
  Hn << h(0), h(1), h(2), h(3), h(4), h(5), h(6), h(7), h(8);
  // A singular homography maps the plane to a line: reject (scale-free test
  // on the conditioned matrix; the denormalised one can be badly scaled).
  if (std::abs((Hn / Hn.norm()).determinant()) < 1e-12) return {};
  Eigen::Matrix3d H = T2.inverse() * Hn * T1;
  const double scale = H.norm();
  if (!(scale > 0) || !AllFinite(H)) return {};
  H /= scale;
  return {H};
}

void HomographyEstimator::Residuals(const std::vector<X_t>& x1, const std::vector<Y_t>& x2,
                                    const M_t& H, std::vector<double>* r) {
  r->resize(x1.size());
  for (size_t i = 0; i < x1.size(); ++i) {
    const Eigen::Vector3d p = H * x1[i].homogeneous();
    (*r)[i] = std::abs(p.z()) > 1e-12 ? (p.hnormalized() - x2[i]).squaredNorm() : kHuge;
  }
}

// ---------------------------------------------------------------- essential
std::vector<Eigen::Matrix3d> EssentialEstimator::Estimate(const std::vector<X_t>& x1,
                                                          const std::vector<Y_t>& x2) {
  const size_t n = x1.size();
  if (n < 8) return {};
  Eigen::Matrix3d T1, T2;
  if (!HartleyNormalise(x1, &T1) || !HartleyNormalise(x2, &T2)) return {};
  Eigen::Matrix<double, 9, 1> e;
  const auto fill = [&](auto* A) { FillEssentialRows(x1, x2, T1, T2, A); };
  if (!DltNullVector(static_cast<Eigen::Index>(n), fill, &e)) return {};  // degenerate configuration
  Eigen::Matrix3d En;
  En << e(0), e(1), e(2), e(3), e(4), e(5), e(6), e(7), e(8);
  Eigen::Matrix3d E = T2.transpose() * En * T1;
  if (!AllFinite(E)) return {};
  Eigen::JacobiSVD<Eigen::Matrix3d> svd_e(E, Eigen::ComputeFullU | Eigen::ComputeFullV);
  if (!(svd_e.singularValues()(0) > 0)) return {};
  E = svd_e.matrixU() * Eigen::Vector3d(1, 1, 0).asDiagonal() * svd_e.matrixV().transpose();
  if (!AllFinite(E)) return {};
  return {E};
}

void EssentialEstimator::Residuals(const std::vector<X_t>& x1, const std::vector<Y_t>& x2,
                                   const M_t& E, std::vector<double>* r) {
  r->resize(x1.size());
  for (size_t i = 0; i < x1.size(); ++i) {
    const Eigen::Vector3d p = x1[i].homogeneous(), q = x2[i].homogeneous();
    const Eigen::Vector3d Ep = E * p, Etq = E.transpose() * q;
    const double num = q.dot(Ep);
    const double den = Ep.head<2>().squaredNorm() + Etq.head<2>().squaredNorm();
    (*r)[i] = den > 1e-300 ? num * num / den : kHuge;
  }
}

}  // namespace hapcine
