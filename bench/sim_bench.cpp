// bench_sim: physics steps per second of the twin (servo drives and encoders
// included) against bare mj_step on the same compiled model, and optionally
// writes that model's MJCF for mujoco-testspeed (bench/sim_vs_testspeed.sh).
//   bench_sim [--steps N] [--write-model FILE] [--effects ideal|realistic]
//             [--timestep S] [--rate HZ]
// Prints "name steps_per_second" lines and "sim_seconds_per_wall_second"
// of the twin (steps/s x timestep: the figure that compares runs at
// different timesteps; effects: realistic needs 0.25 ms, see SCHEMA.md).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>

#include "models/robot_yaml.hpp"
#include "sim/sampling.hpp"
#include "sim/twin.hpp"

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Best of `trials` timings of fn() over n steps, in steps per second.
template <class F>
double best_rate(long n, int trials, F&& fn) {
  double best = 0.0;
  for (int t = 0; t < trials; ++t) {
    const auto t0 = Clock::now();
    fn(n);
    best = std::max(best, n / seconds_since(t0));
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  long steps = 200000;
  std::string model_out, effects = "ideal";
  double timestep = 0.0005, rate = 2000.0;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--steps") && i + 1 < argc) steps = std::stol(argv[++i]);
    else if (!std::strcmp(argv[i], "--write-model") && i + 1 < argc) model_out = argv[++i];
    else if (!std::strcmp(argv[i], "--effects") && i + 1 < argc) effects = argv[++i];
    else if (!std::strcmp(argv[i], "--timestep") && i + 1 < argc) timestep = std::stod(argv[++i]);
    else if (!std::strcmp(argv[i], "--rate") && i + 1 < argc) rate = std::stod(argv[++i]);
    else {
      std::fprintf(stderr, "usage: bench_sim [--steps N] [--write-model FILE] [--effects ideal|realistic] "
                           "[--timestep S] [--rate HZ]\n");
      return 2;
    }
  }
  if (effects != "ideal" && effects != "realistic") {
    std::fprintf(stderr, "bench_sim: --effects: '%s' is not ideal or realistic\n", effects.c_str());
    return 2;
  }
  using namespace gpm;
  using namespace gpm::sim;
  const Robot robot;  // nominal
  TwinConfig config;
  config.encoder.noise_rad = 1e-5;  // the noise path included
  config.mjcf.timestep_s = timestep;
  config.mjcf.solref_timeconst_s = std::max(config.mjcf.solref_timeconst_s, 2.0 * timestep);
  config.servo_rate_hz = rate;
  if (effects == "realistic") config.effects = realistic_effects();
  const TwinModel model(robot, config);
  if (!model_out.empty()) write_file_atomic(model_out, model.xml());

  // Bare mj_step on the twin's own mjModel, drives off (ctrl noise as testspeed).
  DataPtr bare(mj_makeData(model.mj()));
  Rng rng(1);
  const double bare_rate = best_rate(steps, 3, [&](long n) {
    for (long k = 0; k < n; ++k) {
      for (int a = 0; a < model.mj()->nu; ++a) bare->ctrl[a] = 0.01 * rng.normal();
      mj_step(model.mj(), bare.get());
    }
  });

  // Twin: servo loop and encoders at every step (2 kHz), holding a commanded offset.
  TwinState state(model, 1);
  twin_command(state, state.last.readings + Eigen::Vector3d(0.001, -0.001, 0.0005), Eigen::Vector3d::Zero());
  const double twin_rate = best_rate(steps, 3, [&](long n) {
    for (long k = 0; k < n; ++k) twin_step(model, state);
  });

  // Twin driven along a circle by the controller (IK every servo period), logging off.
  TwinState state2(model, 1);
  Session session = make_session(model, state2, robot, nullptr);
  const CirclePath circle{robot.home, 30.0, 1.0, 1e9};
  const double period = model.timestep_s() * model.steps_per_tick();
  long tick = 0;
  const double ctrl_rate = best_rate(steps, 3, [&](long n) {
    for (long k = 0; k < n; k += model.steps_per_tick()) advance(session, path_at(circle, period * tick++));
  });

  std::printf("bare_mj_step %.0f\n", bare_rate);
  std::printf("twin_step %.0f\n", twin_rate);
  std::printf("twin_with_controller %.0f\n", ctrl_rate);
  std::printf("twin_overhead_vs_bare %.3f\n", bare_rate / twin_rate - 1.0);
  std::printf("sim_seconds_per_wall_second %.3f\n", twin_rate * timestep);
  return 0;
}
