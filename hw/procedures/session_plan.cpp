#include "hw/procedures/session_plan.hpp"

#include <filesystem>

#include <fmt/format.h>

#include "models/errors.hpp"
#include "models/yaml_util.hpp"
#include "sim/scenario.hpp"

namespace gpm::hw {
SessionPlan load_poses_plan(const std::string& path) {
  const YAML::Node root = load_yaml_file(path);
  if (!root.IsMap()) throw InputError(path + ": expected a map with keys poses (and optionally sampling)");
  yaml_check_keys(root, path, "", {"poses", "sampling"});
  // `gpm design` writes its poses as a scenario's sampling: {pattern: list, poses: [...]}.
  const YAML::Node given = root["sampling"];
  const bool designed = !root["poses"] && given && given.IsMap() && given["poses"] && given["pattern"] &&
                        given["pattern"].IsScalar() && given["pattern"].Scalar() == "list";
  const YAML::Node poses = designed ? given["poses"] : root["poses"];
  if (!poses || !poses.IsSequence() || poses.size() == 0) {
    throw InputError(yaml_where(path, poses ? poses : root, "poses") +
                     "expected a non-empty list of [x, y] poses in mm");
  }
  // The scenario schema's sampling plan (pattern list) reads poses and settings
  // (sim/scenario.cpp): one parser for both files.
  YAML::Node sampling = YAML::Clone(given ? given : YAML::Node(YAML::NodeType::Map));
  if (!sampling.IsMap()) throw InputError(yaml_where(path, given, "sampling") + "expected a map");
  if (designed) sampling.remove("pattern"), sampling.remove("poses");
  for (const char* key : {"pattern", "poses", "centre", "radius", "count", "from", "to"}) {
    if (sampling[key]) {
      throw InputError(yaml_where(path, sampling[key], fmt::format("sampling.{}", key)) +
                       "unknown key (valid: move_speed_mm_s, settle, average_s)");
    }
  }
  sampling["pattern"] = "list";
  sampling["poses"] = poses;
  YAML::Node scenario(YAML::NodeType::Map);
  scenario["name"] = std::filesystem::path(path).stem().string();
  scenario["sampling"] = sampling;
  const sim::Scenario sc = sim::scenario_from_yaml(scenario, path, std::filesystem::path(path).parent_path().string());
  SessionPlan plan;
  plan.poses = sc.sampling->poses;
  plan.options = sc.sampling->options;
  return plan;
}

SessionPlan plan_from_scenario(const std::string& path) {
  const sim::Scenario sc = sim::load_scenario(path);
  if (!sc.sampling) throw InputError(path + ": the scenario has no 'sampling' section (poses to sample)");
  if (sc.sampling->needs_design())
    throw InputError(fmt::format("{}: sampling.pattern: {}: its poses are designed for the calibration when the "
                                 "procedure runs, which the hw layer does not do (gpm run {} --hardware HW.yaml, or "
                                 "gpm sample --scenario, design them); a stop-and-go plan takes poses given or drawn: "
                                 "disc, circle, line, list",
                                 path, sc.sampling->pattern == sim::PosePattern::kTrajectory ? "trajectory" : "designed",
                                 path));
  SessionPlan plan;
  plan.poses = sim::plan_poses(*sc.sampling, sc.seed);
  plan.options = sc.sampling->options;
  return plan;
}

}  // namespace gpm::hw
