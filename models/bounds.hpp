// Documented ranges of the numbers a user gives (command-line flags, scenario
// keys) and the sizes of the files the toolkit reads (docs/CLI.md, "Limits"): every
// count that sizes work or memory has an upper bound, checked before any work,
// and a refusal names the flag or key, the value and the valid range (exit 2).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include <yaml-cpp/yaml.h>

namespace gpm {

// A closed range [lo, hi]; whole: only integers; unit names what is counted
// or measured, for the message ("evaluations", "rad").
struct Bound {
  double lo = 0.0;
  double hi = 0.0;
  bool whole = false;
  const char* unit = "";
};

namespace limits {
// Error-function evaluations of a global method (GA, PSO, DE; gpm calibrate,
// gpm compare, gpm paper, a scenario's calibration.budget).
inline constexpr Bound kEvaluations{1, 1e10, true, "evaluations"};
// Levenberg-Marquardt iterations (gpm calibrate --budget with lm, calibration.budget).
inline constexpr Bound kLmIterations{1, 1e6, true, "iterations"};
// Encoder noise 1-sigma assumed or simulated (--sigma, calibration.sigma).
inline constexpr Bound kEncoderSigma{1e-12, 1.0, false, "rad"};
// Encoder resolution, 2^bits counts per turn (gpm calibrate --encoder-bits; 0: ideal), as the scenario's encoder.bits.
inline constexpr Bound kEncoderBits{0, 40, true, "bits"};
// Simulated encoder noise of synthetic samples (0: noiseless).
inline constexpr Bound kNoiseSigma{0.0, 1.0, false, "rad"};
// Time a passive link may take to cross its play after its force changes sign (calibration.crossing_s).
inline constexpr Bound kCrossingTime{0.0, 1.0, false, "s"};
// Largest correlation of the friction twist's column with the latch skew's
// at which a friction speed is tried (calibration.drive_friction.max_skew_correlation; 1: every speed).
inline constexpr Bound kSkewCorrelation{0.0, 1.0, false, "(a correlation)"};
// Scale of a robust loss (--loss cauchy:SCALE, calibration.loss), residual units.
inline constexpr Bound kLossScale{1e-12, 1e6, false, "(residual units: rad for ml)"};
// Samples (poses) generated in one data set (study --n, compare --samples).
inline constexpr Bound kSamples{1, 1e5, true, "samples"};
// Monte-Carlo trials (study montecarlo --trials).
inline constexpr Bound kTrials{2, 1e4, true, "trials"};
// Poses per calibration of the effects study (study effects --count; 0: each procedure's own).
inline constexpr Bound kStudyPoses{12, 2000, true, "poses"};
inline constexpr Bound kPopulation{1, 1e4, true, "robots"};
inline constexpr Bound kThreads{1, 64, true, "threads"};
// Interpolation points per circle of the zero-offset search (zero --points).
inline constexpr Bound kCirclePoints{6, 3600, true, "points"};
// Dwell at each interpolation point (zero --dwell).
inline constexpr Bound kDwell{0.0, 60.0, false, "s"};
// Random seeds (every --seed, calibration.seed): exact in a double.
inline constexpr Bound kSeed{0, 9007199254740992.0, true, ""};
// Poses of a designed calibration set (design --count, gpm.design count).
inline constexpr Bound kDesignPoses{1, 1e4, true, "poses"};
// Candidate grid spacing of the design (design --grid-step, gpm.design grid_step).
inline constexpr Bound kGridStep{1.0, 100.0, false, "mm"};
// Extra margin of the design's candidates (design --guard, gpm.design guard).
inline constexpr Bound kDesignGuard{0.0, 100.0, false, "mm"};
// Drift events of one monitoring scenario (events:).
inline constexpr std::size_t kMaxEvents = 1000;
// Bytes of a YAML file read (robot, result, scenario, poses, hardware file).
inline constexpr std::size_t kMaxYamlBytes = std::size_t{4} << 20;
// Bytes of a samples CSV read (about a million samples).
inline constexpr std::size_t kMaxCsvBytes = std::size_t{64} << 20;
}  // namespace limits

// "a whole number from 1 to 1e+10 evaluations": the valid values of b.
std::string describe(const Bound& b);

// True when v lies in b (and is whole where b wants it).
bool within(double v, const Bound& b);

// v if within b; otherwise throws InputError
// "WHERE: must be DESCRIBE(b), got TEXT" (TEXT: the value as given, or v).
double check_bound(double v, const Bound& b, std::string_view where, std::string_view text = {});

// The number in text (the whole text, finite; a leading + allowed), within b;
// throws InputError "WHERE: ..." naming the text otherwise (an empty text is
// not a number).
double parse_bounded(std::string_view text, const Bound& b, std::string_view where);

// A number at a YAML node within b; errors name file, line and keypath.
double yaml_within(const YAML::Node& node, const std::string& file, std::string_view keypath, const Bound& b);

// The items of a comma-separated list given on the command line (spaces
// around an item dropped); throws InputError "WHERE: 'X' is given twice
// (items I and J); give each once" (issue 36.12).
std::vector<std::string> split_unique_list(std::string_view list, std::string_view where);

// The content of a regular file given as input, at most max_bytes: throws
// InputError "FILE: ..." when it cannot be opened, is a folder, a FIFO, a
// device or a socket (opened without blocking: a FIFO without a writer is
// refused at once), or holds more.
std::string read_input_file(const std::string& path, std::size_t max_bytes);

}  // namespace gpm
