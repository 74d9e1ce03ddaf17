// gpm simulate SCENARIO.yaml -o DIR: runs a scenario on the MuJoCo twin and
// writes DIR/samples.csv, trajectory.csv, actual.yaml and model.xml
// (sim/simulate.hpp). Bad input exits 2 with one line.
#include <chrono>
#include <memory>
#include <string>

#include <fmt/format.h>

#include "app/cli_text.hpp"
#include "app/commands.hpp"
#include "app/data_files.hpp"
#include "app/progress_mode.hpp"
#include "app/written_files.hpp"
#include "models/errors.hpp"
#include "models/output_file.hpp"
#include "calib/model_test.hpp"
#include "calib/reading_model.hpp"
#include "run/sampling_design.hpp"
#include "sim/simulate.hpp"

namespace gpm::cli {
namespace {

struct SimulateOptions {
  std::string scenario;
  std::string out;
  std::string progress;  // --progress (app/progress_mode.hpp)
};

}  // namespace

void add_simulate(CLI::App& app) {
  auto opt = std::make_shared<SimulateOptions>();
  auto* cmd = app.add_subcommand(
      "simulate", "Simulate a scenario on the MuJoCo twin: DIR/samples.csv, trajectory.csv, actual.yaml, model.xml");
  cmd->add_option("scenario", opt->scenario, "Scenario: a YAML file, or a name from the scenario library (gpm help scenarios); its keys: gpm help schema")->required();
  cmd->add_option("-o,--out", opt->out, "Output folder")->required();
  add_progress_option(cmd, opt->progress);
  cmd->callback([opt] {
    const auto t0 = std::chrono::steady_clock::now();
    opt->scenario = resolve_scenario(opt->scenario);  // a file, or a library name
    // DIR's files against every input (the scenario and the files it names),
    // and not a hardware session's folder: before anything is read.
    check_output_folder(opt->out, sim::simulation_output_names());
    sim::Scenario s = sim::load_scenario(opt->scenario);
    // `designed` and `trajectory` plans: poses designed for the default gauge.
    scenario::design_sampling(s, default_free_mask(),
                              calib::reading_sigma(calib::encoder_step_rad(s.twin.encoder.bits), s.twin.encoder.noise_rad));
    sim::SimulationResult r;
    try {
      Progress progress = counting_progress(progress_mode(opt->progress), "gpm simulate", "simulated s");
      r = sim::simulate_to_folder(s, opt->out, &progress);  // trajectory.csv streamed, all files or none
    } catch (const sim::SimError& e) {
      throw InputError(fmt::format("{}: {}", opt->scenario, e.what()));
    }
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    int unsettled = 0;
    for (const auto& smp : r.samples) unsettled += smp.settled ? 0 : 1;
    const bool on_the_fly = s.sampling && s.sampling->pattern == sim::PosePattern::kTrajectory;
    fmt::print("scenario         {}\n", s.name);
    if (on_the_fly)  // never at rest by design: "settled" does not apply
      fmt::print("samples          {} (taken on the fly along the excitation path)\n", r.samples.size());
    else if (unsettled == 0)
      fmt::print("samples          {} (each taken at rest)\n", r.samples.size());
    else
      fmt::print("samples          {} ({} of them not at rest within the settle timeout: marked settled = 0)\n",
                 r.samples.size(), unsettled);
    fmt::print("trajectory rows  {}\n", r.log.count);
    fmt::print("simulated        {:.3f} s in {:.3f} s wall\n", r.simulated_s, wall);
    fmt::print("loop closure     max gap {:.3g} {}\n", r.max_violation_m * 1e6, um());
    fmt::print("drive torque     max {:.3f} N m\n", r.max_torque);
    print_written(opt->out, 17);  // samples.csv, trajectory.csv, actual.yaml, model.xml
  });
}

}  // namespace gpm::cli
