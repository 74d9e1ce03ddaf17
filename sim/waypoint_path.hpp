// A continuous excitation path through calibration poses, for sampling on the
// fly: the poses are ordered into a short tour, joined by a centripetal
// Catmull-Rom spline (C1, passes through every pose, no cusps or
// self-intersections within a segment), and traversed with a speed profile
// that respects a peak speed, a tangential acceleration limit and a normal
// (centripetal) acceleration limit v^2 kappa <= a_normal; it starts and ends
// at rest. Pure geometry (mm, s), like sim/trajectory.hpp.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace gpm::sim {

// Limits of the time law along the spline.
struct WaypointLimits {
  double max_speed_mm_s = 150.0;
  double max_accel_mm_s2 = 1500.0;   // tangential
  double max_normal_mm_s2 = 1500.0;  // centripetal, v^2 * curvature
};

// The path as a dense table (arc length step about step_mm): time, position
// and velocity at each node; between nodes the motion follows the chord at
// constant tangential acceleration.
struct WaypointPath {
  std::vector<double> t;               // s, increasing, t.front() = 0
  std::vector<Eigen::Vector2d> p;      // mm
  std::vector<Eigen::Vector2d> v;      // mm/s
  std::vector<double> pose_times;      // time at which the path passes each waypoint, in tour order
  double length_mm = 0.0;
};

// The poses in a short visiting order starting nearest to `start`: nearest
// neighbour, then 2-opt improvement of the open tour. Returns indices into poses.
std::vector<int> tour_order(const Eigen::Vector2d& start, const std::vector<Eigen::Vector2d>& poses);

// The spline through points (in the given order, at least 2, consecutive
// points distinct) with the time law of limits, tabulated every ~step_mm.
WaypointPath make_waypoint_path(const std::vector<Eigen::Vector2d>& points, const WaypointLimits& limits,
                                double step_mm = 0.1);

// The excitation path of a calibration: from start through every pose in
// tour_order, under limits.
WaypointPath excitation_path(const Eigen::Vector2d& start, const std::vector<Eigen::Vector2d>& poses,
                             const WaypointLimits& limits);

// What every point of a planned path must keep: why p is not allowed (for
// instance gpm::margin_violation of models/drive_margin.hpp), empty when it is.
using PointCheck = std::function<std::string(const Eigen::Vector2d&)>;

// How excitation_path kept the check.
struct PathRepair {
  int vias = 0;               // via points put between consecutive points
  std::vector<Eigen::Vector2d> points;  // the points the spline passes, in order (start, poses and vias)
};

// The excitation path of excitation_path, with every point of it (checked
// every check_mm of arc) passing check. Where the spline between two
// consecutive points leaves it, a via point is put between them (the chord's
// midpoint, or a point up to 150 mm off the chord whose two chords keep the
// check) and the spline is made again, until the whole path keeps it.
// Throws InputError, before anything moves, naming the pose and the reason
// when a pose breaks it or no via point joins two poses.
WaypointPath excitation_path(const Eigen::Vector2d& start, const std::vector<Eigen::Vector2d>& poses,
                             const WaypointLimits& limits, const PointCheck& check, PathRepair* repair = nullptr,
                             double check_mm = 0.5);

// Position and velocity at time t (clamped to [0, duration]; zero velocity outside).
void waypoint_at(const WaypointPath& path, double t, Eigen::Vector2d& p, Eigen::Vector2d& v);

// Duration of the path (s).
inline double waypoint_duration(const WaypointPath& path) { return path.t.empty() ? 0.0 : path.t.back(); }

}  // namespace gpm::sim
