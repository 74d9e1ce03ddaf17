// Margins from losing control (models/drive_margin.hpp).
#include "models/drive_margin.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "models/kinematics.hpp"

namespace gpm {
namespace {

int driven_count(const DriveMask& drives) {
  return static_cast<int>(std::count(drives.begin(), drives.end(), true));
}

// The two driven chains of a five-bar (i < j), or (-1, -1) with three drives.
std::pair<int, int> driven_pair(const DriveMask& drives) {
  if (driven_count(drives) != 2) return {-1, -1};
  int i = -1, j = -1;
  for (int k = 0; k < kNumChains; ++k)
    if (drives[static_cast<size_t>(k)]) (i < 0 ? i : j) = k;
  return {i, j};
}

// The measures of geometry g with its hub at p and joints q (eq. 11's
// transmission by gpm::conditioning; the pair's type 2 in closed form).
DriveMargins measures_at(const Geometry& g, const Eigen::Vector2d& p, const JointAngles& q, const DriveMask& drives) {
  DriveMargins m;
  m.reach_mm = INFINITY;
  for (int i = 0; i < kNumChains; ++i) {
    const double d = (p - g.A(i)).norm();
    const double edge = std::min(g.la_(i) + g.lb_(i) - d, d - std::abs(g.la_(i) - g.lb_(i)));
    if (edge < m.reach_mm) m.reach_mm = edge, m.reach_chain = i;
  }
  const Conditioning c = conditioning(g, q);
  m.transmission = c.transmission.minCoeff(&m.transmission_chain);
  const auto [i, j] = driven_pair(drives);
  m.direct = i < 0 ? c.direct : std::sqrt(std::max(0.0, 1.0 - std::abs(std::cos(q.theta_b[i] - q.theta_b[j]))));
  m.ok = std::isfinite(m.transmission) && std::isfinite(m.direct);
  return m;
}

// Where the mechanism of geometry g goes when its driven joints take the
// controller's commands theta_m (free joints follow), and its measures there.
// A mechanism that cannot assemble there has no margin: when the driven
// chains' passive circles do not meet (or three elbows are collinear) it is
// past a type-2 singularity (direct 0); when the hub leaves some chain's
// annulus, past the reach (reach_mm and transmission 0).
// hub: where it goes (unset when it cannot assemble).
DriveMargins driven_mechanism(const Geometry& g, const Branches& branch, const Eigen::Vector3d& theta_m,
                              const DriveMask& drives, int pair_mode, std::optional<Eigen::Vector2d>& hub) {
  DriveMargins none;
  none.ok = true;
  const Eigen::Vector3d theta_a = active_from_readings(g, theta_m);
  const auto [i, j] = driven_pair(drives);
  std::optional<Eigen::Vector2d> fk;  // eq. 32-34
  if (i >= 0) {
    fk = forward_kinematics_two(g, theta_a, i, j, pair_mode);
  } else if (const auto r = forward_kinematics(g, theta_a)) {
    fk = r->p;
  }
  if (!fk) {
    none.direct = 0.0;
    none.transmission = none.reach_mm = INFINITY;
    return none;
  }
  const Eigen::Vector2d p = *fk;
  hub = p;
  for (int k = 0; k < kNumChains; ++k)
    if (!try_chain_ik(g, k, p, branch[static_cast<size_t>(k)])) {
      none.reach_mm = none.transmission = 0.0;
      none.reach_chain = none.transmission_chain = k;
      none.direct = INFINITY;
      return none;
    }
  JointAngles q = inverse_kinematics(g, p, branch);
  // The driven joints stay where they are driven (the IK on their branch
  // agrees unless the chain folded through its own type-1 pose).
  for (int k = 0; k < kNumChains; ++k)
    if (drives[static_cast<size_t>(k)]) {
      q.theta_a[k] = theta_a[k];
      const Eigen::Vector2d B = g.A(k) + g.la_(k) * Eigen::Vector2d(std::cos(theta_a[k]), std::sin(theta_a[k]));
      q.theta_b[k] = std::atan2(p.y() - B.y(), p.x() - B.x());  // eq. 34
    }
  return measures_at(g, p, q, drives);
}

}  // namespace

DriveMargins drive_margins(const Robot& controller, const Eigen::Vector2d& p, const DriveMask& drives) {
  const Geometry& g = controller.geometry;
  for (int k = 0; k < kNumChains; ++k)
    if (!try_chain_ik(g, k, p, controller.branch[static_cast<size_t>(k)])) return {};
  return measures_at(g, p, inverse_kinematics(g, p, controller.branch), drives);
}

DriveMargins drive_margins(const Robot& controller, const Eigen::Vector2d& p, const DriveMask& drives,
                           const ModelTolerance& tolerance) {
  DriveMargins m = drive_margins(controller, p, drives);
  if (!m.ok) return m;
  const Geometry& g0 = controller.geometry;
  // The controller's commands for p (eq. 31, 35) and the five-bar's assembly mode there.
  const JointAngles q0 = inverse_kinematics(g0, p, controller.branch);
  const Eigen::Vector3d theta_m = readings_from_active(g0, q0.theta_a);
  const auto [pi, pj] = driven_pair(drives);
  const int mode = pi < 0 ? 0 : assembly_mode(g0, q0.theta_a, p, pi, pj);
  double d_reach = 0.0, d_trans = 0.0, d_direct = 0.0, deviation2 = 0.0;
  // A measure some mechanism within the tolerance has lost (it cannot assemble).
  bool lost_reach = false, lost_direct = false;
  // The change between +t and -t; a lost side counts as lost.
  const auto change = [](double a, double b, bool& lost) {
    if (a == 0.0 || b == 0.0) lost = true;
    return std::isfinite(a) && std::isfinite(b) ? 0.5 * std::abs(a - b) : 0.0;
  };
  for (int k = 0; k < kNumParams; ++k) {
    const double t = tolerance_of(tolerance, k);
    if (!(t > 0.0)) continue;
    Geometry plus = g0, minus = g0;
    plus[k] += t;
    minus[k] -= t;
    std::optional<Eigen::Vector2d> hub_a, hub_b;
    const DriveMargins a = driven_mechanism(plus, controller.branch, theta_m, drives, mode, hub_a);
    const DriveMargins b = driven_mechanism(minus, controller.branch, theta_m, drives, mode, hub_b);
    // A side that cannot assemble has lost direct already (below).
    if (hub_a && hub_b) deviation2 += 0.25 * (*hub_a - *hub_b).squaredNorm();
    d_reach += change(a.reach_mm, b.reach_mm, lost_reach);
    bool lost_trans = false;
    d_trans += change(a.transmission, b.transmission, lost_trans);
    if (lost_trans) {
      lost_reach = true;
      m.transmission_chain = a.transmission == 0.0 ? a.transmission_chain : b.transmission_chain;
      m.reach_chain = m.transmission_chain;
    }
    d_direct += change(a.direct, b.direct, lost_direct);
  }
  m.reach_mm = lost_reach ? 0.0 : m.reach_mm - d_reach;
  m.transmission = lost_reach ? 0.0 : m.transmission - d_trans;
  m.direct = lost_direct ? 0.0 : m.direct - d_direct;
  m.deviation_mm = std::sqrt(deviation2);
  return m;
}

double tolerance_of(const ModelTolerance& t, int k) {
  return is_offset(k) ? t.offset_rad : is_length(k) ? t.link_mm : t.base_mm;
}

std::string margin_violation(const Robot& controller, const Eigen::Vector2d& p, const DriveMask& drives,
                             const PathMargin& margin) {
  const DriveMargins m = drive_margins(controller, p, drives, margin.tolerance);
  const auto [i, j] = driven_pair(drives);
  if (!m.ok) return fmt::format("({:.3f}, {:.3f}) mm is out of reach", p.x(), p.y());
  if (m.direct < margin.singularity) {
    const std::string which =
        i < 0 ? std::string("the three passive links")
              : fmt::format("the five-bar of chains {} and {} (passive links nearly parallel)", i + 1, j + 1);
    return fmt::format("({:.3f}, {:.3f}) mm is near a type-2 singularity of {}: measure {:.3f} below the margin {:.3g}",
                       p.x(), p.y(), which, m.direct, margin.singularity);
  }
  if (m.transmission < margin.singularity) {
    const bool driven = drives[static_cast<size_t>(m.transmission_chain)];
    return fmt::format(
        "({:.3f}, {:.3f}) mm is near a type-1 singularity of {} chain {}: |sin(theta_a - theta_b)| {:.3f} below the "
        "margin {:.3g}",
        p.x(), p.y(), driven ? "driven" : "free", m.transmission_chain + 1, m.transmission, margin.singularity);
  }
  if (m.reach_mm < margin.reach_mm)
    return fmt::format("({:.3f}, {:.3f}) mm is {:.2f} mm from the reach of chain {}, inside the margin {:.3g} mm",
                       p.x(), p.y(), m.reach_mm, m.reach_chain + 1, margin.reach_mm);
  if (m.deviation_mm > margin.deviation_mm)
    return fmt::format(
        "at ({:.3f}, {:.3f}) mm a mechanism within the model's tolerance would put the hub {:.2f} mm from the plan "
        "(RSS over the parameters), beyond the margin {:.3g} mm",
        p.x(), p.y(), m.deviation_mm, margin.deviation_mm);
  return {};
}

}  // namespace gpm
