// gpm calibrate: identify kinematic parameters from encoder samples (paper
// section 3; docs/ARCHITECTURE.md command line) with gpm run's procedure
// (run/calibration_procedure.hpp: the motion model for samples taken on the
// fly, whose file has the times and drive torques; else the static fit; the
// model test for both). Parses, calls the procedure, prints, writes the
// result YAML atomically (with --json, prints the result file's content as one
// JSON document instead of the text). Bad input: exit 2 with one line; LM not
// converged: the result is written (diagnostics.converged: false), exit code 1;
// a cost that is not finite or a result that is not a usable robot: one line,
// exit 1, nothing written (issue 36.1, 36.5).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "app/cli_text.hpp"
#include "app/commands.hpp"
#include "app/json_output.hpp"
#include "app/number_options.hpp"
#include "calib/calibrate.hpp"
#include "calib/initial.hpp"
#include "calib/lm.hpp"
#include "calib/positioning_error.hpp"
#include "calib/result_yaml.hpp"
#include "calib/sample_check.hpp"
#include "models/bounds.hpp"
#include "models/errors.hpp"
#include "models/progress.hpp"
#include "models/output_file.hpp"
#include "models/robot_yaml.hpp"
#include "models/samples.hpp"
#include "run/calibration_inputs.hpp"
#include "run/calibration_procedure.hpp"
#include "run/run_spec.hpp"

