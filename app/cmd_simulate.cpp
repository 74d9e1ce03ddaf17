// gpm simulate SCENARIO.yaml -o DIR: runs a scenario on the MuJoCo twin and
// writes DIR/samples.csv, trajectory.csv, actual.yaml and model.xml
// (sim/simulate.hpp). Bad input exits 2 with one line.
#include <chrono>
#include <memory>
#include <string>

#include <fmt/format.h>

#include "app/commands.hpp"
#include "app/data_files.hpp"
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
};

}  // namespace

void add_simulate(CLI::App& app) {
  auto opt = std::make_shared<SimulateOptions>();
  auto* cmd = app.add_subcommand(
      "simulate", "Simulate a scenario on the MuJoCo twin: DIR/samples.csv, trajectory.csv, actual.yaml, model.xml");
  cmd->add_option("scenario", opt->scenario, "Scenario: a YAML file, or a name from the scenario library (gpm help scenarios); its keys: gpm help schema")->required();
  cmd->add_option("-o,--out", opt->out, "Output folder")->required();
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
      Progress progress = Progress::terminal("gpm simulate", "simulated s");  // on a terminal only
      r = sim::simulate_to_folder(s, opt->out, &progress);  // trajectory.csv streamed, all files or none
    } catch (const sim::SimError& e) {
      throw InputError(fmt::format("{}: {}", opt->scenario, e.what()));
    }
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    int unsettled = 0;
    for (const auto& smp : r.samples) unsettled += smp.settled ? 0 : 1;
    fmt::print("scenario         {}\n", s.name);
    fmt::print("samples          {} ({} did not settle)\n", r.samples.size(), unsettled);
    fmt::print("trajectory rows  {}\n", r.log.count);
    fmt::print("simulated        {:.3f} s in {:.3f} s wall\n", r.simulated_s, wall);
    fmt::print("loop closure     max gap {:.3g} um\n", r.max_violation_m * 1e6);
    fmt::print("drive torque     max {:.3f} N m\n", r.max_torque);
    fmt::print("wrote            {}/samples.csv, trajectory.csv, actual.yaml, model.xml\n", opt->out);
  });
}

}  // namespace gpm::cli
