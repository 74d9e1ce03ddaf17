#include "calib/initial.hpp"

#include <fmt/format.h>

#include "models/errors.hpp"
#include "models/kinematics.hpp"

namespace gpm::calib {

Geometry offsets_from_reference(const Robot& model, const Eigen::Vector3d& theta_m_ref,
                                const Eigen::Vector2d& reference_xy) {
  JointAngles q;
  try {
    q = inverse_kinematics(model.geometry, reference_xy, model.branch);
  } catch (const ReachError& e) {
    throw InputError(fmt::format("--reference-point ({}, {}): not reachable with the model: {}",
                                 reference_xy.x(), reference_xy.y(), e.what()));
  }
  Geometry g = model.geometry;
  for (int i = 0; i < kNumChains; ++i) g[dth(i)] = wrap_pi(q.theta_a[i] - theta_m_ref[i]);  // step 3
  return g;
}

}  // namespace gpm::calib
