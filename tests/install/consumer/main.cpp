// Consumer of the installed gpm package (tests/install/test_install.sh). Loads
// the nominal robot from the data folder (gpm::models_dir()), checks that FK
// inverts IK at home, and calibrates exact synthetic readings of a robot that
// differs from it: the estimate must recover the differences (identifiable
// parameters, xa1 ya1 xa2 ya2 fixed). Prints the data folder; exit 0 when all
// checks pass, 1 otherwise.
#include <cmath>
#include <cstdio>

#include "calib/lm.hpp"
#include "calib/synthetic.hpp"
#include "models/data_dir.hpp"
#include "models/kinematics.hpp"
#include "models/robot_yaml.hpp"

int main() {
  const gpm::Robot nominal = gpm::load_robot(gpm::models_dir() + "/gpm2002.yaml");
  std::printf("models_dir %s\nrobot %s\n", gpm::models_dir().c_str(), nominal.name.c_str());

  // IK then FK at home returns home.
  const gpm::JointAngles q = gpm::inverse_kinematics(nominal.geometry, nominal.home, nominal.branch);
  const auto f = gpm::forward_kinematics(nominal.geometry, q.theta_a);
  const double fk_error = f ? (f->p - nominal.home).norm() : INFINITY;
  std::printf("fk(ik(home)) error %.3g mm\n", fk_error);

  // The actual robot: longer la3 and lb1, encoder offsets, A3 moved.
  gpm::Robot actual = nominal;
  actual.geometry[gpm::kLa3] += 0.4;
  actual.geometry[gpm::kLb1] -= 0.3;
  actual.geometry[gpm::kDth2] += 0.01;
  actual.geometry[gpm::kXa3] += 0.5;
  const gpm::Samples samples = gpm::calib::workspace_samples(actual, 40, 7);

  // As in docs/INSTALL.md's "Installing" section.
  const gpm::calib::Problem problem{samples.theta_m, nominal.geometry, gpm::default_free_mask()};
  const gpm::calib::Result r = gpm::calib::calibrate_lm(problem, {});
  double worst = 0.0;
  for (int i = 0; i < gpm::kNumParams; ++i) worst = std::fmax(worst, std::fabs(r.geometry[i] - actual.geometry[i]));
  std::printf("calibration: converged %d, largest parameter error %.3g\n", r.converged ? 1 : 0, worst);
  return fk_error < 1e-9 && r.converged && worst < 1e-6 ? 0 : 1;
}
