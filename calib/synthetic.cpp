#include "calib/synthetic.hpp"

#include <random>

#include <fmt/format.h>

#include "models/errors.hpp"
#include "models/kinematics.hpp"

namespace gpm::calib {

std::vector<Eigen::Vector2d> disc_poses(const Robot& actual, int n, const Eigen::Vector2d& centre,
                                        double radius, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Eigen::Vector2d> out;
  long tries = 0;
  while (static_cast<int>(out.size()) < n) {
    if (++tries > 1000L * (n + 10)) {
      throw InputError(fmt::format("disc around ({}, {}) of radius {} mm: too few reachable poses "
                                   "(got {} of {})", centre.x(), centre.y(), radius, out.size(), n));
    }
    const Eigen::Vector2d d(u(rng), u(rng));
    if (d.squaredNorm() > 1.0) continue;
    const Eigen::Vector2d p = centre + radius * d;
    if (check_reach(actual, p).ok) out.push_back(p);
  }
  return out;
}

Samples samples_at(const Robot& actual, const std::vector<Eigen::Vector2d>& poses, double sigma,
                   std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma > 0.0 ? sigma : 1.0);
  Samples s;
  s.has_xy = true;
  for (size_t j = 0; j < poses.size(); ++j) {
    const JointAngles q = inverse_kinematics(actual.geometry, poses[j], actual.branch);
    Eigen::Vector3d t = readings_from_active(actual.geometry, q.theta_a);
    if (sigma > 0.0)
      for (int k = 0; k < 3; ++k) t[k] += noise(rng);
    s.id.push_back(static_cast<long>(j));
    s.theta_m.push_back(t);
    s.xy.push_back(poses[j]);
  }
  return s;
}

}  // namespace gpm::calib