namespace gpm::cli {
namespace {

struct CalibrateOptions {
  std::string data, model, out;
  std::string fix = "xa1,ya1,xa2,ya2";
  std::string cost = "ml";
  std::string method = "lm";
  std::string init = "model";
  std::string reference_reading, reference_point;
  long seed = 1;
  long budget = 0;  // lm: iterations (default 200); global: evaluations (default 1.5e6)
  bool budget_given = false;
  double sigma = 0.0;
  bool sigma_given = false;
  bool allow_rank_deficient = false;
  bool json = false;
  std::string loss = "plain";
  int encoder_bits = 0;  // 2^bits counts per turn; default: the robot's data sheet
  bool encoder_bits_given = false;
  bool static_fit = false;  // the static fit even for samples taken on the fly
};

// "FILE:LINE (sample ID)" for each data row, counting lines as the CSV reader
// does (first non-blank line is the header, blank lines are skipped).
std::vector<std::string> row_labels(const std::string& path, const Samples& s) {
  std::ifstream in(path, std::ios::binary);
  std::string line;
  std::vector<std::string> out;
  int line_no = 0;
  bool header = false;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    if (!header) {
      header = true;
      continue;
    }
    const size_t j = out.size();
    out.push_back(fmt::format("{}:{} (sample {})", path, line_no, j < s.id.size() ? s.id[j] : static_cast<long>(j)));
  }
  return out;
}

// Parses "a,b[,c]" into exactly n finite numbers; flag names the option.
std::vector<double> parse_numbers(const std::string& text, size_t n, const std::string& flag,
                                  const std::string& example) {
  std::vector<double> v;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    size_t used = 0;
    double x = 0.0;
    try {
      x = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    while (used < item.size() && item[used] == ' ') ++used;
    if (used == 0 || used != item.size() || !std::isfinite(x)) {
      throw InputError(fmt::format("{}: '{}' is not a finite number (expected {} comma-separated numbers, e.g. {})",
                                   flag, item, n, example));
    }
    v.push_back(x);
  }
  if (v.size() != n) {
    throw InputError(fmt::format("{}: expected {} comma-separated numbers, e.g. {}; got {}", flag, n, example, v.size()));
  }
  return v;
}

// The positioning 1-sigma the calibration states over the 80 mm disc round
// home (the calibrated model's own sensitivities: no actual robot to judge it
// by) and its carried share, as gpm run's position line states them; empty
// without a covariance or where the disc is out of reach.
std::string positioning_sigma_line(const Robot& robot, const calib::Result& r) {
  const std::optional<calib::PositioningError> p = calib::stated_positioning(robot, r);
  if (!p) return {};
  std::string line = fmt::format("positioning over the 80 mm disc: stated 1-sigma {:.2f} {} per axis{}",
                                 p->stated_sigma_rms_um, um(), carried_share(p->carried_sigma_rms_um));
  if (p->carried_sigma_rms_um > 0.0) line += ", carried at the data sheet's amplitude";
  return line + "\n";
}

// The terminal's account of the calibration: parameters, diagnostics, model test.
void print_result(const CalibrateOptions& o, const Robot& robot, const Samples& samples, const calib::Problem& problem,
                  const scenario::CalibrationOutcome& outcome, const scenario::FileProcedure& proc) {
  const calib::Result& r = outcome.result;
  fmt::print("calibrated {} from {} samples with {} ({}), {} free parameters, {}\n", robot.name,
             samples.size(), r.method, calib::cost_name(r.cost), r.free.count(), proc.model);
  fmt::print("{:<6} {:>16} {:>16} {:>12}\n", "param", "start", "estimate", "1-sigma");
  for (int i = 0; i < kNumParams; ++i) {
    if (!r.free.test(static_cast<size_t>(i))) continue;
    fmt::print("{:<6} {:>16.9f} {:>16.9f} {:>12.3g}\n", param_name(i), problem.start[i], r.geometry[i],
               r.sigma[static_cast<size_t>(i)]);
  }
  fmt::print("J = {:.6g}, iterations {}, evaluations {}, rank {} of {}, condition number {:.4g}",
             r.final_cost, r.iterations, r.evaluations, r.rank, r.free.count(), r.condition_number);
  if (r.kmrmse_mm) fmt::print(", kmrmse {:.6g} mm", *r.kmrmse_mm);
  fmt::print(", {:.3f} s\n", r.seconds);
  fmt::print("{}", terminal_text(positioning_sigma_line(robot, r)));
  if (outcome.model_test)
    fmt::print("{}\n", terminal_text(scenario::model_test_line(*outcome.model_test, proc.sigma_stated)));
  else
    fmt::print("model test not made (no reading 1-sigma: --sigma or --encoder-bits; or no more samples than "
               "free parameters)\n");
  fmt::print("{} -> {}\n", r.converged ? "converged" : "NOT converged", o.out);
}

// The calibration problem of the samples: the robot file's geometry as the
// start, or its offsets from the reference reading (--init reference).
calib::Problem problem_of(const CalibrateOptions& o, const Robot& robot, const Samples& samples, const FreeMask& fixed) {
  calib::Problem problem;
  problem.theta_m = samples.theta_m;
  problem.free = ~fixed;
  problem.start = robot.geometry;
  const bool reference = o.init == "reference" || !o.reference_reading.empty();
  if (o.init != "model" && o.init != "reference") {
    throw InputError(fmt::format("--init: '{}' is not model or reference", o.init));
  }
  if (reference) {
    if (o.reference_reading.empty()) {
      throw InputError("--init reference: give the encoder readings at the reference point with "
                       "--reference-reading T1,T2,T3 (rad)");
    }
    const auto t = parse_numbers(o.reference_reading, 3, "--reference-reading", "1.02,3.05,4.80");
    Eigen::Vector2d ref = robot.home;
    if (!o.reference_point.empty()) {
      const auto p = parse_numbers(o.reference_point, 2, "--reference-point", "216.5,250");
      ref = {p[0], p[1]};
    }
    problem.start = calib::offsets_from_reference(robot, {t[0], t[1], t[2]}, ref);
  } else if (!o.reference_point.empty()) {
    throw InputError("--reference-point: only meaningful with --reference-reading T1,T2,T3");
  }
  return problem;
}

void run(const CalibrateOptions& o) {
  const auto cost = calib::parse_cost(o.cost);
  if (!cost) throw InputError(fmt::format("--cost: '{}' is not one of j1, j2, j3, ml", o.cost));
  const calib::Method method = calib::parse_method(o.method, "--method");
  const calib::RobustLoss loss = calib::parse_loss(o.loss, "--loss");
  // --budget counts iterations for lm, evaluations for the global methods:
  // each has its own bound (docs/CLI.md, Limits), checked before any work.
  if (o.budget_given)
    check_bound(static_cast<double>(o.budget), method == calib::Method::kLM ? limits::kLmIterations : limits::kEvaluations,
                "--budget");
  const std::string model_path = o.model.empty() ? default_model_path() : o.model;
  const Robot robot = load_robot(model_path);
  const Samples samples = read_samples_csv(o.data);
  const FreeMask fixed = parse_param_list(o.fix, "--fix");

  const calib::Problem problem = problem_of(o, robot, samples, fixed);
  calib::check_samples(problem, row_labels(o.data, samples));
  // Output policy (models/output_file.hpp): refused before the work when the
  // result would overwrite an input or cannot be written.
  check_output_file(o.out, {o.data, model_path});
  calib::MethodOptions mo;
  mo.method = method;
  mo.cost = *cost;
  mo.seed = static_cast<std::uint64_t>(o.seed);
  mo.allow_rank_deficient = o.allow_rank_deficient;
  mo.loss = loss;
  if (o.budget_given) {
    if (method == calib::Method::kLM) mo.lm_max_iterations = static_cast<int>(o.budget);
    else mo.budget = o.budget;
  }
  // Checked here, not by a CLI11 validator: the message is the Python
  // binding's too (python/bind_calibrate.cpp).
  if (o.sigma_given) mo.encoder_sigma = check_bound(o.sigma, limits::kEncoderSigma, "--sigma");
  const scenario::FileProcedure proc = scenario::samples_file_procedure(
      samples, robot, problem.start, problem.free, mo,
      o.encoder_bits_given ? std::optional<int>(o.encoder_bits) : std::nullopt, o.static_fit);
  if (proc.motion_not_used)
    std::fprintf(stderr, "gpm: warning: %s\n",
                 "the samples were taken on the fly, but their motion model needs --method lm --cost ml: "
                 "calibrated with the static model");
  // A global method's budget on a terminal (models/progress.hpp): evaluations, rate, ETA.
  gpm::Progress progress = method == calib::Method::kLM
                               ? gpm::Progress::silent()
                               : gpm::Progress::terminal("gpm calibrate: " + std::string(calib::method_name(method)), "evaluations",
                                                         static_cast<double>(mo.budget));
  scenario::ProcedureOptions po = proc.options;
  if (progress.active()) po.method.progress = [&progress](long done, long, double) { progress.update(static_cast<double>(done)); };
  const scenario::CalibrationOutcome outcome =
      scenario::calibrate_samples(scenario::sample_series(samples), proc.inputs, po);
  progress.finish();
  const calib::Result& r = outcome.result;
  calib::usable_robot(robot, r.geometry);  // else exit 1, nothing written

  for (const auto& note : r.notes) std::fprintf(stderr, "gpm: warning: %s\n", terminal_text(note).c_str());
  const std::string text =
      calib::result_to_yaml(r, robot.name) + (outcome.model_test ? scenario::model_test_yaml(*outcome.model_test, 2) : "");
  write_file_atomic(o.out, text);
  if (!r.converged) set_exit(1);
  if (o.json) {
    // The result file's content (the same text, read back as JSON) and nothing else.
    print_json(yaml_text_to_json(text, o.out));
    return;
  }
  print_result(o, robot, samples, problem, outcome, proc);
}

}  // namespace

