#include "models/data_sheet.hpp"

#include <array>
#include <cmath>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "models/errors.hpp"
#include "models/yaml_util.hpp"

namespace gpm {
namespace {

// A stated item: its key, member, the valid range of its nominal and unit.
struct Item {
  const char* key;
  Stated DataSheet::*member;
  double lo, hi;  // nominal within [lo, hi]; lo_open: > lo
  bool lo_open;
  const char* unit;
};

constexpr std::array<Item, 12> kItems{{
    {"encoder_accuracy_rad", &DataSheet::encoder_accuracy_rad, 0.0, 0.01, false, "rad"},
    {"transmission_error_rad", &DataSheet::transmission_error_rad, 0.0, 0.01, false, "rad"},
    {"rotor_inertia_kg_m2", &DataSheet::rotor_inertia_kg_m2, 0.0, 0.01, true, "kg m^2"},
    {"active_link_mass_kg", &DataSheet::active_link_mass_kg, 0.0, 100.0, true, "kg"},
    {"passive_link_mass_kg", &DataSheet::passive_link_mass_kg, 0.0, 100.0, true, "kg"},
    {"end_effector_mass_kg", &DataSheet::end_effector_mass_kg, 0.0, 100.0, true, "kg"},
    {"coulomb_Nm", &DataSheet::coulomb_Nm, 0.0, 20.0, false, "N m"},
    {"viscous_Nm_s", &DataSheet::viscous_Nm_s, 0.0, 100.0, false, "N m s/rad"},
    {"stiffness_Nm_per_rad", &DataSheet::stiffness_Nm_per_rad, 1.0, 1e9, false, "N m/rad"},
    {"clearance_mm", &DataSheet::clearance_mm, 0.0, 1.0, false, "mm"},
    {"latch_skew_s", &DataSheet::latch_skew_s, 0.0, 0.005, false, "s"},
    {"warm_up_time_constant_s", &DataSheet::warm_up_time_constant_s, 1.0, 1e6, false, "s"},
}};

std::string join(const std::string& a, const char* b) { return a.empty() ? b : a + "." + b; }

// A number at n within [lo, hi] (lo_open: above lo), the error naming the range and unit.
double ranged(const YAML::Node& n, const std::string& file, const std::string& key, double lo, double hi, bool lo_open,
              const char* unit) {
  const double v = yaml_number(n, file, key);
  if ((lo_open ? !(v > lo) : !(v >= lo)) || !(v <= hi))
    throw InputError(yaml_where(file, n, key) + fmt::format("{} is out of range (valid: {}{} to {} {})", v,
                                                            lo_open ? "> " : "", lo, hi, unit));
  return v;
}

// The tolerance of a stated value: `tolerance: r` (+-r, 0 to 1) or `factor: [lo, hi]`.
void read_tolerance(const YAML::Node& n, const std::string& file, const std::string& key, Stated& s) {
  if (n["tolerance"] && n["factor"])
    throw InputError(yaml_where(file, n, key) + "give tolerance (+-r) or factor ([lo, hi]), not both");
  if (const YAML::Node t = n["tolerance"]) {
    const double r = ranged(t, file, key + ".tolerance", 0.0, 1.0, false, "(a fraction: 0.1 is +-10 %)");
    s.factor_min = 1.0 - r;
    s.factor_max = 1.0 + r;
  }
  if (const YAML::Node f = n["factor"]) {
    const std::string fk = key + ".factor";
    if (!f.IsSequence() || f.size() != 2)
      throw InputError(yaml_where(file, f, fk) + "expected [lo, hi], factors of the nominal, e.g. [0.5, 2]");
    s.factor_min = ranged(f[0], file, fk + "[0]", 0.0, 1.0, false, "(a factor)");
    s.factor_max = ranged(f[1], file, fk + "[1]", 1.0, 100.0, false, "(a factor)");
  }
}

// One stated item: a number (exact) or {nominal, tolerance | factor}.
Stated read_stated(const YAML::Node& n, const std::string& file, const std::string& key, const Item& item) {
  if (n.IsScalar()) return Stated{ranged(n, file, key, item.lo, item.hi, item.lo_open, item.unit), 1.0, 1.0};
  if (!n.IsMap())
    throw InputError(yaml_where(file, n, key) +
                     fmt::format("expected a number ({}) or {{nominal: {}, tolerance: r}} or {{nominal: {}, factor: [lo, hi]}}",
                                 item.unit, item.unit, item.unit));
  yaml_check_keys(n, file, key, {"nominal", "tolerance", "factor"});
  if (!n["nominal"]) throw InputError(yaml_where(file, n, key) + fmt::format("missing key 'nominal' ({})", item.unit));
  Stated s{ranged(n["nominal"], file, key + ".nominal", item.lo, item.hi, item.lo_open, item.unit), 1.0, 1.0};
  read_tolerance(n, file, key, s);
  return s;
}

}  // namespace

double DataSheet::joint_harmonic_max_rad() const {
  return std::hypot(transmission_error_rad.max(), gear_ratio == 1.0 ? encoder_accuracy_rad.max() : 0.0);
}

DataSheet data_sheet_from_yaml(const YAML::Node& node, const std::string& file, const std::string& keypath) {
  if (!node.IsMap())
    throw InputError(yaml_where(file, node, keypath) +
                     "expected a map of the robot's stated values (gear_ratio, encoder_bits, coulomb_Nm, ...; docs/FORMATS.md)");
  yaml_check_keys(node, file, keypath,
                  {"gear_ratio", "encoder_bits", "cogging_periods", "encoder_accuracy_rad", "transmission_error_rad", "rotor_inertia_kg_m2", "active_link_mass_kg",
                   "passive_link_mass_kg", "end_effector_mass_kg", "coulomb_Nm", "viscous_Nm_s", "stiffness_Nm_per_rad",
                   "clearance_mm", "latch_skew_s", "warm_up_time_constant_s"});
  DataSheet d;
  if (const YAML::Node g = node["gear_ratio"])
    d.gear_ratio = ranged(g, file, join(keypath, "gear_ratio"), 1.0, 200.0, false, "motor revolutions per joint revolution");
  if (const YAML::Node b = node["encoder_bits"])
    d.encoder_bits = static_cast<int>(yaml_integer(b, file, join(keypath, "encoder_bits"), 8, 32));
  if (const YAML::Node p = node["cogging_periods"])
    d.cogging_periods = static_cast<int>(yaml_integer(p, file, join(keypath, "cogging_periods"), 0, 1000));
  for (const Item& item : kItems)
    if (const YAML::Node n = node[item.key]) d.*item.member = read_stated(n, file, join(keypath, item.key), item);
  return d;
}

std::string data_sheet_to_yaml(const DataSheet& d) {
  std::string out = "data_sheet:          # stated by the robot's documents: nominal, factor range of the real value\n";
  out += fmt::format("  gear_ratio: {}\n  encoder_bits: {}\n  cogging_periods: {}\n", format_exact(d.gear_ratio),
                     d.encoder_bits, d.cogging_periods);
  for (const Item& item : kItems) {
    const Stated& s = d.*item.member;
    out += fmt::format("  {}: {{nominal: {}, factor: [{}, {}]}}\n", item.key, format_exact(s.nominal),
                       format_exact(s.factor_min), format_exact(s.factor_max));
  }
  return out;
}

}  // namespace gpm
