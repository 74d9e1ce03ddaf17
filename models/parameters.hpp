// The 15 geometric parameters of a 3-RRR planar manipulator (docs/ARCHITECTURE.md):
// base joints A1..A3, active links la, passive links lb, encoder zero offsets
// dth (theta_a = theta_m + dth, paper eq. 1 and 35). Millimetres and radians.
#pragma once

#include <array>
#include <bitset>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

namespace gpm {

inline constexpr int kNumParams = 15;
inline constexpr int kNumChains = 3;

// Index of each parameter in Geometry::values; order as in docs/FORMATS.md.
enum Param : int {
  kXa1, kYa1, kXa2, kYa2, kXa3, kYa3,
  kLa1, kLa2, kLa3,
  kLb1, kLb2, kLb3,
  kDth1, kDth2, kDth3,
};

// Name of parameter i ("xa1" ... "dth3").
std::string_view param_name(int i);

// Index of the parameter called name, or nullopt.
std::optional<int> param_index(std::string_view name);

// The valid name closest to name (edit distance), for "did you mean" hints.
std::string nearest_param_name(std::string_view name);

// Edit distance between two strings (Levenshtein), used for suggestions.
int edit_distance(std::string_view a, std::string_view b);

// True for the six link lengths (which must be positive).
bool is_length(int i);

// True for the three encoder zero offsets (radians); the rest are mm.
bool is_offset(int i);

// Index helpers for chain i in 0..2.
constexpr int xa(int i) { return kXa1 + 2 * i; }
constexpr int ya(int i) { return kYa1 + 2 * i; }
constexpr int la(int i) { return kLa1 + i; }
constexpr int lb(int i) { return kLb1 + i; }
constexpr int dth(int i) { return kDth1 + i; }

// The 15 parameter values of one mechanism.
struct Geometry {
  std::array<double, kNumParams> values{};

  double& operator[](int i) { return values[static_cast<size_t>(i)]; }
  double operator[](int i) const { return values[static_cast<size_t>(i)]; }

  // Base joint A_i (mm), i in 0..2.
  Eigen::Vector2d A(int i) const { return {(*this)[xa(i)], (*this)[ya(i)]}; }
  double la_(int i) const { return (*this)[la(i)]; }
  double lb_(int i) const { return (*this)[lb(i)]; }
  double dth_(int i) const { return (*this)[dth(i)]; }

  // The GPM2002's nominal geometry: A1=(0,250), A2=(433,0), A3=(433,500),
  // all links 244 mm, offsets 0 (paper section 2.5).
  static Geometry gpm2002_nominal();

  bool operator==(const Geometry&) const = default;
};

// Which parameters are free (estimated) and which fixed (known).
using FreeMask = std::bitset<kNumParams>;

// Parses a comma-separated list of parameter names ("xa1,ya1,xa2,ya2").
// Throws InputError naming `what` (e.g. "--fix") and suggesting the nearest
// valid name for an unknown one.
FreeMask parse_param_list(std::string_view list, std::string_view what);

// Names of the set bits of mask, comma-separated.
std::string format_param_list(const FreeMask& mask);

// The default gauge: xa1, ya1, xa2, ya2 fixed, the other 11 free (docs/ARCHITECTURE.md).
FreeMask default_free_mask();

}  // namespace gpm
