// gpm study: calibration studies on synthetic data from the analytic model.
//   gpm study samples      synthetic encoder samples of a known robot (CSV with true x,y)
//   gpm study crb          Cramer-Rao bound of the free parameters for given samples
//   gpm study montecarlo   noisy trials: empirical RMS error over the bound, per cost
//   gpm study effects      each physical effect of the realistic twin: its bias on calibration
//   gpm study population   a scenario over N robots of the class: the accuracy a user gets, and its 1-sigma
//                          (--scheduler ADDRESS: on a Dask cluster, by the Python module's gpm.study)
#include <cmath>
#include <cstdio>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <spawn.h>
#include <sys/wait.h>

#include "app/cli_text.hpp"
#include "app/commands.hpp"
#include "app/data_files.hpp"
#include "app/progress_mode.hpp"
#include "app/written_files.hpp"
#include "app/number_options.hpp"
#include "calib/crb.hpp"
#include "calib/identifiability.hpp"
#include "calib/montecarlo.hpp"
#include "calib/paper_values.hpp"
#include "calib/sample_check.hpp"
#include "calib/synthetic.hpp"
#include "models/bounds.hpp"
#include "models/errors.hpp"
#include "models/output_file.hpp"
#include "models/robot_yaml.hpp"
#include "models/samples.hpp"
#include "run/effects_study.hpp"
#include "run/population_study.hpp"

