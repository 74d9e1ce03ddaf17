// The pose list file written by `gpm design`: YAML that is a scenario's
// sampling plan (scenarios/SCHEMA.md, `sampling.pattern: list`):
//
//   # comment lines: how the poses were chosen and their bounds
//   sampling:
//     pattern: list
//     poses:
//       - [x, y]
//       ...
//
// The file is itself a valid scenario (a sampling section alone, the default
// robot), so `gpm simulate POSES.yaml -o DIR` samples the poses on the twin;
// the `sampling:` block can be pasted into any scenario. Numbers are written
// in the shortest form that reads back to the same double.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace gpm::calib::excitation {

// YAML text of the pose list; each line of `comment` becomes a "# " line on top.
std::string pose_list_yaml(const std::vector<Eigen::Vector2d>& poses, const std::string& comment);

}  // namespace gpm::calib::excitation
