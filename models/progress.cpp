#include "models/progress.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <unistd.h>

#include <fmt/format.h>

namespace gpm {
namespace {

// "12.5" for a count with a fraction, "12" for a whole one.
std::string amount(double v) {
  if (std::abs(v - std::round(v)) < 1e-9 && std::abs(v) < 1e15) return fmt::format("{:.0f}", v);
  return fmt::format("{:.1f}", v);
}

std::string duration(double s) {
  if (s < 60.0) return fmt::format("{:.1f} s", s);
  const long m = static_cast<long>(s / 60.0);
  return fmt::format("{} min {:02.0f} s", m, std::floor(s - 60.0 * m));
}

}  // namespace

Progress::Progress(std::string what, std::string unit, double total, Sink sink, Clock clock,
                   double min_interval_s)
    : what_(std::move(what)),
      unit_(std::move(unit)),
      total_(total),
      sink_(std::move(sink)),
      clock_(std::move(clock)),
      min_interval_s_(min_interval_s) {
}

Progress::Progress(Progress&& o) noexcept
    : what_(std::move(o.what_)),
      unit_(std::move(o.unit_)),
      total_(o.total_),
      sink_(std::move(o.sink_)),
      clock_(std::move(o.clock_)),
      min_interval_s_(o.min_interval_s_),
      start_(o.start_),
      last_(o.last_),
      done0_(o.done0_),
      started_(o.started_),
      width_(o.width_),
      finished_(o.finished_) {
  o.sink_ = nullptr;
  o.finished_ = true;
}

Progress::~Progress() {
  if (sink_ && !finished_) finish();
}

Progress Progress::silent() { return Progress("", "", 0.0, nullptr, nullptr); }

Progress Progress::terminal(std::string what, std::string unit, double total) {
  Sink sink;
  if (::isatty(STDERR_FILENO)) {
    sink = [](const std::string& s) {
      std::fputs(s.c_str(), stderr);
      std::fflush(stderr);
    };
  }
  Clock clock = [] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
  };
  return Progress(std::move(what), std::move(unit), total, std::move(sink), std::move(clock));
}

std::string Progress::line(double done, double elapsed_s) const {
  std::string s = fmt::format("{}  {}", what_, amount(done));
  if (total_ > 0) s += fmt::format("/{}", amount(total_));
  s += fmt::format(" {}", unit_);
  if (elapsed_s > 0 && done > done0_) {
    const double rate = (done - done0_) / elapsed_s;
    s += fmt::format("  {:.1f} {}/s", rate, unit_);
    if (total_ > 0 && done <= total_) s += fmt::format("  ETA {}", duration((total_ - done) / rate));
  }
  return s;
}

void Progress::update(double done) {
  if (!sink_ || finished_) return;
  const double now = clock_();
  if (!started_) {  // the rate counts from the first update: set-up time is not work
    started_ = true;
    start_ = last_ = now;
    done0_ = done;
    return;
  }
  if (now - last_ < min_interval_s_) return;
  last_ = now;
  std::string s = line(done, now - start_);
  const size_t len = s.size();
  if (len < width_) s.append(width_ - len, ' ');  // blank what the last line wrote beyond this one
  width_ = len;
  sink_(fmt::format("\r{}", s));
}

void Progress::finish() {
  if (finished_) return;
  finished_ = true;
  if (sink_ && width_ > 0) sink_(fmt::format("\r{:{}}\r", "", width_));
}

}  // namespace gpm
