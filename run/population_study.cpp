#include "run/population_study.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include "models/errors.hpp"
#include "models/output_file.hpp"
#include "models/yaml_util.hpp"
#include "report/population_report.hpp"
#include "run/parallel_runs.hpp"
#include "run/runner.hpp"
#include "run/table_cells.hpp"

namespace gpm::scenario {
namespace {

constexpr auto number = json_finite;

double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::vector<std::uint64_t> seeds_of(const std::string& scenario_file, const PopulationOptions& o) {
  if (!o.seeds.empty()) return o.seeds;
  const YAML::Node root = load_yaml_file(scenario_file);
  const std::uint64_t first =
      root["seed"] ? static_cast<std::uint64_t>(yaml_integer(root["seed"], scenario_file, "seed", 0, 1LL << 53)) : 1;
  std::vector<std::uint64_t> v;
  for (int k = 0; k < o.count; ++k) v.push_back(first + static_cast<std::uint64_t>(k));
  return v;
}

PopulationRobot failed_robot(PopulationRobot r, const std::string& why) {
  r.failure = why;
  r.calibrated_static_um = r.floor_um = r.floor_ratio = r.chi2_per_dof = r.worst_sigma_ratio = NAN;
  return r;
}

// The parameters' errors in their stated 1-sigma.
void judge_parameters(const calib::Result& c, const Geometry& actual, PopulationRobot& r) {
  r.worst_sigma_ratio = 0.0;
  for (int k = 0; k < kNumParams; ++k) {
    const auto u = static_cast<size_t>(k);
    if (!c.free.test(u) || !(c.sigma[u] > 0.0) || !std::isfinite(c.sigma[u])) continue;
    r.error[u] = c.geometry[k] - actual[k];
    r.sigma[u] = c.sigma[u];
    const double ratio = std::abs(r.error[u]) / r.sigma[u];
    ++r.estimated;
    if (ratio <= 3.0) ++r.within_3_sigma;
    if (ratio > r.worst_sigma_ratio) r.worst_sigma_ratio = ratio, r.worst_param = std::string(param_name(k));
  }
}

// The monitor on a healthy robot (after learning, before the first event)
// and its detection of the first event.
void judge_monitor(const MonitorOutcome& m, PopulationRobot& r) {
  r.monitored = true;
  r.learning_s = m.learning_end_s - m.learning_start_s;
  r.learned_scale = m.learned.scale;
  const auto& events = m.scenario.twin.events;
  double first = m.simulated_s;
  int first_index = -1;
  for (std::size_t e = 0; e < events.size(); ++e)
    if (events[e].at_s < first) first = events[e].at_s, first_index = static_cast<int>(e);
  r.monitored_s = std::max(0.0, first - m.learning_end_s);
  for (const MonitorAlarm& a : m.alarms) {
    if (a.t_s < first) ++r.false_alarms;
    else ++r.alarms_after_event;
  }
  r.false_alarms_per_hour = r.monitored_s > 0.0 ? 3600.0 * r.false_alarms / r.monitored_s : NAN;
  r.event = first_index >= 0;
  if (r.event)
    for (const MonitorDetection& d : m.detections)
      if (d.event == first_index && d.detected_s) {
        r.detection_delay_s = *d.detected_s - d.at_s;
        r.detection = d.explanation;
      }
}

PopulationRobot robot_of(const RunOutcome& o, PopulationRobot r) {
  r.plan_deviation_mm = o.plan_deviation_mm;
  r.friction_balance = o.friction_balance;
  if (!o.calibration) return failed_robot(r, o.refused.value_or("no calibration"));
  r.notes = o.calibration->notes;
  if (!o.calibration->converged) return failed_robot(r, "calibration did not converge");
  r.calibrated_static_um = o.after ? o.after->static_rms_um : NAN;
  r.floor_um = o.floor ? o.floor->static_rms_um : NAN;
  r.floor_ratio = r.calibrated_static_um / r.floor_um;
  if (o.floor_ratio_ci95) r.floor_ratio_ci95 = *o.floor_ratio_ci95;
  if (o.model_test) {
    r.model_test_passed = o.model_test->passed;
    r.calls_for = o.model_test->calls_for;
    r.chi2_per_dof = o.model_test->dof > 0 ? o.model_test->chi2 / o.model_test->dof : NAN;
  } else {
    r.chi2_per_dof = NAN;
  }
  if (!o.positioning) return failed_robot(r, "the calibrated model reaches no point of the workspace disc");
  r.positioning = *o.positioning;
  r.positioning_bound_um = o.positioning_bound_um.value_or(NAN);
  judge_parameters(*o.calibration, o.sim.actual.geometry, r);
  if (o.monitor) judge_monitor(*o.monitor, r);
  return r;
}

// One robot through the runner; a failed run is a row of the study.
PopulationRobot run_robot(const RunSpec& spec, const std::string& file, PopulationRobot r) {
  r.error.fill(NAN);
  r.sigma.fill(NAN);
  r.effects = spec.sim.twin.effects;
  try {
    return robot_of(run_scenario(spec, file), r);
  } catch (const Error& e) {  // refused, diverged, stopped: a result of the study, not a stop
    return failed_robot(r, e.what());
  }
}

}  // namespace

std::string population_robot_scenario(const std::string& scenario_file, std::uint64_t seed, bool keep_effects) {
  YAML::Node root = load_yaml_file(scenario_file);
  if (!root.IsMap()) throw InputError(fmt::format("{}: expected a scenario (a map of sections)", scenario_file));
  if (root["hardware"])
    throw InputError(fmt::format("{}: hardware: a population study runs twins; remove the hardware key", scenario_file));
  root["seed"] = seed;
  if (!keep_effects) root["effects"] = "randomized";
  root.remove("expect");
  if (const YAML::Node robot = root["robot"]; robot && robot.IsScalar()) {
    const std::filesystem::path p(robot.as<std::string>());
    if (p.is_relative()) {
      const std::filesystem::path base = std::filesystem::absolute(scenario_file).parent_path();
      root["robot"] = (base / p).lexically_normal().string();
    }
  }
  YAML::Emitter em;
  em << root;
  return fmt::format("# robot {} of a population of {} (gpm study population); gpm run re-runs it alone\n{}\n", seed,
                     std::filesystem::path(scenario_file).filename().string(), em.c_str());
}

PopulationStudy run_population_study(const std::string& scenario_file, const PopulationOptions& options,
                                     const PopulationProgress& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  PopulationStudy study;
  study.scenario = scenario_file;
  study.randomized = !options.keep_effects;
  // Every robot's spec first: bad input shows before any run.
  const std::vector<std::uint64_t> seeds = seeds_of(scenario_file, options);
  const std::string base = std::filesystem::path(scenario_file).parent_path().string();
  std::vector<RunSpec> specs;
  study.robots.resize(seeds.size());
  for (size_t k = 0; k < seeds.size(); ++k) {
    PopulationRobot& r = study.robots[k];
    r.seed = seeds[k];
    r.scenario_text = population_robot_scenario(scenario_file, seeds[k], options.keep_effects);
    RunSpec s = parse_run_spec(r.scenario_text, fmt::format("{} (robot {})", scenario_file, seeds[k]),
                               base.empty() ? "." : base);
    s.outputs.report = false;
    specs.push_back(s);
  }
  if (!specs.empty()) study.name = specs.front().sim.name;
  std::vector<PopulationRobot> finished(specs.size());
  int done = 0;
  run_in_parallel(
      specs.size(), options.threads,
      [&](size_t k) {
        const auto c0 = std::chrono::steady_clock::now();
        finished[k] = run_robot(specs[k], scenario_file, study.robots[k]);
        finished[k].seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - c0).count();
      },
      [&](size_t k) {
        study.robots[k] = finished[k];
        if (progress) progress(study.robots[k], ++done, static_cast<int>(specs.size()));
      });
  study.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return study;
}

