#include "calib/excitation/pose_list.hpp"

#include <sstream>

#include <fmt/format.h>

namespace gpm::calib::excitation {

std::string pose_list_yaml(const std::vector<Eigen::Vector2d>& poses, const std::string& comment) {
  std::string out;
  std::istringstream lines(comment);
  for (std::string line; std::getline(lines, line);) out += line.empty() ? "#\n" : "# " + line + "\n";
  out += "sampling:\n  pattern: list\n  poses:\n";
  for (const Eigen::Vector2d& p : poses) out += fmt::format("    - [{}, {}]\n", p.x(), p.y());
  return out;
}

}  // namespace gpm::calib::excitation
