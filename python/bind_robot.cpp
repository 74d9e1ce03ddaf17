// gpm.Robot, gpm.load_robot, gpm.read_samples: the robot model
// (models/robot_yaml.hpp, models/kinematics.hpp) and encoder samples
// (models/samples.hpp) in Python.
#include <memory>
#include <string>

#include <fmt/format.h>
#include <pybind11/operators.h>
#include <pybind11/stl.h>

#include "models/data_dir.hpp"
#include "models/errors.hpp"
#include "models/kinematics.hpp"
#include "models/robot_yaml.hpp"
#include "models/samples.hpp"
#include "python/bindings.hpp"
#include "python/convert.hpp"
#include "python/errors.hpp"

namespace gpm::python {
namespace {

// The robot's active angles at (x, y) on its branches; throws ReachError.
JointAngles pose_angles(const Robot& r, double x, double y) {
  return inverse_kinematics(r.geometry, {x, y}, r.branch);
}

// Forward kinematics of one row of readings; throws InputError when the
// elbows are collinear (no unique radical centre).
Eigen::Vector2d fk_row(const Robot& r, const Eigen::Vector3d& theta_m, size_t row) {
  const auto f = forward_kinematics(r.geometry, active_from_readings(r.geometry, theta_m));
  if (!f) {
    throw InputError(fmt::format("fk: readings row {} ({}, {}, {}) put the three elbows on one line: no unique "
                                 "end-effector position",
                                 row, theta_m[0], theta_m[1], theta_m[2]));
  }
  return f->p;
}

py::array_t<double> vec(const Eigen::VectorXd& v) {
  py::array_t<double> a(v.size());
  for (Eigen::Index k = 0; k < v.size(); ++k) a.mutable_at(k) = v[k];
  return a;
}

// An (n, cols) float64 array whose row j is row(j) (an Eigen vector of cols entries).
template <class Row>
py::array_t<double> rows_array(size_t n, py::ssize_t cols, const Row& row) {
  py::array_t<double> out({static_cast<py::ssize_t>(n), cols});
  auto o = out.mutable_unchecked<2>();
  for (size_t j = 0; j < n; ++j) {
    const auto v = row(j);
    for (py::ssize_t k = 0; k < cols; ++k) o(j, k) = v[k];
  }
  return out;
}

}  // namespace

// The robot's data sheet as a dict: gear_ratio, encoder_bits, cogging_periods,
// and each stated value as {nominal, min, max} (units in its key).
py::dict data_sheet_dict(const Robot& r) {
  const DataSheet& d = r.data_sheet;
  py::dict out;
  out["gear_ratio"] = d.gear_ratio;
  out["encoder_bits"] = d.encoder_bits;
  out["cogging_periods"] = d.cogging_periods;
  const std::pair<const char*, const Stated*> items[] = {
      {"encoder_accuracy_rad", &d.encoder_accuracy_rad}, {"rotor_inertia_kg_m2", &d.rotor_inertia_kg_m2},
      {"active_link_mass_kg", &d.active_link_mass_kg},   {"passive_link_mass_kg", &d.passive_link_mass_kg},
      {"end_effector_mass_kg", &d.end_effector_mass_kg}, {"coulomb_Nm", &d.coulomb_Nm},
      {"viscous_Nm_s", &d.viscous_Nm_s},                 {"stiffness_Nm_per_rad", &d.stiffness_Nm_per_rad},
      {"clearance_mm", &d.clearance_mm},                 {"latch_skew_s", &d.latch_skew_s},
      {"warm_up_time_constant_s", &d.warm_up_time_constant_s}};
  for (const auto& [key, s] : items) {
    py::dict v;
    v["nominal"] = s->nominal;
    v["min"] = s->min();
    v["max"] = s->max();
    out[key] = v;
  }
  return out;
}

namespace {

// gpm.Robot's constructor and its data: name, geometry, home, branch, limits, data sheet.
void bind_robot_data(py::class_<Robot>& robot) {
  robot
      .def(py::init([](const py::object& geometry, const py::object& name_arg) {
             const std::string name = text_arg(name_arg, "name", "the robot's name");
             Robot r;
             r.name = name;
             if (!geometry.is_none() && !py::isinstance<py::dict>(geometry))
               throw InputTypeError(fmt::format("geometry: expected a dict of parameters (e.g. {{\"la1\": 244.1}}), "
                                                "got {}", type_name(geometry)));
             if (!geometry.is_none()) r.geometry = geometry_from_dict(geometry.cast<py::dict>(), r.geometry, "geometry");
             validate_robot(r, "Robot(geometry=...)");
             return r;
           }),
           py::arg("geometry") = py::none(), py::arg("name") = "GPM2002")
      .def_readwrite("name", &Robot::name, "Name of the robot (labels result files).")
      .def_property(
          "geometry", [](const Robot& r) { return geometry_dict(r.geometry); },
          [](Robot& r, const py::dict& d) {
            Robot next = r;
            next.geometry = geometry_from_dict(d, r.geometry, "geometry");
            validate_robot(next, "Robot.geometry");
            r = next;
          },
          "Dict of the 15 parameters xa1 ya1 xa2 ya2 xa3 ya3 (base joints, mm), la1..la3 (active links, mm), "
          "lb1..lb3 (passive links, mm), dth1..dth3 (encoder zero offsets, rad). A copy: assign a dict (all or "
          "some keys) to change the robot.")
      .def_property_readonly(
          "home", [](const Robot& r) { return vec(r.home); }, "Home position (x, y) in mm, a copy.")
      .def_property_readonly(
          "branch", [](const Robot& r) { return py::make_tuple(r.branch[0], r.branch[1], r.branch[2]); },
          "Elbow branch (+1 or -1) of each chain.")
      .def_property_readonly(
          "limits",
          [](const Robot& r) {
            py::dict d;
            d["reach_margin"] = r.limits.reach_margin;
            d["min_transmission"] = r.limits.min_transmission;
            d["min_direct"] = r.limits.min_direct;
            return d;
          },
          "Workspace margins: reach_margin (mm), min_transmission and min_direct (singularity measures).")
      .def_property_readonly("data_sheet", &data_sheet_dict,
                             "What the robot's documents state (models/data_sheet.hpp, docs/FORMATS.md): gear_ratio, "
                             "encoder_bits, and for each stated value (coulomb_Nm, rotor_inertia_kg_m2, ...) a dict "
                             "nominal, min, max (the tolerance). A copy; the calibration reads these, never the twin's truth.");
}

// gpm.Robot's kinematics: ik, ik_angles, fk, jacobian, conditioning, check_reach.
void bind_robot_kinematics(py::class_<Robot>& robot) {
  robot.def(
          "ik",
          [](const Robot& r, double x, double y) {
            const JointAngles q = pose_angles(r, x, y);
            return vec(readings_from_active(r.geometry, q.theta_a));
          },
          py::arg("x"), py::arg("y"),
          "Inverse kinematics (paper eq. 31, 35): the encoder readings theta_m (3,) in rad at end-effector (x, y) "
          "mm on the robot's branches. Raises gpm.InputError naming the chain and the shortfall when out of reach.")
      .def(
          "ik",
          [](const Robot& r, const py::array_t<double, py::array::c_style | py::array::forcecast>& points) {
            const auto p = points_from_array(points, "ik(points)");
            return rows_array(p.size(), 3, [&](size_t j) {
              return Eigen::Vector3d(readings_from_active(r.geometry, inverse_kinematics(r.geometry, p[j], r.branch).theta_a));
            });
          },
          py::arg("points"),
          "Inverse kinematics of (n, 2) end-effector positions (mm): the (n, 3) encoder readings (rad), e.g. the "
          "noiseless readings of calibration poses. Raises gpm.InputError for the first point out of reach.")
      .def(
          "ik_angles",
          [](const Robot& r, double x, double y) {
            const JointAngles q = pose_angles(r, x, y);
            return py::make_tuple(vec(q.theta_a), vec(q.theta_b));
          },
          py::arg("x"), py::arg("y"),
          "Joint angles at (x, y): (theta_a, theta_b), active angles in [0, 2 pi) and passive in (-pi, pi] "
          "(eq. 31, 34). Raises gpm.InputError when out of reach.")
      .def(
          "fk",
          [](const Robot& r, const py::array_t<double, py::array::c_style | py::array::forcecast>& readings)
              -> py::array_t<double> {
            const bool single = readings.ndim() == 1;
            const auto rows = readings_from_array(readings, "fk(readings)");
            py::array_t<double> out = rows_array(rows.size(), 2, [&](size_t j) { return fk_row(r, rows[j], j); });
            if (single) return out.reshape({py::ssize_t{2}});
            return out;
          },
          py::arg("readings"),
          "Forward kinematics from encoder readings: (3,) -> (2,) or (n, 3) -> (n, 2) end-effector positions in "
          "mm, the radical centre of the three passive circles (eq. 32-33 with the docs/PAPER_NOTES.md).")
      .def(
          "jacobian",
          [](const Robot& r, double x, double y) {
            const Matrix32d J = active_jacobian(r.geometry, pose_angles(r, x, y));
            return matrix_array(J);
          },
          py::arg("x"), py::arg("y"),
          "Active Jacobian d theta_a / d(x, y) at end-effector (x, y): a (3, 2) array in rad/mm (eq. 11).")
      .def(
          "conditioning",
          [](const Robot& r, double x, double y) {
            const Conditioning c = conditioning(r.geometry, pose_angles(r, x, y));
            py::dict d;
            d["transmission"] = vec(c.transmission);
            d["min_transmission"] = c.min_transmission;
            d["direct"] = c.direct;
            d["jacobian_condition"] = c.jacobian_condition;
            return d;
          },
          py::arg("x"), py::arg("y"),
          "Singularity measures at (x, y): transmission (3,) = |sin(theta_a - theta_b)| per chain and its "
          "minimum (type 1, 0 at a serial singularity), direct (type 2, 1 for passive links 120 deg apart, 0 at a "
          "parallel singularity) and jacobian_condition (condition number of eq. 11).")
      .def(
          "check_reach",
          [](const Robot& r, double x, double y) {
            const Reach reach = check_reach(r, {x, y});
            return py::make_tuple(reach.ok, reach.reason);
          },
          py::arg("x"), py::arg("y"),
          "(ok, reason): whether (x, y) is reachable keeping the robot's margins; reason says what is violated.");
}

// gpm.Robot as a file: to_yaml, save, ==, repr.
void bind_robot_file(py::class_<Robot>& robot) {
  robot.def(
          "to_yaml", [](const Robot& r) { return robot_to_yaml(r); },
          "The robot file text (YAML, every number written exactly).")
      .def(
          "save", [](const Robot& r, const py::object& path) { save_robot(r, path_arg(path, "path")); }, py::arg("path"),
          "Writes the robot file atomically.")
      .def(py::self == py::self)
      .def("__repr__", [](const Robot& r) {
        return fmt::format("<gpm.Robot '{}' la=({}, {}, {}) dth=({}, {}, {})>", r.name, r.geometry[kLa1],
                           r.geometry[kLa2], r.geometry[kLa3], r.geometry[kDth1], r.geometry[kDth2], r.geometry[kDth3]);
      });
}

// gpm.load_robot, read_samples, models_dir and scenarios_dir.
void bind_robot_loaders(py::module_& m) {
  m.def(
      "load_robot",
      [](const py::object& path) {
        return load_robot(path.is_none() ? models_dir() + "/gpm2002.yaml" : path_arg(path, "path"));
      },
      py::arg("path") = py::none(),
      "Loads and validates a robot file (YAML); without a path, the nominal GPM2002 (models/gpm2002.yaml). "
      "Raises gpm.InputError with one line naming the file, key and what would be valid.");

  m.def(
      "read_samples",
      [](const py::object& path, bool with_xy) -> py::object {
        auto s = std::make_unique<Samples>(read_samples_csv(path_arg(path, "path")));
        const Samples* raw = s.get();
        // The arrays view the vectors of s in place; the capsule owns s.
        py::capsule owner(s.release(), [](void* p) { delete static_cast<Samples*>(p); });
        auto theta = view_rows(raw->theta_m.empty() ? nullptr : raw->theta_m.front().data(), raw->size(), 3,
                               sizeof(Eigen::Vector3d), owner, true);
        if (!with_xy) return theta;
        if (!raw->has_xy) return py::make_tuple(theta, py::none());
        auto xy = view_rows(raw->xy.front().data(), raw->xy.size(), 2, sizeof(Eigen::Vector2d), owner, true);
        return py::make_tuple(theta, xy);
      },
      py::arg("path"), py::arg("with_xy") = false,
      "Reads a samples CSV (columns found by name: sample,theta_m1,theta_m2,theta_m3[,x,y]): an (n, 3) float64 "
      "array of encoder readings in rad, without a copy of the parsed data. with_xy=True returns (readings, xy) "
      "with xy the (n, 2) true end-effector positions in mm, or None when the file has no x,y columns.");

  m.def("models_dir", &models_dir, "Folder of the nominal robot files (gpm2002.yaml, gpm2002.xml).");
  m.def("scenarios_dir", &scenarios_dir, "Folder of the scenario library (*.yaml).");
}

}  // namespace

void bind_robot(py::module_& m) {
  py::class_<Robot> robot(m, "Robot", R"doc(
The robot model: 15 geometric parameters, home, elbow branches and workspace
margins (models/robot.hpp). Millimetres and radians throughout.

Robot(geometry=None, name="GPM2002") starts from the GPM2002's nominal
geometry and replaces the parameters given in the dict `geometry`.
Use gpm.load_robot(path) for a robot file.
)doc");
  bind_robot_data(robot);
  bind_robot_kinematics(robot);
  bind_robot_file(robot);
  bind_robot_loaders(m);
}

}  // namespace gpm::python
