// gpm: the command line of the GPM2002 digital twin and calibration toolkit.
// Thin: parses, calls the libraries, prints. Exit codes (DESIGN.md): 0 success,
// 1 the run worked but failed its expectations, 2 bad input (one line on stderr).
#include <cstdio>
#include <exception>
#include <filesystem>

#include <fmt/format.h>
#include <glog/logging.h>

#include "app/commands.hpp"
#include "models/data_dir.hpp"
#include "models/errors.hpp"

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

}  // namespace gpm::cli

int main(int argc, char** argv) {
  // Ceres logs through glog; gpm reports solver problems itself (result notes),
  // so only fatal glog messages reach the terminal.
  FLAGS_minloglevel = google::GLOG_FATAL;
  FLAGS_logtostderr = true;
  google::InitGoogleLogging(argv[0]);
  CLI::App app{"gpm: digital twin and auto-calibration toolkit for the GPM2002 planar 3-RRR manipulator"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "gpm 0.1.0");
  gpm::cli::add_kin(app);
  gpm::cli::add_simulate(app);
  gpm::cli::add_calibrate(app);
  gpm::cli::add_run(app);
  gpm::cli::add_render(app);
  gpm::cli::add_compare(app);
  gpm::cli::add_study(app);
  gpm::cli::add_design(app);
  gpm::cli::add_sample(app);
  gpm::cli::add_zero(app);
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
  } catch (const std::exception& e) {
    std::fprintf(stderr, "gpm: internal error: %s\n", e.what());
    return 3;
  }
  return gpm::cli::exit_code();
}
