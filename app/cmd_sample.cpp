// gpm sample: a calibration sampling session on the hardware named by a
// hardware file (the twin or real drives: only the config differs). Samples
// are appended and flushed as they are taken; --resume continues a file. A
// scenario whose poses are designed (designed, trajectory) is sampled by the
// procedure of gpm run --hardware, without the calibration.
// Exit 0 done; 1 the session failed (drives disabled, samples kept); 2 bad
// input; 130 interrupted (SIGINT/SIGTERM/SIGHUP: drives disabled, samples kept).
#include <cstdio>
#include <filesystem>

#include <fmt/format.h>

#include "app/commands.hpp"
#include "app/data_files.hpp"
#include "hw/hardware_config.hpp"
#include "hw/hw_errors.hpp"
#include "hw/procedures/sampling_session.hpp"
#include "hw/procedures/session_plan.hpp"
#include "hw/procedures/stop_on_signal.hpp"
#include "models/errors.hpp"
#include "models/measured_data.hpp"
#include "models/output_file.hpp"
#include "run/run_spec.hpp"
#include "run/runner.hpp"

namespace gpm::cli {
namespace {

struct SampleArgs {
  std::string hardware, poses, scenario, out;
  bool resume = false;
};

// The resume hint of a stopped session that kept samples in a.out.
std::string go_on_line(const SampleArgs& a) {
  if (!std::filesystem::exists(a.out)) return {};
  return fmt::format("; to go on: gpm sample --hardware {} {} {} -o {} --resume", a.hardware,
                     a.poses.empty() ? "--scenario" : "--poses", a.poses.empty() ? a.scenario : a.poses, a.out);
}

// A scenario whose poses are designed (pattern designed or trajectory): the
// procedure of gpm run --hardware without its calibration (run/runner.hpp):
// the poses designed for this hardware, a path on the fly sampled in passes.
void sample_designed(const scenario::RunSpec& spec, const SampleArgs& a) {
  try {
    const scenario::HardwareSampling r = scenario::sample_through_hardware(spec, a.out);
    if (r.first_pass)
      std::printf("first pass %s (%s); its %zu samples in %s planned the second pass\n",
                  r.first_pass->planned ? "as planned" : "ended early", r.first_pass->why.c_str(), r.first_pass->samples,
                  scenario::first_pass_samples_path(a.out).c_str());
    std::printf("%s: %zu samples in %s (%.2f s of robot time)\n", r.description.c_str(), r.samples, a.out.c_str(),
                r.robot_time_s);
  } catch (const hw::Interrupted& e) {
    std::fprintf(stderr, "gpm: %s%s\n", e.what(), go_on_line(a).c_str());
    set_exit(hw::kInterruptedExit);
  } catch (const hw::HardwareError& e) {
    std::fprintf(stderr, "gpm: error: %s%s\n", e.what(), go_on_line(a).c_str());
    set_exit(1);
  }
}

void run_sample(SampleArgs a) {
  if (!a.scenario.empty()) a.scenario = resolve_scenario(a.scenario);  // a file, or a library name
  if (a.poses.empty() == a.scenario.empty()) {
    throw InputError("gpm sample: give exactly one of --poses POSES.yaml or --scenario S.yaml");
  }
  // Never one of the inputs, nor the samples file of a gpm run --hardware
  // folder (models/measured_data.hpp), before anything is read; a sampling
  // log is continued by hw::SampleLog's rules (--resume, one session at a time).
  declare_output(a.out);
  refuse_measured_file(a.out, nullptr, /*sampling_session=*/true);
  const hw::HardwareConfig config = hw::load_hardware_config(a.hardware);
  if (!a.scenario.empty()) {
    scenario::RunSpec spec = scenario::load_run_spec(a.scenario);
    if (spec.sim.sampling && spec.sim.sampling->needs_design()) {
      spec.hardware = a.hardware;
      spec.hardware_resume = a.resume;
      sample_designed(spec, a);
      return;
    }
  }
  hw::SessionPlan plan = a.poses.empty() ? hw::plan_from_scenario(a.scenario) : hw::load_poses_plan(a.poses);
  plan.modes = config.modes;
  if (config.dither_mm) plan.dither_mm = *config.dither_mm;
  auto robot = hw::make_hardware(config);
  const hw::StopOnSignal signals;
  hw::SampleLog log(a.out, a.resume);
  try {
    const hw::SessionResult r = hw::run_sampling_session(*robot, plan, log, signals.flag());
    std::printf("%s: %ld samples taken, %ld already in %s, %zu in all (%.2f s session time)\n",
                robot->describe().c_str(), r.taken, r.skipped, a.out.c_str(), log.size(), r.duration_s);
  } catch (const InputError&) {
    log.close_and_discard_if_empty();
    throw;
  } catch (const hw::Interrupted& e) {
    log.close_and_discard_if_empty();
    std::fprintf(stderr, "gpm: %s\n", e.what());
    set_exit(hw::kInterruptedExit);
  } catch (const hw::HardwareError& e) {
    log.close_and_discard_if_empty();
    std::fprintf(stderr, "gpm: error: %s%s\n", e.what(), go_on_line(a).c_str());
    set_exit(1);
  }
}

}  // namespace

void add_sample(CLI::App& app) {
  auto args = std::make_shared<SampleArgs>();
  auto* cmd = app.add_subcommand("sample", "Run a calibration sampling session on the twin or real drives (hardware file)");
  cmd->add_option("--hardware", args->hardware, "hardware file (backend twin, modbus or plugin, safety limits; gpm help hardware)")->required();
  cmd->add_option("--poses", args->poses, "poses file: poses: [[x, y], ...] (mm)");
  cmd->add_option("--scenario", args->scenario, "scenario whose sampling plan gives the poses (a file or a library name: gpm help scenarios)");
  cmd->add_option("-o,--output", args->out, "samples CSV, appended as samples are taken")->required();
  cmd->add_flag("--resume", args->resume, "continue an existing samples file, skipping recorded poses");
  cmd->callback([args] { run_sample(*args); });
}

}  // namespace gpm::cli