namespace gpm::cli {
namespace {

struct StudyOptions {
  std::string actual = "table5";
  std::string data, out, fix = "xa1,ya1,xa2,ya2", costs = "ml,j3";
  int n = 50, trials = 50;
  double radius = 80.0, sigma = 0.0;
  long seed = 1;
  bool check = false, check_each = false;
  double goal_ml = 1.05, goal_j3 = 1.2;
  std::string effects;        // study effects: cases (empty: every one)
  int effects_count = 0;      // study effects: poses per calibration (0: each procedure's own)
  int threads = 2;
  std::string scenario;         // study population: the scenario
  int population_count = 30;    // study population: robots
  std::string seeds;            // study population: these robots' seeds instead of --count
  bool keep_effects = false;    // study population: the scenario's effects, not randomized
  std::string scheduler;        // study population: a running Dask scheduler's address (empty: threads here)
  bool threads_given = false;   // study population: --threads was given
  std::string progress;         // montecarlo, effects, population: --progress (app/progress_mode.hpp)
};

// "table5", "section3" (paper values, calib/paper_values.hpp) or a robot file.
Robot actual_robot(const std::string& what) {
  Robot r;
  if (what == "table5") r.geometry = calib::table5_actual();
  else if (what == "section3") r.geometry = calib::section3_actual();
  else r = load_robot(what);
  return r;
}

void positive(double v, const char* flag) {
  if (!(v > 0.0) || !std::isfinite(v)) throw InputError(fmt::format("{}: must be a positive number, got {}", flag, v));
}

void run_samples(const StudyOptions& o) {
  positive(o.radius, "--radius");
  check_bound(o.sigma, limits::kNoiseSigma, "--sigma");
  const Robot r = actual_robot(o.actual);
  check_output_file(o.out, {o.actual});  // models/output_file.hpp: never over an input
  const auto poses = calib::disc_poses(r, o.n, r.home, o.radius, static_cast<std::uint64_t>(o.seed));
  write_samples_csv(calib::samples_at(r, poses, o.sigma, static_cast<std::uint64_t>(o.seed) + 7777), o.out);
  fmt::print("{} samples of {} in a disc of {} mm around home (seed {}, noise {} rad) -> {}\n", o.n, o.actual,
             o.radius, o.seed, o.sigma, o.out);
}

void run_crb(const StudyOptions& o) {
  check_bound(o.sigma, limits::kEncoderSigma, "--sigma");
  const Robot r = actual_robot(o.actual);
  const Samples s = read_samples_csv(o.data);
  const FreeMask free = ~parse_param_list(o.fix, "--fix");
  // The same refusals as gpm calibrate (issue 14.10): too few samples, bad
  // readings, then a free set the samples cannot identify (the bound would be
  // infinite, printed as -nan).
  calib::Problem problem;
  problem.theta_m = s.theta_m;
  problem.free = free;
  problem.start = r.geometry;
  calib::check_samples(problem);
  const calib::Identifiability id = calib::analyse_identifiability(s.theta_m, r.geometry, free);
  const int p = static_cast<int>(free.count());
  if (id.rank < p) {
    throw InputError(fmt::format(
        "--fix: the {} free parameters ({}) are not identifiable from encoder angles (rank {} of {}): {}; {} "
        "(the bound is infinite along those directions)",
        p, format_param_list(free), id.rank, p, id.description, id.advice));
  }
  const auto sd = calib::crb_sigma(r.geometry, free, s.theta_m, o.sigma);
  fmt::print("Cramer-Rao bound, {} samples, encoder sigma {} rad (readings taken as noiseless of {})\n", s.size(),
             o.sigma, o.actual);
  for (int i = 0; i < kNumParams; ++i)
    if (free.test(static_cast<size_t>(i))) fmt::print("{:<6} {:>12.4g}\n", param_name(i), sd[static_cast<size_t>(i)]);
}

void run_montecarlo(const StudyOptions& o) {
  calib::MonteCarloOptions mc = calib::default_montecarlo_options();
  mc.actual = actual_robot(o.actual).geometry;
  mc.free = ~parse_param_list(o.fix, "--fix");
  for (int i = 0; i < kNumParams; ++i)
    mc.start[i] = mc.free.test(static_cast<size_t>(i)) ? Geometry::gpm2002_nominal()[i] : mc.actual[i];
  mc.trials = o.trials;
  mc.samples = o.n;
  positive(o.radius, "--radius");
  mc.radius_mm = o.radius;
  mc.sigma = o.sigma > 0.0 ? check_bound(o.sigma, limits::kEncoderSigma, "--sigma") : 1e-4;
  mc.seed = static_cast<std::uint64_t>(o.seed);
  mc.costs.clear();
  for (const std::string& c : split_unique_list(o.costs, "--costs")) {
    const auto cost = calib::parse_cost(c);
    if (!cost) throw InputError(fmt::format("--costs: '{}' is not one of j1, j2, j3, ml", c));
    mc.costs.push_back(*cost);
  }
  const auto status = StatusReporter::on_stderr("gpm study montecarlo", progress_mode(o.progress));
  status->update(fmt::format("{} trials of {} samples", mc.trials, mc.samples));
  const auto rows = calib::run_montecarlo(mc);
  status->finish();
  fmt::print("Monte-Carlo: {} trials, {} samples in a disc of {} mm around home, sigma {} rad, {} free\n",
             mc.trials, mc.samples, mc.radius_mm, mc.sigma, mc.free.count());
  fmt::print("empirical RMS error / Cramer-Rao bound per parameter (reported 1-sigma / bound in brackets)\n");
  fmt::print("{:<6} {:>12}", "param", "bound");
  for (const auto& r : rows) fmt::print(" {:>18}", calib::cost_name(r.cost));
  fmt::print("\n");
  for (int i = 0; i < kNumParams; ++i) {
    const auto u = static_cast<size_t>(i);
    if (!mc.free.test(u)) continue;
    fmt::print("{:<6} {:>12.4g}", param_name(i), rows.front().bound[u]);
    for (const auto& r : rows) fmt::print(" {:>9.3f} [{:5.3f}]", r.ratio[u], r.mean_reported_sigma[u] / r.bound[u]);
    fmt::print("\n");
  }
  fmt::print("{:<19}", "max ratio");
  for (const auto& r : rows) fmt::print(" {:>18.3f}", r.max_ratio);
  fmt::print("\n{:<19}", "rms ratio");
  for (const auto& r : rows) fmt::print(" {:>18.3f}", r.rms_ratio);
  fmt::print("\n{:<19}", "normalised ratio");
  for (const auto& r : rows) fmt::print(" {:>18.3f}", r.normalised_ratio);
  fmt::print("\n{:<19}", "failed trials");
  for (const auto& r : rows) fmt::print(" {:>18}", r.failures);
  fmt::print("\n(rms ratio: sqrt(mean over parameters of ratio^2); with {} trials one ratio fluctuates by about\n"
             " {:.0f}% from sampling alone. normalised ratio: sqrt(mean e' F e / p) with F the Fisher information,\n"
             " 1 for an efficient estimator in the linear regime; it grows when errors of several mm along\n"
             " the poorly determined direction leak, by curvature, into the well determined ones)\n",
             mc.trials, 100.0 / std::sqrt(2.0 * mc.trials));
  if (o.check || o.check_each) {
    bool ok = true;
    for (const auto& r : rows) {
      const double goal = r.cost == calib::Cost::kML ? o.goal_ml : r.cost == calib::Cost::kJ3 ? o.goal_j3 : INFINITY;
      const double v = o.check_each ? r.max_ratio : r.rms_ratio;
      const bool pass = v <= goal && r.failures == 0;
      fmt::print("check {}: {} ratio {:.3f} <= {}: {}\n", calib::cost_name(r.cost), o.check_each ? "max" : "rms", v,
                 goal, pass ? "ok" : "FAILED");
      ok = ok && pass;
    }
    if (!ok) set_exit(1);
  }
}

// Effects study (run/effects_study.hpp): every case of every procedure through the runner.
void run_effects(const StudyOptions& o) {
  const std::string& out = o.out;
  const std::string& effects = o.effects;
  const int count = o.effects_count, threads = o.threads;
  if (std::filesystem::exists(out) && !std::filesystem::is_directory(out))
    throw InputError(fmt::format("-o: '{}' exists and is not a folder", out));
  scenario::EffectsStudyOptions so;
  if (!effects.empty()) {
    so.cases.clear();
    for (const std::string& name : split_unique_list(effects, "--effects")) {
      const auto c = scenario::parse_effect_case(name);
      if (!c)
        throw InputError(fmt::format("--effects: '{}' is not one of ideal, compliance, clearance, friction, thermal, "
                                     "encoder_cyclic, encoder_skew, all, drive_train, encoder_motor, every", name));
      so.cases.push_back(*c);
    }
  }
  if (count != 0 && !within(count, limits::kStudyPoses))
    throw InputError(fmt::format("--count: must be {} (12 poses identify the 11 parameters), or 0 for each "
                                 "procedure's own, got {}", describe(limits::kStudyPoses), count));
  if (count > 0) so.sample_count = count;
  if (threads < 1 || threads > 64) throw InputError(fmt::format("--threads: must be 1 to 64, got {}", threads));
  so.threads = threads;
  const auto procedures = scenario::default_study_procedures();
  fmt::print("effects study: {} effect cases x {} procedures on {} thread(s)\n", so.cases.size(), procedures.size(),
             so.threads);
  const auto status = StatusReporter::on_stderr("gpm study effects", progress_mode(o.progress));
  const std::size_t runs = so.cases.size() * procedures.size();
  std::size_t done = 0;
  status->update(fmt::format("0 of {} runs done", runs));
  const auto study = scenario::run_effects_study(procedures, so, [&](const scenario::EffectsRow& r) {
    status->update(fmt::format("{} of {} runs done", ++done, runs));
    fmt::print("  {:<17} {:<15} calibrated / floor {:>7.2f}, worst {} {:.1f} {}{} ({:.1f} s)\n", r.procedure,
               r.effect, r.floor_ratio, r.worst_param, r.worst_error_um, um(), r.failure ? " [" + *r.failure + "]" : "",
               r.seconds);
    std::fflush(stdout);
  });
  status->finish();
  scenario::write_effects_study(study, out);
  fmt::print("{}", scenario::effects_markdown_table(study));
  fmt::print("{} runs in {:.0f} s\n", study.rows.size(), study.seconds);
  print_written(out);  // effects.md, effects.html, effects.json, figures
}

extern "C" char** environ;

// The folder holding the gpm Python module beside this executable: the build
// tree's build/python for build/app/gpm, PREFIX/lib/python3/dist-packages for
// PREFIX/bin/gpm; empty when neither holds it (the interpreter's own path then).
std::string python_module_dir() {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) return {};
  const std::filesystem::path prefix = exe.parent_path().parent_path();
  for (const auto& dir : {prefix / "python", prefix / "lib" / "python3" / "dist-packages"}) {
    for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
      const std::string name = entry.path().filename().string();
      if (name.starts_with("gpm.") && name.ends_with(".so")) return dir.string();
    }
  }
  return {};
}

