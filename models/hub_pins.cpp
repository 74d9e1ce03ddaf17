#include "models/hub_pins.hpp"

#include <fmt/format.h>

#include "models/yaml_util.hpp"

namespace gpm {

bool MjcfEffects::pinned_hub() const {
  for (const auto& p : hub_pin_m)
    if (p[0] != 0.0 || p[1] != 0.0) return true;
  return false;
}

// theta_i = chain_ik(g, i, p + p_i / kMetresPerMm) (p and g in mm, p_i in m).
JointAngles hub_assembly_ik(const Geometry& g, const Eigen::Vector2d& p, const Branches& branch,
                            const MjcfEffects& fx) {
  if (!fx.pinned_hub()) return inverse_kinematics(g, p, branch);
  JointAngles q;
  for (int i = 0; i < kNumChains; ++i) {
    const auto& pin = fx.hub_pin_m[static_cast<size_t>(i)];
    const ChainAngles c = chain_ik(g, i, p + Eigen::Vector2d(pin[0], pin[1]) / kMetresPerMm, branch[static_cast<size_t>(i)]);
    q.theta_a[i] = c.theta_a, q.theta_b[i] = c.theta_b;
  }
  return q;
}

// In the ee frame (origin pin 1, world-aligned at home): hub centre -p_1, pin i at p_i - p_1 (m).
std::string hub_pin_body(const std::string& in, double lb_m, double theta_b1, const MjcfOptions& o) {
  const auto& p = o.effects.hub_pin_m;
  const auto num = [](double v) { return format_exact(v); };
  const std::string c = fmt::format("{} {}", num(-p[0][0]), num(-p[0][1]));
  std::string x;
  x += fmt::format("{}<body name=\"ee\" pos=\"{} 0 0\" euler=\"0 0 {}\">\n", in, num(lb_m), num(-theta_b1));
  x += fmt::format("{}  <joint name=\"hub_r\" type=\"hinge\" axis=\"0 0 1\" damping=\"{}\"/>\n", in,
                   num(o.passive_damping));
  x += fmt::format("{}  <inertial pos=\"{} 0\" mass=\"{}\" diaginertia=\"{} {} {}\"/>\n", in, c, num(o.ee_mass_kg),
                   num(1e-5), num(1e-5), num(1e-5));
  x += fmt::format("{}  <geom name=\"geom_ee\" type=\"cylinder\" size=\"0.02 0.01\" pos=\"{} 0.03\" "
                   "rgba=\"0.8 0.1 0.1 1\"/>\n", in, c);
  x += fmt::format("{}  <site name=\"ee\" pos=\"{} 0\" size=\"0.008\"/>\n", in, c);
  for (int i = 1; i < kNumChains; ++i)
    x += fmt::format("{}  <site name=\"pin_b{}\" pos=\"{} {} 0\" size=\"0.002\"/>\n", in, i + 1,
                     num(p[static_cast<size_t>(i)][0] - p[0][0]), num(p[static_cast<size_t>(i)][1] - p[0][1]));
  x += in + "</body>\n";
  return x;
}

std::string hub_site(const MjcfEffects& fx, int i) {
  return fx.pinned_hub() ? fmt::format("pin_b{}", i + 1) : std::string("ee");
}

}  // namespace gpm
