// bench_sim: physics steps per second of the twin (servo drives and encoders
// included) against bare mj_step on the same compiled model, and optionally
// writes that model's MJCF for mujoco-testspeed (bench/sim_vs_testspeed.sh).
//   bench_sim [--steps N] [--write-model FILE] [--timestep S] [--rate HZ]
//             [--effects ideal|realistic|compliance|clearance|friction|thermal|encoder|drive|all] [--profile]
// Prints "name steps_per_second" lines and "sim_seconds_per_wall_second"
// of the twin (steps/s x timestep: the figure that compares runs at
// different timesteps; effects: realistic needs 0.25 ms, see SCHEMA.md).
// With effects, the ideal twin at the same timestep and rate is timed in
// fifteen interleaved rounds of steps / 10 (so that load from other processes
// hits both alike) and "effects_vs_ideal_per_step" is their ratio of best
// rates in thread CPU time (goal for
// realistic: at most 1.5). --profile prints MuJoCo's stage timers per step
// of both twins (where a step's time goes), and of the effects twin driven
// along a circle by its controller, with the solver's iterations per step.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <string>
#include <tuple>

#include "models/robot_yaml.hpp"
#include "sim/sampling.hpp"
#include "sim/twin.hpp"

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// CPU seconds of this thread (insensitive to other processes taking the core).
double thread_cpu_s() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
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

// MuJoCo's own timers (mjData.timer, clocked by mjcb_time) per twin step over
// n steps, in microseconds, beside the whole twin step's time: where a step's
// time goes (the twin's own part is the step minus MuJoCo's stages).
void print_profile(const char* name, const gpm::sim::TwinModel& model, gpm::sim::TwinState& state, long n) {
  mjData* d = state.data.get();
  // Monotonic clock (vDSO, tens of ns a call; the thread CPU clock is a system call).
  mjcb_time = [] {
    return static_cast<mjtNum>(1e-3 * std::chrono::duration<double, std::nano>(Clock::now().time_since_epoch()).count());
  };  // microseconds
  for (int t = 0; t < mjNTIMER; ++t) d->timer[t].duration = 0.0, d->timer[t].number = 0;
  const auto t0 = Clock::now();
  for (long k = 0; k < n; ++k) gpm::sim::twin_step(model, state);
  const double step_us = 1e6 * seconds_since(t0) / static_cast<double>(n);
  mjcb_time = nullptr;
  static const char* const kNames[mjNTIMER] = {"step", "forward", "inverse", "position", "velocity", "actuation",
                                               "acceleration", "constraint", "pos_kinematics", "pos_inertia",
                                               "pos_collision", "pos_make", "pos_project"};
  std::printf("%s_profile_us_per_step twin_step %.3f", name, step_us);
  for (int t = mjTIMER_POSITION; t < mjNTIMER; ++t)
    if (t != mjTIMER_POS_COLLISION) std::printf(" %s %.3f", kNames[t], d->timer[t].duration / static_cast<double>(n));
  std::printf("\n");
}

