// gpm.design, gpm.pose_bounds and gpm.crb: excitation design
// (calib/excitation/excitation.hpp, fisher.hpp, pose_list.hpp) and the
// Cramer-Rao bound (calib/crb.hpp) in Python, with the checks of `gpm design`.
#include <cmath>
#include <memory>
#include <string>

#include <fmt/format.h>
#include <pybind11/stl.h>

#include "calib/crb.hpp"
#include "calib/excitation/excitation.hpp"
#include "calib/excitation/pose_list.hpp"
#include "models/bounds.hpp"
#include "models/errors.hpp"
#include "models/kinematics.hpp"
#include "models/robot_yaml.hpp"
#include "python/bindings.hpp"
#include "python/convert.hpp"
#include "python/errors.hpp"

namespace gpm::python {
namespace {

namespace ex = calib::excitation;

py::array_t<double> vec(const Eigen::VectorXd& v) {
  py::array_t<double> a(v.size());
  for (Eigen::Index k = 0; k < v.size(); ++k) a.mutable_at(k) = v[k];
  return a;
}

py::dict bounds_dict(const ex::Bounds& b) {
  py::list names;
  for (int i : b.free_index) names.append(std::string(param_name(i)));
  py::dict d;
  d["free"] = names;
  d["sigma"] = vec(b.sigma);
  d["scaled"] = vec(b.scaled);
  d["worst_mm"] = b.worst_mm;
  d["worst_param"] = b.worst_param >= 0 ? py::object(py::str(std::string(param_name(b.worst_param)))) : py::none();
  d["mean_mm"] = b.mean_mm;
  d["log_det"] = b.log_det;
  return d;
}

struct PyDesign {
  ex::Design design;
  ex::DesignOptions options;
};

// A read-only (n, 2) view of one pose list of the design held by self (no copy).
py::array_t<double> poses_view(const py::object& self, std::vector<Eigen::Vector2d> ex::Design::*list) {
  const auto& p = self.cast<const PyDesign&>().design.*list;
  return view_rows(p.empty() ? nullptr : p.front().data(), p.size(), 2, sizeof(Eigen::Vector2d), self);
}

// gpm.Design: the chosen poses, the greedy start, their bounds, and the pose list file.
void bind_design_class(py::module_& m) {
  py::class_<PyDesign, std::shared_ptr<PyDesign>>(m, "Design", R"doc(
Calibration poses chosen by gpm.design, with their Cramer-Rao bounds at the
nominal geometry (calib/excitation/excitation.hpp).
)doc")
      .def_property_readonly(
          "poses", [](py::object self) { return poses_view(self, &ex::Design::poses); },
          "(n, 2) chosen poses in mm (a read-only view into the design, no copy).")
      .def_property_readonly(
          "start", [](py::object self) { return poses_view(self, &ex::Design::start); },
          "(n, 2) greedy D-optimal start of the exchange, mm.")
      .def_property_readonly(
          "bounds", [](const PyDesign& d) { return bounds_dict(d.design.bounds); },
          "Bounds of the poses: dict free (names), sigma (own units), scaled (mm; offsets as rad x la_i), "
          "worst_mm, worst_param, mean_mm, log_det.")
      .def_property_readonly(
          "start_bounds", [](const PyDesign& d) { return bounds_dict(d.design.start_bounds); },
          "Bounds of the greedy start (same keys as bounds).")
      .def_property_readonly(
          "candidates", [](const PyDesign& d) { return d.design.candidates; }, "Size of the candidate grid.")
      .def_property_readonly(
          "exchanges", [](const PyDesign& d) { return d.design.exchanges; }, "Swaps made by the exchange stages.")
      .def_property_readonly(
          "positioning_bound_um",
          [](const PyDesign& d) -> py::object {
            if (d.options.criterion != ex::Criterion::kPositioning) return py::none();
            return py::float_(d.design.positioning_bound_um);
          },
          "With the positioning criterion: its value, the positioning RMS over the 80 mm disc at best (um); else None.")
      .def(
          "to_yaml",
          [](const PyDesign& d, const std::string& comment) { return ex::pose_list_yaml(d.design.poses, comment); },
          py::arg("comment") = "gpm.design",
          "The pose list as scenario YAML (sampling.pattern: list), as `gpm design -o` writes it.")
      .def(
          "save",
          [](const PyDesign& d, const py::object& path, const std::string& comment) {
            write_file_atomic(path_arg(path, "path"), ex::pose_list_yaml(d.design.poses, comment));
          },
          py::arg("path"), py::arg("comment") = "gpm.design",
          "Writes the pose list atomically; the file is a scenario: gpm.simulate(path) samples the poses.")
      .def("__repr__", [](const PyDesign& d) {
        const ex::Bounds& b = d.design.bounds;
        return fmt::format("<gpm.Design {} poses by the {} criterion from {} candidates ({} exchanges): worst bound "
                           "{:.4g} mm ({}), mean {:.4g} mm; the greedy start's worst {:.4g} mm>",
                           d.design.poses.size(), ex::criterion_name(d.options.criterion), d.design.candidates,
                           d.design.exchanges, b.worst_mm, b.worst_param >= 0 ? param_name(b.worst_param) : "none",
                           b.mean_mm, d.design.start_bounds.worst_mm);
      });
}

// gpm.design: the excitation design of gpm design.
void bind_design_function(py::module_& m) {
  m.def(
      "design",
      [](const py::object& robot, const py::object& count, const py::object& sigma, const py::object& fix,
         const py::object& criterion, const py::object& grid_step, const py::object& guard) {
        auto out = std::make_shared<PyDesign>();
        out->options = ex::checked_design_options(
            number_arg(count, "count", limits::kDesignPoses), number_arg(sigma, "sigma", limits::kEncoderSigma),
            ~param_set(fix, "fix"), text_arg(criterion, "criterion", "d, worst or positioning"), number_arg(grid_step, "grid_step", limits::kGridStep),
            number_arg(guard, "guard", limits::kDesignGuard), false);
        const Robot r = robot.is_none() ? Robot{} : robot_arg(robot, "robot");
        py::gil_scoped_release unlocked;
        out->design = ex::design_poses(r, out->options);
        return out;
      },
      py::arg("robot") = py::none(), py::arg("count") = 50, py::arg("sigma") = 1e-4,
      py::arg("fix") = std::vector<std::string>{"xa1", "ya1", "xa2", "ya2"}, py::arg("criterion") = "worst",
      py::arg("grid_step") = 5.0, py::arg("guard") = ex::Guard{}.reach_mm,
      R"doc(
Chooses `count` calibration poses that make the free parameters most
accurate (excitation design, as `gpm design`), at the geometry of `robot`
(default: the nominal GPM2002, what is known before calibration).

criterion  "worst" (minimise the largest Cramer-Rao bound, offsets as
           rad x la_i), "d" (maximise log det of the Fisher information)
           or "positioning" (minimise the positioning bound over the 80 mm
           disc round home, each encoder's error once per joint revolution
           estimated under the data sheet's prior; depends on sigma);
sigma      encoder noise (rad); scales the bounds, not the poses (but for
           "positioning", where it weighs the readings against the prior);
fix        parameters held fixed (default xa1, ya1, xa2, ya2);
grid_step  candidate grid spacing (mm); guard  extra reach margin (mm).
Returns a gpm.Design. Raises gpm.InputError for bad options.
)doc");
}

// The noiseless encoder readings: readings (n, 3) rad when given, else those of poses (n, 2) mm.
std::vector<Eigen::Vector3d> crb_readings(const Robot& robot, const py::object& readings, const py::object& poses) {
  if (!readings.is_none()) return readings_from_array(readings, "readings");
  std::vector<Eigen::Vector3d> theta;
  for (const auto& p : points_from_array(poses, "poses")) {
    const JointAngles q = inverse_kinematics(robot.geometry, p, robot.branch);
    theta.push_back(readings_from_active(robot.geometry, q.theta_a));
  }
  return theta;
}

// gpm.crb's dict: free names, std per name, covariance and Fisher information.
py::dict crb_dict(const py::object& robot_object, const py::object& readings, const py::object& sigma_arg,
                  const py::object& fix, const py::object& poses) {
  const Robot robot = robot_arg(robot_object, "robot");
  if (readings.is_none() == poses.is_none())
    throw InputError("crb: give exactly one of readings= (n, 3) rad or poses= (n, 2) mm");
  const double sigma = number_arg(sigma_arg, "sigma", limits::kEncoderSigma);
  const FreeMask free = ~param_set(fix, "fix");
  const std::vector<Eigen::Vector3d> theta = crb_readings(robot, readings, poses);
  if (theta.size() < free.count())
    throw InputError(fmt::format("crb: {} samples cannot bound {} free parameters (need at least {})", theta.size(),
                                 free.count(), free.count()));
  const Eigen::MatrixXd fisher = calib::fisher_information(robot.geometry, free, theta, sigma);
  const Eigen::MatrixXd bound = calib::cramer_rao_bound(robot.geometry, free, theta, sigma);
  const auto sd = calib::crb_sigma(robot.geometry, free, theta, sigma);
  py::dict std_dict;
  for (int i = 0; i < kNumParams; ++i)
    if (free.test(static_cast<size_t>(i))) std_dict[py::str(std::string(param_name(i)))] = sd[static_cast<size_t>(i)];
  py::dict d;
  d["free"] = param_names(free);
  d["std"] = std_dict;
  d["covariance"] = matrix_array(bound);
  d["fisher"] = matrix_array(fisher);
  return d;
}

// gpm.pose_bounds and gpm.crb: Cramer-Rao bounds of poses or readings.
void bind_bounds(py::module_& m) {
  m.def(
      "pose_bounds",
      [](const py::object& robot, const py::handle& poses, const py::object& sigma, const py::object& fix) {
        const auto p = points_from_array(poses, "poses");
        const FreeMask free = ~param_set(fix, "fix");
        return bounds_dict(ex::pose_bounds(robot_arg(robot, "robot"), free, p,
                                           number_arg(sigma, "sigma", limits::kEncoderSigma)));
      },
      py::arg("robot"), py::arg("poses"), py::arg("sigma") = 1e-4,
      py::arg("fix") = std::vector<std::string>{"xa1", "ya1", "xa2", "ya2"},
      "Cramer-Rao bounds of an (n, 2) set of poses (mm) at the robot's geometry, as a dict (see Design.bounds). "
      "Raises gpm.InputError for a pose the robot cannot reach.");

  m.def(
      "crb",
      &crb_dict,
      py::arg("robot"), py::arg("readings") = py::none(), py::arg("sigma") = 1e-4,
      py::arg("fix") = std::vector<std::string>{"xa1", "ya1", "xa2", "ya2"}, py::arg("poses") = py::none(),
      R"doc(
Cramer-Rao bound of the free parameters (calib/crb.hpp) at the robot's
geometry taken as the truth, for iid encoder noise sigma (rad): from the
noiseless readings (n, 3) of the samples, or from poses (n, 2) mm (their
readings by inverse kinematics). Returns a dict: free (names), std (name ->
bound, mm or rad), covariance (k, k) = sigma^2 (J' J)^-1 and fisher (k, k)
= J' J / sigma^2, with J the Jacobian of the ML residual.
)doc");
}

}  // namespace

void bind_design(py::module_& m) {
  bind_design_class(m);
  bind_design_function(m);
  bind_bounds(m);
}

}  // namespace gpm::python
