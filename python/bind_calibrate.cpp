// gpm.calibrate and gpm.CalibrationResult: calibration from encoder readings
// (calib/lm.hpp, the method dispatch of the global solvers, calib/sample_check.hpp)
// with the checks and messages of `gpm calibrate` (app/cmd_calibrate.cpp), and
// the result file (calib/result_yaml.hpp).
#include <cmath>
#include <optional>
#include <string>

#include <fmt/format.h>
#include <pybind11/stl.h>

#include "calib/lm.hpp"
#include "calib/result_yaml.hpp"
#include "calib/sample_check.hpp"
#include "models/bounds.hpp"
#include "models/errors.hpp"
#include "python/bindings.hpp"
#include "python/convert.hpp"
#include "calib/calibrate.hpp"

namespace gpm::python {
namespace {

// A calibration result and the robot it was calibrated from (whose name,
// home, branches and limits a calibrated robot keeps).
struct CalibrationResult {
  calib::Result result;
  Robot base;
};

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
  d["notes"] = r.notes;
  return d;
}

CalibrationResult calibrate(const py::handle& readings, const Robot& robot, const py::object& fix,
                            const std::string& cost_text, const std::string& method, const py::object& sigma,
                            bool allow_rank_deficient, const py::object& budget, long seed,
                            const py::object& true_xy) {
  // Checks in the order of app/cmd_calibrate.cpp, with its messages; the
  // argument is named as in Python (cost=, method=, ...).
  const auto cost = calib::parse_cost(cost_text);
  if (!cost) throw InputError(fmt::format("cost: '{}' is not one of j1, j2, j3, ml", cost_text));
  const calib::Method method_value = calib::parse_method(method, "method");
  std::optional<long> budget_value;
  if (!budget.is_none()) {
    budget_value = budget.cast<long>();
    check_bound(static_cast<double>(*budget_value),
                method_value == calib::Method::kLM ? limits::kLmIterations : limits::kEvaluations, "budget");
  }
  check_bound(static_cast<double>(seed), limits::kSeed, "seed");
  calib::Problem problem;
  problem.theta_m = readings_from_array(readings, "readings");
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
    else mo.budget = *budget_value;
  }
  if (!sigma.is_none()) {
    mo.encoder_sigma = check_bound(sigma.cast<double>(), limits::kEncoderSigma, "sigma");
  }
  if (!xy.empty()) mo.true_xy = &xy;

  CalibrationResult out{{}, robot};
  {
    py::gil_scoped_release unlocked;
    calib::check_samples(problem);
    out.result = calib::calibrate(problem, mo);
  }
  for (const auto& note : out.result.notes) {
    if (PyErr_WarnEx(PyExc_RuntimeWarning, note.c_str(), 1) != 0) throw py::error_already_set();
  }
  return out;
}

}  // namespace

void bind_calibrate(py::module_& m) {
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
          [](const CalibrationResult& c) {
            py::dict d;
            for (int i = 0; i < kNumParams; ++i)
              if (c.result.free.test(static_cast<size_t>(i)))
                d[py::str(std::string(param_name(i)))] = c.result.sigma[static_cast<size_t>(i)];
            return d;
          },
          "Dict of the 1-sigma of each estimated parameter (NaN when unknown).")
      .def_property_readonly(
          "diagnostics", [](const CalibrationResult& c) { return diagnostics(c.result); },
          "Dict: method, cost_function, cost (final J), iterations, evaluations, rank, free_parameters, "
          "condition_number, kmrmse_mm (when true_xy was given), seconds, converged, rank_deficient, notes.")
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
          [](const CalibrationResult& c) -> py::object {
            if (!c.result.covariance) return py::none();
            return matrix_array(*c.result.covariance);
          },
          "15 x 15 covariance of the parameters in docs/FORMATS.md order (zero rows and columns for fixed ones), or "
          "None when the solver computed none.")
      .def_property_readonly(
          "robot",
          [](const CalibrationResult& c) {
            Robot r = c.base;
            r.geometry = c.result.geometry;
            return r;
          },
          "The calibrated robot: the input robot (name, home, branches, limits) with the estimated geometry.")
      .def(
          "to_yaml", [](const CalibrationResult& c) { return calib::result_to_yaml(c.result, c.base.name); },
          "The result file text (YAML), as `gpm calibrate -o` writes it.")
      .def(
          "save",
          [](const CalibrationResult& c, const py::object& path) {
            calib::save_result(c.result, c.base.name, path_arg(path, "path"));
          },
          py::arg("path"), "Writes the result file (YAML) atomically; it can serve as a robot model.")
      .def("__repr__", [](const CalibrationResult& c) {
        return fmt::format("<gpm.CalibrationResult {} ({}), {} free, J = {:.6g}, {}>", c.result.method,
                           calib::cost_name(c.result.cost), c.result.free.count(), c.result.final_cost,
                           c.result.converged ? "converged" : "NOT converged");
      });

  m.def("calibrate", &calibrate, py::arg("readings"), py::arg("robot"),
        py::arg("fix") = std::vector<std::string>{"xa1", "ya1", "xa2", "ya2"}, py::arg("cost") = "ml",
        py::arg("method") = "lm", py::arg("sigma") = py::none(), py::arg("allow_rank_deficient") = false,
        py::arg("budget") = py::none(), py::arg("seed") = 1, py::arg("true_xy") = py::none(),
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
true_xy   optional (n, 2) true end-effector positions (mm) for kmrmse (eq. 40).

Bad input raises gpm.InputError (a ValueError) with the command line's
message (fewer samples than free parameters, circles that do not meet,
a rank-deficient free set naming what to fix, unknown names). A solve that
does not converge returns normally with .converged False; the solver's
warnings are issued as RuntimeWarning. The GIL is released while solving.
)doc");

  m.def(
      "load_result",
      [](const py::object& path, const py::object& robot) {
        CalibrationResult c{calib::load_result(path_arg(path, "path")), Robot{}};
        if (!robot.is_none()) c.base = robot.cast<Robot>();
        return c;
      },
      py::arg("path"), py::arg("robot") = py::none(),
      "Loads a result file written by `gpm calibrate` or CalibrationResult.save; robot (default: the nominal "
      "GPM2002) supplies home, branches and limits of .robot.");
}

}  // namespace gpm::python
