// MJCF generation (see mjcf.hpp). Numbers for a GPM2002-sized machine, all
// assumptions rather than datasheet values (the paper gives only geometry):
// - Links: aluminium bars of 244 mm. Active 40 x 15 mm section: 2700 kg/m^3 x
//   0.244 x 0.040 x 0.015 = 0.40 kg; passive 30 x 12 mm with bearings: 0.25 kg.
//   Slender-rod inertia m L^2 / 12 about the link's own centre.
// - Drives: 400 W low-inertia AC servo (rotor 0.26e-4 kg m^2, rated 1.27 N m,
//   6000 rpm) behind a 10:1 reducer: armature 0.26e-4 x 10^2 = 0.0026 kg m^2,
//   output torque 12.7 N m rated, about 38 N m peak (sim/servo_drive.hpp).
// - Damping: 0.05 N m s/rad on the reducer output (a few per cent of rated
//   torque at 1 rad/s); 0.002 N m s/rad on the passive bearings.
// - Equality constraints: solref 0.001 1 (two 0.5 ms steps, the stiffest
//   MuJoCo accepts) and solimp 0.9999 0.9999. Measured with one drive
//   commanded 0.01 rad off (about 4 N m internal preload): loop gap 2.8 um with
//   the MuJoCo notes' (docs/ARCHITECTURE.md) 0.002 1 / 0.99 0.999, 0.7 um with 0.001 1 / 0.99 0.999,
//   0.07 um with 0.001 1 / 0.999 0.9999, 0.007 um with these defaults; the
//   step rate is unchanged (tests/sim/test_twin.cpp checks < 0.1 um).
#include "models/mjcf.hpp"

#include <cmath>

#include <fmt/format.h>

#include "models/errors.hpp"
#include "models/hub_pins.hpp"
#include "models/kinematics.hpp"
#include "models/xml_escape.hpp"
#include "models/yaml_util.hpp"

