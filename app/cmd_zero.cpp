// gpm zero: zero-offset auto-calibration on the moving robot (paper section
// 2.4) through a hardware file (twin or drives). One run per --start (paper
// Table 1: different initial estimates); --compare adds the other method and
// the section-3 calibration (ML, offsets only) on the same hardware.
// Writes DIR/report.md (the table), DIR/offsets.yaml (geometry with the found
// offsets, usable as `calibration:` of a hardware file) and DIR/trace.csv
// (every evaluation, appended as it is made).
// Exit 0 done; 1 a run stopped (one line on stderr; drives disabled; trace kept); 2 bad input;
// 130 interrupted (SIGINT/SIGTERM/SIGHUP: drives disabled, later runs skipped, the report and
// trace of what was done written).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <unistd.h>
#include <sstream>

#include <fmt/format.h>

#include "app/commands.hpp"
#include "app/number_options.hpp"
#include "models/measured_data.hpp"
#include "models/output_file.hpp"
#include "report/report_document.hpp"
#include "models/pose_layouts.hpp"
#include "hw/hardware_config.hpp"
#include "hw/hw_errors.hpp"
#include "hw/procedures/sampling_session.hpp"
#include "hw/procedures/section3_offsets.hpp"
#include "hw/procedures/stop_on_signal.hpp"
#include "hw/procedures/zero_offset_search.hpp"
#include "models/errors.hpp"
#include "models/robot_yaml.hpp"