// The twin driven along a 60 mm circle in 4 s by the controller (one drive
// loop tick a step, as gpm run's accuracy test drives the main job's twin):
// thread CPU per tick without timers, then MuJoCo's stage timers per tick,
// and the constraint solver's iterations per step (mean, largest, share of
// steps with more than one) and rows, over n ticks.
void print_moving_profile(const char* name, const gpm::sim::TwinModel& model, const gpm::Robot& robot, long n) {
  using namespace gpm::sim;
  TwinState state(model, 1);
  Session session = make_session(model, state, robot, nullptr);
  const CirclePath circle{robot.home, 60.0, 4.0, 1e9};
  const double period = model.timestep_s() * model.steps_per_tick();
  long tick = 0;
  const double c0 = thread_cpu_s();
  for (long k = 0; k < n; ++k) advance(session, path_at(circle, period * static_cast<double>(tick++)));
  const double tick_us = 1e6 * (thread_cpu_s() - c0) / static_cast<double>(n);
  mjData* d = state.data.get();
  mjcb_time = [] {
    return static_cast<mjtNum>(1e-3 * std::chrono::duration<double, std::nano>(Clock::now().time_since_epoch()).count());
  };
  for (int t = 0; t < mjNTIMER; ++t) d->timer[t].duration = 0.0, d->timer[t].number = 0;
  long iterations = 0, most = 0, more = 0, rows = 0;
  for (long k = 0; k < n; ++k) {
    advance(session, path_at(circle, period * static_cast<double>(tick++)));
    iterations += d->solver_iter, rows += d->nefc, more += d->solver_iter > 1;
    most = std::max<long>(most, d->solver_iter);
  }
  mjcb_time = nullptr;
  const double per = 1.0 / static_cast<double>(n);
  std::printf("%s_moving_cpu_us_per_tick %.3f (steps per tick %d)\n", name, tick_us, model.steps_per_tick());
  std::printf("%s_moving_mujoco_us_per_tick position %.3f (kinematics %.3f inertia %.3f make %.3f) velocity %.3f "
              "actuation %.3f acceleration %.3f constraint %.3f\n",
              name, d->timer[mjTIMER_POSITION].duration * per, d->timer[mjTIMER_POS_KINEMATICS].duration * per,
              d->timer[mjTIMER_POS_INERTIA].duration * per, d->timer[mjTIMER_POS_MAKE].duration * per,
              d->timer[mjTIMER_VELOCITY].duration * per, d->timer[mjTIMER_ACTUATION].duration * per,
              d->timer[mjTIMER_ACCELERATION].duration * per, d->timer[mjTIMER_CONSTRAINT].duration * per);
  std::printf("%s_moving_solver iterations_per_step %.3f largest %ld more_than_one %.1f%% constraint_rows %.2f\n", name,
              static_cast<double>(iterations) * per, most, 100.0 * static_cast<double>(more) * per,
              static_cast<double>(rows) * per);
}

}  // namespace

