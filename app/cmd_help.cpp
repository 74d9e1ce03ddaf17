// gpm help [TOPIC]: the documentation an installed user has (issue 35.5).
//   gpm help             the topics, where their files are, and the subcommands
//   gpm help schema      prints PREFIX/share/gpm/scenarios/SCHEMA.md (other topics alike)
//   gpm help scenarios   the scenario library: names gpm run, simulate, monitor take
//   gpm help run         the same as gpm run --help
#include <cstdio>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "app/commands.hpp"
#include "app/data_files.hpp"
#include "models/data_dir.hpp"
#include "models/errors.hpp"

namespace gpm::cli {
namespace {

// The topics and subcommands, with the files' paths.
void print_topics(CLI::App& app) {
  fmt::print("gpm help TOPIC prints a document of {}:\n", data_root());
  for (const DocTopic& t : doc_topics()) fmt::print("  {:<11} {} ({})\n", t.name, t.contents, doc_path(t));
  fmt::print("  {:<11} the scenario library: the names gpm run, simulate and monitor take ({})\n", "scenarios",
             scenarios_dir());
  std::vector<std::string> names;
  for (const CLI::App* sub : app.get_subcommands({}))
    if (sub->get_name() != "help") names.push_back(sub->get_name());
  fmt::print("gpm help COMMAND is gpm COMMAND --help: {}\n", fmt::join(names, ", "));
}

// The scenario library, one name and description a line.
void print_scenarios() {
  fmt::print("scenario library {} (gpm run NAME -o DIR):\n", scenarios_dir());
  for (const std::string& n : scenario_names())
    fmt::print("  {:<50} {}\n", n, scenario_description(scenarios_dir() + "/" + n + ".yaml"));
}

// Prints the topic's document; InputError when it is not installed.
void print_document(const DocTopic& t) {
  const std::string path = doc_path(t);
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw InputError(fmt::format("gpm help {}: {} is missing (install with cmake --install, or set GPM_DATA_DIR "
                                 "to the folder holding scenarios/ and docs/)",
                                 t.name, path));
  std::ostringstream text;
  text << in.rdbuf();
  std::fputs(text.str().c_str(), stdout);
}

void run_help(CLI::App& app, const std::string& topic) {
  if (topic.empty()) return print_topics(app);
  if (topic == "scenarios") return print_scenarios();
  for (const DocTopic& t : doc_topics())
    if (t.name == topic) return print_document(t);
  for (CLI::App* sub : app.get_subcommands({}))
    if (sub->get_name() == topic && topic != "help") {
      std::fputs(sub->help().c_str(), stdout);
      return;
    }
  std::vector<std::string> names{"scenarios"};
  for (const DocTopic& t : doc_topics()) names.push_back(t.name);
  for (const CLI::App* sub : app.get_subcommands({}))
    if (sub->get_name() != "help") names.push_back(sub->get_name());
  throw InputError(fmt::format("gpm help: no topic '{}'; topics: {}", topic, fmt::join(names, ", ")));
}

}  // namespace

void add_help(CLI::App& app) {
  auto topic = std::make_shared<std::string>();
  auto* cmd = app.add_subcommand(
      "help", "Print an installed document: gpm help schema (scenario files), formats, cli, procedures, "
              "monitoring, own-robot, hardware; gpm help scenarios lists the scenario library");
  cmd->add_option("topic", *topic, "A topic or a subcommand; none: list them with their files");
  cmd->callback([&app, topic] { run_help(app, *topic); });
}

}  // namespace gpm::cli
