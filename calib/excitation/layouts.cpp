#include "calib/excitation/layouts.hpp"

#include "models/pose_layouts.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/format.h>

#include "calib/synthetic.hpp"
#include "models/errors.hpp"

namespace gpm::calib::excitation {

std::vector<Eigen::Vector2d> line_layout(const Eigen::Vector2d& from, const Eigen::Vector2d& to, int count) {
  if (count < 2) throw InputError(fmt::format("a line needs at least 2 poses, got {}", count));
  return line_points(from, to, count);
}

std::vector<Eigen::Vector2d> circle_layout(const Eigen::Vector2d& centre, double radius, int count) {
  return circle_points(centre, radius, count);
}

std::vector<LayoutBounds> compare_layouts(const Robot& nominal, const ComparisonOptions& o) {
  const DesignOptions& d = o.design;
  const Eigen::Vector2d h = nominal.home;
  const Eigen::Vector2d dx(o.radius, 0.0);
  std::vector<LayoutBounds> rows;
  auto add = [&](std::string name, std::string description, std::vector<Eigen::Vector2d> poses) {
    Bounds b = pose_bounds(nominal, d.free, poses, d.sigma);
    rows.push_back({std::move(name), std::move(description), std::move(poses), std::move(b)});
  };
  add("line", fmt::format("paper's line: horizontal through home, x = {} to {} mm", h.x() - o.radius, h.x() + o.radius),
      line_layout(h - dx, h + dx, d.count));
  add(fmt::format("circle{:g}", o.radius), fmt::format("circle of radius {:g} mm about home, evenly spaced", o.radius),
      circle_layout(h, o.radius, d.count));
  add(fmt::format("disc{:g}", o.radius), fmt::format("random disc of radius {:g} mm about home (seed {})", o.radius, o.seed),
      disc_poses(nominal, d.count, h, o.radius, o.seed));
  add(fmt::format("disc{:g}", o.wide_radius),
      fmt::format("random disc of radius {:g} mm about home, clipped to the reachable set with margins (seed {})",
                  o.wide_radius, o.seed),
      disc_poses(nominal, d.count, h, o.wide_radius, o.seed));
  const Design opt = design_poses(nominal, d);
  rows.push_back({"optimised",
                  fmt::format("{}-optimal design on a {:g} mm grid, greedy start + exchange", criterion_name(d.criterion),
                              d.grid_step_mm),
                  opt.poses, opt.bounds});
  return rows;
}

double improvement_over_best_other(const std::vector<LayoutBounds>& rows) {
  if (rows.size() < 2) return std::numeric_limits<double>::quiet_NaN();
  double best_other = std::numeric_limits<double>::infinity();
  for (size_t k = 0; k + 1 < rows.size(); ++k) best_other = std::min(best_other, rows[k].bounds.worst_mm);
  return best_other / rows.back().bounds.worst_mm;
}

}  // namespace gpm::calib::excitation
