// summary.json (run/summary_json.hpp), written with nlohmann::json.
#include "run/summary_json.hpp"

#include <cmath>

#include <nlohmann/json.hpp>

#include "run/runner.hpp"
#include "run/table_cells.hpp"

namespace gpm::scenario {
namespace {

constexpr auto number = json_finite;  // null when not finite (JSON has no NaN)

nlohmann::json accuracy(const std::optional<Accuracy>& a) {
  if (!a) return nullptr;
  return {{"static_rms_um", number(a->static_rms_um)},
          {"static_max_um", number(a->static_max_um)},
          {"path_rms_um", number(a->path_rms_um)}};
}

}  // namespace

std::string summary_json(const RunOutcome& o) {
  nlohmann::json j;
  j["verdict"] = o.passed() ? "passed" : "failed";
  j["robot_time_s"] = number(o.sim.sampling_s);
  if (o.positioning)
    j["positioning_um"] = {{"rms", number(o.positioning->rms_um)},
                           {"max", number(o.positioning->max_um)},
                           {"stated_sigma_rms", number(o.positioning->stated_sigma_rms_um)},
                           {"normalised_rms", number(o.positioning->normalised_rms)},
                           {"carried_sigma_rms", number(o.positioning->carried_sigma_rms_um)},
                           {"bound_rms", o.positioning_bound_um ? number(*o.positioning_bound_um) : nullptr},
                           {"points", o.positioning->points}};
  else if (o.stated_positioning)  // through hardware: the 1-sigma stated, the error not known
    j["positioning_um"] = {{"rms", nullptr},
                           {"max", nullptr},
                           {"stated_sigma_rms", number(o.stated_positioning->stated_sigma_rms_um)},
                           {"normalised_rms", nullptr},
                           {"carried_sigma_rms", number(o.stated_positioning->carried_sigma_rms_um)},
                           {"bound_rms", nullptr},
                           {"points", o.stated_positioning->points}};
  else
    j["positioning_um"] = nullptr;
  j["accuracy"] = {{"nominal", accuracy(o.before)}, {"calibrated", accuracy(o.after)}, {"actual", accuracy(o.floor)}};
  if (o.floor_ratio_ci95)
    j["floor_ratio"] = {{"value", number(o.after->static_rms_um / o.floor->static_rms_um)},
                        {"ci95", {number((*o.floor_ratio_ci95)[0]), number((*o.floor_ratio_ci95)[1])}}};
  nlohmann::json params = nlohmann::json::object();
  if (o.calibration) {
    for (int k = 0; k < kNumParams; ++k) {
      if (!o.calibration->free[k]) continue;
      params[std::string(param_name(k))] = {{"actual", number(o.sim.actual.geometry.values[k])},
                                            {"estimated", number(o.calibration->geometry.values[k])},
                                            {"std", number(o.calibration->sigma[k])},
                                            {"crb", number(o.crb[k])}};
    }
  }
  j["parameters"] = params;
  if (o.model_test) {
    j["model_test"] = {{"chi2", number(o.model_test->chi2)},
                       {"dof", number(o.model_test->dof)},
                       {"p_value", number(o.model_test->p_value)},
                       {"carried_chi2", number(o.model_test->carried_chi2)},
                       {"doubt_chi2", number(o.model_test->doubt_chi2)},
                       {"passed", o.model_test->passed}};
  } else {
    j["model_test"] = nullptr;
  }
  if (o.first_pass) {
    nlohmann::json change = nlohmann::json::array(), sigma = nlohmann::json::array();
    for (int i = 0; i < 3; ++i) {
      change.push_back(number(o.first_pass->offsets_change_rad[static_cast<std::size_t>(i)]));
      sigma.push_back(number(o.first_pass->offsets_sigma_rad[static_cast<std::size_t>(i)]));
    }
    j["first_pass"] = {{"why", o.first_pass->why},
                       {"planned", o.first_pass->planned},
                       {"samples", o.first_pass->samples},
                       {"robot_time_s", number(o.first_pass->robot_time_s)},
                       {"offsets_change_rad", change},
                       {"offsets_sigma_rad", sigma}};
  }
  if (std::isfinite(o.plan_deviation_mm)) j["plan_deviation_mm"] = o.plan_deviation_mm;
  if (o.monitor) j["monitor"] = monitor_summary(*o.monitor);
  return j.dump(2) + "\n";
}

}  // namespace gpm::scenario
