// gpm kin: inverse and forward kinematics of a robot file, with conditioning.
//   gpm kin home            the home configuration
//   gpm kin ik X Y          active and passive angles for an end-effector target
//   gpm kin fk T1 T2 T3     end-effector from three active angles (or readings)
// With --json: one JSON document on stdout with the same content as the text.
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "app/commands.hpp"
#include "app/json_output.hpp"
#include "models/kinematics.hpp"
#include "models/robot_yaml.hpp"

namespace gpm::cli {
namespace {

struct KinOptions {
  std::string model;
  std::vector<double> xy;
  std::vector<double> angles;
  bool readings = false;
  bool json = false;
};

// The configuration as one JSON document (the keys mirror the text output;
// numbers are exact, non-finite ones null).
void print_configuration_json(const Robot& robot, const Eigen::Vector2d& p, const JointAngles& q,
                              std::optional<double> closure_mm2) {
  const Conditioning c = conditioning(robot.geometry, q);
  const Eigen::Vector3d m = readings_from_active(robot.geometry, q.theta_a);
  const Reach r = check_reach(robot, p);
  const auto vec = [](const Eigen::Vector3d& v) {
    Json a = Json::array();
    for (int i = 0; i < 3; ++i) a.push_back(json_number(v[i]));
    return a;
  };
  Json j;
  j["robot"] = robot.name;
  j["end_effector_mm"] = {{"x", json_number(p.x())}, {"y", json_number(p.y())}};
  j["theta_a_rad"] = vec(q.theta_a);
  j["theta_b_rad"] = vec(q.theta_b);
  j["theta_m_rad"] = vec(m);
  j["transmission"] = vec(c.transmission);
  j["transmission_margin"] = json_number(robot.limits.min_transmission);
  j["passive_spread"] = json_number(c.direct);
  j["passive_spread_margin"] = json_number(robot.limits.min_direct);
  j["jacobian_condition"] = json_number(c.jacobian_condition);
  j["workspace"] = {{"inside", r.ok}, {"reason", r.reason}};
  if (closure_mm2) j["closure_mm2"] = json_number(*closure_mm2);
  print_json(j);
}

void print_configuration(const Robot& robot, const Eigen::Vector2d& p, const JointAngles& q) {
  const Conditioning c = conditioning(robot.geometry, q);
  const Eigen::Vector3d m = readings_from_active(robot.geometry, q.theta_a);
  fmt::print("robot            {}\n", robot.name);
  fmt::print("end-effector     x = {:.6f} mm, y = {:.6f} mm\n", p.x(), p.y());
  fmt::print("chain            {:>14} {:>14} {:>14}\n", "1", "2", "3");
  fmt::print("theta_a (rad)    {:>14.10f} {:>14.10f} {:>14.10f}\n", q.theta_a[0], q.theta_a[1], q.theta_a[2]);
  fmt::print("theta_b (rad)    {:>14.10f} {:>14.10f} {:>14.10f}\n", q.theta_b[0], q.theta_b[1], q.theta_b[2]);
  fmt::print("theta_m (rad)    {:>14.10f} {:>14.10f} {:>14.10f}\n", m[0], m[1], m[2]);
  fmt::print("transmission     {:>14.4f} {:>14.4f} {:>14.4f}   (|sin(theta_a - theta_b)|, type-1 margin {})\n",
             c.transmission[0], c.transmission[1], c.transmission[2], robot.limits.min_transmission);
  fmt::print("passive spread   {:.4f}   (type-2 measure, margin {})\n", c.direct, robot.limits.min_direct);
  fmt::print("cond(J)          {:.4f}   (eq. 11 Jacobian)\n", c.jacobian_condition);
  const Reach r = check_reach(robot, p);
  fmt::print("workspace        {}\n", r.ok ? "inside, with margins" : "outside: " + r.reason);
}

}  // namespace

void add_kin(CLI::App& app) {
  auto opt = std::make_shared<KinOptions>();
  auto* kin = app.add_subcommand("kin", "Kinematics of a robot file: home, ik, fk");
  kin->require_subcommand(1);

  auto* home = kin->add_subcommand("home", "Print the home configuration");
  home->add_option("--model", opt->model, "Robot file (YAML); default: the nominal GPM2002");
  home->add_flag("--json", opt->json, "One JSON document on stdout instead of the text");
  home->callback([opt] {
    const Robot robot = load_robot(opt->model.empty() ? default_model_path() : opt->model);
    const JointAngles q = inverse_kinematics(robot.geometry, robot.home, robot.branch);
    if (opt->json) print_configuration_json(robot, robot.home, q, std::nullopt);
    else print_configuration(robot, robot.home, q);
  });

  auto* ik = kin->add_subcommand("ik", "Inverse kinematics: active and passive angles for X Y (mm)");
  ik->add_option("xy", opt->xy, "End-effector X Y in mm")->required()->expected(2);
  ik->add_option("--model", opt->model, "Robot file (YAML); default: the nominal GPM2002");
  ik->add_flag("--json", opt->json, "One JSON document on stdout instead of the text");
  ik->callback([opt] {
    const Robot robot = load_robot(opt->model.empty() ? default_model_path() : opt->model);
    const Eigen::Vector2d p(opt->xy[0], opt->xy[1]);
    const JointAngles q = inverse_kinematics(robot.geometry, p, robot.branch);
    if (opt->json) print_configuration_json(robot, p, q, std::nullopt);
    else print_configuration(robot, p, q);
  });

  auto* fk = kin->add_subcommand("fk", "Forward kinematics from three active angles T1 T2 T3 (rad)");
  fk->add_option("angles", opt->angles, "Active angles in rad")->required()->expected(3);
  fk->add_flag("--readings", opt->readings, "The angles are encoder readings (theta_a = theta_m + dth)");
  fk->add_option("--model", opt->model, "Robot file (YAML); default: the nominal GPM2002");
  fk->add_flag("--json", opt->json, "One JSON document on stdout instead of the text");
  fk->callback([opt] {
    const Robot robot = load_robot(opt->model.empty() ? default_model_path() : opt->model);
    Eigen::Vector3d t(opt->angles[0], opt->angles[1], opt->angles[2]);
    if (opt->readings) t = active_from_readings(robot.geometry, t);
    const auto f = forward_kinematics(robot.geometry, t);
    if (!f) throw InputError("gpm kin fk: the three elbows are collinear; the end-effector is not determined");
    JointAngles q;
    q.theta_a = t;
    q.theta_b = f->theta_b;
    if (opt->json) {
      print_configuration_json(robot, f->p, q, f->power);
      return;
    }
    print_configuration(robot, f->p, q);
    fmt::print("closure          {:.6g} mm^2   (power of O w.r.t. each passive circle; 0 when the loops close)\n",
               f->power);
  });
}

}  // namespace gpm::cli
