// gpm-drive-emulator: serves a register map over Modbus TCP, backed by the
// MuJoCo twin of a scenario, so the `modbus` backend can run without drives.
// Binds to 127.0.0.1 unless --bind says otherwise (a loopback address or
// name; anything else needs --allow-non-loopback). Runs until SIGINT/SIGTERM.
// Exit 0 stopped, 1 the server failed, 2 bad flags or files (one line).
#include <csignal>
#include <cstdio>
#include <thread>

#include <CLI/CLI.hpp>

#include "hw/backends/drive_emulator.hpp"
#include "hw/hardware_config.hpp"
#include "hw/hw_errors.hpp"
#include "models/errors.hpp"

namespace {
volatile std::sig_atomic_t g_stop = 0;
void on_signal(int) { g_stop = 1; }
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"gpm-drive-emulator: Modbus TCP servo-drive emulator backed by the GPM2002 twin"};
  std::string map_path, scenario;
  gpm::hw::EmulatorOptions opt;
  app.add_option("--map", map_path, "register map YAML")->required();
  app.add_option("--scenario", scenario, "scenario YAML giving the twin's actual robot")->required();
  std::string bind = opt.bind_address;
  bool allow_non_loopback = false;
  app.add_option("--bind", bind, "loopback address or name to listen on (default 127.0.0.1)");
  app.add_flag("--allow-non-loopback", allow_non_loopback,
               "allow --bind beyond this machine (0.0.0.0, a LAN address): no authentication");
  app.add_option("--port", opt.port, "port 0..65535 (0: ephemeral, printed)");
  app.add_option("--command-period", opt.command_period_s, "client's command period (s, 1e-4..1), for feed-forward");
  app.add_option("--comms-watchdog", opt.comms_watchdog_s, "drive-side comms watchdog (s)");
  app.add_flag("--stepped", opt.stepped,
               "the plant advances one command period per latch trigger (per client cycle), not in real time "
               "(lock step with a hardware file's modbus.timing: stepped)");
  app.add_option("--drop-after-writes", opt.faults.drop_after_writes, "fault: drop the connection");
  app.add_option("--delay-after-writes", opt.faults.delay_after_writes, "fault: delay replies");
  app.add_option("--delay", opt.faults.delay_s, "reply delay (s)");
  app.add_option("--fault-after-writes", opt.faults.fault_after_writes, "fault: set the fault bit");
  app.add_option("--fault-axis", opt.faults.fault_axis, "axis of the fault (0..2)")->check(CLI::Range(0, 2));
  app.add_option("--garbage-after-writes", opt.faults.garbage_after_writes, "fault: garbage positions");
  app.add_option("--garbage-axis", opt.faults.garbage_axis, "axis of the garbage (0..2)")->check(CLI::Range(0, 2));
  app.add_option("--slip-after-writes", opt.faults.slip_after_writes, "fault: an encoder slips (offset jump)");
  app.add_option("--slip-axis", opt.faults.slip_axis, "axis of the slip (0..2)")->check(CLI::Range(0, 2));
  app.add_option("--slip-counts", opt.faults.slip_counts, "size of the slip (counts)");
  app.add_option("--stall-after-writes", opt.faults.stall_after_writes,
                 "fault: the server stalls (requests read, never answered)");
  app.add_option("--stall", opt.faults.stall_s, "how long each swallowed request holds the server (s)");
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "gpm-drive-emulator: error: %s (see --help)\n", e.what());
    return 2;
  }
  try {
    opt.bind_address = gpm::hw::emulator_bind_address(bind, allow_non_loopback);
    gpm::hw::validate_emulator_options(opt);
    const gpm::hw::RegisterMap map = gpm::hw::load_register_map(map_path);
    const gpm::hw::TwinBackendConfig twin =
        gpm::hw::twin_config_from_scenario(scenario, opt.command_period_s);
    gpm::hw::DriveEmulator emu(map, twin, opt);
    std::signal(SIGINT, on_signal);
    std::signal(SIGTERM, on_signal);
    const int port = emu.start();
    std::printf("gpm-drive-emulator: listening on %s:%d\n", opt.bind_address.c_str(), port);
    std::fflush(stdout);
    while (!g_stop && emu.error().empty()) std::this_thread::sleep_for(std::chrono::milliseconds(20));
    emu.stop();
    if (!emu.error().empty()) {
      std::fprintf(stderr, "gpm-drive-emulator: error: %s\n", emu.error().c_str());
      return 1;
    }
  } catch (const gpm::InputError& e) {
    std::fprintf(stderr, "gpm-drive-emulator: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "gpm-drive-emulator: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
