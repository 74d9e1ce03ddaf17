// The one signal policy of every command that moves a robot (gpm sample,
// gpm zero, gpm run --hardware): while a StopOnSignal lives, SIGINT, SIGTERM
// and SIGHUP only request a stop. The procedure's next control cycle sees the
// request (Motion::cycle), disables the drives first (emergency stop) and
// throws Interrupted; the command keeps what was recorded, says so in one line
// on stderr and exits 130 (kInterruptedExit).
#pragma once

#include <atomic>

namespace gpm::hw {

// Exit code of a command stopped by a signal.
inline constexpr int kInterruptedExit = 130;

class StopOnSignal {
 public:
  // Installs the handlers (the previous ones come back on destruction) and
  // clears any earlier request.
  StopOnSignal();
  ~StopOnSignal();
  StopOnSignal(const StopOnSignal&) = delete;
  StopOnSignal& operator=(const StopOnSignal&) = delete;

  // The flag a procedure polls each cycle (true once a signal came).
  const std::atomic<bool>* flag() const;
  // The signal that requested the stop (0 while none).
  static int signal_number();
  // Its name for the one-line message ("SIGINT", ...).
  static const char* signal_name();
};

}  // namespace gpm::hw