PopulationSummary PopulationStudy::summary() const {
  PopulationSummary s;
  s.robots = static_cast<int>(robots.size());
  std::vector<double> rms, normalised, bound, floor;
  int estimated = 0, within = 0, tested = 0, passed = 0;
  for (const PopulationRobot& r : robots) {
    if (r.failure) {
      ++s.failed;
      continue;
    }
    rms.push_back(r.positioning.rms_um);
    if (r.positioning.stated_sigma_rms_um > 0.0) normalised.push_back(r.positioning.normalised_rms);
    if (std::isfinite(r.positioning_bound_um)) bound.push_back(r.positioning_bound_um);
    if (std::isfinite(r.floor_ratio)) floor.push_back(r.floor_ratio);
    if (r.floor_ratio_ci95[1] < 1.0) ++s.robots_below_floor;
    estimated += r.estimated, within += r.within_3_sigma;
    s.worst_sigma_ratio = std::max(s.worst_sigma_ratio, r.worst_sigma_ratio);
    if (r.model_test_passed) ++tested, passed += *r.model_test_passed ? 1 : 0;
  }
  s.positioning_median_um = median(rms);
  s.positioning_max_um = rms.empty() ? NAN : *std::max_element(rms.begin(), rms.end());
  s.positioning_bound_median_um = median(bound);
  s.floor_ratio_median = median(floor);
  s.within_3_sigma_fraction = estimated > 0 ? static_cast<double>(within) / estimated : NAN;
  s.model_test_pass_fraction = tested > 0 ? static_cast<double>(passed) / tested : NAN;
  s.normalised_positioning_median = median(normalised);
  std::vector<double> deviation;
  for (const PopulationRobot& r : robots) {
    if (!std::isfinite(r.plan_deviation_mm)) continue;
    deviation.push_back(r.plan_deviation_mm);
    if (!(r.plan_deviation_mm <= s.plan_deviation_max_mm))
      s.plan_deviation_max_mm = r.plan_deviation_mm, s.plan_deviation_worst_seed = r.seed;
  }
  s.plan_deviation_median_mm = median(deviation);
  std::vector<double> delays;
  for (const PopulationRobot& r : robots) {
    if (r.failure || !r.monitored) continue;
    ++s.monitored;
    s.false_alarms += r.false_alarms;
    s.monitored_hours += r.monitored_s / 3600.0;
    if (r.false_alarms > 0) ++s.robots_with_false_alarms;
    if (r.event) ++s.events;
    if (r.detection_delay_s) ++s.detected, delays.push_back(*r.detection_delay_s);
  }
  s.false_alarms_per_hour = s.monitored_hours > 0.0 ? s.false_alarms / s.monitored_hours : NAN;
  s.detection_delay_median_s = median(delays);
  s.detection_delay_max_s = delays.empty() ? NAN : *std::max_element(delays.begin(), delays.end());
  return s;
}

