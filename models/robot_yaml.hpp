// Robot file (YAML) load and save (docs/FORMATS.md, file contracts). Saving then
// loading returns the same Robot to the last bit.
#pragma once

#include <string>

#include <yaml-cpp/yaml.h>

#include "models/robot.hpp"

namespace gpm {

// Loads and validates a robot file; throws InputError with one clear line
// (file, line, key, what is wrong, what is valid).
Robot load_robot(const std::string& path);

// Parses a robot from YAML text; file names the source in errors.
Robot parse_robot(const std::string& text, const std::string& file);

// Builds a Robot from an already parsed node (for robot sections embedded in
// scenario files); keypath prefixes every key in errors.
Robot robot_from_yaml(const YAML::Node& root, const std::string& file, const std::string& keypath);

// Reads a `geometry:` map of all 15 parameters, validating each.
Geometry geometry_from_yaml(const YAML::Node& node, const std::string& file,
                            const std::string& keypath);

// One parameter's 1-sigma in a result's `std:` map: .nan (not determined) or
// a finite value in [0, 100] mm or [0, 1] rad; throws InputError naming key.
double sigma_from_yaml(const YAML::Node& value, const std::string& file, const std::string& key, int param);

// What a result file holds for a computed 1-sigma: itself within the bounds
// sigma_from_yaml accepts, else NaN (written .nan: not determined).
double sigma_for_file(double sigma, int param);

// Checks a whole robot: positive lengths and a reachable home on its branches.
// Throws InputError prefixed with where.
void validate_robot(const Robot& robot, const std::string& where);

// YAML text of a robot, every number written exactly.
std::string robot_to_yaml(const Robot& robot);

// YAML text of a geometry map body (15 lines "  key: value"), indented by indent.
std::string geometry_to_yaml(const Geometry& g, int indent);

// Writes a robot file atomically (temporary file then rename); throws
// InputError if the path is not writable.
void save_robot(const Robot& robot, const std::string& path);

// Writes text to path by the output policy (models/output_file.hpp): staged
// and renamed, devices written in place, links followed.
void write_file_atomic(const std::string& path, const std::string& text);

}  // namespace gpm
