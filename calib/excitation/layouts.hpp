// Reference pose layouts and their comparison with the optimised design at an
// equal number of poses and noise (issue 10, paper section 4.5):
//   line       the paper's first attempt, "50 configurations all in a line"
//              (section 4.5). The paper gives no coordinates; we take the
//              horizontal line through home, home -/+ (radius, 0), ends
//              included (the diameter of the circle below);
//   circle     evenly spaced on a circle of `radius` about home, the paper's
//              second attempt (first pose at home + (radius, 0));
//   disc       uniform random in a disc of `radius` about home, seeded;
//   wide disc  uniform random in a disc of `wide_radius` about home, clipped
//              to the reachable set with the robot's margins by rejection
//              (calib/synthetic.hpp: a drawn pose failing check_reach is
//              dropped and another drawn);
//   optimised  design_poses (excitation.hpp).
// All bounds are Cramer-Rao bounds at the nominal geometry (fisher.hpp).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "calib/excitation/excitation.hpp"
#include "calib/excitation/fisher.hpp"
#include "models/robot.hpp"

namespace gpm::calib::excitation {

// count poses evenly spaced from `from` to `to`, both ends included (count >= 2).
std::vector<Eigen::Vector2d> line_layout(const Eigen::Vector2d& from, const Eigen::Vector2d& to, int count);

// count poses evenly spaced on a circle, the first at centre + (radius, 0).
std::vector<Eigen::Vector2d> circle_layout(const Eigen::Vector2d& centre, double radius, int count);

struct ComparisonOptions {
  DesignOptions design;       // count, sigma, free set, criterion of the optimised set
  double radius = 80.0;       // line half-length, circle and disc radius (mm)
  double wide_radius = 150.0; // the wide disc (mm)
  std::uint64_t seed = 1;     // random discs
};

// One layout and its bounds.
struct LayoutBounds {
  std::string name;         // short key: line, circle80, disc80, disc150, optimised
  std::string description;  // one line
  std::vector<Eigen::Vector2d> poses;
  Bounds bounds;
};

// The five layouts of the comparison, in the order above (optimised last).
std::vector<LayoutBounds> compare_layouts(const Robot& nominal, const ComparisonOptions& options);

// Best (smallest) worst-parameter bound among all layouts but the last, divided
// by the last one's: how many times better the optimised set is.
double improvement_over_best_other(const std::vector<LayoutBounds>& rows);

}  // namespace gpm::calib::excitation