int main(int argc, char** argv) {
  long steps = 200000;
  std::string model_out, effects = "ideal";
  double timestep = 0.0005, rate = 2000.0;
  bool profile = false;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--steps") && i + 1 < argc) steps = std::stol(argv[++i]);
    else if (!std::strcmp(argv[i], "--write-model") && i + 1 < argc) model_out = argv[++i];
    else if (!std::strcmp(argv[i], "--effects") && i + 1 < argc) effects = argv[++i];
    else if (!std::strcmp(argv[i], "--timestep") && i + 1 < argc) timestep = std::stod(argv[++i]);
    else if (!std::strcmp(argv[i], "--rate") && i + 1 < argc) rate = std::stod(argv[++i]);
    else if (!std::strcmp(argv[i], "--profile")) profile = true;
    else {
      std::fprintf(stderr, "usage: bench_sim [--steps N] [--write-model FILE] [--effects ideal|realistic|...|encoder_geometry|all] "
                           "[--timestep S] [--rate HZ] [--profile]\n");
      return 2;
    }
  }
  using namespace gpm;
  using namespace gpm::sim;
  // One effect of the realistic preset alone, all of them, or none.
  const Effects real = realistic_effects();
  Effects fx;
  if (effects == "realistic") fx = real;
  else if (effects == "compliance") fx.mjcf.compliance_rad_per_Nm = real.mjcf.compliance_rad_per_Nm;
  else if (effects == "clearance") fx.mjcf.clearance_m = real.mjcf.clearance_m;
  else if (effects == "friction") fx.mjcf.coulomb_Nm = real.mjcf.coulomb_Nm, fx.mjcf.viscous_Nm_s = real.mjcf.viscous_Nm_s;
  else if (effects == "thermal") fx.thermal = real.thermal;
  else if (effects == "encoder") fx.encoder_cyclic_rad = real.encoder_cyclic_rad, fx.encoder_skew_s = real.encoder_skew_s;
  else if (effects == "drive" || effects == "encoder_geometry" || effects == "all") {
    // Drawn as the randomized preset draws them (sim/drive_train.hpp, sim/encoder_error.hpp),
    // motor encoders behind 10:1; "all": both on top of the realistic preset.
    if (effects == "all") fx = real;
    fx.gear_ratio = 10.0;
    Rng draw(1);
    if (effects != "encoder_geometry") draw_drive_train(draw, fx);
    if (effects != "drive") draw_encoder_and_geometry(draw, fx);
    if (effects == "encoder_geometry") fx.thermal.rise_K = 3.0, fx.thermal.expansion_per_K = 23e-6;
  } else if (effects != "ideal") {
    std::fprintf(stderr, "bench_sim: --effects: '%s' is not ideal, realistic, compliance, clearance, friction, "
                         "thermal, encoder, drive, encoder_geometry or all\n", effects.c_str());
    return 2;
  }
  const Robot robot;  // nominal
  TwinConfig config;
  config.encoder.noise_rad = 1e-5;  // the noise path included
  config.mjcf.timestep_s = timestep;
  config.mjcf.solref_timeconst_s = std::max(config.mjcf.solref_timeconst_s, 2.0 * timestep);
  config.servo_rate_hz = rate;
  config.effects = fx;
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

  // The ideal twin at the same timestep and drive rate, interleaved with this one.
  double effects_rate = twin_rate, ideal_rate = 0.0, effects_cpu_rate = 0.0, ideal_cpu_rate = 0.0;
  if (effects != "ideal") {
    TwinConfig ideal_config = config;
    ideal_config.effects = Effects{};
    const TwinModel ideal(robot, ideal_config);
    TwinState si(ideal, 1), se(model, 1);
    for (TwinState* st : {&si, &se})
      twin_command(*st, st->last.readings + Eigen::Vector3d(0.001, -0.001, 0.0005), Eigen::Vector3d::Zero());
    const long n = std::max(1L, steps / 10);
    for (int round = 0; round < 15; ++round) {
      double c0 = thread_cpu_s();
      ideal_rate = std::max(ideal_rate, best_rate(n, 1, [&](long m) {
        for (long k = 0; k < m; ++k) twin_step(ideal, si);
      }));
      double c1 = thread_cpu_s();
      ideal_cpu_rate = std::max(ideal_cpu_rate, n / (c1 - c0));
      effects_rate = std::max(effects_rate, best_rate(n, 1, [&](long m) {
        for (long k = 0; k < m; ++k) twin_step(model, se);
      }));
      effects_cpu_rate = std::max(effects_cpu_rate, n / (thread_cpu_s() - c1));
    }
    // Constraint solver work per step (MuJoCo's own counters), both twins.
    for (auto [name, m, st] : {std::tuple{"ideal", &ideal, &si}, std::tuple{"effects", &model, &se}}) {
      double iter = 0.0, rows = 0.0;
      const int n = 1000;
      for (int k = 0; k < n; ++k) {
        twin_step(*m, *st);
        iter += st->data->solver_iter, rows += st->data->nefc;
      }
      std::printf("%s_nv %d solver_iterations_per_step %.2f constraint_rows %.2f\n", name, m->mj()->nv, iter / n,
                  rows / n);
    }
    if (profile) {
      for (auto [name, m, st] : {std::tuple{"ideal", &ideal, &si}, std::tuple{"effects", &model, &se}})
        print_profile(name, *m, *st, n);
      print_moving_profile("effects", model, robot, n);
    }
  }

  std::printf("bare_mj_step %.0f\n", bare_rate);
  std::printf("twin_step %.0f\n", twin_rate);
  std::printf("twin_with_controller %.0f\n", ctrl_rate);
  std::printf("twin_overhead_vs_bare %.3f\n", bare_rate / twin_rate - 1.0);
  std::printf("sim_seconds_per_wall_second %.3f\n", twin_rate * timestep);
  if (effects != "ideal") {
    std::printf("ideal_twin_step %.0f\n", ideal_rate);
    // Per step, from thread CPU time (the wall-clock figure swings with the machine's load).
    std::printf("effects_vs_ideal_per_step %.2f\n", ideal_cpu_rate / effects_cpu_rate);
    std::printf("effects_vs_ideal_per_step_wall %.2f\n", ideal_rate / effects_rate);
  }
  return 0;
}
