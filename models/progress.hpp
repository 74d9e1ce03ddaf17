// Progress of a long loop on a terminal: one line on stderr, rewritten in
// place with \r, at most a few times a second, showing how much is done (of
// how much), the rate and the time left. Silent when stderr is not a
// terminal, so logs, pipes and tests stay clean.
//
// Use:
//   gpm::Progress p = gpm::Progress::terminal("gpm render", "frames", n);
//   for (int k = 0; k < n; ++k) { ...; p.update(k + 1); }
//   p.finish();
#pragma once

#include <functional>
#include <string>

namespace gpm {

class Progress {
 public:
  using Clock = std::function<double()>;                  // seconds, monotonic
  using Sink = std::function<void(const std::string&)>;  // receives the text to write

  // A reporter of `what` counted in `unit` ("frames", "s simulated") up to
  // total (0: unknown, no ETA) writing to sink (nullptr: silent) with time
  // from clock, rewriting at most once per min_interval_s.
  Progress(std::string what, std::string unit, double total, Sink sink, Clock clock,
           double min_interval_s = 0.25);
  // Clears the line if finish() was not called.
  ~Progress();
  // The moved-from reporter is silent.
  Progress(Progress&& other) noexcept;
  Progress& operator=(Progress&&) = delete;
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  // A reporter on stderr when stderr is a terminal (silent otherwise), timed
  // by the steady clock.
  static Progress terminal(std::string what, std::string unit, double total = 0.0);

  // A reporter that writes nothing (for a caller that was asked to be quiet).
  static Progress silent();

  // Records that `done` units are done. The first call starts the clock
  // (the rate counts the units done after it, so set-up time is left out);
  // later calls rewrite the line when min_interval_s has passed since the
  // last one.
  void update(double done);

  // Erases the line (if one was written); later updates are ignored.
  void finish();

  // The line for `done` units, elapsed_s seconds after the first update, e.g.
  // "gpm render  120/294 frames  97.3 frames/s  ETA 1.8 s".
  std::string line(double done, double elapsed_s) const;

  // True when something will be written (a sink is set).
  bool active() const { return static_cast<bool>(sink_); }

 private:
  std::string what_, unit_;
  double total_;
  Sink sink_;
  Clock clock_;
  double min_interval_s_;
  double start_ = 0.0, last_ = 0.0;
  double done0_ = 0.0;  // units done at the first update
  bool started_ = false;
  size_t width_ = 0;  // length of the last line written (to blank it)
  bool finished_ = false;
};

}  // namespace gpm
