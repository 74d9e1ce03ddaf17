// The robot's data sheet (robot file section `data_sheet:`, docs/FORMATS.md):
// what the documents of the robot a user actually has state of its drives,
// encoders and links, each value with the tolerance the real machine lies in.
// The calibration and the drift monitor read these, never the twin's truth
// (sim/effects.hpp, models/mjcf.hpp MjcfOptions), which may lie anywhere in
// the tolerances (docs/ARCHITECTURE.md, data sheet and truth).
#pragma once

#include <string>

namespace YAML {
class Node;
}  // namespace YAML

namespace gpm {

// One stated value: the nominal and the range a real robot's value lies in,
// as factors of the nominal (+-10 %: [0.9, 1.1]; "up to": [0, 1]; exact: [1, 1]).
struct Stated {
  double nominal = 0.0;
  double factor_min = 1.0;
  double factor_max = 1.0;

  // Smallest value the tolerance admits: nominal x factor_min.
  double min() const { return nominal * factor_min; }
  // Largest value the tolerance admits: nominal x factor_max.
  double max() const { return nominal * factor_max; }
  bool operator==(const Stated&) const = default;
};

// The GPM2002's data sheet by default: a 400 W low-inertia AC servo (rotor
// 0.26e-4 kg m^2, 17-bit absolute encoder) behind a 10:1 precision planetary
// reducer, aluminium links; each drive alike. Torques, friction and stiffness
// are referred to the reducer's output (joint units, as MjcfOptions states
// them); the friction acts on the motor side of the transmission's compliance.
struct DataSheet {
  double gear_ratio = 10.0;  // N: motor revolutions per joint revolution (exact)
  int encoder_bits = 17;     // 2^bits counts per motor revolution (exact)
  // P: the motor's cogging periods per revolution, the least common multiple of its slots and poles (12 and 8;
  // exact); 0: not stated
  int cogging_periods = 24;
  // Once-per-revolution error amplitude of each encoder (rad): +-4 arcsec accuracy class, up to.
  Stated encoder_accuracy_rad{2e-5, 0.0, 1.0};
  // The reducer's kinematic (transmission) error once per output revolution, amplitude (rad): up to
  // 1.5 arcmin, a precision planetary's transmission accuracy class.
  Stated transmission_error_rad{4.3633e-4, 0.0, 1.0};
  Stated rotor_inertia_kg_m2{2.6e-5, 0.9, 1.1};   // J_r, motor side, +-10 %
  Stated active_link_mass_kg{0.40, 0.95, 1.05};   // aluminium bar 244 x 40 x 15 mm, +-5 %
  Stated passive_link_mass_kg{0.25, 0.95, 1.05};  // aluminium bar 244 x 30 x 12 mm, +-5 %
  Stated end_effector_mass_kg{0.10, 0.8, 1.2};    // hub and tool, +-20 %
  // Drive friction (reducer, seals, bearings) in joint units: Coulomb F (N m)
  // and viscous b (N m s/rad), each within half to twice its nominal.
  Stated coulomb_Nm{0.3, 0.5, 2.0};
  Stated viscous_Nm_s{0.15, 0.5, 2.0};
  Stated stiffness_Nm_per_rad{1e4, 0.8, 1.2};     // k: reducer torsional stiffness, +-20 %
  Stated clearance_mm{0.005, 0.0, 2.0};           // c: radial clearance of each passive pin (bearing CN class)
  // Latch skew: drive i+1 latches its encoder this long after drive i (s; a serial bus).
  Stated latch_skew_s{50e-6, 0.0, 2.0};
  Stated warm_up_time_constant_s{600.0, 0.5, 2.0};  // tau_T: first-order warm-up of the mechanism (s)

  // The largest error once per joint revolution it admits (rad): the reducer's, and the encoder's own
  // when it sits on the joint (N = 1), in quadrature.
  double joint_harmonic_max_rad() const;
  // The rotor inertia reflected to the joint, J_r N^2 (kg m^2).
  double reflected_inertia_kg_m2() const { return rotor_inertia_kg_m2.nominal * gear_ratio * gear_ratio; }
  // Torsional compliance at the output, 1 / k (rad/N m).
  double compliance_rad_per_Nm() const { return 1.0 / stiffness_Nm_per_rad.nominal; }
  bool operator==(const DataSheet&) const = default;
};

// Reads a `data_sheet:` map at keypath of file; a key left out keeps its
// GPM2002 value. Throws InputError naming file, line, key, what is wrong and
// the valid range.
DataSheet data_sheet_from_yaml(const YAML::Node& node, const std::string& file, const std::string& keypath);

// The `data_sheet:` section of a robot file (YAML text, every number exact):
// data_sheet_from_yaml reads it back to the last bit.
std::string data_sheet_to_yaml(const DataSheet& sheet);

}  // namespace gpm