namespace gpm {
namespace {

// Exact decimal text of a number (MJCF reads it back to the same double).
std::string num(double x) { return format_exact(x); }

// Arm of the sites side_b2, side_b3 across the passive link from its tip
// (clearance): the tendon to ee measures the hub's transverse offset, with
// the axial play's second-order share (1e-5 m)^2 / (2 arm) = 5e-10 m.
constexpr double kSideArm_m = 0.1;

// Inertial element of a slender rod of length L (m) along +x from the body origin.
std::string rod_inertial(double mass, double length, double radius) {
  const double i_axial = 0.5 * mass * radius * radius;
  const double i_trans = mass * length * length / 12.0;
  return fmt::format(R"(<inertial pos="{} 0 0" mass="{}" diaginertia="{} {} {}"/>)",
                     num(0.5 * length), num(mass), num(i_axial), num(i_trans), num(i_trans));
}

// One chain's values as the MJCF writes them: index i (n = i + 1 in names),
// link lengths (m), the home angles (active, and passive relative to it),
// clearance c (m), compliance, and the drive's damping, friction and the
// clearance joint's or tendon's limit attributes.
struct ChainText {
  int i = 0, n = 1;
  double la_m = 0.0, lb_m = 0.0, ta = 0.0, rel = 0.0, c = 0.0, compliance = 0.0;
  std::string damping, friction, limit;
};

// The drives' friction time constant as a solreffriction attribute (none at
// MuJoCo's default; 0: two physics steps).
std::string friction_solref(const MjcfOptions& o) {
  const double T = o.effects.friction_timeconst_s;
  if (T == kMujocoFrictionTimeconst) return {};
  return fmt::format(" solreffriction=\"{} 1\"", num(T > 0.0 ? T : 2.0 * o.timestep_s));
}

// Chain i's values at the home assembly q.
ChainText chain_text(const Geometry& g, const JointAngles& q, const MjcfOptions& o, int i) {
  const MjcfEffects& fx = o.effects;
  ChainText t;
  t.i = i;
  t.n = i + 1;
  t.la_m = g.la_(i) * kMetresPerMm;
  t.lb_m = g.lb_(i) * kMetresPerMm;
  t.ta = q.theta_a[i];
  t.rel = q.theta_b[i] - q.theta_a[i];  // passive joint is relative to its parent
  t.c = fx.clearance_m[static_cast<size_t>(i)];
  t.compliance = fx.compliance_rad_per_Nm[static_cast<size_t>(i)];
  t.damping = num(o.active_damping + fx.viscous_Nm_s[static_cast<size_t>(i)]);
  t.friction = fx.coulomb_Nm[static_cast<size_t>(i)] > 0.0
                   ? fmt::format(" frictionloss=\"{}\"{}", num(fx.coulomb_Nm[static_cast<size_t>(i)]), friction_solref(o))
                   : std::string();
  // Loose passive joints (docs/ARCHITECTURE.md: clearance). A radial
  // clearance c at the elbow pin and at the hub pin lets the hub sit
  // anywhere within 2c of the passive link's tip (the two pins' discs of
  // radius c summed), so each passive link's length |O - B_i| gives by up
  // to +-2c. Chains 2 and 3 need no degree of freedom for it: instead of
  // the connect (3 rows), a spatial tendon clear_b{i} from site tip_b{i} to
  // site ee, limited to length 2c (one row, only while the play is taken
  // up). Chain 1 carries the hub body: a slide clear_b1x along the link
  // after joint_b1, range +-2c; the passive link is a two-force member, so
  // only the axial part of the play changes the closure (the transverse
  // part turns the link, second order, c^2 / lb).
  // The slide or tendon stands for both pins, so their centring springs
  // and dampers act in series: half the stiffness and half the damping.
  t.limit = fmt::format(
      "limited=\"true\" range=\"{} {}\" stiffness=\"{}\" damping=\"{}\" solreflimit=\"{} 1\" "
      "solimplimit=\"{} {} {}\"", num(i == 0 ? -2.0 * t.c : 0.0), num(2.0 * t.c), num(0.5 * fx.clearance_stiffness_N_per_m),
      num(0.5 * fx.clearance_damping_N_s_per_m), num(fx.clearance_solref_s), num(fx.clearance_solimp),
      num(fx.clearance_solimp), num(o.solimp_width_m));
  return t;
}

// The model's opening: name, the parameters as a comment, compiler, option and defaults.
std::string mjcf_preamble(const Robot& actual, const MjcfOptions& o) {
  const Geometry& g = actual.geometry;
  std::string x;
  x += fmt::format("<mujoco model=\"{}\">\n", xml_escape(actual.name));
  x += "  <!-- Generated by gpm (models/mjcf.cpp) from the parameters below; metres and radians.\n";
  for (int i = 0; i < kNumParams; ++i)
    x += fmt::format("       {} = {}\n", param_name(i), num(g[i]));
  x += "  -->\n";
  x += "  <compiler angle=\"radian\" inertiafromgeom=\"false\"/>\n";
  // Room for every constraint row the mechanism can have (3 per connect, 1
  // per tendon equality, limit and frictionloss row: under 30 with every
  // effect) and no contacts (they are off): MuJoCo's default, 500 rows and
  // 100 contacts, sizes each mjData's scratch stack to 10 MB, which every
  // twin state allocates and touches (sim/twin.cpp stops a run that fills it).
  x += "  <size njmax=\"100\" nconmax=\"10\"/>\n";
  x += fmt::format("  <option timestep=\"{}\">\n    <flag contact=\"disable\"/>\n  </option>\n",
                   num(o.timestep_s));
  x += "  <default>\n";
  x += "    <geom contype=\"0\" conaffinity=\"0\" mass=\"0\"/>\n";
  x += fmt::format("    <equality solref=\"{} {}\" solimp=\"{} {} {}\"/>\n", num(o.solref_timeconst_s),
                   num(o.solref_dampratio), num(o.solimp_dmin), num(o.solimp_dmax),
                   num(o.solimp_width_m));
  x += "  </default>\n";
  return x;
}

// Chain t's loose-pin tendons (chains 2 and 3 with clearance): clear_b{n} and side_b{n}.
std::string clearance_tendons(const ChainText& t, const MjcfEffects& fx) {
  if (!(t.c > 0.0 && t.i > 0)) return {};
  // springlength must be given: MuJoCo 2.2 takes a tendon's rest length
  // (-1, the default) at qpos_spring, where every joint sits at its
  // springref (0 unless given), not at qpos0: there tip_b{i} is 0.72 m
  // from ee, so the "centring" spring pushed the pins apart with ~70 N
  // and held the hub on the rim of the play whatever the load.
  std::string tendons = fmt::format("    <spatial name=\"clear_b{}\" {} springlength=\"0\">\n      <site site=\"tip_b{}\"/>\n"
                                    "      <site site=\"{}\"/>\n    </spatial>\n", t.n, t.limit, t.n, hub_site(fx, t.i));
  // The transverse part of the play is held at 0, as chain 1's slide
  // holds it (second order in the closure, c^2 / lb): tendon side_b{i}
  // from site side_b{i}, kSideArm_m across the link from its tip, to ee
  // is kept at its home length by a tendon equality (its length is the
  // arm minus the hub's transverse offset, plus axial^2 / (2 arm)); left
  // free, the hub slid round the rim of its disc (docs/ARCHITECTURE.md).
  tendons += fmt::format("    <spatial name=\"side_b{}\">\n      <site site=\"side_b{}\"/>\n"
                         "      <site site=\"{}\"/>\n    </spatial>\n", t.n, t.n, hub_site(fx, t.i));
  return tendons;
}

// Chain t's drive at A_i: the opening of body link_a{n} and its hinge; with
// a compliant transmission also the rotor body before it and its twist
// tendon (appended to tendons).
std::string drive_bodies(const Geometry& g, const ChainText& t, const MjcfOptions& o, std::string& tendons) {
  const int n = t.n, i = t.i;
  const std::string link_open = fmt::format("    <body name=\"link_a{}\" pos=\"{} {} 0\" euler=\"0 0 {}\">\n", n,
                                            num(g[xa(i)] * kMetresPerMm), num(g[ya(i)] * kMetresPerMm), num(t.ta));
  if (!(t.compliance > 0.0))
    return link_open + fmt::format("      <joint name=\"joint_a{}\" type=\"hinge\" axis=\"0 0 1\" ref=\"{}\" "
                                   "damping=\"{}\" armature=\"{}\"{}/>\n",
                                   n, num(t.ta), t.damping, num(o.armature_kg_m2), t.friction);
  // Transmission compliance: a rotor body of its own at A_i (hinge
  // joint_m with the armature, the damping and friction, whose
  // frictionloss the twin takes over in closed form: sim/rotor_friction.hpp;
  // the actuator)
  // and the link on its usual absolute hinge joint_a, joined by a fixed
  // tendon twist_a{i} = qpos(joint_m) - qpos(joint_a) of stiffness
  // 1 / compliance, at rest at zero twist (both joints have ref =
  // springref = home angle; springref defaults to 0, not to ref,
  // docs/ARCHITECTURE.md). Two trees instead of the rotor carrying the
  // link: the same dynamics, a shallower mass matrix (cheaper per step).
  std::string x = fmt::format("    <body name=\"rotor_a{}\" pos=\"{} {} 0\">\n", n,
                              num(g[xa(i)] * kMetresPerMm), num(g[ya(i)] * kMetresPerMm));
  x += fmt::format("      <joint name=\"joint_m{}\" type=\"hinge\" axis=\"0 0 1\" ref=\"{}\" springref=\"{}\" "
                   "damping=\"{}\" armature=\"{}\"{}/>\n",
                   n, num(t.ta), num(t.ta), t.damping, num(o.armature_kg_m2), t.friction);
  x += fmt::format("      <inertial pos=\"0 0 0\" mass=\"{}\" diaginertia=\"{} {} {}\"/>\n",
                   num(o.effects.rotor_mass_kg), num(1e-6), num(1e-6), num(1e-6));
  x += "    </body>\n";
  x += link_open;
  x += fmt::format("      <joint name=\"joint_a{}\" type=\"hinge\" axis=\"0 0 1\" ref=\"{}\" springref=\"{}\"/>\n",
                   n, num(t.ta), num(t.ta));
  tendons += fmt::format("    <fixed name=\"twist_a{}\" stiffness=\"{}\">\n      <joint joint=\"joint_m{}\" coef=\"1\"/>\n"
                         "      <joint joint=\"joint_a{}\" coef=\"-1\"/>\n    </fixed>\n",
                         n, num(1.0 / t.compliance), n, n);
  return x;
}

// The end-effector body ee (on chain 1's passive link, at indentation inb):
// the pinned hub's plate or a plain hub.
std::string ee_body(const std::string& inb, double lb_m, const JointAngles& q, const MjcfOptions& o) {
  if (o.effects.pinned_hub()) return hub_pin_body(inb, lb_m, q.theta_b[0], o);  // a small plate with its own rotation
  std::string x = fmt::format("{}<body name=\"ee\" pos=\"{} 0 0\">\n", inb, num(lb_m));
  x += fmt::format("{}  <inertial pos=\"0 0 0\" mass=\"{}\" diaginertia=\"{} {} {}\"/>\n", inb,
                   num(o.ee_mass_kg), num(1e-5), num(1e-5), num(1e-5));
  x += inb + "  <geom name=\"geom_ee\" type=\"cylinder\" size=\"0.02 0.01\" pos=\"0 0 0.03\" "
       "rgba=\"0.8 0.1 0.1 1\"/>\n";
  x += inb + "  <site name=\"ee\" pos=\"0 0 0\" size=\"0.008\"/>\n";
  x += inb + "</body>\n";
  return x;
}

// Chain t's passive link body link_b{n} inside link_a (indentation in): its
// hinge, chain 1's clearance slide, sites, and on chain 1 the end-effector.
std::string passive_body(const std::string& in, const ChainText& t, const JointAngles& q, const MjcfOptions& o) {
  const int n = t.n;
  const double r = o.link_radius_m;
  std::string x = fmt::format("{}<body name=\"link_b{}\" pos=\"{} 0 0.03\" euler=\"0 0 {}\">\n", in, n,
                              num(t.la_m), num(t.rel));
  const std::string inb = in + "  ";
  x += fmt::format("{}<joint name=\"joint_b{}\" type=\"hinge\" axis=\"0 0 1\" ref=\"{}\" "
                   "damping=\"{}\"/>\n", inb, n, num(t.rel), num(o.passive_damping));
  // After the hinge: the slide turns with the passive link.
  if (t.c > 0.0 && t.i == 0)
    x += fmt::format("{}<joint name=\"clear_b1x\" type=\"slide\" axis=\"1 0 0\" {}/>\n", inb, t.limit);
  x += inb + rod_inertial(o.passive_link_mass_kg, t.lb_m, 0.8 * r) + "\n";
  x += fmt::format("{}<geom name=\"geom_b{}\" type=\"capsule\" fromto=\"0 0 0 {} 0 0\" "
                   "size=\"{}\" rgba=\"0.9 0.6 0.2 1\"/>\n", inb, n, num(t.lb_m), num(0.8 * r));
  x += fmt::format("{}<site name=\"tip_b{}\" pos=\"{} 0 0\" size=\"0.005\"/>\n", inb, n, num(t.lb_m));
  if (t.c > 0.0 && t.i > 0)
    x += fmt::format("{}<site name=\"side_b{}\" pos=\"{} {} 0\" size=\"0.002\"/>\n", inb, n, num(t.lb_m),
                     num(kSideArm_m));
  if (t.i == 0) x += ee_body(inb, t.lb_m, q, o);
  x += in + "</body>\n";
  return x;
}

// Chain t's bodies in the worldbody: drive, active link, passive link (tendons collects its tendons).
std::string chain_bodies(const Geometry& g, const ChainText& t, const JointAngles& q, const MjcfOptions& o,
                         std::string& tendons) {
  tendons += clearance_tendons(t, o.effects);
  const double r = o.link_radius_m;
  const std::string in = "      ";  // indentation inside link_a
  std::string x = drive_bodies(g, t, o, tendons);
  x += in + rod_inertial(o.active_link_mass_kg, t.la_m, r) + "\n";
  x += fmt::format("{}<geom name=\"geom_a{}\" type=\"capsule\" fromto=\"0 0 0 {} 0 0\" "
                   "size=\"{}\" rgba=\"0.2 0.4 0.8 1\"/>\n", in, t.n, num(t.la_m), num(r));
  x += fmt::format("{}<site name=\"base_a{}\" pos=\"0 0 0\" size=\"0.02\"/>\n", in, t.n);
  x += passive_body(in, t, q, o);
  x += "    </body>\n";
  return x;
}

// The equality section: chains 2 and 3 closed on ee by a connect, or held
// across by their side tendon when loose; empty when there is none.
std::string equality_section(const Geometry& g, const MjcfEffects& fx) {
  std::string connects;
  for (int i = 1; i < kNumChains; ++i) {
    if (fx.clearance_m[static_cast<size_t>(i)] > 0.0) {  // closed by its clearance tendon, held across
      connects += fmt::format("    <tendon name=\"hold_b{}\" tendon1=\"side_b{}\"/>\n", i + 1, i + 1);
      continue;
    }
    connects += fmt::format("    <connect name=\"close_b{}\" body1=\"link_b{}\" body2=\"ee\" anchor=\"{} 0 0\"/>\n",
                            i + 1, i + 1, num(g.lb_(i) * kMetresPerMm));
  }
  return connects.empty() ? std::string() : "  <equality>\n" + connects + "  </equality>\n";
}

// The actuator section: one motor per chain, on the rotor when the transmission is compliant.
std::string actuator_section(const MjcfEffects& fx) {
  std::string x = "  <actuator>\n";
  for (int i = 0; i < kNumChains; ++i) {
    const char* joint = fx.compliance_rad_per_Nm[static_cast<size_t>(i)] > 0.0 ? "joint_m" : "joint_a";
    x += fmt::format("    <motor name=\"motor_a{}\" joint=\"{}{}\" gear=\"1\"/>\n", i + 1, joint, i + 1);
  }
  return x + "  </actuator>\n";
}

}  // namespace

bool MjcfEffects::compliant() const {
  for (double v : compliance_rad_per_Nm) if (v > 0.0) return true;
  return false;
}

bool MjcfEffects::loose() const {
  for (double v : clearance_m) if (v > 0.0) return true;
  return false;
}

double transmission_omega(const MjcfOptions& o, int chain, double la_m) {
  const double compliance = o.effects.compliance_rad_per_Nm[static_cast<size_t>(chain)];
  if (!(compliance > 0.0)) return 0.0;
  const double i_link = o.active_link_mass_kg * la_m * la_m / 3.0;  // rod about its end
  return std::sqrt((1.0 / compliance) * (1.0 / o.armature_kg_m2 + 1.0 / i_link));
}

std::string mjcf_from_robot(const Robot& actual, const MjcfOptions& o) {
  const Geometry& g = actual.geometry;
  JointAngles q;
  try {
    q = hub_assembly_ik(g, actual.home, actual.branch, o.effects);  // eq. 29-31 (per pin with hub pin offsets)
  } catch (const ReachError& e) {
    throw InputError(fmt::format(
        "the actual parameters cannot assemble at home ({}, {}): {}", actual.home.x(),
        actual.home.y(), e.what()));
  }
  std::string x = mjcf_preamble(actual, o);
  x += "  <worldbody>\n";
  x += "    <light pos=\"0.2165 0.25 1.5\" dir=\"0 0 -1\"/>\n";
  std::string tendons;  // compliant transmissions, loose hub pins of chains 2 and 3
  for (int i = 0; i < kNumChains; ++i) x += chain_bodies(g, chain_text(g, q, o, i), q, o, tendons);
  x += "  </worldbody>\n";
  x += equality_section(g, o.effects);
  if (!tendons.empty()) x += "  <tendon>\n" + tendons + "  </tendon>\n";
  x += actuator_section(o.effects);
  x += "</mujoco>\n";
  return x;
}

}  // namespace gpm
