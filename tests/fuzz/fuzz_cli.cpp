// Fuzz target for the command line (app/cmd_*.cpp and CLI11): an argument
// vector (the input split at NUL bytes) is parsed by the `gpm` app with every
// subcommand registered as in app/main.cpp; the parse stops after every option
// conversion, validator and requirement has run and before any subcommand's
// callback (CLI11 calls the top app's pre_callback first), so nothing is
// simulated or written. (Removing the callbacks instead would free the option
// storage they own: the callbacks keep each subcommand's options alive.)
// Any outcome other than a clean parse, a CLI11 ParseError (exit 2) or a help /
// version request (a crash, a sanitizer report, another exception) is a bug.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "app/commands.hpp"
#include "models/data_dir.hpp"
#include "models/errors.hpp"

// set_exit, default_model_path, ... come from app/cli_main.cpp (gpm_cli).

namespace {

// Thrown when parsing and validation are complete, before any callback runs.
struct Parsed {};

// The gpm app, stopping before the callbacks.
class ValidateOnlyApp : public CLI::App {
 public:
  using CLI::App::App;
  void pre_callback() override { throw Parsed{}; }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::vector<std::string> args;  // CLI11 takes them in reverse order
  std::string cur;
  for (size_t i = 0; i < size; ++i) {
    if (data[i] == 0) {
      args.push_back(cur);
      cur.clear();
    } else {
      cur += static_cast<char>(data[i]);
    }
  }
  args.push_back(cur);
  if (args.size() > 64) return 0;
  std::vector<std::string> reversed(args.rbegin(), args.rend());

  ValidateOnlyApp app{"gpm"};
  gpm::cli::add_commands(app, gpm::cli::add_render);
  try {
    app.parse(reversed);
    __builtin_trap();  // pre_callback always throws: a parse that returns ran no validation stop
  } catch (const Parsed&) {
  } catch (const CLI::ParseError&) {
    // Usage errors (exit 2), --help and --version: all expected.
  } catch (const gpm::InputError&) {
    // A validator may read a file (e.g. ExistingFile) and refuse it: exit 2.
  }
  return 0;
}
