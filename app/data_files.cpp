// Documentation and scenario library of the data root (app/data_files.hpp).
#include "app/data_files.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "app/cli_text.hpp"
#include "models/data_dir.hpp"
#include "models/errors.hpp"

namespace gpm::cli {
namespace fs = std::filesystem;

const std::vector<DocTopic>& doc_topics() {
  static const std::vector<DocTopic> topics{
      {"schema", "scenarios/SCHEMA.md", "the scenario file: every key, its units and default"},
      {"formats", "docs/FORMATS.md", "every file gpm reads or writes: robot, samples, results, reports"},
      {"cli", "docs/CLI.md", "the command line: subcommands, exit codes, limits, output files"},
      {"procedures", "docs/PROCEDURES.md", "the calibration procedures and when to use which"},
      {"monitoring", "docs/MONITORING.md", "what gpm monitor's alarms and estimates mean"},
      {"own-robot", "docs/OWN_ROBOT.md", "calibrating your own robot: the files to write"},
      {"hardware", "hw/README.md", "hardware files: backends twin, modbus and plugin, safety limits"},
  };
  return topics;
}

std::string doc_path(const DocTopic& topic) { return (fs::path(data_root()) / topic.file).string(); }

std::vector<std::string> scenario_names() {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(scenarios_dir(), ec))
    if (entry.path().extension() == ".yaml" && entry.is_regular_file(ec)) names.push_back(entry.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

std::string resolve_scenario(const std::string& arg) {
  std::error_code ec;
  if (arg.empty() || fs::exists(arg, ec) || arg.find('/') != std::string::npos) return arg;
  const fs::path library(scenarios_dir());
  for (const fs::path& candidate : {library / arg, library / (arg + ".yaml")})
    if (fs::is_regular_file(candidate, ec)) return candidate.string();
  const std::vector<std::string> names = scenario_names();
  const std::string stem = fs::path(arg).extension() == ".yaml" ? fs::path(arg).stem().string() : arg;
  const std::vector<std::string> near = close_names(stem, names);
  throw InputError(fmt::format("scenario '{}': no such file here nor in the scenario library {}; {}library names: {}",
                               cut(arg), library.string(),
                               near.empty() ? "" : fmt::format("did you mean '{}'? ", fmt::join(near, "' or '")),
                               fmt::join(names, ", ")));
}

std::string scenario_description(const std::string& path) {
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);)
    if (line.rfind("description:", 0) == 0) {
      const std::size_t first = line.find_first_not_of(" \t\"'", 12);
      if (first == std::string::npos) return "";
      std::string text = line.substr(first);
      while (!text.empty() && (text.back() == '"' || text.back() == '\'' || text.back() == ' ')) text.pop_back();
      return cut(text, 100);
    }
  return "";
}

}  // namespace gpm::cli
