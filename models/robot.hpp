// The robot model (constant during a run): geometry, home, elbow branches and
// the safety margins of its workspace. Mutable state lives elsewhere.
#pragma once

#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "models/data_sheet.hpp"
#include "models/parameters.hpp"

namespace gpm {

// Elbow branch of one chain: the active link lies counter-clockwise (+1) or
// clockwise (-1) of the line A_i -> O (docs/ARCHITECTURE.md; default +1 for all chains).
using Branches = std::array<int, kNumChains>;

// Workspace margins used by reachability and singularity checks.
struct Limits {
  // Distance (mm) a target must keep from both edges of each chain's annulus
  // |la - lb| <= |A_i O| <= la + lb.
  double reach_margin = 2.0;
  // Type-1 (serial) singularity: each |sin(theta_a - theta_b)| must stay above.
  double min_transmission = 0.15;
  // Type-2 (parallel) singularity: smallest singular value of the three passive
  // link directions, normalised to 1 for directions 120 degrees apart.
  double min_direct = 0.15;

  bool operator==(const Limits&) const = default;
};

// What a calibration result file adds to a robot (docs/FORMATS.md: a result file is
// also a robot file; its `std`, `fixed` and `diagnostics` are kept).
struct CalibrationRecord {
  // `std:` the 1-sigma of each estimated parameter (NaN or inf where the file
  // says .nan / .inf); empty for parameters it does not list.
  std::array<std::optional<double>, kNumParams> sigma{};
  FreeMask fixed;  // `fixed:` the parameters held at known values
  // `diagnostics:` key and value (flow YAML text, e.g. `12`, `lm`, `[a, b]`) in
  // file order; the known keys are validated on reading.
  std::vector<std::pair<std::string, std::string>> diagnostics;

  // Equal, with a NaN sigma equal to a NaN sigma (a round trip keeps them).
  bool operator==(const CalibrationRecord& o) const {
    for (size_t i = 0; i < sigma.size(); ++i) {
      if (sigma[i].has_value() != o.sigma[i].has_value()) return false;
      if (sigma[i] && !(*sigma[i] == *o.sigma[i] || (std::isnan(*sigma[i]) && std::isnan(*o.sigma[i]))))
        return false;
    }
    return fixed == o.fixed && diagnostics == o.diagnostics;
  }
};

struct Robot {
  std::string name = "GPM2002";
  Geometry geometry = Geometry::gpm2002_nominal();
  Eigen::Vector2d home{216.5, 250.0};
  Branches branch{+1, +1, +1};
  Limits limits;
  // What the robot's documents state of its drives, encoders and links
  // (`data_sheet:`; the GPM2002's when the file has none): all the
  // calibration and the monitor know of them (models/data_sheet.hpp).
  DataSheet data_sheet;
  std::optional<CalibrationRecord> calibration;  // present when read from a result file

  bool operator==(const Robot&) const = default;
};

}  // namespace gpm
