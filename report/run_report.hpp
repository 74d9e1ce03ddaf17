// The report of a `gpm run`: before/after accuracy first, then the
// parameter table (actual, nominal, estimated, 1-sigma, error, bound), the
// diagnostics, the expectations, and figures. The report library uses only
// models/: the run library (run/) passes everything in as plain data.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "models/parameters.hpp"
#include "models/robot.hpp"
#include "report/positioning_map_svg.hpp"
#include "report/report_document.hpp"

namespace gpm::report {

// Accuracy of one controller model on the twin (run/compensation.hpp).
struct RunAccuracy {
  std::string label;  // "nominal", "calibrated"
  double static_rms_um = 0.0, static_max_um = 0.0;
  double path_rms_um = 0.0, path_max_um = 0.0;
  double static_preload_rms_nm = 0.0, path_preload_rms_nm = 0.0;
  std::vector<double> path_t_s;         // time from the path's start (s)
  std::vector<double> path_error_um;    // |actual - desired| at path_t_s (um)
};

// One Levenberg-Marquardt iteration: J after it and the length of the step
// tried (in the solver's parameters); iteration 0 is the start.
struct RunLmIteration {
  int iteration = 0;
  double cost = 0.0, step_norm = 0.0;
  bool accepted = true;
};

// The calibration's result, as the report shows it.
struct RunCalibration {
  std::string method;  // "lm", "de", ...
  std::string cost;    // "j1", ..., "ml"
  Geometry geometry;
  FreeMask free;
  std::array<double, kNumParams> sigma{};  // NaN: unknown
  double final_cost = 0.0;
  long iterations = 0, evaluations = 0;
  int rank = 0;
  double condition_number = 0.0;
  std::optional<double> kmrmse_mm;
  double seconds = 0.0;
  bool converged = true;
  std::vector<std::string> notes;
  std::vector<std::pair<long, double>> history;  // (evaluations, best J)
  std::vector<RunLmIteration> lm_iterations;     // every LM iteration (empty: a global method alone)
};

// One expectation and its outcome.
struct RunCheck {
  std::string name, detail;
  bool passed = true;
};

// Chi-square test of the residuals against the encoder noise.
struct RunModelTest {
  double chi2 = 0.0, dof = 0.0, p_value = 1.0, sigma_rad = 0.0;
  bool passed = true;
  std::string diagnosis;
  double doubt_chi2 = 0.0;  // what the doubt where a joint may rest adds to chi2 on average (calib/model_test.hpp)
};

// Everything the run report shows.
struct RunReport {
  std::string name;                  // the scenario's name
  std::string scenario_file;
  std::string hardware_description;  // empty: in-process simulation
  double seconds = 0.0;
  Robot nominal;                     // the controller's model before calibration
  Geometry actual;                   // the truth
  std::vector<Eigen::Vector2d> sample_xy;   // calibration samples (mm)
  std::vector<Eigen::Vector2d> test_poses;  // accuracy test poses (mm)
  std::optional<std::string> refused;       // calibration refused: the diagnosis
  std::optional<RunCalibration> calibration;
  double crb_sigma_rad = 0.0;
  std::array<double, kNumParams> crb{};     // CRB 1-sigma at the truth (NaN: fixed)
  std::vector<double> residual_urad;        // ML residual per sample after calibration
  std::optional<RunAccuracy> before, after;
  std::optional<RunAccuracy> floor;         // the controller given the actual parameters and reading errors
  std::optional<std::array<double, 2>> floor_ratio_ci95;  // 95 % interval of calibrated / floor (none: not known)
  std::optional<RunModelTest> model_test;
  // The calibrated model's positioning error over the workspace (um): RMS,
  // max, the stated 1-sigma per axis, error / 1-sigma (1 when honest) and
  // the share of the 1-sigma an error carried unestimated adds (0: none).
  std::optional<std::array<double, 5>> positioning_um;
  std::optional<double> positioning_bound_um;  // the least RMS the readings allow (none: not known)
  // Through hardware (no truth): the stated 1-sigma per axis and its carried
  // share (um; RMS over the disc), positioning_map then holding each point's 1-sigma.
  std::optional<std::array<double, 2>> stated_positioning_um;
  std::vector<RunPositioningPoint> positioning_map;  // the error at each point of the disc (empty: not measured)
  double robot_time_s = 0.0;                // robot time of the sampling
  bool on_the_fly = false;                  // the samples taken while moving (else at rest at each pose)
  std::vector<RunCheck> checks;
};

// Builds the report of a finished run.
ReportDocument build_run_report(const RunReport& run);

// A failed model test is accounted for by the stated 1-sigma when the
// calibrated model's positioning error over the workspace is at most this
// many times it (the normalised RMS; 1 when the 1-sigma is honest).
inline constexpr double kStatedSigmaCovers = 1.5;

// What a model test means for the result, for the report and the terminal alike.
struct ModelTestVerdict {
  bool passed = true;
  double scatter = 1.0;               // sqrt(chi2 / dof): the readings' scatter over the encoders' 1-sigma
  std::optional<double> positioning;  // positioning error / stated 1-sigma, when measured
  bool covered = false;               // failed, and positioning <= kStatedSigmaCovers
};

// The verdict of a model test (chi2 over dof degrees of freedom, passed or
// not) given the positioning error over the stated 1-sigma, if measured.
ModelTestVerdict model_test_verdict(bool passed, double chi2, double dof, std::optional<double> normalised_rms);

// The verdict in one line for a terminal (ASCII): "the readings scatter 3.1x
// the encoders' 1-sigma; the stated 1-sigma accounts for it (positioning
// error 0.9x the stated 1-sigma)", or that it understates the error, or that
// the residuals are as small as the encoders explain.
std::string model_test_verdict_line(const ModelTestVerdict& v);

}  // namespace gpm::report
