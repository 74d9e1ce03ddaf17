// End-effector motion in the plane (mm, s): sample pose sets and continuous
// paths. Pure geometry; the controller turns poses into joint commands.
#pragma once

#include <variant>
#include <vector>

#include <Eigen/Core>

#include "models/rng.hpp"

namespace gpm::sim {

// Desired end-effector position (mm) and velocity (mm/s) at one instant.
struct PathPoint {
  Eigen::Vector2d p = Eigen::Vector2d::Zero();
  Eigen::Vector2d v = Eigen::Vector2d::Zero();
};

// Circle at constant speed, counter-clockwise from centre + (radius, 0).
struct CirclePath {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  double radius = 0.0;       // mm
  double period_s = 1.0;     // one revolution
  double revolutions = 1.0;  // total length of the path
};

// Straight line at constant speed.
struct LinePath {
  Eigen::Vector2d from = Eigen::Vector2d::Zero();
  Eigen::Vector2d to = Eigen::Vector2d::Zero();
  double duration_s = 1.0;
};

// Point-to-point move: straight line with a minimum-jerk time law
// s = 10 u^3 - 15 u^4 + 6 u^5 (zero velocity and acceleration at both ends).
struct MovePath {
  Eigen::Vector2d from = Eigen::Vector2d::Zero();
  Eigen::Vector2d to = Eigen::Vector2d::Zero();
  double duration_s = 0.0;
};

using Path = std::variant<CirclePath, LinePath, MovePath>;

// Position and velocity on a path at time t (clamped to [0, duration]).
PathPoint path_at(const Path& path, double t);

// Total duration of a path (s).
double path_duration(const Path& path);

// A point-to-point move whose peak Cartesian speed (1.875 L / T for minimum
// jerk) is max_speed_mm_s, lasting at least min_duration_s.
MovePath make_move(const Eigen::Vector2d& from, const Eigen::Vector2d& to, double max_speed_mm_s,
                   double min_duration_s = 0.05);

// count poses uniform over a disc (r = R sqrt(u), angle uniform), from rng.
std::vector<Eigen::Vector2d> disc_poses(const Eigen::Vector2d& centre, double radius, int count,
                                        Rng& rng);

}  // namespace gpm::sim
