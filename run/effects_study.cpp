#include "run/effects_study.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <variant>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "models/data_dir.hpp"
#include "models/errors.hpp"
#include "models/output_file.hpp"
#include "report/effects_report.hpp"
#include "models/rng.hpp"
#include "run/parallel_runs.hpp"
#include "run/runner.hpp"
#include "run/table_cells.hpp"

namespace gpm::scenario {
namespace {

constexpr double kLinkMm = 244.0;  // offsets counted as length at the nominal link

struct CaseName {
  EffectCase c;
  const char* name;
};
constexpr CaseName kCaseNames[] = {
    {EffectCase::kIdeal, "ideal"},         {EffectCase::kCompliance, "compliance"},
    {EffectCase::kClearance, "clearance"}, {EffectCase::kFriction, "friction"},
    {EffectCase::kThermal, "thermal"},     {EffectCase::kEncoderCyclic, "encoder_cyclic"},
    {EffectCase::kEncoderSkew, "encoder_skew"}, {EffectCase::kAll, "all"},
    {EffectCase::kDriveTrain, "drive_train"},   {EffectCase::kEncoderMotor, "encoder_motor"},
    {EffectCase::kEvery, "every"},
};

// The geared machine's effects (sim/drive_train.hpp, sim/encoder_error.hpp)
// drawn once, behind the GPM2002's 10:1 reducer, onto e.
void add_drive_train(sim::Effects& e) {
  e.gear_ratio = 10.0;
  Rng rng(kDrawSeed);
  sim::draw_drive_train(rng, e);
}
void add_encoder_motor(sim::Effects& e, const sim::Effects& realistic) {
  e.gear_ratio = 10.0;
  e.encoder_cyclic_rad = realistic.encoder_cyclic_rad;  // now once per motor revolution
  Rng rng(kDrawSeed + 1);
  sim::draw_encoder_and_geometry(rng, e);
}

constexpr auto number = json_finite;

// Applies the options' reductions to one procedure's spec, and the case's effects.
RunSpec case_spec(const StudyProcedure& p, EffectCase c, const EffectsStudyOptions& o) {
  RunSpec s = p.spec;
  // The realistic values whatever the procedure's file holds, with its (seeded) encoder phases.
  sim::Effects realistic = sim::realistic_effects();
  realistic.encoder_phase_rad = p.spec.sim.twin.effects.encoder_phase_rad;
  s.sim.twin.effects = effects_for_case(c, realistic);
  s.expect = Expectations{};  // the study reports numbers; it checks nothing per run
  s.outputs.report = false;
  if (o.sample_count && s.sim.sampling) {
    s.sim.sampling->count = *o.sample_count;
    s.sim.sampling->poses.clear();
  }
  if (s.compensation) {
    if (o.compensation_count && static_cast<size_t>(*o.compensation_count) < s.compensation->poses.size())
      s.compensation->poses.resize(static_cast<size_t>(*o.compensation_count));
    if (o.path_revolutions)
      if (auto* circle = std::get_if<sim::CirclePath>(&s.compensation->path)) circle->revolutions = *o.path_revolutions;
  }
  return s;
}

EffectsRow row_of(const RunOutcome& o) {
  EffectsRow r;
  r.error.fill(NAN);
  r.crb.fill(NAN);
  r.nominal_um = o.before ? o.before->static_rms_um : NAN;
  r.calibrated_um = o.after ? o.after->static_rms_um : NAN;
  r.floor_um = o.floor ? o.floor->static_rms_um : NAN;
  r.floor_ratio = r.calibrated_um / r.floor_um;
  if (o.model_test) r.model_test_passed = o.model_test->passed;
  r.motion_estimated = o.in_motion || o.spec.calibration.estimate_compliance.value_or(false) ||
                       o.spec.calibration.estimate_skew.value_or(false);
  r.motion_nu = o.motion_nu;
  r.motion_nu_sigma = o.motion_nu_sigma;
  if (!o.calibration) {
    r.failure = o.refused.value_or("no calibration");
    return r;
  }
  if (!o.calibration->converged) r.failure = "calibration did not converge";
  double worst = -1.0, worst_crb = -1.0;
  for (int k = 0; k < kNumParams; ++k) {
    if (!o.calibration->free.test(static_cast<size_t>(k))) continue;
    const auto u = static_cast<size_t>(k);
    r.error[u] = o.calibration->geometry[k] - o.sim.actual.geometry[k];
    r.crb[u] = o.crb[u];
    const double um = std::abs(r.error[u]) * (is_offset(k) ? kLinkMm : 1.0) * 1e3;
    if (um > worst) worst = um, r.worst_param = std::string(param_name(k));
    const double in_sigmas = r.crb[u] > 0.0 ? std::abs(r.error[u]) / r.crb[u] : NAN;
    if (std::isfinite(in_sigmas) && in_sigmas > worst_crb) worst_crb = in_sigmas, r.worst_crb_param = std::string(param_name(k));
  }
  r.worst_error_um = worst;
  r.worst_crb_ratio = worst_crb >= 0.0 ? worst_crb : NAN;
  return r;
}

EffectsRow failed_row(const std::string& why) {
  EffectsRow r;
  r.failure = why;
  r.error.fill(NAN);
  r.crb.fill(NAN);
  r.worst_error_um = r.worst_crb_ratio = r.nominal_um = r.calibrated_um = r.floor_um = r.floor_ratio = NAN;
  return r;
}

// The report's data of the study (report/effects_report.hpp).
report::EffectsReport effects_report_data(const EffectsStudy& s) {
  const sim::Effects fx = sim::realistic_effects();
  report::EffectsReport e;
  e.realistic = {fx.mjcf.compliance_rad_per_Nm[0], fx.mjcf.clearance_m[0] * 1e6, fx.mjcf.coulomb_Nm[0],
                 fx.mjcf.viscous_Nm_s[0], fx.thermal.expansion_per_K, fx.thermal.rise_K,
                 fx.thermal.time_constant_s, fx.encoder_cyclic_rad[0], fx.encoder_skew_s[1], fx.encoder_skew_s[2]};
  for (const StudyProcedure& p : s.procedures) {
    report::EffectsProcedure proc{p.name, p.description, {}};
    for (int k = 0; k < kNumParams; ++k)
      if (!p.spec.calibration.fixed.test(static_cast<size_t>(k))) proc.free.push_back(k);
    e.procedures.push_back(proc);
  }
  for (EffectCase c : s.cases) e.cases.push_back(effect_case_name(c));
  e.rows = s.rows;
  e.seconds = s.seconds;
  return e;
}

}  // namespace

std::vector<EffectCase> all_effect_cases() {
  std::vector<EffectCase> v;
  for (const CaseName& n : kCaseNames) v.push_back(n.c);
  return v;
}

std::string effect_case_name(EffectCase c) {
  for (const CaseName& n : kCaseNames)
    if (n.c == c) return n.name;
  return "?";
}

std::optional<EffectCase> parse_effect_case(const std::string& name) {
  for (const CaseName& n : kCaseNames)
    if (name == n.name) return n.c;
  return std::nullopt;
}

sim::Effects effects_for_case(EffectCase c, const sim::Effects& realistic) {
  sim::Effects e;  // ideal
  e.encoder_phase_rad = realistic.encoder_phase_rad;
  switch (c) {
    case EffectCase::kIdeal: break;
    case EffectCase::kCompliance: e.mjcf.compliance_rad_per_Nm = realistic.mjcf.compliance_rad_per_Nm; break;
    case EffectCase::kClearance: e.mjcf.clearance_m = realistic.mjcf.clearance_m; break;
    case EffectCase::kFriction:
      e.mjcf.coulomb_Nm = realistic.mjcf.coulomb_Nm;
      e.mjcf.viscous_Nm_s = realistic.mjcf.viscous_Nm_s;
      break;
    case EffectCase::kThermal: e.thermal = realistic.thermal; break;
    case EffectCase::kEncoderCyclic: e.encoder_cyclic_rad = realistic.encoder_cyclic_rad; break;
    case EffectCase::kEncoderSkew: e.encoder_skew_s = realistic.encoder_skew_s; break;
    case EffectCase::kAll: e = realistic; break;
    case EffectCase::kDriveTrain: add_drive_train(e); break;
    case EffectCase::kEncoderMotor: add_encoder_motor(e, realistic); break;
    case EffectCase::kEvery:
      e = realistic;
      add_drive_train(e);
      add_encoder_motor(e, realistic);
      break;
  }
  return e;
}

std::vector<StudyProcedure> default_study_procedures() {
  const std::string dir = scenarios_dir();
  std::vector<StudyProcedure> v(2);
  v[0].name = "on the fly";
  v[0].description =
      "today's default (main.yaml): designed poses sampled on the fly, joint 1 torque-off, compliance, skew, "
      "friction twist and joint clearance estimated with the geometry";
  v[0].scenario = dir + "/main.yaml";
  v[1].name = "disc stop-and-go";
  v[1].description =
      "the former default (procedure_disc_stopgo_realistic.yaml): random poses in a disc, stop-and-go, three "
      "position-controlled drives";
  v[1].scenario = dir + "/procedure_disc_stopgo_realistic.yaml";
  for (StudyProcedure& p : v) p.spec = load_run_spec(p.scenario);
  return v;
}

EffectsStudy run_effects_study(const std::vector<StudyProcedure>& procedures, const EffectsStudyOptions& options,
                               const EffectsProgress& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  if (options.sample_count && *options.sample_count < 12)
    throw InputError(fmt::format("study effects: --count: {} poses cannot identify 11 parameters (use at least 12)",
                                 *options.sample_count));
  EffectsStudy study;
  study.procedures = procedures;
  study.cases = options.cases;
  const size_t nc = options.cases.size(), n = procedures.size() * nc;
  // The specs first (bad input shows before any run).
  std::vector<RunSpec> specs;
  for (size_t k = 0; k < n; ++k) specs.push_back(case_spec(procedures[k / nc], options.cases[k % nc], options));
  study.rows.resize(n);
  std::vector<EffectsRow> finished(n);
  run_in_parallel(
      n, options.threads,
      [&](size_t k) {
        const auto c0 = std::chrono::steady_clock::now();
        EffectsRow& r = finished[k];
        try {
          r = row_of(run_scenario(specs[k], procedures[k / nc].scenario));
        } catch (const Error& e) {  // refused, diverged: a result of the study, not a stop
          r = failed_row(e.what());
        }
        r.procedure = procedures[k / nc].name;
        r.effect = effect_case_name(options.cases[k % nc]);
        r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - c0).count();
      },
      [&](size_t k) {
        study.rows[k] = finished[k];
        if (progress) progress(study.rows[k]);
      });
  study.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return study;
}