// `--scheduler ADDRESS`: the study runs on that Dask cluster through the
// Python module (python/study.py main), in the interpreter the module is
// built for ($GPM_PYTHON, default Debian's /usr/bin/python3); its exit code is ours.
void run_population_dask(const StudyOptions& o) {
  const char* env_python = std::getenv("GPM_PYTHON");
  const std::string python = env_python && *env_python ? env_python : "/usr/bin/python3";
  std::vector<std::string> args = {python, "-c", "import sys, gpm.study; sys.exit(gpm.study.main(sys.argv[1:]))",
                                   o.scenario, "-o", o.out, "--scheduler", o.scheduler};
  if (o.seeds.empty()) args.insert(args.end(), {"--count", std::to_string(o.population_count)});
  else args.insert(args.end(), {"--seeds", o.seeds});
  if (o.keep_effects) args.emplace_back("--keep-effects");
  const std::string dir = python_module_dir();
  if (!dir.empty()) {
    const char* old = std::getenv("PYTHONPATH");
    ::setenv("PYTHONPATH", (old && *old ? dir + ":" + old : dir).c_str(), 1);
  }
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::fflush(stdout);
  pid_t pid = 0;
  if (const int err = ::posix_spawn(&pid, python.c_str(), nullptr, nullptr, argv.data(), environ); err != 0)
    throw InputError(fmt::format("--scheduler: cannot run the Python interpreter {} (set GPM_PYTHON): {}", python,
                                 std::strerror(err)));
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  set_exit(WIFEXITED(status) ? WEXITSTATUS(status) : 1);
}

