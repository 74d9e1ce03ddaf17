#include "app/cli_main.hpp"

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <glog/logging.h>

#include "app/commands.hpp"
#include "models/data_dir.hpp"
#include "models/errors.hpp"
#include "models/output_file.hpp"

namespace gpm::cli {
namespace {
int g_exit = 0;
}

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
  install_output_signal_cleanup();
  track_command_files(true);  // every input against every output, by identity (models/output_file.hpp)
  // Ceres logs through glog; the toolkit reports solver problems itself
  // (result notes), so only fatal glog messages reach the terminal.
  FLAGS_minloglevel = google::GLOG_FATAL;
  FLAGS_logtostderr = true;
  if (!google::IsGoogleLoggingInitialized()) google::InitGoogleLogging(argv[0]);
  if (argc >= 2 && argv[1][0] != '-') {
    std::vector<std::string> names;
    bool known = false;
    for (const CLI::App* sub : app.get_subcommands({})) {
      names.push_back(sub->get_name());
      known = known || sub->get_name() == argv[1];
    }
    if (!known) {
      std::fprintf(stderr, "gpm: error: unknown subcommand '%s'; valid: %s (see gpm --help)\n", argv[1],
                   fmt::format("{}", fmt::join(names, ", ")).c_str());
      return 2;
    }
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
    std::fprintf(stderr, "gpm: error: %s (see gpm --help)\n", e.what());
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
