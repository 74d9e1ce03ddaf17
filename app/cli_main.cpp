#include "app/cli_main.hpp"

#include <cstdio>
#include <cstdlib>
#include <exception>

#include <fmt/format.h>

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
    std::fprintf(stderr, "gpm: internal error: %s (a bug: please report this)\n", e.what());
    return 3;
  }
  return exit_code();
}

}  // namespace gpm::cli