// Population study (run/population_study.hpp): the scenario over N robots of the class.
void run_population(const StudyOptions& o) {
  if (std::filesystem::exists(o.out) && !std::filesystem::is_directory(o.out))
    throw InputError(fmt::format("-o: '{}' exists and is not a folder", o.out));
  if (!o.scheduler.empty() && o.threads_given)
    throw InputError("--threads: not with --scheduler (the Dask workers run the robots; give dask-worker --nthreads)");
  scenario::PopulationOptions po;
  po.count = o.population_count;
  po.keep_effects = o.keep_effects;
  po.threads = o.threads;
  if (!o.seeds.empty())
    for (const std::string& s : split_unique_list(o.seeds, "--seeds"))
      po.seeds.push_back(static_cast<std::uint64_t>(parse_bounded(s, limits::kSeed, "--seeds")));
  if (!o.scheduler.empty()) return run_population_dask(o);
  fmt::print("population study: {} robots of {} on {} thread(s){}\n", po.seeds.empty() ? po.count : static_cast<int>(po.seeds.size()),
             o.scenario, po.threads, po.keep_effects ? " (the scenario's effects)" : " (every effect drawn per robot)");
  std::fflush(stdout);
  const auto status = StatusReporter::on_stderr("gpm study population", progress_mode(o.progress));
  status->update("robots running");
  const auto study = scenario::run_population_study(
      o.scenario, po, [&status](const scenario::PopulationRobot& r, int done, int total) {
        status->update(fmt::format("{} of {} robots done", done, total));
        if (r.failure)
          fmt::print("  [{}/{}] robot {}: failed: {} ({:.0f} s)\n", done, total, r.seed, *r.failure, r.seconds);
        else
          fmt::print("  [{}/{}] robot {}: positioning {:.2f} {} RMS (stated 1-sigma {:.2f}), worst parameter {:.1f} "
                     "sigma ({}), model test {} ({:.0f} s)\n",
                     done, total, r.seed, r.positioning.rms_um, um(), r.positioning.stated_sigma_rms_um, r.worst_sigma_ratio,
                     r.worst_param, r.model_test_passed ? (*r.model_test_passed ? "passes" : "fails") : "-", r.seconds);
        std::fflush(stdout);
      });
  status->finish();
  scenario::write_population_study(study, o.out);
  fmt::print("{}", scenario::population_markdown(study));
  fmt::print("{} robots in {:.0f} s\n", study.robots.size(), study.seconds);
  print_written(o.out);  // population.md, .html, .json, figures, robot_SEED.yaml
}

}  // namespace

