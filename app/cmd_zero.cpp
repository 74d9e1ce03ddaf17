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
#include "app/written_files.hpp"
#include "models/measured_data.hpp"
#include "models/output_file.hpp"
#include "report/report_document.hpp"
#include "report/zero_report.hpp"
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

std::string offsets_yaml(const Robot& controller, const Eigen::Vector3d& offsets,
                         const std::vector<report::ZeroRun>& runs) {
  Geometry g = controller.geometry;
  for (int i = 0; i < 3; ++i) g[dth(i)] = offsets[i];
  std::string y = "# gpm zero: controller geometry with the zero offsets found (mean of the successful runs)\n";
  y += "geometry:\n" + geometry_to_yaml(g, 2);
  y += "zero_offsets:\n";
  for (const report::ZeroRun& r : runs) {
    if (!r.ok) continue;
    y += fmt::format("  - {{run: {}, method: {}, offsets: [{:.9f}, {:.9f}, {:.9f}], motions: {}, robot_s: {:.3f}}}\n",
                     r.label, r.method, r.offsets[0], r.offsets[1], r.offsets[2], r.motions, r.robot_s);
  }
  return y;
}

// The files gpm zero writes into its output folder.
const std::vector<std::string> kZeroOutputs{"report.md", "report.html", "offsets.yaml", "trace.csv",
                                            "section3_samples.csv"};

// The search options every run shares, validated (InputError otherwise).
hw::ZeroSearchOptions search_options(const ZeroArgs& a, const hw::HardwareConfig& config) {
  hw::ZeroSearchOptions base;
  base.reference = config.controller.home;
  base.circle_radius_mm = a.radius;
  base.circle_points = a.points;
  base.circle_dwell_s = a.dwell;
  base.sensor_joint = a.sensor_joint - 1;
  hw::validate_zero_search_options(base);
  return base;
}

// Checks the poses known before the first motion against the hardware's limits:
// every --start the runs jog to, and the comparison's section-3 poses.
void check_poses_before_motion(const ZeroArgs& a, const hw::HardwareConfig& config,
                               const std::vector<std::optional<Eigen::Vector2d>>& starts, int sensor_joint,
                               const std::vector<Eigen::Vector2d>& section3_poses) {
  const auto robot = hw::make_hardware(config);  // nothing moves
  std::vector<Eigen::Vector2d> jogs;
  for (const auto& s : starts)
    if (s) jogs.push_back(*s);
  hw::SessionPlan jog_plan = hw::section3_plan(jogs, sensor_joint);
  jog_plan.dither_mm = 0.0;
  hw::check_plan_poses(*robot, jog_plan);
  if (a.compare) hw::check_plan_poses(*robot, hw::section3_plan(section3_poses, sensor_joint));
}

// One gpm zero session: its runs as the report shows them, the trace and how it ended.
struct ZeroSession {
  const ZeroArgs& args;
  const hw::HardwareConfig& config;
  hw::ZeroSearchOptions base;
  std::ofstream* trace = nullptr;  // null: no output folder
  std::vector<report::ZeroRun> runs;
  std::string first_error, hardware_description, interrupted;
  hw::StopOnSignal signals;
};

// Appends one evaluation of the search to trace.csv (when there is one).
void trace_candidate(std::ofstream* trace, const std::string& label, hw::ZeroMethod m, const hw::ZeroCandidate& z) {
  if (!trace) return;
  *trace << fmt::format("{},{},{},{},{},{:.4f},{:.4f},{:.9f},{:.9f},{:.9f},{:.9f},{:.9f},{:.9f},{:.6e}\n", label,
                        hw::zero_method_name(m), z.index, z.round, z.d_mm, z.shift.x(), z.shift.y(), z.readings[0],
                        z.readings[1], z.readings[2], z.offsets[0], z.offsets[1], z.offsets[2], z.E);
  trace->flush();
}

// Runs one zero-offset search (skipped once interrupted) and records its row.
void run_search(ZeroSession& s, const std::string& label, hw::ZeroMethod m,
                const std::optional<Eigen::Vector2d>& start) {
  if (!s.interrupted.empty()) return;
  hw::ZeroSearchOptions o = s.base;
  o.method = m;
  if (start) {
    o.jog_to_start = true;
    o.start = *start;
  }
  auto robot = hw::make_hardware(s.config);
  s.hardware_description = robot->describe();
  const auto sink = [&](const hw::ZeroCandidate& z) { trace_candidate(s.trace, label, m, z); };
  hw::ZeroSearchResult r;
  try {
    r = hw::run_zero_offset_search(*robot, o, sink, s.signals.flag());
  } catch (const hw::ZeroSearchStopped& e) {  // drives disabled; what was done is in partial()
    r = e.partial();
    if (e.interrupted()) s.interrupted = label + ": " + r.error;
  }
  report::ZeroRun row{label, hw::zero_method_name(m), start, r.initial_offsets, r.offsets, r.motions, r.circles,
                      r.robot_time_s, r.wall_time_s, r.ok, r.error};
  if (!r.ok && s.first_error.empty()) s.first_error = label + ": " + r.error;
  std::printf("%s %s: %s\n", label.c_str(), row.method.c_str(),
              r.ok ? fmt::format("offsets {} rad, {} motions, {:.1f} s", report::zero_offsets_text(r.offsets),
                                 r.motions, r.robot_time_s)
                         .c_str()
                   : ("stopped: " + r.error).c_str());
  s.runs.push_back(row);
}