std::vector<std::vector<std::string>> effects_table_rows(const EffectsStudy& s) {
  return report::effects_table_rows(s.rows);
}

std::string effects_markdown_table(const EffectsStudy& s) { return report::effects_markdown_table(s.rows); }

std::string effects_json(const EffectsStudy& s) {
  nlohmann::json j;
  j["seconds"] = number(s.seconds);
  j["procedures"] = nlohmann::json::array();
  for (const StudyProcedure& p : s.procedures)
    j["procedures"].push_back({{"name", p.name}, {"description", p.description}, {"scenario", p.spec.sim.name},
                               {"seed", p.spec.sim.seed}});
  j["effects"] = nlohmann::json::array();
  for (EffectCase c : s.cases) j["effects"].push_back(effect_case_name(c));
  j["rows"] = nlohmann::json::array();
  for (const EffectsRow& r : s.rows) {
    nlohmann::json row;
    row["procedure"] = r.procedure;
    row["effect"] = r.effect;
    row["failure"] = r.failure ? nlohmann::json(*r.failure) : nlohmann::json(nullptr);
    nlohmann::json params = nlohmann::json::object();
    for (int k = 0; k < kNumParams; ++k) {
      const auto u = static_cast<size_t>(k);
      if (!std::isfinite(r.error[u])) continue;
      params[std::string(param_name(k))] = {{"error", r.error[u]}, {"crb", number(r.crb[u])}};
    }
    row["parameters"] = params;
    row["worst_parameter"] = r.worst_param;
    row["worst_error_um"] = number(r.worst_error_um);
    row["worst_crb_parameter"] = r.worst_crb_param;
    row["worst_crb_ratio"] = number(r.worst_crb_ratio);
    row["static_rms_um"] = {{"nominal", number(r.nominal_um)}, {"calibrated", number(r.calibrated_um)},
                            {"actual", number(r.floor_um)}};
    row["floor_ratio"] = number(r.floor_ratio);
    row["model_test_passed"] = r.model_test_passed ? nlohmann::json(*r.model_test_passed) : nlohmann::json(nullptr);
    if (r.motion_estimated)
      row["estimated_effects"] = {{"skew_s2_s", r.motion_nu[0]}, {"skew_s3_s", r.motion_nu[1]},
                                  {"compliance_rad_per_Nm", {r.motion_nu[2], r.motion_nu[3], r.motion_nu[4]}}};
    row["seconds"] = number(r.seconds);
    j["rows"].push_back(row);
  }
  return j.dump(2) + "\n";
}

report::ReportDocument effects_report(const EffectsStudy& s) { return report::effects_report(effects_report_data(s)); }

void write_effects_study(const EffectsStudy& s, const std::string& dir) {
  OutputFolder out(dir);
  out.add("effects.json", effects_json(s));
  effects_report(s).stage(out, "effects", "gpm study effects");
  out.commit();
}

}  // namespace gpm::scenario