void add_study(CLI::App& app) {
  auto o = std::make_shared<StudyOptions>();
  auto* study = app.add_subcommand("study", "Calibration studies: samples, crb, montecarlo on synthetic data; effects on the twin");
  study->require_subcommand(1);

  auto* samples = study->add_subcommand("samples", "Write synthetic encoder samples (with true x,y) of a known robot");
  samples->add_option("--actual", o->actual, "table5, section3 (paper values) or a robot file")->capture_default_str();
  samples->add_option("--n", o->n, "Number of samples")->capture_default_str()->transform(number_in(limits::kSamples));
  samples->add_option("--radius", o->radius, "Disc radius around home (mm)")->capture_default_str();
  samples->add_option("--seed", o->seed, "Random seed")->capture_default_str()->transform(number_in(limits::kSeed));
  samples->add_option("--sigma", o->sigma, "Encoder noise 1-sigma (rad)")->capture_default_str();
  samples->add_option("-o,--output", o->out, "Samples CSV")->required();
  samples->callback([o] { run_samples(*o); });

  auto* crb = study->add_subcommand("crb", "Cramer-Rao bound of the free parameters for given samples");
  crb->add_option("--data", o->data, "Noiseless samples CSV of the true robot")->required();
  crb->add_option("--actual", o->actual, "The true robot: table5, section3 or a robot file")->capture_default_str();
  crb->add_option("--fix", o->fix, "Fixed parameters")->capture_default_str();
  crb->add_option("--sigma", o->sigma, "Encoder noise 1-sigma (rad)")->required();
  crb->callback([o] { run_crb(*o); });

  auto* mc = study->add_subcommand("montecarlo", "Noisy trials: empirical RMS error over the Cramer-Rao bound");
  mc->add_option("--actual", o->actual, "The true robot: table5, section3 or a robot file")->capture_default_str();
  mc->add_option("--fix", o->fix, "Fixed parameters (held at their true values)")->capture_default_str();
  mc->add_option("--trials", o->trials, "Number of noisy trials")->capture_default_str()->transform(number_in(limits::kTrials));
  mc->add_option("--n", o->n, "Samples per trial")->capture_default_str()->transform(number_in(limits::kSamples));
  mc->add_option("--radius", o->radius, "Disc radius around home (mm)")->capture_default_str();
  mc->add_option("--sigma", o->sigma, "Encoder noise 1-sigma (rad); default 1e-4");
  mc->add_option("--seed", o->seed, "Random seed")->capture_default_str()->transform(number_in(limits::kSeed));
  mc->add_option("--costs", o->costs, "Error functions to compare")->capture_default_str();
  mc->add_flag("--check", o->check, "Exit 1 unless the rms ratio is within the goals (ml 1.05, j3 1.2)");
  mc->add_flag("--check-each", o->check_each,
               "Exit 1 unless every parameter's ratio is within the goals (needs ~500 trials to beat sampling noise)");
  add_progress_option(mc, o->progress);
  mc->callback([o] { run_montecarlo(*o); });

  auto* effects = study->add_subcommand(
      "effects", "Each physical effect of the realistic twin alone, all and none: its bias on the identified "
                 "parameters and on the accuracy after calibration, for today's and the former default procedure");
  effects->add_option("-o,--output", o->out, "Output folder (effects.md, effects.html, effects.json, figures)")
      ->required();
  effects->add_option("--effects", o->effects,
                      "Comma-separated cases (default every one: ideal, compliance, clearance, friction, thermal, "
                      "encoder_cyclic, encoder_skew, all, drive_train, encoder_motor, every)");
  effects->add_option("--count", o->effects_count, "Poses per calibration, 12 to 2000 (default: each procedure's own)");
  effects->add_option("--threads", o->threads, "Runs in parallel")->capture_default_str();
  add_progress_option(effects, o->progress);
  effects->callback([o] { run_effects(*o); });

  auto* population = study->add_subcommand(
      "population", "A scenario over N robots of the class (actual geometry and every effect drawn per robot): the "
                    "positioning error of each calibrated model, and its parameter errors in their stated 1-sigma");
  population->add_option("scenario", o->scenario, "Scenario: a YAML file, or a name from the scenario library (e.g. main; gpm help scenarios)")->required();
  population->add_option("-o,--output", o->out, "Output folder (population.md/.html/.json, figures, robot_SEED.yaml)")
      ->required();
  population->add_option("--count", o->population_count, "Robots (seeds: the scenario's seed + 0 .. count - 1)")
      ->capture_default_str()
      ->transform(number_in(limits::kPopulation));
  population->add_option("--seeds", o->seeds, "Comma-separated seeds of the robots to run instead (re-run chosen ones)");
  population->add_flag("--keep-effects", o->keep_effects,
                       "Keep the scenario's effects (only the geometry differs between robots)");
  auto* threads = population->add_option("--threads", o->threads, "Robots in parallel")
                      ->capture_default_str()
                      ->transform(number_in(limits::kThreads));
  population->add_option("--scheduler", o->scheduler,
                         "A running Dask scheduler (tcp://HOST:8786): the robots run on its workers through the "
                         "Python module (gpm.study); writes population.json, .csv, .png, robot_SEED.yaml");
  add_progress_option(population, o->progress);
  population->callback([o, threads] {
    o->threads_given = threads->count() > 0;
    o->scenario = resolve_scenario(o->scenario);  // a file, or a library name
    run_population(*o);
  });
}

}  // namespace gpm::cli
