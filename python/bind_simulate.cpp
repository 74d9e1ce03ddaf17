// gpm.simulate and gpm.Simulation: one run of a scenario on the MuJoCo twin
// (sim/simulate.hpp, sim/scenario.hpp), its samples and trajectory as NumPy
// views into the run's records.
#include <algorithm>
#include <memory>
#include <string>

#include <fmt/format.h>
#include <pybind11/stl.h>

#include "python/bindings.hpp"
#include "python/convert.hpp"
#include "sim/scenario.hpp"
#include "sim/simulate.hpp"

namespace gpm::python {
namespace {

struct Simulation {
  sim::Scenario scenario;
  sim::SimulationResult result;
};

// An (n,) read-only float64 view of one double per record, `stride` bytes apart.
py::array_t<double> view_column(const double* first, size_t n, size_t stride, py::handle base) {
  static const double empty = 0.0;
  if (n == 0) first = &empty;
  py::array_t<double> a({static_cast<py::ssize_t>(n)}, {static_cast<py::ssize_t>(stride)}, first, base);
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

template <class Record, class Member>
py::array_t<double> rows_of(const std::vector<Record>& v, Member member, size_t cols, py::handle base) {
  return view_rows(v.empty() ? nullptr : (v.front().*member).data(), v.size(), cols, sizeof(Record), base);
}

py::dict samples_dict(py::object self) {
  const auto& s = self.cast<const Simulation&>().result.samples;
  using R = sim::SampleRecord;
  py::array_t<long> id(static_cast<py::ssize_t>(s.size()));
  py::array_t<bool> settled(static_cast<py::ssize_t>(s.size()));
  for (size_t j = 0; j < s.size(); ++j) {
    id.mutable_at(j) = s[j].id;
    settled.mutable_at(j) = s[j].settled;
  }
  py::dict d;
  d["sample"] = id;
  d["theta_m"] = rows_of(s, &R::theta_m, 3, self);
  d["theta_a"] = rows_of(s, &R::theta_a, 3, self);
  d["xy"] = rows_of(s, &R::xy_mm, 2, self);
  d["target"] = rows_of(s, &R::target, 2, self);
  d["settled"] = settled;
  d["settle_time_s"] = view_column(s.empty() ? nullptr : &s.front().settle_time_s, s.size(), sizeof(R), self);
  return d;
}

py::dict trajectory_dict(py::object self) {
  const auto& rows = self.cast<const Simulation&>().result.log.rows;
  using R = sim::LogRow;
  py::dict d;
  d["t"] = view_column(rows.empty() ? nullptr : &rows.front().t, rows.size(), sizeof(R), self);
  d["desired"] = rows_of(rows, &R::desired, 2, self);
  d["actual"] = rows_of(rows, &R::actual, 2, self);
  d["readings"] = rows_of(rows, &R::readings, 3, self);
  d["torque"] = rows_of(rows, &R::torque, 3, self);
  d["violation_m"] = view_column(rows.empty() ? nullptr : &rows.front().violation_m, rows.size(), sizeof(R), self);
  return d;
}

// Simulation's repr: the samples, the time, the trajectory and the physics' figures in two lines.
std::string simulation_repr(const Simulation& s) {
  const sim::SimulationResult& r = s.result;
  const auto settled = std::count_if(r.samples.begin(), r.samples.end(), [](const auto& x) { return x.settled; });
  const Geometry& a = r.actual.geometry;
  return fmt::format(
      "<gpm.Simulation '{}': {} samples ({} settled) in {:.3f} s of robot time, {:.3f} s simulated, {} trajectory "
      "rows\n  max torque {:.4g} N m, max loop-closure violation {:.3g} m; actual la=({:.4f}, {:.4f}, {:.4f}) "
      "dth=({:.5f}, {:.5f}, {:.5f})>",
      s.scenario.name, r.samples.size(), settled, r.sampling_s, r.simulated_s, r.log.rows.size(), r.max_torque,
      r.max_violation_m, a[kLa1], a[kLa2], a[kLa3], a[kDth1], a[kDth2], a[kDth3]);
}

}  // namespace

void bind_simulate(py::module_& m) {
  py::class_<Simulation, std::shared_ptr<Simulation>>(m, "Simulation", R"doc(
One simulation run of a scenario on the MuJoCo twin (gpm.simulate). Arrays
are read-only views into the run's records (no copies), valid as long as any
of them or this object lives.
)doc")
      .def_property_readonly(
          "readings",
          [](py::object self) {
            return rows_of(self.cast<const Simulation&>().result.samples, &sim::SampleRecord::theta_m, 3, self);
          },
          "(n, 3) averaged encoder readings of the samples (rad): the input of gpm.calibrate.")
      .def_property_readonly(
          "xy",
          [](py::object self) {
            return rows_of(self.cast<const Simulation&>().result.samples, &sim::SampleRecord::xy_mm, 2, self);
          },
          "(n, 2) true end-effector positions of the samples (mm).")
      .def_property_readonly("samples", &samples_dict,
                             "Dict of the samples (samples.csv): sample (n,) ids, theta_m (n, 3) readings, theta_a "
                             "(n, 3) true active angles, xy (n, 2) true end-effector, target (n, 2) commanded pose, "
                             "settled (n,) bool, settle_time_s (n,).")
      .def_property_readonly("trajectory", &trajectory_dict,
                             "Dict of the trajectory log (trajectory.csv): t (m,), desired (m, 2) and actual (m, 2) "
                             "end-effector (mm), readings (m, 3) rad, torque (m, 3) N m, violation_m (m,).")
      .def_property_readonly(
          "actual", [](const Simulation& s) { return s.result.actual; },
          "The actual (true) robot of the run: the controller's robot with the scenario's perturbation.")
      .def_property_readonly(
          "controller", [](const Simulation& s) { return s.scenario.controller; },
          "The controller's robot model (the scenario's robot): the start of a calibration.")
      .def_property_readonly(
          "model_xml", [](const Simulation& s) { return s.result.model_xml; }, "The MJCF model of the twin.")
      .def_property_readonly(
          "max_violation_m", [](const Simulation& s) { return s.result.max_violation_m; },
          "Largest loop-closure violation over the run (m).")
      .def_property_readonly(
          "max_torque", [](const Simulation& s) { return s.result.max_torque; }, "Largest joint torque (N m).")
      .def_property_readonly(
          "simulated_s", [](const Simulation& s) { return s.result.simulated_s; }, "Simulated time (s).")
      .def_property_readonly(
          "sampling_s", [](const Simulation& s) { return s.result.sampling_s; },
          "Robot time of the sampling, from the first move to the last reading (s).")
      .def_property_readonly(
          "name", [](const Simulation& s) { return s.scenario.name; }, "The scenario's name.")
      .def(
          "save", [](const Simulation& s, const py::object& dir) {
            sim::write_simulation(s.result, path_arg(dir, "dir"));
          },
          py::arg("dir"),
          "Writes samples.csv, trajectory.csv, actual.yaml and model.xml into dir, all or nothing (as `gpm "
          "simulate -o DIR`).")
      .def("__repr__", &simulation_repr);

  m.def(
      "simulate",
      [](const py::object& path) {
        auto out = std::make_shared<Simulation>();
        out->scenario = sim::load_scenario(path_arg(path, "scenario_path"));
        py::gil_scoped_release unlocked;
        out->result = sim::run_simulation(out->scenario);
        return out;
      },
      py::arg("scenario_path"),
      R"doc(
Runs a scenario file on the MuJoCo twin (as `gpm simulate`): builds the
actual robot, checks every target, takes the samples and follows the path.
Returns a gpm.Simulation (samples and trajectory as arrays). Raises
gpm.InputError for a bad scenario or an unreachable target, gpm.SimError if
the physics diverges.
)doc");
}

}  // namespace gpm::python
