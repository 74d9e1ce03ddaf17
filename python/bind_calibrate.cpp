// gpm.calibrate and gpm.CalibrationResult: calibration from encoder readings
// (and, for samples taken on the fly, their times and drive torques) by gpm
// run's procedure (run/calibration_procedure.hpp: the motion model or the
// static fit, then the model test) with the checks and messages of `gpm
// calibrate` (app/cmd_calibrate.cpp), and the result file (calib/result_yaml.hpp).
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include <fmt/format.h>
#include <pybind11/stl.h>

#include "calib/lm.hpp"
#include "calib/parameterization.hpp"
#include "calib/positioning_error.hpp"
#include "calib/residuals.hpp"
#include "calib/result_yaml.hpp"
#include "calib/sample_check.hpp"
#include "models/bounds.hpp"
#include "models/errors.hpp"
#include "python/bindings.hpp"
#include "python/convert.hpp"
#include "python/errors.hpp"
#include "calib/calibrate.hpp"
#include "models/robot_yaml.hpp"
#include "models/samples.hpp"
#include "run/calibration_procedure.hpp"

namespace gpm::python {
namespace {

// A calibration result and the robot it was calibrated from (whose name,
// home, branches and limits a calibrated robot keeps).
struct CalibrationResult {
  calib::Result result;
  Robot base;
  std::optional<calib::ModelTest> model_test;  // gpm.calibrate's (none from load_result)
  std::vector<Eigen::Vector3d> readings;       // those the static model was fitted to (empty: none, or in motion)
};

// The normalised ML residuals r_j / sigma of the readings at the estimate
// (calib/residuals.hpp; sigma: the model test's), whose squares sum to the
// model test's chi2; None without readings (a loaded result, a fit in motion).
py::object normalised_residuals(const CalibrationResult& c) {
  if (c.readings.empty() || !c.model_test) return py::none();
  const calib::ParamVector x = calib::to_solver(c.result.geometry, calib::Cost::kML);
  py::array_t<double> out(static_cast<py::ssize_t>(c.readings.size()));
  for (std::size_t j = 0; j < c.readings.size(); ++j) {
    double r = 0.0;
    if (!calib::MlResidual(c.readings[j])(x.data(), &r)) r = std::numeric_limits<double>::infinity();
    out.mutable_at(static_cast<py::ssize_t>(j)) = r / c.model_test->sigma_rad;
  }
  return out;
}

// The result file's text: the result and, where made, the model test (as gpm calibrate writes it).
std::string result_text(const CalibrationResult& c) {
  return calib::result_to_yaml(c.result, c.base.name) +
         (c.model_test ? scenario::model_test_yaml(*c.model_test, 2) : std::string());
}

py::dict diagnostics(const calib::Result& r) {
  py::dict d;
  d["method"] = r.method;
  d["cost_function"] = std::string(calib::cost_name(r.cost));
  d["cost"] = r.final_cost;
  d["iterations"] = r.iterations;
  d["evaluations"] = r.evaluations;
  d["rank"] = r.rank;
  d["free_parameters"] = r.free.count();
  d["condition_number"] = r.condition_number;
  if (r.kmrmse_mm) d["kmrmse_mm"] = *r.kmrmse_mm;
  d["seconds"] = r.seconds;
  d["converged"] = r.converged;
  d["rank_deficient"] = r.rank_deficient;
  py::list notes;
  for (const auto& note : r.notes) notes.append(python_words(note));
  d["notes"] = notes;
  return d;
}

py::dict model_test_dict(const calib::ModelTest& t) {
  py::dict d;
  d["chi2"] = t.chi2;
  d["dof"] = t.dof;
  d["chi2_per_dof"] = t.chi2 / t.dof;
  d["p_value"] = t.p_value;
  d["carried_chi2"] = t.carried_chi2;
  d["doubt_chi2"] = t.doubt_chi2;
  d["sigma_rad"] = t.sigma_rad;
  d["passed"] = t.passed;
  if (!t.passed) d["diagnosis"] = python_words(t.diagnosis);
  return d;
}

// The (n, 3) array a of name as rows, checked against n readings; none: empty.
std::vector<Eigen::Vector3d> optional_rows(const py::object& a, const std::string& name, std::size_t n) {
  if (a.is_none()) return {};
  std::vector<Eigen::Vector3d> v = readings_from_array(a, name);
  if (v.size() != n) throw InputError(fmt::format("{}: {} rows for {} rows of readings", name, v.size(), n));
  return v;
}

// The samples of gpm.calibrate's arrays (readings, and times and torques where given), checked as the file reader does.
Samples samples_of(const py::handle& readings, const py::object& t, const py::object& tau_last,
                   const py::object& tau_between) {
  Samples s;
  s.theta_m = readings_from_array(readings, "readings");
  const std::size_t n = s.theta_m.size();
  for (std::size_t j = 0; j < n; ++j) s.id.push_back(static_cast<long>(j));
  if (!t.is_none()) {
    const auto times = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(t);
    if (!times || times.ndim() != 1)
      throw InputTypeError(fmt::format("t: expected an (n,) array of times in s, one per row of readings, got {}",
                                       type_name(t)));
    s.t.assign(times.data(), times.data() + times.size());
    if (s.t.size() != n) throw InputError(fmt::format("t: {} times for {} rows of readings", s.t.size(), n));
    for (std::size_t j = 0; j < n; ++j)
      if (!std::isfinite(s.t[j]) || (j > 0 && !(s.t[j] > s.t[j - 1])))
        throw InputError(fmt::format("t[{}]: {} is not a finite time after t[{}] (the times must increase)", j, s.t[j],
                                     j > 0 ? j - 1 : 0));
  }
  s.tau_last = optional_rows(tau_last, "tau_last", n);
  s.tau_between = optional_rows(tau_between, "tau_between", n);
  return s;
}

CalibrationResult calibrate(const py::handle& readings, const py::object& robot_object, const py::object& fix,
                            const py::object& cost_arg, const py::object& method_arg, const py::object& sigma,
                            const py::object& rank_deficient_arg, const py::object& budget, const py::object& seed_arg,
                            const py::object& true_xy, const py::object& t, const py::object& tau_last,
                            const py::object& tau_between, const py::object& encoder_bits, const py::object& static_arg) {
  // Checks in the order of app/cmd_calibrate.cpp, with its messages; the
  // argument is named as in Python (cost=, method=, ...).
  const Robot robot = robot_arg(robot_object, "robot");
  const std::string cost_text = text_arg(cost_arg, "cost", "one of j1, j2, j3, ml");
  const std::string method = text_arg(method_arg, "method", "one of lm, ga, pso, de, de+lm");
  const bool allow_rank_deficient = flag_arg(rank_deficient_arg, "allow_rank_deficient");
  const bool static_model = flag_arg(static_arg, "static_model");
  const auto cost = calib::parse_cost(cost_text);
  if (!cost) throw InputError(fmt::format("cost: '{}' is not one of j1, j2, j3, ml", cost_text));
  const calib::Method method_value = calib::parse_method(method, "method");
  std::optional<long long> budget_value;
  if (!budget.is_none())
    budget_value = whole_arg(budget, "budget",
                             method_value == calib::Method::kLM ? limits::kLmIterations : limits::kEvaluations);
  const long long seed = whole_arg(seed_arg, "seed", limits::kSeed);
  Samples samples = samples_of(readings, t, tau_last, tau_between);
  std::optional<int> bits;
  if (!encoder_bits.is_none()) bits = static_cast<int>(whole_arg(encoder_bits, "encoder_bits", limits::kEncoderBits));
  calib::Problem problem;
  problem.theta_m = samples.theta_m;
  problem.free = ~param_set(fix, "fix");
  problem.start = robot.geometry;
  std::vector<Eigen::Vector2d> xy;
  if (!true_xy.is_none()) {
    xy = points_from_array(true_xy, "true_xy");
    if (xy.size() != problem.theta_m.size()) {
      throw InputError(fmt::format("true_xy: {} rows for {} rows of readings", xy.size(), problem.theta_m.size()));
    }
  }
  calib::MethodOptions mo;
  mo.method = method_value;
  mo.cost = *cost;
  mo.seed = static_cast<std::uint64_t>(seed);
  mo.allow_rank_deficient = allow_rank_deficient;
  if (budget_value) {
    if (method_value == calib::Method::kLM) mo.lm_max_iterations = static_cast<int>(*budget_value);
    else mo.budget = static_cast<long>(*budget_value);
  }
  if (!sigma.is_none()) {
    mo.encoder_sigma = number_arg(sigma, "sigma", limits::kEncoderSigma);
  }
  if (!xy.empty()) samples.xy = xy, samples.has_xy = true;

  const scenario::FileProcedure proc =
      scenario::samples_file_procedure(samples, robot, problem.start, problem.free, mo, bits, static_model);
  if (proc.motion_not_used &&
      PyErr_WarnEx(PyExc_RuntimeWarning,
                   "the samples were taken on the fly, but their motion model needs method lm with cost ml: "
                   "calibrated with the static model", 1) != 0)
    throw py::error_already_set();
  CalibrationResult out{{}, robot, std::nullopt, {}};
  {
    py::gil_scoped_release unlocked;
    calib::check_samples(problem);
    scenario::CalibrationOutcome c = scenario::calibrate_samples(scenario::sample_series(samples), proc.inputs, proc.options);
    out.result = std::move(c.result);
    out.model_test = c.model_test;
    if (!proc.options.in_motion) out.readings = samples.theta_m;
  }
  for (const auto& note : out.result.notes) {
    if (PyErr_WarnEx(PyExc_RuntimeWarning, python_words(note).c_str(), 1) != 0) throw py::error_already_set();
  }
  return out;
}

// CalibrationResult's repr: the solve and the model test in a line each, then
// the estimated parameters with their 1-sigma, three to a line.
std::string result_repr(const CalibrationResult& c) {
  const calib::Result& r = c.result;
  std::string out = fmt::format("<gpm.CalibrationResult {} ({}): {} free, {} in {} iterations, J = {:.4g}, rank {}",
                                r.method, calib::cost_name(r.cost), r.free.count(),
                                r.converged ? "converged" : "NOT converged", r.iterations, r.final_cost, r.rank);
  if (r.kmrmse_mm) out += fmt::format(", kmrmse {:.4g} mm", *r.kmrmse_mm);
  if (c.model_test) {
    const calib::ModelTest& t = *c.model_test;
    out += fmt::format("\n  model test {}: chi2/dof = {:.4g} for {:g} dof, p = {:.3g} (reading sigma {:.3g} rad)",
                       t.passed ? "passed" : "failed", t.chi2 / t.dof, t.dof, t.p_value, t.sigma_rad);
  }
  int k = 0;
  for (int i = 0; i < kNumParams; ++i) {
    if (!r.free.test(static_cast<size_t>(i))) continue;
    out += (k++ % 3 == 0 ? "\n  " : "   ");
    out += fmt::format("{:<4} {:.6f} \u00b1 {:.2g}", param_name(i), r.geometry[i], r.sigma[static_cast<size_t>(i)]);
  }
  return out + ">";
}

// CalibrationResult.std: the 1-sigma of each estimated parameter by name.
py::dict sigma_dict(const CalibrationResult& c) {
  py::dict d;
  for (int i = 0; i < kNumParams; ++i)
    if (c.result.free.test(static_cast<size_t>(i)))
      d[py::str(std::string(param_name(i)))] = c.result.sigma[static_cast<size_t>(i)];
  return d;
}

// The positioning 1-sigma the result states over the 80 mm disc round the
// robot's home, by the calibrated model's own sensitivities, as `gpm
// calibrate` prints it (none without a covariance or out of reach).
py::object stated_positioning_dict(const CalibrationResult& c) {
  const std::optional<calib::PositioningError> p = calib::stated_positioning(c.base, c.result);
  if (!p) return py::none();
  py::dict d;
  d["stated_sigma_rms"] = p->stated_sigma_rms_um;
  d["carried_sigma_rms"] = p->carried_sigma_rms_um;
  d["points"] = p->points;
  return d;
}

// CalibrationResult.diagnostics: the solver's diagnostics, the model test and the stated positioning 1-sigma.
py::dict diagnostics_dict(const CalibrationResult& c) {
  py::dict d = diagnostics(c.result);
  if (c.model_test) d["model_test"] = model_test_dict(*c.model_test);
  const py::object positioning = stated_positioning_dict(c);
  if (!positioning.is_none()) d["positioning_um"] = positioning;
  return d;
}

// CalibrationResult.covariance: 15 x 15 array, or None.
py::object covariance_array(const CalibrationResult& c) {
  if (!c.result.covariance) return py::none();
  return matrix_array(*c.result.covariance);
}

// CalibrationResult.robot: the input robot with the estimated geometry.
Robot calibrated_robot(const CalibrationResult& c) {
  Robot r = c.base;
  r.geometry = c.result.geometry;
  return r;
}

// CalibrationResult.convergence: the LM iterations as lists.
py::dict convergence_dict(const CalibrationResult& c) {
  py::dict d;
  py::list it, cost, accepted;
  for (const auto& i : c.result.lm_iterations) it.append(i.iteration), cost.append(i.cost), accepted.append(i.accepted);
  d["iteration"] = it;
  d["cost"] = cost;
  d["accepted"] = accepted;
  return d;
}

// gpm.CalibrationResult: the estimate, its 1-sigma and diagnostics, and the result file.
void bind_result_class(py::module_& m) {
  py::class_<CalibrationResult>(m, "CalibrationResult", R"doc(
The outcome of gpm.calibrate (or gpm.load_result): the geometry, the 1-sigma
of the estimated parameters and the solver's diagnostics, as written to the
result file by `gpm calibrate` (docs/FORMATS.md file contracts).
)doc")
      .def_property_readonly(
          "geometry", [](const CalibrationResult& c) { return geometry_dict(c.result.geometry); },
          "Dict of all 15 parameters (estimated and fixed), mm and rad.")
      .def_property_readonly(
          "std",
          &sigma_dict,
          "Dict of the 1-sigma of each estimated parameter (NaN when unknown).")
      .def_property_readonly(
          "diagnostics",
          &diagnostics_dict,
          "Dict: method, cost_function, cost (final J), iterations, evaluations, rank, free_parameters, "
          "condition_number, kmrmse_mm (when true_xy was given), seconds, converged, rank_deficient, notes, and "
          "model_test (chi2, dof, chi2_per_dof, p_value, sigma_rad, passed, diagnosis when failed; when made), and "
          "positioning_um (with a covariance: stated_sigma_rms, the positioning 1-sigma per axis over the 80 mm "
          "disc round home, carried_sigma_rms, its share of the error once per joint revolution carried, and "
          "points; um, as `gpm calibrate` prints them).")
      .def_property_readonly(
          "start", [](const CalibrationResult& c) { return geometry_dict(c.base.geometry); },
          "Dict of the 15 parameters the calibration started from (the robot given to gpm.calibrate; the "
          "nominal GPM2002, or load_result's robot, for a loaded result).")
      .def_property_readonly(
          "fixed", [](const CalibrationResult& c) { return param_names(~c.result.free); },
          "Names of the parameters held fixed.")
      .def_property_readonly(
          "free", [](const CalibrationResult& c) { return param_names(c.result.free); },
          "Names of the estimated parameters.")
      .def_property_readonly(
          "converged", [](const CalibrationResult& c) { return c.result.converged; },
          "Whether the solver met its tolerances (the command line exits 1 when not).")
      .def_property_readonly(
          "covariance",
          &covariance_array,
          "15 x 15 covariance of the parameters in docs/FORMATS.md order (zero rows and columns for fixed ones), or "
          "None when the solver computed none.")
      .def_property_readonly(
          "robot",
          &calibrated_robot,
          "The calibrated robot: the input robot (name, home, branches, limits) with the estimated geometry.")
      .def(
          "to_yaml", [](const CalibrationResult& c) { return result_text(c); },
          "The result file text (YAML), as `gpm calibrate -o` writes it.")
      .def(
          "save",
          [](const CalibrationResult& c, const py::object& path) {
            write_file_atomic(path_arg(path, "path"), result_text(c));
          },
          py::arg("path"), "Writes the result file (YAML) atomically; it can serve as a robot model.")
      .def_property_readonly(
          "convergence",
          &convergence_dict,
          "Dict of the last LM solve, one entry per iteration: iteration, cost (J after the step), accepted "
          "(False: the step raised J and was rejected); empty lists for a global method or a loaded result.")
      .def_property_readonly("residuals", &normalised_residuals,
                             "(n,) ML residual of each reading at the estimate over the model test's reading "
                             "1-sigma (their squares sum to diagnostics['model_test']['chi2']); None for a loaded "
                             "result or a calibration with the motion model.")
      .def("__repr__", &result_repr);
}

// gpm.calibrate: the calibration procedure of gpm calibrate.
void bind_calibrate_function(py::module_& m) {
  m.def("calibrate", &calibrate, py::arg("readings"), py::arg("robot"),
        py::arg("fix") = std::vector<std::string>{"xa1", "ya1", "xa2", "ya2"}, py::arg("cost") = "ml",
        py::arg("method") = "lm", py::arg("sigma") = py::none(), py::arg("allow_rank_deficient") = false,
        py::arg("budget") = py::none(), py::arg("seed") = 1, py::arg("true_xy") = py::none(),
        py::arg("t") = py::none(), py::arg("tau_last") = py::none(), py::arg("tau_between") = py::none(),
        py::arg("encoder_bits") = py::none(), py::arg("static_model") = false,
        R"doc(
Identifies the robot's parameters from encoder readings (paper section 3), as
`gpm calibrate` does, and returns a gpm.CalibrationResult.

readings  (n, 3) encoder readings in rad (e.g. gpm.read_samples(path));
robot     gpm.Robot: the start geometry and the values of fixed parameters;
fix       names held fixed (list or comma-separated string); the default
          gauge fixes xa1, ya1, xa2, ya2, the other 11 are estimated;
cost      "ml" (maximum likelihood), "j1" (eq. 37), "j2" (eq. 39), "j3" (eq. 43);
method    "lm" (Ceres Levenberg-Marquardt), "ga", "pso", "de", "de+lm";
sigma     encoder noise 1-sigma (rad) for the uncertainty; None: estimated
          from the residuals;
allow_rank_deficient  solve an unidentifiable free set with a minimum-norm step;
budget    lm: maximum iterations (200); global: evaluations (1.5e6);
seed      seed of the global methods;
true_xy   optional (n, 2) true end-effector positions (mm) for kmrmse (eq. 40);
t, tau_last, tau_between  optional: the time of each reading (n, s) and the
          drive torques before it ((n, 3), N m; samples.csv columns t,
          tau_last1..3, tau_between1..3). All three, evenly spaced times
          (samples taken on the fly), method lm and cost ml: the geometry is
          estimated with gpm run's motion model, as `gpm calibrate` does;
encoder_bits  the encoders' 2^N counts per turn for the reading 1-sigma when
          sigma is None (default: the robot's data sheet, 17);
static_model  the static fit even for samples taken on the fly.

Every calibration ends with the chi-square model test of its residuals
against the reading 1-sigma: diagnostics["model_test"].

Bad input raises gpm.InputError (a ValueError) with the command line's
message in Python's words (fewer samples than free parameters, circles that
do not meet, a rank-deficient free set naming what to fix, unknown names;
budget, seed, sigma, encoder_bits out of range name their valid range); an
argument of the wrong type raises gpm.InputTypeError (also a TypeError). A solve that
does not converge returns normally with .converged False; the solver's
warnings are issued as RuntimeWarning. The GIL is released while solving.
)doc");
}

// gpm.load_result: a result file as a CalibrationResult.
void bind_load_result(py::module_& m) {
  m.def(
      "load_result",
      [](const py::object& path, const py::object& robot) {
        CalibrationResult c{calib::load_result(path_arg(path, "path")), Robot{}, std::nullopt, {}};
        if (!robot.is_none()) c.base = robot.cast<Robot>();
        return c;
      },
      py::arg("path"), py::arg("robot") = py::none(),
      "Loads a result file written by `gpm calibrate` or CalibrationResult.save; robot (default: the nominal "
      "GPM2002) supplies home, branches and limits of .robot.");
}

}  // namespace

void bind_calibrate(py::module_& m) {
  bind_result_class(m);
  bind_calibrate_function(m);
  bind_load_result(m);
}

}  // namespace gpm::python
