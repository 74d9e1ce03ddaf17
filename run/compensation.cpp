#include "run/compensation.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include <Eigen/Cholesky>

#include "models/errors.hpp"
#include "models/kinematics.hpp"
#include "models/rng.hpp"
#include "sim/waypoint_path.hpp"

namespace gpm::scenario {
namespace {

double rms(const std::vector<double>& v) {
  if (v.empty()) return 0.0;
  double s = 0.0;
  for (double x : v) s += x * x;
  return std::sqrt(s / static_cast<double>(v.size()));
}

double max_of(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, x);
  return m;
}

}  // namespace

double internal_preload(const Geometry& g, const Eigen::Vector2d& p, const Eigen::Vector3d& tau,
                        const Branches& branch) {
  const std::optional<JointAngles> angles = try_inverse_kinematics(g, p, branch);
  if (!angles) return NAN;
  const Matrix32d J = active_jacobian(g, *angles);
  // P = I - J (J'J)^-1 J' (eq. 15): torques in the null space of J' do no
  // work on the end-effector (virtual work: f = J' tau).
  const Eigen::Matrix3d P =
      Eigen::Matrix3d::Identity() - J * (J.transpose() * J).ldlt().solve(J.transpose());
  return (P * tau).norm();
}

Accuracy measure_accuracy(const Robot& actual, const sim::TwinConfig& twin,
                          const Robot& controller, const CompensationPlan& plan,
                          unsigned long long seed, const std::string& label, Progress* progress,
                          double max_tracking_mm, bool oracle, const calib::ReadingModel* drive_train) {
  Accuracy acc;
  acc.label = label;
  const sim::TwinModel model(actual, twin);
  sim::TwinState state(model, seed);
  sim::Session session = sim::make_session(model, state, controller, nullptr);
  session.max_tracking_mm = max_tracking_mm;
  session.oracle = oracle;
  if (drive_train)
    session.readings_for = [m = *drive_train](const Eigen::Vector3d& theta_a, const Eigen::Vector3d& dth) {
      Eigen::Vector3d r;
      for (int i = 0; i < 3; ++i) r[i] = wrap_2pi(calib::reading_at(m, i, theta_a[i] - dth[i]));
      return r;
    };

  // The poses are visited in a short tour from where the robot stands
  // (sim/waypoint_path.hpp), their errors kept in the plan's order.
  std::vector<double> preload;
  acc.static_error_um.assign(plan.poses.size(), 0.0);
  long id = 0;
  if (progress) progress->update(0);
  for (const int k : sim::tour_order(session.desired, plan.poses)) {
    const Eigen::Vector2d& target = plan.poses[static_cast<std::size_t>(k)];
    const sim::SampleRecord r = sim::take_sample(session, target, id++, plan.sampling);
    if (progress) progress->update(static_cast<double>(id));
    acc.static_error_um[static_cast<std::size_t>(k)] = (r.xy_mm - target).norm() * 1e3;
    const sim::TwinSnapshot snap = sim::advance(session, sim::PathPoint{target, Eigen::Vector2d::Zero()});
    preload.push_back(internal_preload(actual.geometry, snap.ee_mm, snap.torque, actual.branch));
  }
  acc.static_rms_um = rms(acc.static_error_um);
  acc.static_max_um = max_of(acc.static_error_um);
  acc.static_preload_rms_nm = rms(preload);

  // Approach the path start, then log only the path itself.
  sim::follow_path(session, sim::make_move(session.desired, sim::path_at(plan.path, 0.0).p,
                                           plan.move_speed_mm_s));
  session.log = &acc.path_log;
  sim::follow_path(session, plan.path);
  std::vector<double> err, path_preload;
  for (const sim::LogRow& row : acc.path_log.rows) {
    err.push_back((row.actual - row.desired).norm() * 1e3);
    path_preload.push_back(internal_preload(actual.geometry, row.actual, row.torque, actual.branch));
  }
  acc.path_rms_um = rms(err);
  acc.path_max_um = max_of(err);
  acc.path_preload_rms_nm = rms(path_preload);
  if (progress) progress->finish();
  return acc;
}

std::array<double, 2> rms_ratio_interval(const std::vector<double>& a, const std::vector<double>& b,
                                         std::uint64_t seed, int resamples) {
  if (a.size() != b.size() || a.empty() || resamples < 40)
    throw InputError(fmt::format("ratio interval: {} and {} errors, {} resamples (equal sizes, at least one pose and "
                                 "40 resamples)", a.size(), b.size(), resamples));
  Rng rng(seed);
  std::vector<double> ratio(static_cast<std::size_t>(resamples));
  for (double& q : ratio) {
    double sa = 0.0, sb = 0.0;
    for (std::size_t k = 0; k < a.size(); ++k) {
      const std::size_t j = rng.below(a.size());
      sa += a[j] * a[j], sb += b[j] * b[j];
    }
    q = sb > 0.0 ? std::sqrt(sa / sb) : INFINITY;
  }
  std::sort(ratio.begin(), ratio.end());
  const auto at = [&](double p) { return ratio[static_cast<std::size_t>(std::lround(p * (resamples - 1)))]; };
  return {at(0.025), at(0.975)};
}

}  // namespace gpm::scenario
