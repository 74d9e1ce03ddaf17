#include "calib/global/identifiability.hpp"

#include <cmath>
#include <limits>

#include <Eigen/Dense>
#include <fmt/format.h>

namespace gpm::calib::global {

using Eigen::Vector2d;
using Eigen::Vector3d;

Eigen::MatrixXd closure_jacobian(const std::vector<Vector3d>& theta_m, const Geometry& g,
                                 const FreeMask& free) {
  std::vector<int> cols;
  for (int p = 0; p < kNumParams; ++p)
    if (free[static_cast<size_t>(p)]) cols.push_back(p);
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(static_cast<long>(theta_m.size()),
                                            static_cast<long>(cols.size()));
  for (size_t j = 0; j < theta_m.size(); ++j) {
    std::array<Vector2d, 3> B, dir;
    for (int i = 0; i < 3; ++i) {
      const double th = theta_m[j][i] + g[dth(i)];  // eq. 35
      dir[static_cast<size_t>(i)] = Vector2d(std::cos(th), std::sin(th));
      B[static_cast<size_t>(i)] = g.A(i) + g[la(i)] * dir[static_cast<size_t>(i)];  // eq. 30
    }
    // Radical centre relative to B1 (eq. 32-33, ERRATA).
    const Vector2d d2 = B[1] - B[0], d3 = B[2] - B[0];
    const double q1 = g[kLb1] * g[kLb1];
    const double r2 = 0.5 * (d2.squaredNorm() + q1 - g[kLb2] * g[kLb2]);
    const double r3 = 0.5 * (d3.squaredNorm() + q1 - g[kLb3] * g[kLb3]);
    const double det = d2.x() * d3.y() - d2.y() * d3.x();
    if (!(std::abs(det) > 1e-12 * (d2.squaredNorm() + d3.squaredNorm()))) continue;
    const Vector2d u((r2 * d3.y() - r3 * d2.y()) / det, (d2.x() * r3 - d3.x() * r2) / det);
    const Vector2d O = B[0] + u;
    Eigen::Matrix3d M;
    for (int i = 0; i < 3; ++i) M.row(i) << 2.0 * (O - B[static_cast<size_t>(i)]).transpose(), -1.0;
    const Eigen::RowVector3d row_g = M.inverse().row(2);  // d g = -row_g . dF
    for (size_t c = 0; c < cols.size(); ++c) {
      const int p = cols[c];
      Vector3d dF = Vector3d::Zero();
      for (int i = 0; i < 3; ++i) {
        const Vector2d w = O - B[static_cast<size_t>(i)];
        Vector2d dB = Vector2d::Zero();
        if (p == xa(i)) dB = Vector2d(1, 0);
        if (p == ya(i)) dB = Vector2d(0, 1);
        if (p == la(i)) dB = dir[static_cast<size_t>(i)];
        if (p == dth(i)) dB = g[la(i)] * Vector2d(-dir[static_cast<size_t>(i)].y(), dir[static_cast<size_t>(i)].x());
        dF[i] = -2.0 * w.dot(dB) - (p == lb(i) ? 2.0 * g[lb(i)] : 0.0);
      }
      J(static_cast<long>(j), static_cast<long>(c)) = -row_g.dot(dF);
    }
  }
  return J;
}

Eigen::Matrix<double, kNumParams, 1> similarity_direction(const Geometry& g, const FreeMask& free) {
  Eigen::Matrix<double, kNumParams, 1> S = Eigen::Matrix<double, kNumParams, 1>::Zero(), R = S;
  for (int i = 0; i < 3; ++i) {
    const double dx = g[xa(i)] - g[kXa1], dy = g[ya(i)] - g[kYa1];
    S[xa(i)] = dx;  // scale about A1
    S[ya(i)] = dy;
    S[la(i)] = g[la(i)];
    S[lb(i)] = g[lb(i)];
    R[xa(i)] = -dy;  // rotation about A1
    R[ya(i)] = dx;
    R[dth(i)] = 1.0;
  }
  // Combinations a S + b R with zero change of every fixed parameter.
  Eigen::MatrixXd C(0, 2);
  for (int p = 0; p < kNumParams; ++p) {
    if (free[static_cast<size_t>(p)]) continue;
    C.conservativeResize(C.rows() + 1, 2);
    C.row(C.rows() - 1) << S[p], R[p];
  }
  Eigen::Vector2d ab(1.0, 0.0);
  if (C.rows() > 0) {
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(C, Eigen::ComputeFullV);
    const auto& sv = svd.singularValues();
    const double smax = sv.size() ? sv(0) : 0.0;
    const double smin = sv.size() >= 2 ? sv(1) : 0.0;
    if (C.rows() >= 2 && smin > 1e-9 * smax) return Eigen::Matrix<double, kNumParams, 1>::Zero();
    ab = svd.matrixV().col(1);
  }
  Eigen::Matrix<double, kNumParams, 1> v = ab[0] * S + ab[1] * R;
  for (int p = 0; p < kNumParams; ++p)
    if (!free[static_cast<size_t>(p)]) v[p] = 0.0;
  const double n = v.norm();
  return n > 0 ? Eigen::Matrix<double, kNumParams, 1>(v / n) : v;
}

Identifiability closure_identifiability(const std::vector<Vector3d>& theta_m, const Geometry& g,
                                        const FreeMask& free) {
  Identifiability id;
  const Eigen::MatrixXd J = closure_jacobian(theta_m, g, free);
  id.free_count = static_cast<int>(J.cols());
  Eigen::VectorXd scale = J.colwise().norm().transpose();
  for (long c = 0; c < scale.size(); ++c) scale[c] = scale[c] > 0 ? 1.0 / scale[c] : 1.0;
  const Eigen::MatrixXd Js = J * scale.asDiagonal();
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(Js, Eigen::ComputeThinV);
  id.singular_values = svd.singularValues();
  const long k = id.singular_values.size();
  const double smax = k ? id.singular_values(0) : 0.0;
  for (long i = 0; i < k; ++i)
    if (id.singular_values(i) > 1e-9 * smax) ++id.rank;
  if (k < id.free_count) {  // fewer samples than parameters
    id.condition_number = std::numeric_limits<double>::infinity();
  } else {
    const double smin = id.singular_values(k - 1);
    id.condition_number = smin > 0 ? smax / smin : std::numeric_limits<double>::infinity();
  }

  // Compare the weakest direction (in parameter units) with the similarity family.
  const auto fam = similarity_direction(g, free);
  id.similarity_alignment = std::numeric_limits<double>::quiet_NaN();
  if (fam.norm() > 0 && k == id.free_count && k > 0) {
    const Eigen::VectorXd weakest = scale.asDiagonal() * svd.matrixV().col(k - 1);
    Eigen::VectorXd f(id.free_count);
    int c = 0;
    for (int p = 0; p < kNumParams; ++p)
      if (free[static_cast<size_t>(p)]) f[c++] = fam[p];
    id.similarity_alignment = std::abs(weakest.normalized().dot(f.normalized()));
  }

  if (id.rank == id.free_count) {
    id.diagnosis = fmt::format("rank {} of {}: all free parameters identifiable (condition number {:.3g})",
                               id.rank, id.free_count, id.condition_number);
  } else if (std::isfinite(id.similarity_alignment) && id.similarity_alignment > 0.999) {
    id.diagnosis = fmt::format(
        "rank {} of {}: scale and rotation about A1 unobservable; the null direction is the "
        "similarity family of ERRATA (|cos| {:.6f}), so the free parameters are not determined: "
        "fix 4 base coordinates (e.g. xa1,ya1,xa2,ya2) at their true values",
        id.rank, id.free_count, id.similarity_alignment);
  } else {
    id.diagnosis = fmt::format("rank {} of {}: {} parameter combination(s) unobservable from these samples",
                               id.rank, id.free_count, id.free_count - id.rank);
  }
  return id;
}

}  // namespace gpm::calib::global