namespace {

// The report's data of the study (report/population_report.hpp).
report::PopulationReport population_report_data(const PopulationStudy& study) {
  report::PopulationReport p{study.name, study.randomized, study.seconds, study.summary(), {}};
  for (const PopulationRobot& r : study.robots)
    p.robots.push_back({r.seed, r.failure, r.positioning.rms_um, r.positioning.max_um,
                        r.positioning.stated_sigma_rms_um, r.positioning_bound_um, r.calibrated_static_um, r.floor_ratio, r.model_test_passed,
                        r.chi2_per_dof, r.error, r.sigma, r.worst_param, r.worst_sigma_ratio, r.estimated,
                        r.within_3_sigma, r.monitored, r.learning_s, r.learned_scale, r.monitored_s, r.false_alarms,
                        r.false_alarms_per_hour, r.event, r.detection_delay_s, r.detection, r.seconds});
  return p;
}

nlohmann::json three(const std::array<double, 3>& a, double scale = 1.0) {
  return {number(a[0] * scale), number(a[1] * scale), number(a[2] * scale)};
}

// Each chain's drive train (sim/drive_train.hpp), as the effects keys name it.
nlohmann::json drive_json(const sim::DriveTrain& d) {
  nlohmann::json chains = nlohmann::json::array();
  for (const sim::DriveChain& c : d.chain)
    chains.push_back({{"backlash_rad", c.backlash_rad},
                      {"drive_stiffness_Nm_per_rad", three(c.stiffness_Nm_per_rad)},
                      {"drive_stiffness_bands_Nm", {c.band_Nm[0], c.band_Nm[1]}},
                      {"drive_hysteresis_rad", c.hysteresis_rad},
                      {"transmission_error_joint_rad", c.te_joint_rad},
                      {"transmission_error_motor_rad", c.te_motor_rad},
                      {"stiction_excess_Nm", c.stiction_excess_Nm},
                      {"friction_load_coefficient", c.load_friction},
                      {"torque_constant_delta", c.torque_constant_delta},
                      {"cogging_Nm", c.cogging_Nm}});
  return chains;
}

nlohmann::json harmonics_json(const sim::Effects& e) {
  nlohmann::json h = nlohmann::json::array();
  for (const sim::EncoderHarmonic& x : e.encoder_harmonics)
    if (x.order > 0) h.push_back({{"order", x.order}, {"amplitude_rad", three(x.amplitude_rad)}});
  return h;
}

nlohmann::json effects_json(const sim::Effects& e) {
  return {{"transmission_stiffness_Nm_per_rad",
           three({1.0 / e.mjcf.compliance_rad_per_Nm[0], 1.0 / e.mjcf.compliance_rad_per_Nm[1],
                  1.0 / e.mjcf.compliance_rad_per_Nm[2]})},
          {"passive_clearance_mm", three(e.mjcf.clearance_m, 1e3)},
          {"coulomb_friction_Nm", three(e.mjcf.coulomb_Nm)},
          {"viscous_friction_Nm_s", three(e.mjcf.viscous_Nm_s)},
          {"friction_timeconst_s", e.mjcf.friction_timeconst_s},
          {"encoder_cyclic_rad", three(e.encoder_cyclic_rad)},
          {"encoder_skew_s", three(e.encoder_skew_s)},
          {"gear_ratio", e.gear_ratio},
          {"drive_train", drive_json(e.drive)},
          {"encoder_harmonics", harmonics_json(e)},
          {"encoder_jitter_s", three(e.encoder_jitter_s)},
          {"hub_pin_offset_um", {three({e.mjcf.hub_pin_m[0][0], e.mjcf.hub_pin_m[1][0], e.mjcf.hub_pin_m[2][0]}, 1e6),
                                 three({e.mjcf.hub_pin_m[0][1], e.mjcf.hub_pin_m[1][1], e.mjcf.hub_pin_m[2][1]}, 1e6)}},
          {"thermal", {{"expansion_per_K", e.thermal.expansion_per_K}, {"rise_K", e.thermal.rise_K},
                       {"time_constant_s", e.thermal.time_constant_s}}}};
}

nlohmann::json robot_json(const PopulationRobot& r) {
  nlohmann::json j;
  j["seed"] = r.seed;
  j["scenario"] = fmt::format("robot_{}.yaml", r.seed);
  j["effects"] = effects_json(r.effects);
  j["failure"] = r.failure ? nlohmann::json(*r.failure) : nlohmann::json(nullptr);
  j["positioning_um"] = {{"rms", number(r.positioning.rms_um)}, {"max", number(r.positioning.max_um)},
                         {"stated_sigma_rms", number(r.positioning.stated_sigma_rms_um)},
                         {"normalised_rms", number(r.positioning.normalised_rms)},
                         {"carried_sigma_rms", number(r.positioning.carried_sigma_rms_um)},
                         {"bound_rms", number(r.positioning_bound_um)}, {"points", r.positioning.points}};
  j["static_rms_um"] = {{"calibrated", number(r.calibrated_static_um)}, {"actual", number(r.floor_um)}};
  j["floor_ratio"] = number(r.floor_ratio);
  j["floor_ratio_ci95"] = {number(r.floor_ratio_ci95[0]), number(r.floor_ratio_ci95[1])};
  j["plan_deviation_mm"] = number(r.plan_deviation_mm);
  j["model_test"] = {{"passed", r.model_test_passed ? nlohmann::json(*r.model_test_passed) : nlohmann::json(nullptr)},
                     {"chi2_per_dof", number(r.chi2_per_dof)}, {"calls_for", r.calls_for}};
  nlohmann::json params = nlohmann::json::object();
  for (int k = 0; k < kNumParams; ++k)
    if (std::isfinite(r.sigma[static_cast<size_t>(k)]))
      params[std::string(param_name(k))] = {{"error", r.error[static_cast<size_t>(k)]},
                                            {"sigma", r.sigma[static_cast<size_t>(k)]}};
  j["parameters"] = params;
  j["within_3_sigma"] = r.within_3_sigma;
  j["estimated"] = r.estimated;
  j["calibration_notes"] = r.notes;
  if (r.friction_balance)  // beside the twin's truth in effects (the viscous friction there is the model's 0.05 less)
    j["friction_balance"] = {{"coulomb_Nm", r.friction_balance->coulomb_Nm},
                             {"viscous_Nm_s", r.friction_balance->viscous_Nm_s},
                             {"coulomb_sigma_Nm", r.friction_balance->coulomb_sigma_Nm},
                             {"viscous_sigma_Nm_s", r.friction_balance->viscous_sigma_Nm_s}};
  if (r.monitored)
    j["monitor"] = {{"learning_s", number(r.learning_s)},
                    {"learned_scale", number(r.learned_scale)},
                    {"monitored_s", number(r.monitored_s)},
                    {"false_alarms", r.false_alarms},
                    {"false_alarms_per_hour", number(r.false_alarms_per_hour)},
                    {"event", r.event},
                    {"detection_delay_s", r.detection_delay_s ? nlohmann::json(*r.detection_delay_s) : nlohmann::json(nullptr)},
                    {"detection", r.detection},
                    {"alarms_after_event", r.alarms_after_event}};
  j["seconds"] = number(r.seconds);
  return j;
}

}  // namespace

