#include "calib/synthetic.hpp"

#include <algorithm>
#include <optional>
#include <string>

#include <fmt/format.h>

#include "models/errors.hpp"
#include "models/kinematics.hpp"
#include "models/rng.hpp"

namespace gpm::calib {

namespace {

// Draws candidate points with draw(rng) until n pass check_reach(actual);
// throws InputError naming region after max_tries candidates.
template <typename Draw>
std::vector<Eigen::Vector2d> reachable_poses(const Robot& actual, int n, std::uint64_t seed, long max_tries,
                                             const std::string& region, Draw draw) {
  Rng rng(seed);
  std::vector<Eigen::Vector2d> out;
  for (long tries = 0; static_cast<int>(out.size()) < n; ++tries) {
    if (tries >= max_tries) {
      throw InputError(fmt::format("{}: too few reachable poses (got {} of {})", region, out.size(), n));
    }
    const auto p = draw(rng);
    if (p && check_reach(actual, *p).ok) out.push_back(*p);
  }
  return out;
}

}  // namespace

std::vector<Eigen::Vector2d> disc_poses(const Robot& actual, int n, const Eigen::Vector2d& centre,
                                        double radius, std::uint64_t seed) {
  const std::string region = fmt::format("disc around ({}, {}) of radius {} mm", centre.x(), centre.y(), radius);
  return reachable_poses(actual, n, seed, 1000L * (n + 10), region,
                         [&](Rng& rng) -> std::optional<Eigen::Vector2d> {
                           const double dx = rng.uniform(-1.0, 1.0);
                           const Eigen::Vector2d d(dx, rng.uniform(-1.0, 1.0));
                           if (d.squaredNorm() > 1.0) return std::nullopt;
                           return Eigen::Vector2d(centre + radius * d);
                         });
}

std::vector<Eigen::Vector2d> workspace_poses(const Robot& actual, int n, std::uint64_t seed) {
  if (n < 1) throw InputError("workspace samples: need at least 1 sample");
  const Geometry& g = actual.geometry;
  double x0 = g[kXa1], x1 = g[kXa1], y0 = g[kYa1], y1 = g[kYa1];
  for (int i = 1; i < 3; ++i) {
    x0 = std::min(x0, g[xa(i)]);
    x1 = std::max(x1, g[xa(i)]);
    y0 = std::min(y0, g[ya(i)]);
    y1 = std::max(y1, g[ya(i)]);
  }
  return reachable_poses(actual, n, seed, 10000L * n, "workspace samples (box of the base joints)",
                         [&](Rng& rng) -> std::optional<Eigen::Vector2d> {
                           const double x = rng.uniform(x0, x1);
                           return Eigen::Vector2d(x, rng.uniform(y0, y1));
                         });
}

Samples samples_at(const Robot& actual, const std::vector<Eigen::Vector2d>& poses, double sigma,
                   std::uint64_t seed) {
  Rng rng(seed);
  Samples s;
  s.has_xy = true;
  for (size_t j = 0; j < poses.size(); ++j) {
    const JointAngles q = inverse_kinematics(actual.geometry, poses[j], actual.branch);
    Eigen::Vector3d t = readings_from_active(actual.geometry, q.theta_a);
    if (sigma > 0.0)
      for (int k = 0; k < 3; ++k) t[k] += rng.normal(0.0, sigma);
    s.id.push_back(static_cast<long>(j));
    s.theta_m.push_back(t);
    s.xy.push_back(poses[j]);
  }
  return s;
}

Samples workspace_samples(const Robot& actual, int n, std::uint64_t seed) {
  return samples_at(actual, workspace_poses(actual, n, seed));
}

}  // namespace gpm::calib
