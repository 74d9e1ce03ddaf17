// Run-time pose design (run/sampling_design.hpp).
#include "run/sampling_design.hpp"

#include <fmt/format.h>

#include "calib/excitation/excitation.hpp"
#include "models/errors.hpp"

namespace gpm::scenario {

void design_sampling(sim::Scenario& s, const FreeMask& free, double sigma_rad,
                     const std::function<bool(const Eigen::Vector2d&)>& admissible) {
  if (!s.sampling) return;
  const int p = static_cast<int>(free.count());
  const bool designed = s.sampling->pattern == sim::PosePattern::kDesigned ||
                        s.sampling->pattern == sim::PosePattern::kTrajectory;
  if (designed && !s.sampling->needs_design() && static_cast<int>(s.sampling->poses.size()) < p)
    throw InputError(fmt::format("{}: sampling.poses: {} designed poses cannot determine {} free parameters; "
                                 "give at least {} (gpm design --count {})",
                                 s.file, s.sampling->poses.size(), p, p, p));
  if (!s.sampling->needs_design()) return;
  if (s.sampling->count < p)
    throw InputError(fmt::format("{}: sampling.count: {} designed poses cannot determine {} free parameters; "
                                 "use a count of at least {}",
                                 s.file, s.sampling->count, p, p));
  calib::excitation::DesignOptions o;
  o.count = s.sampling->count;
  o.free = free;
  o.sigma = sigma_rad > 0.0 ? sigma_rad : 1e-5;
  o.admissible = admissible;
  if (s.sampling->pattern == sim::PosePattern::kTrajectory) {
    // The spline through the poses bulges past them: keep the poses further
    // from the limits than stop-and-go needs, so the path between them stays
    // inside (every millimetre of it is still checked before the robot moves).
    o.guard.reach_mm = 12.0;
    o.guard.transmission = 0.06;
    o.guard.direct = 0.06;
  }
  s.sampling->poses = calib::excitation::design_poses(s.controller, o).poses;
}

}  // namespace gpm::scenario
