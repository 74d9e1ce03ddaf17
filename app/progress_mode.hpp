// Progress of the long commands (gpm run, paper, simulate, study) on stderr
// (issue 35.5): --progress=none|line|bar; by default a bar (one line
// rewritten in place) on a terminal, else a plain line every few seconds, so
// that a log or a pipe shows the command is alive. stdout is never touched.
#pragma once

#include <condition_variable>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

#include <CLI/CLI.hpp>

#include "models/progress.hpp"

namespace gpm::cli {

enum class ProgressMode { kNone, kLine, kBar };

// Seconds between two lines of the line mode.
inline constexpr double kProgressLineInterval = 5.0;

// Adds --progress=none|line|bar to cmd; the choice is stored in choice ("" when not given).
void add_progress_option(CLI::App* cmd, std::string& choice);

// The mode of a --progress choice; "" is bar on a terminal, line otherwise.
ProgressMode progress_mode(const std::string& choice, bool stderr_is_terminal);

// The mode of a --progress choice for this process's stderr.
ProgressMode progress_mode(const std::string& choice);

// A counting reporter (models/progress.hpp) in the mode: bar as on a
// terminal, line mode one line per kProgressLineInterval, none silent.
Progress counting_progress(ProgressMode mode, const std::string& what, const std::string& unit, double total = 0.0);

// Reports a command's current status ("simulating", "table 3 42%"): bar mode
// rewrites one line at each change; line mode writes "WHAT: STATUS, N s"
// once kProgressLineInterval has passed since the last line (or the start),
// also when the status has not changed (tick()); none writes nothing.
class StatusReporter {
 public:
  using Clock = std::function<double()>;                  // seconds, monotonic
  using Sink = std::function<void(const std::string&)>;  // receives the text to write

  StatusReporter(std::string what, ProgressMode mode, Sink sink, Clock clock,
                 double line_interval_s = kProgressLineInterval);
  // On stderr, timed by the steady clock; in line mode a thread calls tick()
  // four times a second until finish(), so that a long stage still shows.
  static std::unique_ptr<StatusReporter> on_stderr(std::string what, ProgressMode mode);
  ~StatusReporter();
  StatusReporter(const StatusReporter&) = delete;
  StatusReporter& operator=(const StatusReporter&) = delete;

  // The command is now doing status.
  void update(const std::string& status);
  // Writes the line mode's line when it is due.
  void tick();
  // Clears the bar, stops the thread; later calls do nothing.
  void finish();

 private:
  void write_line_locked(double now);
  void start_heartbeat();

  std::string what_;
  ProgressMode mode_;
  Sink sink_;
  Clock clock_;
  double interval_;
  double start_ = 0.0, last_line_ = 0.0;
  std::string status_;
  std::size_t width_ = 0;
  bool finished_ = false;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::thread heartbeat_;
};

}  // namespace gpm::cli
