#include "scenarios/runner.hpp"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>

#include <fmt/format.h>
#include <unistd.h>

#include "calib/crb.hpp"
#include "calib/residuals.hpp"
#include "calib/result_yaml.hpp"
#include "models/errors.hpp"
#include "models/kinematics.hpp"
#include "hw/hardware_config.hpp"
#include "hw/procedures/sample_log.hpp"
#include "hw/procedures/sampling_session.hpp"
#include "hw/procedures/stop_on_signal.hpp"
#include "models/robot_yaml.hpp"
#include "models/samples.hpp"
#include "scenarios/calibration_method.hpp"
#include "scenarios/expectations.hpp"
#include "scenarios/run_report.hpp"

namespace gpm::scenario {
namespace fs = std::filesystem;

bool RunOutcome::passed() const {
  for (const Check& c : checks)
    if (!c.passed) return false;
  return true;
}

namespace {

// Encoder noise of one averaged sample: white reading noise over the
// averaging window (one reading per drive period) plus quantisation
// (uniform, step^2 / 12). An a-priori figure for the bound.
double effective_sigma(const sim::Scenario& s) {
  const double q = s.twin.encoder.bits > 0 ? 2.0 * M_PI / std::ldexp(1.0, s.twin.encoder.bits) : 0.0;
  const double n_avg = std::max(1.0, std::round(s.sampling->options.average_s * s.twin.servo_rate_hz));
  const double noise = s.twin.encoder.noise_rad;
  return std::sqrt(noise * noise / n_avg + q * q / 12.0);
}

}  // namespace

namespace {

// Samples through the hardware interface (hw/): the scenario's poses, the
// sampling session of hw/procedures/sampling_session.hpp, every sample on disk as taken.
sim::SimulationResult sample_on_hardware(const RunSpec& spec, const std::string& samples_path,
                                         std::string& description) {
  if (samples_path.empty()) throw InputError("gpm run --hardware: no output folder for the samples");
  const hw::HardwareConfig cfg = hw::load_hardware_config(*spec.hardware);
  hw::SessionPlan plan;
  plan.poses = sim::plan_poses(*spec.sim.sampling, spec.sim.seed);
  plan.options = spec.sim.sampling->options;
  plan.modes = cfg.modes;
  sim::SimulationResult r;
  r.actual = sim::make_actual(spec.sim);
  {
    const hw::StopOnSignal signals;  // hw/procedures/stop_on_signal.hpp: drives off, exit 130
    hw::SampleLog log(samples_path, spec.hardware_resume);
    auto robot = hw::make_hardware(cfg);
    description = fmt::format("{} backend from {}", cfg.backend, *spec.hardware);
    hw::run_sampling_session(*robot, plan, log, signals.flag());
  }
  const Samples s = read_samples_csv(samples_path);
  for (size_t j = 0; j < s.size(); ++j) {
    sim::SampleRecord rec;
    rec.id = s.id[j];
    rec.theta_m = s.theta_m[j];
    rec.target = plan.poses[static_cast<size_t>(s.id[j])];
    // Through the interface only the readings are known; the pose is the
    // target, and the true angles those of the scenario's actual robot there.
    rec.xy_mm = rec.target;
    rec.theta_a = inverse_kinematics(r.actual.geometry, rec.target, r.actual.branch).theta_a;
    rec.settled = true;
    r.samples.push_back(rec);
  }
  return r;
}

}  // namespace

RunOutcome run_scenario(const RunSpec& spec, const std::string& scenario_file, const Progress& progress,
                        const std::string& samples_path) {
  const auto t0 = std::chrono::steady_clock::now();
  auto stage = [&](const std::string& s) { if (progress) progress(s); };
  RunOutcome out;
  out.scenario_file = scenario_file;
  out.spec = spec;
  out.nominal = spec.sim.controller;
  out.calibrated = spec.sim.controller;

  if (spec.hardware) {
    stage("sampling through the hardware interface");
    out.sim = sample_on_hardware(spec, samples_path, out.hardware_description);
  } else {
    stage("simulating the twin");
    out.sim = sim::run_simulation(spec.sim);
  }
  const Robot& actual = out.sim.actual;

  // Calibration problem from the encoder samples alone.
  calib::Problem problem;
  std::vector<Eigen::Vector2d> true_xy;
  std::vector<Eigen::Vector3d> noiseless;
  for (const sim::SampleRecord& r : out.sim.samples) {
    problem.theta_m.push_back(r.theta_m);
    true_xy.push_back(r.xy_mm);  // the true pose in simulation (kmrmse only then)
    noiseless.push_back(readings_from_active(actual.geometry, r.theta_a));
  }
  problem.start = spec.sim.controller.geometry;
  problem.free = ~spec.calibration.fixed;
  // The fixed coordinates define the frame: they must be the true ones (ERRATA).
  if (spec.calibration.start_reference) {
    // Paper section 3.2 step 3: readings at the point believed to be home.
    const JointAngles q = inverse_kinematics(actual.geometry, actual.home, actual.branch);
    const Eigen::Vector3d m = readings_from_active(actual.geometry, q.theta_a);
    const JointAngles qn = inverse_kinematics(problem.start, out.nominal.home, out.nominal.branch);
    for (int i = 0; i < 3; ++i) problem.start[dth(i)] = wrap_pi(qn.theta_a[i] - m[i]);
  }

  out.crb_sigma_rad = spec.calibration.sigma.value_or(effective_sigma(spec.sim));
  if (problem.free.count() <= noiseless.size()) {
    try {
      // The bound scales with sigma: computed at 1 rad and scaled (0 for ideal encoders).
      out.crb = calib::crb_sigma(actual.geometry, problem.free, noiseless, 1.0);
      for (double& v : out.crb) v *= out.crb_sigma_rad;
    } catch (const std::exception&) {
      out.crb.fill(NAN);  // singular information: reported as unidentifiable below
    }
  } else {
    out.crb.fill(NAN);
  }

  stage("calibrating");
  MethodOptions mo;
  mo.method = spec.calibration.method;
  mo.cost = spec.calibration.cost;
  mo.budget = spec.calibration.budget;
  mo.seed = spec.calibration.seed;
  mo.encoder_sigma = spec.calibration.sigma;
  if (!mo.encoder_sigma && spec.sim.twin.encoder.noise_rad > 0) mo.encoder_sigma = out.crb_sigma_rad;
  mo.allow_rank_deficient = spec.calibration.allow_rank_deficient;
  mo.true_xy = spec.hardware ? nullptr : &true_xy;
  try {
    out.calibration = calibrate_with_method(problem, mo);
    out.calibrated.geometry = out.calibration->geometry;
  } catch (const InputError& e) {
    if (!spec.expect.refused_contains) throw;
    out.refused = e.what();
  }

  if (out.calibration) {
    for (const Eigen::Vector3d& m : problem.theta_m) {
      double r = NAN;
      const calib::MlResidual residual(m);
      residual(out.calibration->geometry.values.data(), &r);
      out.residual_urad.push_back(r * 1e6);
    }
  }

  if (spec.compensation) {
    sim::check_targets(spec.sim, actual, spec.compensation->poses);
    stage("measuring accuracy with the nominal model");
    const unsigned long long seed = sim::derive_seed(spec.sim.seed, 4);
    out.before = measure_accuracy(actual, spec.sim.twin, out.nominal, *spec.compensation, seed, "nominal");
    if (out.calibration) {
      stage("measuring accuracy with the calibrated model");
      out.after = measure_accuracy(actual, spec.sim.twin, out.calibrated, *spec.compensation, seed, "calibrated");
    }
  }
  out.checks = evaluate_expectations(out);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

void write_run(const RunOutcome& o, const std::string& dir) {
  std::vector<std::pair<std::string, std::string>> files;
  if (o.hardware_description.empty()) {  // with hardware the session already wrote samples.csv
    files.emplace_back("samples.csv", sim::samples_csv(o.sim.samples));
    files.emplace_back("trajectory.csv", sim::trajectory_csv(o.sim.log));
    files.emplace_back("model.xml", o.sim.model_xml);
  }
  files.emplace_back("actual.yaml", robot_to_yaml(o.sim.actual));
  if (o.calibration) files.emplace_back("calibration.yaml", calib::result_to_yaml(*o.calibration, o.nominal.name));
  if (o.spec.outputs.report) {
    const report::ReportDocument doc = build_report(o);
    files.emplace_back("report.md", doc.markdown());
    files.emplace_back("report.html", doc.html(fmt::format("gpm run: {}", o.spec.sim.name)));
    for (auto& f : doc.figure_files()) files.push_back(std::move(f));
  }

  // All or nothing: write into a temporary sibling folder, then move each file
  // into place (the folder may already hold other files, which are kept).
  const fs::path target(dir);
  std::error_code ec;
  fs::create_directories(target, ec);
  if (ec || !fs::is_directory(target)) {
    throw InputError(fmt::format("{}: cannot create the output folder ({})", dir,
                                 ec ? ec.message() : "not a folder"));
  }
  const fs::path tmp = target / fmt::format(".gpm-run.tmp{}", static_cast<long>(::getpid()));
  fs::create_directories(tmp, ec);
  try {
    for (const auto& [name, text] : files) {
      std::ofstream f(tmp / name, std::ios::binary);
      f << text;
      if (!f) throw InputError(fmt::format("{}: cannot write {} (disk full or not writable?)", dir, name));
    }
    for (const auto& [name, text] : files) fs::rename(tmp / name, target / name);
    fs::remove_all(tmp);
  } catch (...) {
    fs::remove_all(tmp, ec);
    throw;
  }
}

}  // namespace gpm::scenario
