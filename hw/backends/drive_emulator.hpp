// Drive emulator: serves a register map over Modbus TCP, backed by the MuJoCo
// twin in real time, so the `modbus` backend's whole protocol path runs in CI.
// With a latch in the map, a write of an id to the latch register copies
// every axis's actual position (of the same plant tick) to its
// latched_position, the id to its latch_id, and the plant's time of that
// tick (us) to the latch's time registers if the map has them.
// Each axis behaves like a simple servo drive: the power stage comes on at a
// rising edge of its enable bit (not while faulted), follows the position
// command, and goes off when the enable bit clears, on a fault, or when no
// request has arrived for comms_watchdog_s (drive-side comms watchdog).
// Faults can be injected. Binds to 127.0.0.1 unless told otherwise.
#pragma once

#include <array>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <thread>

#include "hw/backends/register_map.hpp"
#include "hw/clock.hpp"
#include "hw/backends/twin_backend.hpp"

namespace gpm::hw {

// Faults to inject, each triggered once the emulator has served the given
// number of write requests (-1: never).
struct EmulatorFaults {
  long drop_after_writes = -1;     // close every connection and stop listening
  long delay_after_writes = -1;    // from then on delay every reply by delay_s
  double delay_s = 0.0;
  long fault_after_writes = -1;    // set the fault bit (and fault_code) of fault_axis
  int fault_axis = 0;
  std::uint16_t fault_code = 0x2310;
  long garbage_after_writes = -1;  // actual position registers of garbage_axis turn to noise
  int garbage_axis = 0;
  // The encoder of slip_axis slips by slip_counts: the drive reads (and
  // servoes on) its angle shifted by that much, an encoder offset jump
  // (dth of that joint changes by -slip_counts counts).
  long slip_after_writes = -1;
  int slip_axis = 0;
  long slip_counts = 0;
  // A stalled server: from then on every request is read and never answered
  // (the connection stays open); each swallowed request holds the server for
  // stall_s on its clock (on a ManualClock: the clock jumps by stall_s, so a
  // client on the same clock sees its response timeout pass at once).
  long stall_after_writes = -1;
  double stall_s = 1.0;
};

// Settings of the emulator.
struct EmulatorOptions {
  std::string bind_address = "127.0.0.1";  // loopback unless told otherwise
  int port = 0;                            // 0: an ephemeral port (see port())
  double tick_s = 0.001;                   // plant update period (on the clock)
  double comms_watchdog_s = 0.3;           // no request this long: power stages off
  double command_period_s = 0.004;         // the client's command period (feed-forward; gpm-drive-emulator
                                           // gives it to the twin: twin_config_from_scenario)
  EmulatorFaults faults;
  // Stepped by the client (for a client in another process, which cannot
  // share a clock): the plant advances by command_period_s at each latch
  // trigger (one per client read cycle) and at nothing else, taking that
  // cycle's setpoint, so its motion depends on the client's commands per
  // cycle, not on when either process ran (a client in lock step:
  // DriveBackend with DriveTiming::kStepped). The comms watchdog, delays and
  // stalls stay on the clock. Needs a latch in the map.
  bool stepped = false;
  // Time of the plant, the watchdog, delays and stalls (nullptr: the wall
  // clock). Every request first brings the plant up to the clock's time, so
  // a client on the same ManualClock (stepped: the clock moves only when the
  // client waits for its next cycle) gets replies that depend on the clock
  // and the requests alone, not on when the serving thread ran.
  Clock* clock = nullptr;
};

// The numeric IPv4 address the emulator binds for name (a dotted quad or a
// host name such as localhost, resolved to its IPv4 address). Throws
// InputError (one line naming the flag) for a name that does not resolve, and
// for an address outside 127.0.0.0/8 (0.0.0.0 listens on every interface)
// unless allow_non_loopback: Modbus TCP has no authentication.
std::string emulator_bind_address(const std::string& name, bool allow_non_loopback);

// Throws InputError (one line naming the flag and the valid range) for
// settings no drive would have: port outside 0..65535, tick or comms
// watchdog not in (0, 60] s, a command period not in [1e-4, 1] s, fault
// counts below -1, a delay outside [0, 60] s, fault axes outside 0..2, slip
// counts beyond +-1e6, a bind address that is not a numeric IPv4 address;
// NaN is outside every range.
void validate_emulator_options(const EmulatorOptions& options);

class DriveEmulator {
 public:
  // An emulator of the drives in map backed by a twin built from twin (the
  // twin's period_s is the client's command period, for velocity feed-forward).
  DriveEmulator(const RegisterMap& map, const TwinBackendConfig& twin, const EmulatorOptions& options);
  // Stops the server thread.
  ~DriveEmulator();
  DriveEmulator(const DriveEmulator&) = delete;
  DriveEmulator& operator=(const DriveEmulator&) = delete;

  // Binds and listens, then serves on a background thread; returns the port.
  // Throws InputError for invalid options (validate_emulator_options),
  // HardwareError if it cannot bind.
  int start();
  // Stops serving and closes every socket; idempotent.
  void stop();
  // The port it listens on (after start()).
  int port() const { return port_; }
  // Which power stages are on now.
  std::array<bool, 3> power_on() const;
  // Write requests served so far.
  long writes() const;
  // The twin's last snapshot (true angles and end-effector).
  sim::TwinSnapshot snapshot() const;
  // Why the server loop stopped on its own (empty while it runs well).
  std::string error() const;
  // Waits (on a condition, not a sleep) until no client is connected and
  // every request received was served; false after timeout_s of wall time.
  bool wait_until_no_clients(double timeout_s);
  // Runs one plant tick now (on the emulator's clock): tests that move an
  // injected clock see its effect at once, without waiting for the server.
  void tick_now();
  // Serves one client connection whose whole request stream is bytes (as if
  // received until the client closed it), then runs one plant tick at time
  // t_s; returns the reply bytes. Needs no listening socket and must not be
  // mixed with start() (tests and the Modbus fuzz target).
  std::string serve_bytes(std::string_view bytes, double t_s);

 private:
  void prepare();
  void serve();
  void tick(double t);
  // Runs a plant tick if one is due at now (on the emulator's clock).
  void tick_if_due(double now);
  // Reads one request from client fd and answers it (faults injected as the
  // options say); a client that hung up or does not read is dropped.
  void handle_request(int fd);
  // Closes client fd and forgets it (waking wait_until_no_clients when none is left).
  void drop_client(int fd);
  // Counts a write request and switches on the faults due after it; false
  // when the fault drops every connection (no reply).
  bool count_write();
  // Holds the reply as a stall or delay fault says (the lock released while
  // held); false when stalled (no reply).
  bool hold_reply();
  // Answers request q (length bytes) on fd from its unit's registers, and
  // latches every axis's position when it writes the latch register.
  void reply(int fd, const std::uint8_t* q, int length, bool latch_write);
  // Whether a client has a request waiting to be read (no wait).
  bool request_waiting() const;
  void close_clients();

  RegisterMap map_;
  EmulatorOptions options_;
  Clock& clock_;
  TwinBackend twin_;
  mutable std::mutex mutex_;
  std::condition_variable clients_gone_;
  std::thread thread_;
  std::atomic<bool> stop_{false};
  int port_ = 0;
  int listen_fd_ = -1;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace gpm::hw
