#include "app/cli_main.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <glog/logging.h>

#include "app/cli_text.hpp"
#include "app/commands.hpp"
#include "app/written_files.hpp"
#include "models/data_dir.hpp"
#include "models/errors.hpp"
#include "models/output_file.hpp"

namespace gpm::cli {
namespace {
int g_exit = 0;

// A level of subcommands takes no positional argument of its own (gpm, gpm kin, gpm study).
bool takes_positionals(const CLI::App& level) {
  for (const CLI::Option* o : level.get_options())
    if (o->get_positional()) return true;
  return false;
}

// The error line for the first word of argv that names no subcommand where one
// is expected (gpm kin hom: "did you mean 'home'?"), or for a level that
// needs a subcommand and got none; empty when the words name subcommands
// (options and the rest are CLI11's to parse).
std::string unknown_subcommand(CLI::App& app, int argc, char** argv) {
  CLI::App* level = &app;
  std::string path = "gpm";
  for (int i = 1;; ++i) {
    const std::vector<CLI::App*> subs = level->get_subcommands({});
    if (subs.empty() || takes_positionals(*level)) return {};
    std::vector<std::string> names;
    for (const CLI::App* sub : subs) names.push_back(sub->get_name());
    const std::string valid = fmt::format("{}", fmt::join(names, ", "));
    if (i >= argc) {
      if (level->get_require_subcommand_min() == 0) return {};
      return fmt::format("{}: name a subcommand: {} (see {} --help)", path, valid, path);
    }
    const std::string word = argv[i];
    if (!word.empty() && word[0] == '-') return {};
    const auto next = std::find_if(subs.begin(), subs.end(), [&](const CLI::App* s) { return s->get_name() == word; });
    if (next == subs.end()) {
      const std::vector<std::string> near = close_names(word, names);
      const std::string hint = near.empty() ? "" : fmt::format("did you mean '{}'? ", fmt::join(near, "' or '"));
      return fmt::format("unknown subcommand '{}' of {}; {}valid: {} (see {} --help)", cut(word), path, hint, valid,
                         path);
    }
    level = *next;
    path += " " + word;
  }
}

// msg with every word longer than 40 characters cut (a 300-digit argument is
// not echoed whole in CLI11's messages); words a validator already cut are kept.
std::string cut_long_words(const std::string& msg) {
  std::string out;
  std::size_t i = 0;
  while (i < msg.size()) {
    const std::size_t end = std::min(msg.find(' ', i), msg.size());
    const std::string word = msg.substr(i, end - i);
    out += word.find("\u2026") == std::string::npos ? cut(word) : word;  // a validator's cut stays
    if (end < msg.size()) out += ' ';
    i = end + 1;
  }
  return out;
}
}  // namespace

void set_exit(int code) { g_exit = code; }
int exit_code() { return g_exit; }

std::string default_model_path() {
  const char* env = std::getenv("GPM_MODEL");
  if (env && *env) return env;
  return gpm::models_dir() + "/gpm2002.yaml";
}

void not_available(const std::string& name, const std::string& issue) {
  throw InputError(fmt::format("gpm {}: not available yet ({} has not landed)", name, issue));
}

int run_app(CLI::App& app, int argc, char** argv) {
  mark_command_start();  // files written from now on are listed (app/written_files.hpp)
  install_output_signal_cleanup();
  track_command_files(true);  // every input against every output, by identity (models/output_file.hpp)
  // Ceres logs through glog; the toolkit reports solver problems itself
  // (result notes), so only fatal glog messages reach the terminal.
  FLAGS_minloglevel = google::GLOG_FATAL;
  FLAGS_logtostderr = true;
  if (!google::IsGoogleLoggingInitialized()) google::InitGoogleLogging(argv[0]);
  if (const std::string wrong = unknown_subcommand(app, argc, argv); !wrong.empty()) {
    std::fprintf(stderr, "gpm: error: %s\n", wrong.c_str());
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "gpm: error: %s (see gpm --help)\n", cut_long_words(e.what()).c_str());
    return 2;
  } catch (const gpm::InputError& e) {
    std::fprintf(stderr, "gpm: error: %s\n", e.what());
    return 2;
  } catch (const std::filesystem::filesystem_error& e) {
    // A file or folder the user named cannot be used: bad input, not a bug.
    std::fprintf(stderr, "gpm: error: %s: %s\n", e.path1().c_str(), e.code().message().c_str());
    return 2;
  } catch (const gpm::Error& e) {
    // The hardware, the physics or the renderer stopped the run (not the
    // user's input, not a bug): one line, exit 1.
    std::fprintf(stderr, "gpm: error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "gpm: internal error: %s (a bug: please report this)\n", e.what());
    return 3;
  } catch (...) {
    std::fprintf(stderr, "gpm: internal error: unknown exception (a bug: please report this)\n");
    return 3;
  }
  return exit_code();
}

}  // namespace gpm::cli
