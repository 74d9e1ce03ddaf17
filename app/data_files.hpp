// What an installed user has (issue 35.5): the documentation and the scenario
// library under PREFIX/share/gpm (the source tree when gpm runs from its
// build), found through models/data_dir.hpp; `gpm help TOPIC` prints them and
// a scenario is named by its library name (gpm run main).
#pragma once

#include <string>
#include <vector>

namespace gpm::cli {

// A document `gpm help NAME` prints: its file relative to the data root.
struct DocTopic {
  std::string name;      // "schema"
  std::string file;      // "scenarios/SCHEMA.md"
  std::string contents;  // "the scenario file format"
};

// Every documentation topic, in the order of `gpm help`.
const std::vector<DocTopic>& doc_topics();

// The installed path of a topic's file (it may be missing).
std::string doc_path(const DocTopic& topic);

// Names of the scenario library (scenarios/*.yaml without .yaml), sorted.
std::vector<std::string> scenario_names();

// The scenario file a command line argument names: the argument itself when
// such a file exists or the argument has a folder in it; else the library's
// NAME or NAME.yaml. Throws InputError listing the library's names (those
// close to the argument first) when neither exists.
std::string resolve_scenario(const std::string& arg);

// The `description:` line of a scenario file, or "".
std::string scenario_description(const std::string& path);

}  // namespace gpm::cli