std::vector<std::string> population_table_header(const PopulationStudy& study) {
  return report::population_table_header(population_report_data(study));
}

std::vector<std::vector<std::string>> population_table_rows(const PopulationStudy& study) {
  return report::population_table_rows(population_report_data(study));
}

std::string population_markdown(const PopulationStudy& study) {
  return report::population_markdown(population_report_data(study));
}

std::string population_json(const PopulationStudy& study) {
  const PopulationSummary s = study.summary();
  nlohmann::json j;
  j["scenario"] = study.scenario;
  j["name"] = study.name;
  j["effects"] = study.randomized ? "randomized" : "scenario";
  j["seconds"] = number(study.seconds);
  j["summary"] = {{"robots", s.robots},
                  {"failed", s.failed},
                  {"positioning_median_um", number(s.positioning_median_um)},
                  {"positioning_max_um", number(s.positioning_max_um)},
                  {"positioning_bound_median_um", number(s.positioning_bound_median_um)},
                  {"floor_ratio_median", number(s.floor_ratio_median)},
                  {"robots_below_floor", s.robots_below_floor},
                  {"within_3_sigma_fraction", number(s.within_3_sigma_fraction)},
                  {"worst_sigma_ratio", number(s.worst_sigma_ratio)},
                  {"model_test_pass_fraction", number(s.model_test_pass_fraction)},
                  {"normalised_positioning_median", number(s.normalised_positioning_median)},
                  {"plan_deviation_median_mm", number(s.plan_deviation_median_mm)},
                  {"plan_deviation_max_mm", number(s.plan_deviation_max_mm)}};
  if (s.monitored > 0)
    j["summary"]["monitor"] = {{"robots", s.monitored},
                               {"false_alarms", s.false_alarms},
                               {"monitored_hours", number(s.monitored_hours)},
                               {"false_alarms_per_hour", number(s.false_alarms_per_hour)},
                               {"robots_with_false_alarms", s.robots_with_false_alarms},
                               {"events", s.events},
                               {"detected", s.detected},
                               {"detection_delay_median_s", number(s.detection_delay_median_s)},
                               {"detection_delay_max_s", number(s.detection_delay_max_s)}};
  j["robots"] = nlohmann::json::array();
  for (const PopulationRobot& r : study.robots) j["robots"].push_back(robot_json(r));
  return j.dump(2) + "\n";
}

report::ReportDocument population_report(const PopulationStudy& study) {
  return report::population_report(population_report_data(study));
}

void write_population_study(const PopulationStudy& study, const std::string& dir) {
  OutputFolder out(dir, {study.scenario});
  out.add("population.json", population_json(study));
  for (const PopulationRobot& r : study.robots) out.add(fmt::format("robot_{}.yaml", r.seed), r.scenario_text);
  population_report(study).stage(out, "population", "gpm study population");
  out.commit();
}

}  // namespace gpm::scenario
