#include "hw/session_plan.hpp"

#include <fmt/format.h>

#include "models/errors.hpp"
#include "models/yaml_util.hpp"
#include "sim/scenario.hpp"

namespace gpm::hw {

SessionPlan load_poses_plan(const std::string& path) {
  const YAML::Node root = load_yaml_file(path);
  if (!root.IsMap()) throw InputError(path + ": expected a map with keys poses (and optionally sampling)");
  yaml_check_keys(root, path, "", {"poses", "sampling"});
  SessionPlan plan;
  const YAML::Node poses = root["poses"];
  if (!poses || !poses.IsSequence() || poses.size() == 0) {
    throw InputError(yaml_where(path, poses ? poses : root, "poses") +
                     "expected a non-empty list of [x, y] poses in mm");
  }
  for (size_t k = 0; k < poses.size(); ++k) {
    const std::string kp = fmt::format("poses[{}]", k);
    if (!poses[k].IsSequence() || poses[k].size() != 2) {
      throw InputError(yaml_where(path, poses[k], kp) + "expected [x, y] in mm");
    }
    plan.poses.emplace_back(yaml_number(poses[k][0], path, kp + "[0]"),
                            yaml_number(poses[k][1], path, kp + "[1]"));
  }
  if (const YAML::Node s = root["sampling"]) {
    yaml_check_keys(s, path, "sampling", {"move_speed_mm_s", "settle", "average_s"});
    auto& o = plan.options;
    if (s["move_speed_mm_s"]) o.move_speed_mm_s = yaml_positive(s["move_speed_mm_s"], path, "sampling.move_speed_mm_s");
    if (s["average_s"]) o.average_s = yaml_positive(s["average_s"], path, "sampling.average_s");
    if (const YAML::Node st = s["settle"]) {
      yaml_check_keys(st, path, "sampling.settle", {"velocity_rad_s", "hold_s", "timeout_s"});
      if (st["velocity_rad_s"]) o.settle.velocity_rad_s = yaml_positive(st["velocity_rad_s"], path, "sampling.settle.velocity_rad_s");
      if (st["hold_s"]) o.settle.hold_s = yaml_positive(st["hold_s"], path, "sampling.settle.hold_s");
      if (st["timeout_s"]) o.settle.timeout_s = yaml_positive(st["timeout_s"], path, "sampling.settle.timeout_s");
    }
  }
  return plan;
}

SessionPlan plan_from_scenario(const std::string& path) {
  const sim::Scenario sc = sim::load_scenario(path);
  if (!sc.sampling) throw InputError(path + ": the scenario has no 'sampling' section (poses to sample)");
  SessionPlan plan;
  plan.poses = sim::plan_poses(*sc.sampling, sc.seed);
  plan.options = sc.sampling->options;
  return plan;
}

}  // namespace gpm::hw