// Runs the section-3 calibration (ML, offsets only) on the same hardware and records its row.
void run_section3(ZeroSession& s, const std::vector<Eigen::Vector2d>& poses) {
  report::ZeroRun row;
  row.label = "section 3";
  row.method = "lm ml (offsets only)";
  try {
    auto robot = hw::make_hardware(s.config);
    // Without -o the samples are kept in memory only (written in place to
    // /dev/null): no temporary to leave behind on any path.
    const std::string csv = s.args.out.empty()
                                ? std::string("/dev/null")
                                : (std::filesystem::path(s.args.out) / "section3_samples.csv").string();
    if (!s.args.out.empty()) std::filesystem::remove(csv);
    const hw::Section3Offsets r = hw::section3_offsets(*robot, poses, s.base.sensor_joint, csv, s.signals.flag());
    row.offsets = r.offsets;
    row.motions = r.motions;
    row.robot_s = r.robot_time_s;
    row.ok = r.converged;
    if (!r.converged) row.error = "LM did not converge";
  } catch (const hw::Interrupted& e) {
    row.error = e.what();
    s.interrupted = "section 3: " + row.error;
  } catch (const hw::HardwareError& e) {
    row.error = e.what();
  }
  if (!row.ok && s.first_error.empty()) s.first_error = "section 3: " + row.error;
  s.runs.push_back(row);
}

// The mean offsets of the main method's successful runs from a --start; none when there is none.
std::optional<Eigen::Vector3d> mean_offsets(const ZeroArgs& a, const std::vector<report::ZeroRun>& runs) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  int n = 0;
  for (const report::ZeroRun& r : runs)
    if (r.ok && r.method == a.method && r.label.rfind("start", 0) == 0) sum += r.offsets, ++n;
  if (n == 0) return std::nullopt;
  return Eigen::Vector3d(sum / n);
}

// Prints the report and, with -o, writes report.md, report.html and offsets.yaml all or none.
void write_zero_outputs(const ZeroSession& s, const std::optional<Eigen::Vector3d>& actual,
                        MeasuredFolder* measured) {
  const ZeroArgs& a = s.args;
  const report::ReportDocument doc = report::zero_report(
      {a.hardware, s.hardware_description, a.method, a.radius, a.points, a.sensor_joint, actual, s.runs});
  std::printf("\n%s", doc.markdown().c_str());
  if (a.out.empty()) return;
  // trace.csv was written as the robot moved and stays (models/output_file.hpp).
  OutputFolder out(a.out, {}, measured);
  doc.stage(out, "report", "gpm zero: zero-offset auto-calibration");
  if (const auto mean = mean_offsets(a, s.runs)) out.add("offsets.yaml", offsets_yaml(s.config.controller, *mean, s.runs));
  out.commit();
  print_written(a.out, 6);  // report.md, report.html, offsets.yaml, trace.csv
}

// Sets the exit code of how the session ended (130 interrupted, 1 a run stopped) with one line on stderr.
void report_end(const ZeroSession& s) {
  if (!s.interrupted.empty()) {
    std::fprintf(stderr, "gpm: %s; the runs before it and its trace are kept%s\n", s.interrupted.c_str(),
                 s.args.out.empty() ? "" : (" in " + s.args.out).c_str());
    set_exit(hw::kInterruptedExit);
  } else if (!s.first_error.empty()) {
    std::fprintf(stderr, "gpm: error: %s\n", s.first_error.c_str());
    set_exit(1);
  }
}

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
  const hw::ZeroSearchOptions base = search_options(a, config);
  const std::vector<Eigen::Vector2d> section3_poses = circle_points(base.reference, a.radius, 12);
  check_poses_before_motion(a, config, starts, base.sensor_joint, section3_poses);

  // trace.csv and section3_samples.csv are measured data: the folder is this
  // session's (models/measured_data.hpp) and no later command overwrites them.
  std::optional<MeasuredFolder> measured;
  std::ofstream trace;
  if (!a.out.empty()) {
    measured.emplace(a.out, "gpm zero", "trace.csv");
    trace.open(measured->samples_path());
    trace << "run,method,index,round,d_mm,shift_x,shift_y,theta_m1,theta_m2,theta_m3,dth1,dth2,dth3,E\n";
  }
  ZeroSession s{a, config, base, trace.is_open() ? &trace : nullptr, {}, {}, {}, {}, {}};
  for (size_t k = 0; k < starts.size(); ++k) run_search(s, fmt::format("start {}", k + 1), method, starts[k]);
  if (a.compare && s.interrupted.empty()) {
    run_search(s, "other method", method == hw::ZeroMethod::kGrid ? hw::ZeroMethod::kDirect : hw::ZeroMethod::kGrid,
               starts[0]);
  }
  if (a.compare && s.interrupted.empty()) run_section3(s, section3_poses);
  write_zero_outputs(s, actual, measured ? &*measured : nullptr);
  report_end(s);
}

}  // namespace

void add_zero(CLI::App& app) {
  auto args = std::make_shared<ZeroArgs>();
  auto* cmd = app.add_subcommand("zero", "Zero-offset auto-calibration on the moving robot (paper section 2.4)");
  cmd->add_option("--hardware", args->hardware, "hardware file (backend twin, modbus or plugin, safety limits; gpm help hardware)")->required();
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
