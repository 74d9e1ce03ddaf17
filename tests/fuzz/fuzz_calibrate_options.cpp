// Fuzz target for gpm calibrate's numbers (app/cmd_calibrate.cpp through
// calib/lm.cpp and calib/robust_loss.cpp, issue 36.1): the input, split at NUL
// bytes into at most four texts, gives --loss, --sigma, --budget and --cost
// (a missing text leaves its option out) of
//   gpm calibrate --data tests/fixtures/samples_table5_noisy.csv -o /dev/null --method lm
// which is parsed and run to the end (20 noisy samples: a run takes
// milliseconds). A clean result, a CLI11 ParseError (exit 2) or a gpm::Error
// (InputError exit 2, a failed calibration exit 1) are the expected outcomes;
// anything else (a signal inside Ceres, a sanitizer report, another exception,
// a hang) is a bug.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/commands.hpp"
#include "app/number_options.hpp"
#include "models/errors.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::vector<std::string> texts(1);
  for (size_t i = 0; i < size; ++i) {
    if (data[i] == 0) texts.emplace_back();
    else texts.back() += static_cast<char>(data[i]);
  }
  if (texts.size() > 4) return 0;
  std::vector<std::string> args = {"gpm", "calibrate", "--data", GPM_SOURCE_DIR "/tests/fixtures/samples_table5_noisy.csv",
                                   "-o",  "/dev/null", "--method", "lm"};
  static const char* const kFlags[] = {"--loss", "--sigma", "--budget", "--cost"};
  for (size_t k = 0; k < texts.size(); ++k) {
    args.push_back(kFlags[k]);
    args.push_back(texts[k]);
  }
  std::vector<std::string> reversed(args.rbegin(), args.rend() - 1);  // CLI11 takes them reversed, without argv[0]
  CLI::App app{"gpm"};  // the calibrate subcommand registered as gpm registers it (app/commands.cpp)
  gpm::cli::add_calibrate(app);
  gpm::cli::check_number_options(app);
  gpm::cli::set_exit(0);
  try {
    app.parse(reversed);
  } catch (const CLI::ParseError&) {
    // Usage errors and refused values: exit 2.
  } catch (const gpm::Error&) {
    // InputError (exit 2) or a calibration that failed in one line (exit 1).
  }
  return 0;
}
