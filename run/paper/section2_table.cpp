#include "run/paper/section2_table.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <fmt/format.h>

#include "calib/paper_values.hpp"
#include "hw/hardware_config.hpp"
#include "hw/procedures/zero_offset_search.hpp"
#include "models/kinematics.hpp"

namespace gpm::paper {

namespace {

// The safety limits of the project's example twin (hw/examples/twin.yaml).
hw::SafetyLimits example_safety() {
  hw::SafetyLimits s;
  s.joint_min = {0.3, 2.4, 4.0};
  s.joint_max = {1.9, 3.8, 5.7};
  s.max_velocity = {1.0, 1.0, 1.0};
  s.max_acceleration = {5.0, 5.0, 5.0};
  s.workspace_centre = {216.5, 250.0};
  s.workspace_radius_mm = 90.0;
  s.workspace_margin_mm = 5.0;
  s.reach_margin_mm = 2.0;
  s.min_transmission = 0.15;
  s.min_direct = 0.15;
  s.max_inconsistency_rad = 0.05;
  s.watchdog_hold_s = 0.1;
  s.watchdog_disable_s = 0.5;
  s.comms_timeout_s = 0.1;
  return s;
}

}  // namespace

Eigen::Vector2d start_for_initial_error(const Robot& model, const Eigen::Vector3d& error) {
  const JointAngles home = inverse_kinematics(model.geometry, model.home, model.branch);
  Geometry g = model.geometry;
  for (int i = 0; i < 3; ++i) g[dth(i)] = 0.0;
  const auto fk = forward_kinematics(g, home.theta_a - error);
  if (!fk) throw std::logic_error("paper: no radical centre for the Table 1 start");
  return fk->p;
}

namespace {

const char* const kStartNote =
    "The three printed initial angles are not one feasible pose of the mechanism (three angles, two degrees "
    "of freedom): the twin starts at the nearest pose, which keeps the feasible part of the paper's error "
    "and drops the rest.";
const char* const kResultNote =
    "The real robot's three results scatter about their mean (encoder resolution, clearance, the search's "
    "final d); the twin's results scatter about its actual offsets by its own amount, so only "
    "the size of the two scatters is comparable.";

// The twin of Table 1 behind the hardware interface: nominal geometry with the twin's offsets.
hw::HardwareConfig table1_hardware(const Robot& actual) {
  hw::HardwareConfig config;
  config.backend = "twin";
  config.controller = actual;  // used only to jog to the starting points (step 1, "by hand")
  config.safety = example_safety();
  hw::TwinBackendConfig twin;
  twin.actual = actual;
  twin.seed = 19;
  twin.period_s = 1.0 / config.rate_hz;
  config.twin = twin;
  return config;
}

// Three rows of experiment k, one per joint: `what` as printed beside ours, starting at `where`.
void add_joint_rows(Table& t, int k, const std::string& what, const Eigen::Vector3d& printed,
                    const Eigen::Vector3d& ours, const char* why, const std::string& where) {
  for (int j = 0; j < 3; ++j) {
    Row row = compare_row(fmt::format("experiment {}: {}, joint {}", k + 1, what, j + 1), "rad",
                          fmt::format("{:.4f}", printed[j]), ours[j], Reason::kSetup, why);
    row.extra_text = where;
    t.rows.push_back(row);
  }
}

// Experiment k's rows: its initial error and its result error per joint against the paper's.
void add_experiment_rows(Table& t, int k, const Eigen::Vector3d& e_paper, const Eigen::Vector3d& paper_result,
                         const Eigen::Vector2d& start, const hw::ZeroSearchResult& r) {
  const std::string where = fmt::format("{:.2f}, {:.2f}", start.x(), start.y());
  add_joint_rows(t, k, "initial error", e_paper, r.initial_offsets - kTable1TwinOffsets, kStartNote, where);
  add_joint_rows(t, k, "result error", paper_result, r.offsets - kTable1TwinOffsets, kResultNote, where);
}

// The spread (max - min) of the three results per joint, the paper's and this run's.
void add_spread_rows(Table& t, const calib::PrintedTable1& pt, const std::array<Eigen::Vector3d, 3>& ours) {
  for (int j = 0; j < 3; ++j) {
    double plo = 1e9, phi = -1e9, olo = 1e9, ohi = -1e9;
    for (int k = 0; k < 3; ++k) {
      plo = std::min(plo, pt.result[k][j]);
      phi = std::max(phi, pt.result[k][j]);
      olo = std::min(olo, ours[static_cast<size_t>(k)][j]);
      ohi = std::max(ohi, ours[static_cast<size_t>(k)][j]);
    }
    t.rows.push_back(compare_row(fmt::format("spread of the three results, joint {}", j + 1), "rad",
                                 fmt::format("{:.4f}", phi - plo), ohi - olo, Reason::kSetup, kResultNote));
  }
}

}  // namespace

Table table1(const Table1Settings& settings) {
  const calib::PrintedTable1 pt = calib::printed_table1();
  Eigen::Vector3d paper_mean = Eigen::Vector3d::Zero();
  for (const auto& r : pt.result) paper_mean += Eigen::Vector3d(r[0], r[1], r[2]) / 3.0;

  Robot actual;  // nominal geometry, offsets of the twin
  for (int i = 0; i < 3; ++i) actual.geometry[dth(i)] = kTable1TwinOffsets[i];
  const hw::HardwareConfig config = table1_hardware(actual);
  hw::ZeroSearchOptions base;
  base.circle_points = settings.circle_points;
  base.d_min_mm = settings.d_min_mm;
  Table t = make_table("table1", "Table 1. Calibration results of the sensor zero positions", fmt::format(
      "Section 2.4 on the MuJoCo twin through the hardware interface (the real GPM2002 is not available): "
      "reference point O = home (216.5, 250), circle of radius {} mm about O with {} interpolation points, d "
      "from {} mm halved down to {} mm, joint {} read only. The twin's actual offsets are ({:.3f}, {:.3f}, "
      "{:.3f}) rad, {}-bit encoders. The real robot's offsets are unknown, so each experiment is compared as "
      "an error: the paper's printed values minus the mean of its three results ({:.4f}, {:.4f}, {:.4f}), "
      "this run's minus the twin's actual offsets. Each experiment starts where the step-2 offsets are off by "
      "the paper's initial error (the radical centre of the home angles minus that error).",
      base.circle_radius_mm, base.circle_points, base.d_initial_mm, base.d_min_mm, base.sensor_joint + 1,
      kTable1TwinOffsets[0], kTable1TwinOffsets[1], kTable1TwinOffsets[2], config.twin->twin.encoder.bits,
      paper_mean[0], paper_mean[1], paper_mean[2]));
  t.extra_column = "start (mm)";

  std::array<Eigen::Vector3d, 3> ours_result;
  for (int k = 0; k < 3; ++k) {
    if (settings.on_experiment) settings.on_experiment(k + 1);
    const Eigen::Vector3d initial(pt.initial[k][0], pt.initial[k][1], pt.initial[k][2]);
    const Eigen::Vector3d e_paper = initial - paper_mean;
    const Eigen::Vector2d start = start_for_initial_error(actual, e_paper);
    hw::ZeroSearchOptions o = base;
    o.jog_to_start = true;
    o.start = start;
    auto robot = hw::make_hardware(config);
    const hw::ZeroSearchResult r = hw::run_zero_offset_search(*robot, o);
    ours_result[static_cast<size_t>(k)] = r.offsets;
    const Eigen::Vector3d paper_result(pt.result[k][0] - paper_mean[0], pt.result[k][1] - paper_mean[1],
                                       pt.result[k][2] - paper_mean[2]);
    add_experiment_rows(t, k, e_paper, paper_result, start, r);
  }
  add_spread_rows(t, pt, ours_result);
  t.notes.push_back(fmt::format(
      "As in the paper, the three experiments converge to the same offsets from different initial estimates; "
      "the search's final d of {} mm corresponds to about {:.1e} rad at the 244 mm links.",
      base.d_min_mm, base.d_min_mm / 244.0));
  return t;
}

}  // namespace gpm::paper
