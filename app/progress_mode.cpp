// Progress of the long commands on stderr (app/progress_mode.hpp).
#include "app/progress_mode.hpp"

#include <chrono>
#include <csignal>
#include <cstdio>

#include <fmt/format.h>
#include <pthread.h>
#include <unistd.h>

namespace gpm::cli {
namespace {

double steady_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

void write_stderr(const std::string& text) {
  std::fputs(text.c_str(), stderr);
  std::fflush(stderr);
}

}  // namespace

void add_progress_option(CLI::App* cmd, std::string& choice) {
  cmd->add_option("--progress", choice,
                  "Progress on stderr: none, line (a line every few seconds) or bar (one line rewritten); "
                  "default: bar on a terminal, line otherwise")
      ->check(CLI::IsMember({"none", "line", "bar"}));
}

ProgressMode progress_mode(const std::string& choice, bool stderr_is_terminal) {
  if (choice == "none") return ProgressMode::kNone;
  if (choice == "line") return ProgressMode::kLine;
  if (choice == "bar") return ProgressMode::kBar;
  return stderr_is_terminal ? ProgressMode::kBar : ProgressMode::kLine;
}

ProgressMode progress_mode(const std::string& choice) { return progress_mode(choice, ::isatty(STDERR_FILENO) != 0); }

Progress counting_progress(ProgressMode mode, const std::string& what, const std::string& unit, double total) {
  if (mode == ProgressMode::kNone) return Progress::silent();
  if (mode == ProgressMode::kBar) return Progress(what, unit, total, write_stderr, steady_seconds);
  // Line mode: the reporter's "\r" + padded line becomes one plain line; its
  // closing blank-out writes nothing.
  const auto line = [](const std::string& text) {
    const std::size_t first = text.find_first_not_of("\r ");
    const std::size_t last = text.find_last_not_of("\r ");
    if (first != std::string::npos) write_stderr(text.substr(first, last - first + 1) + "\n");
  };
  return Progress(what, unit, total, line, steady_seconds, kProgressLineInterval);
}

StatusReporter::StatusReporter(std::string what, ProgressMode mode, Sink sink, Clock clock, double line_interval_s)
    : what_(std::move(what)), mode_(mode), sink_(std::move(sink)), clock_(std::move(clock)), interval_(line_interval_s) {
  if (mode_ != ProgressMode::kNone) start_ = last_line_ = clock_();
}

std::unique_ptr<StatusReporter> StatusReporter::on_stderr(std::string what, ProgressMode mode) {
  auto r = std::make_unique<StatusReporter>(std::move(what), mode, write_stderr, steady_seconds);
  if (mode == ProgressMode::kLine) r->start_heartbeat();
  return r;
}

StatusReporter::~StatusReporter() { finish(); }

void StatusReporter::start_heartbeat() {
  // The thread blocks the stop signals (it inherits the mask at creation), so
  // that SIGINT, SIGTERM and SIGHUP reach the thread that does the work (and
  // interrupt its waits on drives and files).
  sigset_t stop, previous;
  sigemptyset(&stop);
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&stop, sig);
  pthread_sigmask(SIG_BLOCK, &stop, &previous);
  heartbeat_ = std::thread([this] {
    std::unique_lock<std::mutex> lock(mutex_);
    while (!finished_) {
      wake_.wait_for(lock, std::chrono::milliseconds(250));
      if (!finished_) write_line_locked(clock_());
    }
  });
  pthread_sigmask(SIG_SETMASK, &previous, nullptr);
}

void StatusReporter::write_line_locked(double now) {
  if (status_.empty() || now - last_line_ < interval_) return;
  last_line_ = now;
  sink_(fmt::format("{}: {}, {:.0f} s\n", what_, status_, now - start_));
}

void StatusReporter::update(const std::string& status) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (finished_ || mode_ == ProgressMode::kNone) return;
  if (mode_ == ProgressMode::kLine) {
    status_ = status;
    write_line_locked(clock_());
    return;
  }
  if (status == status_) return;
  status_ = status;
  std::string text = fmt::format("{}: {}", what_, status);
  const std::size_t len = text.size();
  if (len < width_) text.append(width_ - len, ' ');
  width_ = len;
  sink_("\r" + text);
}

void StatusReporter::tick() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!finished_ && mode_ == ProgressMode::kLine) write_line_locked(clock_());
}

void StatusReporter::finish() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (finished_) return;
    finished_ = true;
    if (mode_ == ProgressMode::kBar && width_ > 0) sink_(fmt::format("\r{:{}}\r", "", width_));
  }
  wake_.notify_all();
  if (heartbeat_.joinable()) heartbeat_.join();
}

}  // namespace gpm::cli