namespace gpm::cli {
namespace {

struct ZeroArgs {
  std::string hardware, model, method = "grid", out;
  std::vector<std::string> starts;
  bool compare = false;
  double radius = 30.0;
  int points = 24;
  double dwell = 0.0;
  int sensor_joint = 1;
};

// "X,Y" -> point (mm); InputError naming the flag otherwise.
Eigen::Vector2d parse_point(const std::string& s) {
  double x = 0, y = 0;
  char comma = 0, extra = 0;
  std::istringstream in(s);
  if (!(in >> x >> comma >> y) || comma != ',' || (in >> extra) || !std::isfinite(x) || !std::isfinite(y)) {
    throw InputError(fmt::format("--start: '{}' is not X,Y in mm (e.g. 219.5,252)", s));
  }
  return {x, y};
}

hw::ZeroMethod parse_method(const std::string& s) {
  if (s == "grid") return hw::ZeroMethod::kGrid;
  if (s == "direct") return hw::ZeroMethod::kDirect;
  throw InputError(fmt::format("--method: '{}' is not grid or direct", s));
}

// One row of the report table.
struct Row {
  std::string label, method;
  std::optional<Eigen::Vector2d> start;
  Eigen::Vector3d initial = Eigen::Vector3d::Constant(NAN), offsets = Eigen::Vector3d::Constant(NAN);
  int motions = 0, circles = 0;
  double robot_s = 0, wall_s = 0;
  bool ok = false;
  std::string error;
};

std::string v3(const Eigen::Vector3d& v) { return fmt::format("{:.5f}, {:.5f}, {:.5f}", v[0], v[1], v[2]); }

report::ReportDocument zero_report(const ZeroArgs& a, const std::vector<Row>& rows,
                                   const std::optional<Eigen::Vector3d>& actual, const std::string& hw_desc) {
  report::ReportDocument d;
  d.heading(1, "Zero-offset auto-calibration (paper section 2.4)");
  d.paragraph(fmt::format("Hardware: {} ({}). Circle radius {} mm, {} interpolation points, joint {} read only "
                          "(torque off).",
                          a.hardware, hw_desc, a.radius, a.points, a.sensor_joint));
  if (actual) d.paragraph(fmt::format("Actual offsets of the twin: {} rad.", v3(*actual)));
  std::vector<std::vector<std::string>> table;
  for (const Row& r : rows) {
    const std::string start = r.start ? fmt::format("{:.2f}, {:.2f}", r.start->x(), r.start->y()) : "as found";
    std::string err = "unknown";
    if (actual && r.ok) err = fmt::format("{:.2e}", (r.offsets - *actual).cwiseAbs().maxCoeff());
    table.push_back({r.label, r.method, start, r.initial.allFinite() ? v3(r.initial) : "-",
                     r.ok ? v3(r.offsets) : "stopped: " + r.error, err, std::to_string(r.motions),
                     std::to_string(r.circles), fmt::format("{:.1f}", r.robot_s), fmt::format("{:.1f}", r.wall_s)});
  }
  d.table({"run", "method", "start (mm, commanded)", "initial estimate (rad)", "result (rad)",
           "max error vs actual (rad)", "motions", "circles", "robot s", "wall s"},
          table);
  // Spread of the main method's runs (paper Table 1: same offsets from different starts).
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo;
  int n = 0;
  for (const Row& r : rows) {
    if (!r.ok || r.method != a.method || r.label.rfind("start", 0) != 0) continue;
    lo = lo.cwiseMin(r.offsets);
    hi = hi.cwiseMax(r.offsets);
    ++n;
  }
  if (n >= 2) d.paragraph(fmt::format("Spread of the {} {} runs (max - min per joint): {} rad.", n, a.method, v3(hi - lo)));
  return d;
}

std::string offsets_yaml(const Robot& controller, const Eigen::Vector3d& offsets, const std::vector<Row>& rows) {
  Geometry g = controller.geometry;
  for (int i = 0; i < 3; ++i) g[dth(i)] = offsets[i];
  std::string y = "# gpm zero: controller geometry with the zero offsets found (mean of the successful runs)\n";
  y += "geometry:\n" + geometry_to_yaml(g, 2);
  y += "zero_offsets:\n";
  for (const Row& r : rows) {
    if (!r.ok) continue;
    y += fmt::format("  - {{run: {}, method: {}, offsets: [{:.9f}, {:.9f}, {:.9f}], motions: {}, robot_s: {:.3f}}}\n",
                     r.label, r.method, r.offsets[0], r.offsets[1], r.offsets[2], r.motions, r.robot_s);
  }
  return y;
}

// The files gpm zero writes into its output folder.
const std::vector<std::string> kZeroOutputs{"report.md", "report.html", "offsets.yaml", "trace.csv",
                                            "section3_samples.csv"};

void run_zero(const ZeroArgs& a) {
  // The output folder against every input (hardware file, model, the files
  // they name) and not a hardware session's folder, before anything is read.
  if (!a.out.empty()) check_output_folder(a.out, kZeroOutputs);
  const hw::ZeroMethod method = parse_method(a.method);
  std::vector<std::optional<Eigen::Vector2d>> starts;
  for (const std::string& s : a.starts) starts.emplace_back(parse_point(s));
  if (starts.empty()) starts.emplace_back(std::nullopt);
  if (a.sensor_joint < 1 || a.sensor_joint > 3) throw InputError("--sensor-joint: must be 1, 2 or 3");
  hw::HardwareConfig config = hw::load_hardware_config(a.hardware);
  if (!a.model.empty()) config.controller = load_robot(a.model);
  std::optional<Eigen::Vector3d> actual;
  if (config.twin) {
    const Geometry& g = config.twin->actual.geometry;
    actual = Eigen::Vector3d(g[dth(0)], g[dth(1)], g[dth(2)]);
  }
  hw::ZeroSearchOptions base;
  base.reference = config.controller.home;
  base.circle_radius_mm = a.radius;
  base.circle_points = a.points;
  base.circle_dwell_s = a.dwell;
  base.sensor_joint = a.sensor_joint - 1;
  hw::validate_zero_search_options(base);
  // The poses known before the first motion, against the hardware's limits:
  // every --start the runs jog to, and the comparison's section-3 poses.
  const std::vector<Eigen::Vector2d> section3_poses = circle_points(base.reference, a.radius, 12);
  {
    const auto robot = hw::make_hardware(config);  // nothing moves
    std::vector<Eigen::Vector2d> jogs;
    for (const auto& s : starts)
      if (s) jogs.push_back(*s);
    hw::SessionPlan jog_plan = hw::section3_plan(jogs, base.sensor_joint);
    jog_plan.dither_mm = 0.0;
    hw::check_plan_poses(*robot, jog_plan);
    if (a.compare) hw::check_plan_poses(*robot, hw::section3_plan(section3_poses, base.sensor_joint));
  }

  // trace.csv and section3_samples.csv are measured data: the folder is this
  // session's (models/measured_data.hpp) and no later command overwrites them.
  std::optional<MeasuredFolder> measured;
  std::ofstream trace;
  if (!a.out.empty()) {
    measured.emplace(a.out, "gpm zero", "trace.csv");
    trace.open(measured->samples_path());
    trace << "run,method,index,round,d_mm,shift_x,shift_y,theta_m1,theta_m2,theta_m3,dth1,dth2,dth3,E\n";
  }
  std::vector<Row> rows;
  std::string first_error, desc, interrupted;
  const hw::StopOnSignal signals;
  auto run_one = [&](const std::string& label, hw::ZeroMethod m, const std::optional<Eigen::Vector2d>& start) {
    if (!interrupted.empty()) return;
    hw::ZeroSearchOptions o = base;
    o.method = m;
    if (start) {
      o.jog_to_start = true;
      o.start = *start;
    }
    auto robot = hw::make_hardware(config);
    desc = robot->describe();
    const auto sink = [&](const hw::ZeroCandidate& z) {
      if (!trace.is_open()) return;
      trace << fmt::format("{},{},{},{},{},{:.4f},{:.4f},{:.9f},{:.9f},{:.9f},{:.9f},{:.9f},{:.9f},{:.6e}\n",
                           label, hw::zero_method_name(m), z.index, z.round, z.d_mm, z.shift.x(),
                           z.shift.y(), z.readings[0], z.readings[1], z.readings[2], z.offsets[0],
                           z.offsets[1], z.offsets[2], z.E);
      trace.flush();
    };
    hw::ZeroSearchResult r;
    try {
      r = hw::run_zero_offset_search(*robot, o, sink, signals.flag());
    } catch (const hw::ZeroSearchStopped& e) {  // drives disabled; what was done is in partial()
      r = e.partial();
      if (e.interrupted()) interrupted = label + ": " + r.error;
    }
    Row row{label, hw::zero_method_name(m), start, r.initial_offsets, r.offsets, r.motions, r.circles,
            r.robot_time_s, r.wall_time_s, r.ok, r.error};
    if (!r.ok && first_error.empty()) first_error = label + ": " + r.error;
    std::printf("%s %s: %s\n", label.c_str(), row.method.c_str(),
                r.ok ? fmt::format("offsets {} rad, {} motions, {:.1f} s", v3(r.offsets), r.motions, r.robot_time_s).c_str()
                     : ("stopped: " + r.error).c_str());
    rows.push_back(row);
  };
  for (size_t k = 0; k < starts.size(); ++k) run_one(fmt::format("start {}", k + 1), method, starts[k]);
  if (a.compare && interrupted.empty()) {
    run_one("other method", method == hw::ZeroMethod::kGrid ? hw::ZeroMethod::kDirect : hw::ZeroMethod::kGrid,
            starts[0]);
  }
  if (a.compare && interrupted.empty()) {
    Row row;
    row.label = "section 3";
    row.method = "lm ml (offsets only)";
    try {
      auto robot = hw::make_hardware(config);
      // Without -o the samples are kept in memory only (written in place to
      // /dev/null): no temporary to leave behind on any path.
      const std::string csv =
          a.out.empty() ? std::string("/dev/null") : (std::filesystem::path(a.out) / "section3_samples.csv").string();
      if (!a.out.empty()) std::filesystem::remove(csv);
      const hw::Section3Offsets s =
          hw::section3_offsets(*robot, section3_poses, base.sensor_joint, csv, signals.flag());
      row.offsets = s.offsets;
      row.motions = s.motions;
      row.robot_s = s.robot_time_s;
      row.ok = s.converged;
      if (!s.converged) row.error = "LM did not converge";
    } catch (const hw::Interrupted& e) {
      row.error = e.what();
      interrupted = "section 3: " + row.error;
    } catch (const hw::HardwareError& e) {
      row.error = e.what();
    }
    if (!row.ok && first_error.empty()) first_error = "section 3: " + row.error;
    rows.push_back(row);
  }
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int n = 0;
  for (const Row& r : rows)
    if (r.ok && r.method == a.method && r.label.rfind("start", 0) == 0) sum += r.offsets, ++n;
  const report::ReportDocument doc = zero_report(a, rows, actual, desc);
  std::printf("\n%s", doc.markdown().c_str());
  if (!a.out.empty()) {
    // report.md, report.html and offsets.yaml all or none (models/output_file.hpp);
    // trace.csv was written as the robot moved and stays.
    OutputFolder out(a.out, {}, measured ? &*measured : nullptr);
    doc.stage(out, "report", "gpm zero: zero-offset auto-calibration");
    if (n > 0) out.add("offsets.yaml", offsets_yaml(config.controller, sum / n, rows));
    out.commit();
  }
  if (!interrupted.empty()) {
    std::fprintf(stderr, "gpm: %s; the runs before it and its trace are kept%s\n", interrupted.c_str(),
                 a.out.empty() ? "" : (" in " + a.out).c_str());
    set_exit(hw::kInterruptedExit);
  } else if (!first_error.empty()) {
    std::fprintf(stderr, "gpm: error: %s\n", first_error.c_str());
    set_exit(1);
  }
}

}  // namespace

void add_zero(CLI::App& app) {
  auto args = std::make_shared<ZeroArgs>();
  auto* cmd = app.add_subcommand("zero", "Zero-offset auto-calibration on the moving robot (paper section 2.4)");
  cmd->add_option("--hardware", args->hardware, "hardware file (backend twin or modbus, safety limits)")->required();
  cmd->add_option("--model", args->model, "robot file replacing the hardware file's controller (links, bases, home = O)");
  cmd->add_option("--start", args->starts, "X,Y (mm): jog here first and take it as the initial estimate; repeat for several runs");
  cmd->add_option("--method", args->method, "grid (paper steps 5-7) or direct (least squares on E)");
  cmd->add_flag("--compare", args->compare, "also run the other method and the section-3 calibration (ML, offsets only)");
  cmd->add_option("--radius", args->radius, "circle radius (mm)");
  cmd->add_option("--points", args->points, "interpolation points recorded per circle")->transform(number_in(limits::kCirclePoints));
  cmd->add_option("--dwell", args->dwell, "s: stop at each interpolation point and average this long (0: record on the fly)")
      ->transform(number_in(limits::kDwell));
  cmd->add_option("--sensor-joint", args->sensor_joint, "joint read only, torque off (1..3)");
  cmd->add_option("-o,--output", args->out, "report folder: report.md, offsets.yaml, trace.csv");
  cmd->callback([args] { run_zero(*args); });
}

}  // namespace gpm::cli
