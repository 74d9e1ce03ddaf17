#include "hw/procedures/stop_on_signal.hpp"

#include <csignal>

namespace gpm::hw {
namespace {

std::atomic<bool> g_requested{false};
std::atomic<int> g_signal{0};
constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP};
struct sigaction g_previous[3];

void on_stop_signal(int sig) {
  g_signal.store(sig);
  g_requested.store(true);
}

}  // namespace

StopOnSignal::StopOnSignal() {
  g_requested = false;
  g_signal = 0;
  struct sigaction sa {};
  sa.sa_handler = on_stop_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;
  for (int k = 0; k < 3; ++k) sigaction(kSignals[k], &sa, &g_previous[k]);
}

StopOnSignal::~StopOnSignal() {
  for (int k = 0; k < 3; ++k) sigaction(kSignals[k], &g_previous[k], nullptr);
}

const std::atomic<bool>* StopOnSignal::flag() const { return &g_requested; }

int StopOnSignal::signal_number() { return g_signal.load(); }

const char* StopOnSignal::signal_name() {
  switch (g_signal.load()) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    case SIGHUP: return "SIGHUP";
    default: return "a signal";
  }
}

}  // namespace gpm::hw