void add_calibrate(CLI::App& app) {
  auto o = std::make_shared<CalibrateOptions>();
  auto* cmd = app.add_subcommand("calibrate", "Identify kinematic parameters from encoder samples");
  cmd->add_option("--data", o->data, "Samples CSV: sample,theta_m1,theta_m2,theta_m3[,x,y][,t,tau_last1..3,tau_between1..3]")->required();
  cmd->add_option("--model", o->model, "Robot file (YAML) with the start geometry and known values; default: the nominal GPM2002");
  cmd->add_option("-o,--output", o->out, "Result file (YAML)")->required();
  cmd->add_option("--fix", o->fix, "Parameters known and held fixed (comma-separated); at least 4 base coordinates for full rank")
      ->capture_default_str();
  cmd->add_option("--cost", o->cost, "Error function: j1 (eq. 37), j2 (eq. 39), j3 (eq. 43), ml (maximum likelihood)")
      ->capture_default_str();
  cmd->add_option("--method", o->method,
                  "Solver: lm (Ceres Levenberg-Marquardt), ga, pso, de (paper section 4, box of Table 5), "
                  "de+lm (DE then LM; with --cost ml, DE runs on j3)")
      ->capture_default_str();
  cmd->add_option("--seed", o->seed, "Random seed of the global methods (LM is deterministic)")
      ->transform(number_in(limits::kSeed));
  // The bound depends on --method (checked in run); here only the widest.
  cmd->add_option("--budget", o->budget, "lm: maximum iterations (default 200, at most 1e6); ga, pso, de, de+lm: "
                                         "error-function evaluations of the global stage (default 1500000, at most 1e10)")
      ->transform(number_in(limits::kEvaluations))
      ->each([o](const std::string&) { o->budget_given = true; });
  cmd->add_option("--sigma", o->sigma, "Encoder noise 1-sigma (rad, 1e-12 to 1) for the uncertainty; default: "
                                       "estimated from the residuals")
      ->each([o](const std::string&) { o->sigma_given = true; });
  cmd->add_option("--loss", o->loss,
                  "Loss per sample: plain (least squares), cauchy or huber (robust to outlier samples), "
                  "optionally :SCALE in residual units (rad for ml); default scale 2.385 (cauchy) or 1.345 "
                  "(huber) x the noise (--sigma, or estimated robustly from a plain fit)")
      ->capture_default_str();
  cmd->add_option("--encoder-bits", o->encoder_bits,
                  "Encoder resolution, 2^N counts per turn (0: ideal), for the reading 1-sigma of the model test and "
                  "of the motion model when --sigma is not given; default: the robot file's data_sheet (17)")
      ->transform(number_in(limits::kEncoderBits))
      ->each([o](const std::string&) { o->encoder_bits_given = true; });
  cmd->add_flag("--static", o->static_fit,
                "The static model even when the samples were taken on the fly (the file's t, tau_last1..3 and "
                "tau_between1..3 columns are then not used)");
  cmd->add_flag("--allow-rank-deficient", o->allow_rank_deficient,
                "Solve a rank-deficient free set anyway (minimum-norm step; the result says so)");
  cmd->add_option("--init", o->init, "Start offsets: model (the robot file) or reference (section 3.2 step 3)")
      ->capture_default_str();
  cmd->add_option("--reference-reading", o->reference_reading,
                  "Encoder readings T1,T2,T3 (rad) at the reference point; implies --init reference");
  cmd->add_option("--reference-point", o->reference_point, "Reference point X,Y (mm); default: the robot's home");
  cmd->add_flag("--json", o->json,
                "Print the result (the content of the result file) as one JSON document on stdout instead of the text");
  cmd->callback([o] { run(*o); });
}

}  // namespace gpm::cli
