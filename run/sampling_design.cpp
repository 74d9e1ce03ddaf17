// Run-time pose design (run/sampling_design.hpp).
#include "run/sampling_design.hpp"

#include <cmath>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <utility>

#include <fmt/format.h>

#include "calib/excitation/excitation.hpp"
#include "models/drive_margin.hpp"
#include "models/errors.hpp"
#include "models/kinematics.hpp"
#include "models/robot_yaml.hpp"
#include "models/yaml_util.hpp"
#include "sim/simulate.hpp"

namespace gpm::scenario {
namespace {

// Grid points (step mm, one at the robot's home) that keep the path margin
// and are joined to home through such points (4-neighbours): a path cannot
// leave this region without crossing a singularity of the driven mechanism,
// so poses elsewhere could not be visited on one controlled path.
std::set<std::pair<long, long>> safe_region(const Robot& robot, const DriveMask& drives, const PathMargin& margin,
                                            double step) {
  std::set<std::pair<long, long>> region;
  const auto ok = [&](long i, long j) {
    const Eigen::Vector2d p = robot.home + step * Eigen::Vector2d(static_cast<double>(i), static_cast<double>(j));
    return check_reach(robot, p).ok && margin_violation(robot, p, drives, margin).empty();
  };
  if (!ok(0, 0)) return region;
  std::set<std::pair<long, long>> seen{{0, 0}};
  std::deque<std::pair<long, long>> queue{{0, 0}};
  const long bound = static_cast<long>(std::ceil(1000.0 / step));
  while (!queue.empty()) {
    const auto [i, j] = queue.front();
    queue.pop_front();
    region.insert({i, j});
    for (const auto& [di, dj] : {std::pair<long, long>{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
      const std::pair<long, long> n{i + di, j + dj};
      if (std::abs(n.first) > bound || std::abs(n.second) > bound || !seen.insert(n).second) continue;
      if (ok(n.first, n.second)) queue.push_back(n);
    }
  }
  return region;
}

// Everything a design without a hardware admissibility test reads: the
// controller's model, the drives in position mode, the margin, the count,
// the pattern, the free parameters and the reading 1-sigma (exact text).
std::string design_key(const sim::Scenario& s, const FreeMask& free, double sigma_rad) {
  const sim::SamplingPlan& plan = *s.sampling;
  const DriveMask drives = sim::position_drives(s);
  const PathMargin& m = plan.margin;
  return fmt::format("{}|{}{}{}|{} {} {} {} {} {}|{} {}|{}|{}", robot_to_yaml(s.controller), drives[0], drives[1],
                     drives[2], format_exact(m.singularity), format_exact(m.reach_mm), format_exact(m.deviation_mm),
                     format_exact(m.tolerance.base_mm), format_exact(m.tolerance.link_mm),
                     format_exact(m.tolerance.offset_rad), plan.count,
                     static_cast<int>(plan.pattern) * 10 + static_cast<int>(plan.criterion),
                     free.to_string(), format_exact(sigma_rad));
}

// Designs made in this process, by design_key: a population of robots
// described by one data sheet shares one design, made once.
struct DesignMemo {
  std::mutex mutex;
  std::map<std::string, std::vector<Eigen::Vector2d>> poses;
};

DesignMemo& design_memo() {
  static DesignMemo memo;
  return memo;
}

// The criterion of s's design (sampling.criterion): by default, on the fly,
// the positioning the user gets (calib/excitation/positioning_design.hpp)
// where the data sheet states an error once per joint revolution and the
// offsets are free; the worst parameter's bound otherwise.
calib::excitation::Criterion design_criterion(const sim::Scenario& s, const FreeMask& free) {
  using calib::excitation::Criterion;
  const bool told = s.controller.data_sheet.joint_harmonic_max_rad() > 0.0 && free.test(kDth1) &&
                    free.test(kDth1 + 1) && free.test(kDth1 + 2);
  switch (s.sampling->criterion) {
    case sim::DesignCriterion::kWorst: return Criterion::kWorst;
    case sim::DesignCriterion::kD: return Criterion::kDOptimal;
    case sim::DesignCriterion::kPositioning:
      if (!told)
        throw InputError(fmt::format(
            "{}: sampling.criterion: positioning needs an error once per joint revolution in the robot file's data "
            "sheet (encoder_accuracy_rad, transmission_error_rad) and dth1..dth3 free; use worst or d",
            s.file));
      return Criterion::kPositioning;
    case sim::DesignCriterion::kAuto: break;
  }
  return told && s.sampling->pattern == sim::PosePattern::kTrajectory ? Criterion::kPositioning : Criterion::kWorst;
}

}  // namespace

void design_sampling(sim::Scenario& s, const FreeMask& free, double sigma_rad,
                     const std::function<bool(const Eigen::Vector2d&)>& admissible) {
  if (!s.sampling) return;
  const int p = static_cast<int>(free.count());
  const bool designed = s.sampling->pattern == sim::PosePattern::kDesigned ||
                        s.sampling->pattern == sim::PosePattern::kTrajectory;
  if (designed && !s.sampling->needs_design() && static_cast<int>(s.sampling->poses.size()) < p)
    throw InputError(fmt::format("{}: sampling.poses: {} designed poses cannot determine {} free parameters; "
                                 "give at least {} (gpm design --count {})",
                                 s.file, s.sampling->poses.size(), p, p, p));
  if (!s.sampling->needs_design()) return;
  if (s.sampling->count < p)
    throw InputError(fmt::format("{}: sampling.count: {} designed poses cannot determine {} free parameters; "
                                 "use a count of at least {}",
                                 s.file, s.sampling->count, p, p));
  const double sigma = sigma_rad > 0.0 ? sigma_rad : 1e-5;
  const std::string key = admissible ? std::string() : design_key(s, free, sigma);
  if (!key.empty()) {
    const std::lock_guard<std::mutex> lock(design_memo().mutex);
    if (const auto it = design_memo().poses.find(key); it != design_memo().poses.end()) {
      s.sampling->poses = it->second;
      return;
    }
  }
  calib::excitation::DesignOptions o;
  o.count = s.sampling->count;
  o.free = free;
  o.sigma = sigma;
  o.admissible = admissible;
  if (s.sampling->pattern == sim::PosePattern::kTrajectory) {
    // The spline through the poses bulges past them: keep the poses further
    // from the limits than stop-and-go needs, so the path between them stays
    // inside (every millimetre of it is still checked before the robot moves).
    o.guard.reach_mm = 12.0;
    o.guard.transmission = 0.06;
    o.guard.direct = 0.06;
  }
  o.criterion = design_criterion(s, free);
  {
    // Only poses of the region, joined to home, that keeps sampling.path_margin
    // for the drives in position mode (models/drive_margin.hpp): on the fly
    // the path between them is checked and repaired too; stop-and-go moves
    // between poses of one region (the twin's tracking watch stops a move
    // that leaves control anyway).
    // The poses keep a little more than the path needs (0.02 on the measures,
    // 3 mm of reach, a tenth of the deviation), so that the path has room to
    // turn at them.
    PathMargin pose_margin = s.sampling->margin;
    pose_margin.singularity += 0.02;
    pose_margin.reach_mm += 3.0;
    pose_margin.deviation_mm *= 0.9;
    const auto region = std::make_shared<const std::set<std::pair<long, long>>>(
        safe_region(s.controller, sim::position_drives(s), pose_margin, o.grid_step_mm));
    if (static_cast<int>(region->size()) < o.count)
      throw InputError(fmt::format(
          "{}: sampling.path_margin: only {} points of the {} mm grid joined to home keep the margin for the drives in "
          "position mode (singularity {:.3g}, reach_mm {:.3g}, deviation_mm {:.3g}, and 0.02, 3 mm, a tenth more for "
          "poses), fewer than the {} poses: nothing moved; state a smaller margin or count",
          s.file, region->size(), o.grid_step_mm, s.sampling->margin.singularity, s.sampling->margin.reach_mm,
          s.sampling->margin.deviation_mm, o.count));
    const Eigen::Vector2d home = s.controller.home;
    const double step = o.grid_step_mm;
    o.admissible = [admissible, region, home, step](const Eigen::Vector2d& p) {
      const Eigen::Vector2d ij = (p - home) / step;
      return region->count({std::lround(ij.x()), std::lround(ij.y())}) > 0 && (!admissible || admissible(p));
    };
  }
  s.sampling->poses = calib::excitation::design_poses(s.controller, o).poses;
  if (!key.empty()) {
    const std::lock_guard<std::mutex> lock(design_memo().mutex);
    design_memo().poses.emplace(key, s.sampling->poses);
  }
}

}  // namespace gpm::scenario
