// Tests of hw/backends/drive_emulator.cpp: loopback-only ephemeral ports, power stage
// on a rising enable edge, off on the drive-side comms watchdog and on a fault;
// a malformed request or a client that never reads stalls no other client; on
// an injected clock, a stalled client (silent) and a stalled server (no reply)
// and delayed replies are decided by that clock alone, not by the wall time.
// Stepped (lock step with a stepped DriveBackend, hw/backends/drive_backend.cpp):
// N client cycles advance the plant and the latch's time by exactly N periods,
// the readings' times are the drives', a client at another rate or drives on
// their own clock are refused before anything is enabled, and the readings are
// those of the twin backend in process given the same commands; a session on
// the fly through it takes the twin backend's time and samples.
#include <cerrno>
#include <functional>

#include <arpa/inet.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>
#include <netinet/in.h>

#include <gtest/gtest.h>

#include <cmath>
#include <tuple>

#include <fmt/format.h>

#include "hw/backends/drive_backend.hpp"
#include "hw/backends/drive_emulator.hpp"
#include "hw/clock.hpp"
#include "hw/hardware_config.hpp"
#include "hw/hw_errors.hpp"
#include "hw/backends/modbus_transport.hpp"
#include "hw/backends/twin_backend.hpp"
#include "hw/procedures/trajectory_session.hpp"
#include "models/errors.hpp"
#include "models/kinematics.hpp"
#include "models/samples.hpp"
#include "sim/waypoint_path.hpp"
#include "hw_test_util.hpp"

namespace gpm::hw {
namespace {

const std::string kSrc = GPM_SOURCE_DIR;

std::unique_ptr<DriveEmulator> make(const EmulatorOptions& o = {}) {
  const RegisterMap map = load_register_map(kSrc + "/hw/examples/register_map_emulator.yaml");
  return std::make_unique<DriveEmulator>(
      map, twin_config_from_scenario(kSrc + "/tests/fixtures/twin_disc.yaml", 0.004), o);
}


TEST(DriveEmulator, EphemeralPortsDifferAndListenOnLoopbackByDefault) {
  EXPECT_EQ(EmulatorOptions{}.bind_address, "127.0.0.1");
  auto a = make(), b = make();
  const int pa = a->start(), pb = b->start();
  EXPECT_GT(pa, 0);
  EXPECT_NE(pa, pb);
}

TEST(DriveEmulator, BindAddressesResolveAndStayOnLoopback) {
  // localhost once bound 255.255.255.255 (the name went to inet_addr unresolved).
  EXPECT_EQ(emulator_bind_address("localhost", false), "127.0.0.1");
  EXPECT_EQ(emulator_bind_address("127.0.0.1", false), "127.0.0.1");
  EXPECT_EQ(emulator_bind_address("127.3.4.5", false), "127.3.4.5");
  EXPECT_THROW(emulator_bind_address("0.0.0.0", false), InputError);
  EXPECT_THROW(emulator_bind_address("10.1.2.3", false), InputError);
  EXPECT_EQ(emulator_bind_address("0.0.0.0", true), "0.0.0.0");
  EXPECT_THROW(emulator_bind_address("no such host.invalid", true), InputError);
  EXPECT_THROW(emulator_bind_address("", false), InputError);
}

TEST(DriveEmulator, OptionsOutsideTheirRangesAreRefused) {
  EXPECT_NO_THROW(validate_emulator_options(EmulatorOptions{}));
  auto refused = [](auto change) {
    EmulatorOptions o;
    change(o);
    EXPECT_THROW(validate_emulator_options(o), InputError);
  };
  refused([](EmulatorOptions& o) { o.port = -1; });
  refused([](EmulatorOptions& o) { o.port = 70000; });
  refused([](EmulatorOptions& o) { o.comms_watchdog_s = 0; });
  refused([](EmulatorOptions& o) { o.comms_watchdog_s = -1; });
  refused([](EmulatorOptions& o) { o.bind_address = "localhost"; });  // names are resolved first
  refused([](EmulatorOptions& o) { o.faults.delay_s = -0.1; });
  refused([](EmulatorOptions& o) { o.faults.fault_axis = 3; });
  refused([](EmulatorOptions& o) { o.faults.drop_after_writes = -2; });
  refused([](EmulatorOptions& o) { o.faults.stall_after_writes = -2; });
  refused([](EmulatorOptions& o) { o.faults.stall_s = -1; });
  refused([](EmulatorOptions& o) { o.faults.stall_s = std::nan(""); });
  // NaN is outside every range (a NaN command period left the drives standing).
  refused([](EmulatorOptions& o) { o.command_period_s = std::nan(""); });
  refused([](EmulatorOptions& o) { o.command_period_s = 0; });
  refused([](EmulatorOptions& o) { o.command_period_s = 2; });
  refused([](EmulatorOptions& o) { o.comms_watchdog_s = std::nan(""); });
  refused([](EmulatorOptions& o) { o.faults.delay_s = std::nan(""); });
  EmulatorOptions o;
  o.comms_watchdog_s = 0;
  auto emu = make(o);
  EXPECT_THROW(emu->start(), InputError);  // before binding anything
}

// A malformed request (unknown function code) is answered with an exception
// and does not stall the server: libmodbus waits its response timeout (0.5 s by
// default) before flushing, which once blocked every client for that long.
TEST(DriveEmulator, AMalformedRequestDoesNotStallTheServer) {
  auto emu = make();
  const int port = emu->start();
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(static_cast<std::uint16_t>(port));
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
  const std::uint8_t bad[] = {0, 1, 0, 0, 0, 2, 1, 0x55};  // MBAP, unit 1, function 0x55
  ModbusTransport t("127.0.0.1", port, 0.3);
  t.connect();
  ASSERT_EQ(::send(fd, bad, sizeof bad, 0), static_cast<ssize_t>(sizeof bad));
  // Another client, right behind it, is served within its response timeout (0.3 s).
  std::uint16_t st = 0;
  EXPECT_NO_THROW(t.read(1, 10, 1, &st));
  std::uint8_t reply[16] = {};
  ASSERT_EQ(::recv(fd, reply, sizeof reply, 0), 9);  // the exception reply
  EXPECT_EQ(reply[7], 0x55 | 0x80);
  EXPECT_EQ(reply[8], 1);  // illegal function
  ::close(fd);
}

// Connects to port and sends requests without ever reading a reply (its
// receive buffer small, so it fills at once) until the server takes no more
// for 1 s or drops it; returns the socket (to close) and prints the count.
int flood_without_reading(int port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  const int small = 1024;
  ::setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &small, sizeof small);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(static_cast<std::uint16_t>(port));
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
    ADD_FAILURE() << "cannot connect to the emulator";
    return fd;
  }
  // Read 21 registers of unit 1 (a 51-byte reply each), over and over,
  // never reading: until the server takes no more for 1 s (its replies fill
  // every buffer: without a send timeout it would now be stuck) or drops us.
  const std::uint8_t read21[] = {0, 1, 0, 0, 0, 6, 1, 3, 0, 0, 0, 21};
  long sent = 0;
  for (; sent < 2000000; ++sent) {
    if (::send(fd, read21, sizeof read21, MSG_DONTWAIT | MSG_NOSIGNAL) == static_cast<ssize_t>(sizeof read21))
      continue;
    if (errno != EAGAIN && errno != EWOULDBLOCK) break;  // dropped by the server
    pollfd p{fd, POLLOUT, 0};
    if (::poll(&p, 1, 1000) <= 0) break;  // the server stopped reading
    --sent;
  }
  std::printf("sent %ld requests without reading a reply\n", sent);
  EXPECT_GT(sent, 100);
  return fd;
}

// A client that sends requests but never reads the replies: the server drops
// it once a reply cannot be sent, and another client is still served within
// its response timeout.
TEST(DriveEmulator, AClientThatNeverReadsDoesNotStallTheServer) {
  auto emu = make();
  const int port = emu->start();
  const int fd = flood_without_reading(port);
  ModbusTransport t("127.0.0.1", port, 2.0);
  t.connect();
  std::uint16_t st = 0;
  EXPECT_NO_THROW(t.read(1, 10, 1, &st));
  EXPECT_EQ(emu->error(), "");
  ::close(fd);
}

TEST(DriveEmulator, EnableEdgeWatchdogAndFault) {
  // The plant and the watchdog run on a clock the test moves: each request is
  // served before its call returns, and tick_now() shows its effect at once.
  ManualClock clock;
  std::function<void()> emu_tick;
  auto settle_ticks = [&] {
    clock.advance(0.004);
    emu_tick();
  };
  EmulatorOptions o;
  o.clock = &clock;
  o.comms_watchdog_s = 0.15;
  o.faults.fault_after_writes = 5;
  o.faults.fault_axis = 0;
  auto emu = make(o);
  emu_tick = [&] { emu->tick_now(); };
  const int port = emu->start();
  ModbusTransport t("127.0.0.1", port, 0.5);
  t.connect();
  const std::uint16_t on = 1, off = 0;
  t.write(2, 0, 1, &on);  // write 1
  settle_ticks();
  EXPECT_EQ(emu->power_on(), (std::array<bool, 3>{false, true, false}));
  clock.advance(0.1);  // silence shorter than the comms watchdog: still on
  emu->tick_now();
  EXPECT_TRUE(emu->power_on()[1]);
  // Silence longer than the comms watchdog: the drive switches itself off ...
  clock.advance(0.1);
  emu->tick_now();
  EXPECT_EQ(emu->power_on(), (std::array<bool, 3>{false, false, false}));
  // ... and stays off although the enable bit is still set, until a new edge.
  std::uint16_t st = 0;
  t.read(2, 10, 1, &st);
  EXPECT_EQ(st & 1u, 0u);
  t.write(2, 0, 1, &off);  // write 2
  settle_ticks();          // the drive samples its control word every tick
  t.write(2, 0, 1, &on);   // write 3
  settle_ticks();
  EXPECT_TRUE(emu->power_on()[1]);
  t.write(1, 0, 1, &on);   // write 4
  t.write(1, 0, 1, &on);   // write 5: fault on axis 0
  settle_ticks();
  t.read(1, 10, 1, &st);
  EXPECT_EQ(st & (1u << 3), 1u << 3);
  std::uint16_t code = 0;
  t.read(1, 11, 1, &code);
  EXPECT_EQ(code, 0x2310);
  EXPECT_FALSE(emu->power_on()[0]);
}

// A stalled client: connected, drives enabled, then silent. The drives'
// comms watchdog switches them off once the injected clock has passed it,
// not before, however long the wall time (no request comes in either way).
TEST(DriveEmulator, AStalledClientIsSwitchedOffByTheWatchdogOnTheInjectedClock) {
  ManualClock clock;
  EmulatorOptions o;
  o.clock = &clock;
  o.comms_watchdog_s = 0.3;
  auto emu = make(o);
  const int port = emu->start();
  ModbusTransport t("127.0.0.1", port, 0.05, clock);
  t.connect();
  const std::uint16_t on = 1;
  for (int unit = 1; unit <= 3; ++unit) t.write(unit, 0, 1, &on);
  clock.advance(0.004);
  emu->tick_now();
  EXPECT_EQ(emu->power_on(), (std::array<bool, 3>{true, true, true}));
  clock.advance(0.299);  // 0.303 s on the clock since the last request: past the watchdog
  emu->tick_now();
  EXPECT_EQ(emu->power_on(), (std::array<bool, 3>{false, false, false}));
  // The same silence one step shorter than the watchdog keeps them on.
  auto emu2 = make(o);
  ModbusTransport t2("127.0.0.1", emu2->start(), 0.05, clock);
  t2.connect();
  for (int unit = 1; unit <= 3; ++unit) t2.write(unit, 0, 1, &on);
  clock.advance(0.004);
  emu2->tick_now();
  clock.advance(0.29);
  emu2->tick_now();
  EXPECT_EQ(emu2->power_on(), (std::array<bool, 3>{true, true, true}));
}

// A stalled server: after its second write it reads requests and never
// answers. The client's response timeout runs on the injected clock, which
// the stalled server moves (stall_s per swallowed request), so the timeout is
// certain and immediate, with a wall bound of ModbusTransport::kWallBackstopS
// only for a server that would hold the clock still.
TEST(DriveEmulator, AStalledServerIsAResponseTimeoutOnTheInjectedClock) {
  ManualClock clock;
  EmulatorOptions o;
  o.clock = &clock;
  o.faults.stall_after_writes = 2;
  o.faults.stall_s = 1.0;
  auto emu = make(o);
  const int port = emu->start();
  ModbusTransport t("127.0.0.1", port, 0.05, clock);
  t.connect();
  const std::uint16_t on = 1;
  std::uint16_t st = 0;
  t.write(2, 0, 1, &on);  // write 1: answered
  t.read(2, 10, 1, &st);  // answered
  const double t0 = clock.now();
  try {
    t.write(2, 0, 1, &on);  // write 2: swallowed
    FAIL() << "a stalled server answered";
  } catch (const HardwareError& e) {
    EXPECT_NE(std::string(e.what()).find("writing registers 0..0 failed: Connection timed out"), std::string::npos)
        << e.what();
  }
  EXPECT_GE(clock.now() - t0, 1.0);  // the time the stall took, on the clock
  // The drives, silent since, are switched off by their own watchdog.
  clock.advance(0.5);
  emu->tick_now();
  EXPECT_EQ(emu->power_on(), (std::array<bool, 3>{false, false, false}));
  EXPECT_EQ(emu->error(), "");
}

// Delayed replies are late or in time by the injected clock: a delay just
// under the response timeout is answered, one just over it is a timeout,
// whatever the wall time the replies took.
TEST(DriveEmulator, DelayedRepliesAreLateByTheInjectedClockOnly) {
  for (const double delay : {0.045, 0.055}) {
    ManualClock clock;
    EmulatorOptions o;
    o.clock = &clock;
    o.faults.delay_after_writes = 1;
    o.faults.delay_s = delay;
    auto emu = make(o);
    ModbusTransport t("127.0.0.1", emu->start(), 0.05, clock);
    t.connect();
    const std::uint16_t on = 1;
    std::uint16_t st = 0;
    if (delay < 0.05) {  // write 1 and every reply after it come delay late
      EXPECT_NO_THROW(t.write(2, 0, 1, &on)) << delay;
      EXPECT_NO_THROW(t.read(2, 10, 1, &st)) << delay;
      EXPECT_NEAR(clock.now(), 2 * delay, 1e-9);
    } else {
      EXPECT_THROW(t.write(2, 0, 1, &on), HardwareError) << delay;
    }
  }
}

// Lock step: the emulator --stepped and a DriveBackend with stepped timing,
// both on a clock that never moves (neither needs any time but the cycles').
constexpr double kPeriod = 0.004;  // the client's cycle (the fixture twin's command period)

struct LockStep {
  ManualClock frozen;
  RegisterMap map = load_register_map(kSrc + "/hw/examples/register_map_emulator.yaml");
  std::unique_ptr<DriveEmulator> emu;
  int port = 0;

  // An emulator stepped by emulator_period (not stepped: its plant on the frozen clock).
  explicit LockStep(double emulator_period = kPeriod, bool stepped = true) {
    EmulatorOptions o;
    o.clock = &frozen;
    o.stepped = stepped;
    o.command_period_s = emulator_period;
    emu = std::make_unique<DriveEmulator>(
        map, twin_config_from_scenario(kSrc + "/tests/fixtures/twin_disc.yaml", emulator_period), o);
    port = emu->start();
    map.port = port;
  }
  // A stepped client of it at kPeriod.
  std::unique_ptr<DriveBackend> client() {
    return std::make_unique<DriveBackend>(map, std::make_unique<ModbusTransport>("127.0.0.1", port, 0.5, frozen),
                                          kPeriod, frozen, DriveTiming::kStepped);
  }
  // The drives' time of the last latch (us), read by another client (a read latches nothing).
  std::uint32_t latch_us() {
    ModbusTransport t("127.0.0.1", port, 0.5, frozen);
    t.connect();
    std::uint16_t r[2] = {};
    t.read(map.latch->unit_id, map.latch->time_address, 2, r);
    return static_cast<std::uint32_t>(join32(r, map.word_order));
  }
};

// N client cycles advance the emulator's plant and its latch time by exactly
// N periods, whatever the wall time they took (the clocks never moved); each
// reading's time is the drives' latch time in the client's time base.
TEST(DriveEmulator, SteppedAdvancesThePlantOnePeriodPerClientCycle) {
  LockStep ls;
  auto drives = ls.client();
  EXPECT_TRUE(drives->simulated_time());
  drives->configure();
  drives->activate();
  EXPECT_EQ(ls.emu->power_on(), (std::array<bool, 3>{true, true, true}));
  const double plant0 = ls.emu->snapshot().time_s;
  const std::uint32_t us0 = ls.latch_us();
  HardwareCommand hold;
  hold.mode = {JointMode::kPosition, JointMode::kPosition, JointMode::kPosition};
  hold.theta_m = drives->last_state().theta_m;
  const int n = 120;
  for (int k = 1; k <= n; ++k) {
    const double t = k * kPeriod;
    const HardwareState& st = drives->read(t);
    const std::uint32_t us = ls.latch_us();
    EXPECT_EQ(us - us0, static_cast<std::uint32_t>(k * 4000)) << k;  // the drives' time: k periods on
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(st.read_time_s[i], (us - us0) * 1e-6, 1e-12) << k;
    drives->write(hold, t);
  }
  EXPECT_NEAR(ls.emu->snapshot().time_s - plant0, n * kPeriod, 1e-9);
  EXPECT_EQ(ls.latch_us() - us0, static_cast<std::uint32_t>(n * 4000));
  EXPECT_EQ(ls.frozen.now(), 0.0);
  EXPECT_EQ(ls.emu->power_on(), (std::array<bool, 3>{true, true, true}));
  drives->shutdown();
  EXPECT_EQ(ls.emu->error(), "");
}

// A stepped client refuses, before enabling anything, drives that are not
// stepped by it: an emulator on its own clock (its latch time does not move
// between two cycles here) or one stepped at another period.
TEST(DriveEmulator, ASteppedClientRefusesDrivesNotSteppedAtItsRate) {
  for (const auto& [period, stepped, step_ms] :
       {std::tuple{kPeriod, false, "0.000"}, std::tuple{0.001, true, "1.000"}}) {
    LockStep ls(period, stepped);
    auto drives = ls.client();
    try {
      drives->configure();
      ADD_FAILURE() << "configured drives not stepped at the client's period";
    } catch (const HardwareError& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find(fmt::format("latch time advanced by {} ms in one cycle", step_ms)), std::string::npos) << m;
      EXPECT_NE(m.find("one period (4.000 ms)"), std::string::npos) << m;
      EXPECT_NE(m.find("--stepped --command-period 0.004"), std::string::npos) << m;
      EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    }
    EXPECT_EQ(drives->state(), LifecycleState::kError);
    EXPECT_EQ(ls.emu->power_on(), (std::array<bool, 3>{false, false, false}));
  }
  // A map whose latch has no time cannot be stepped.
  RegisterMap no_time = load_register_map(kSrc + "/hw/examples/register_map_emulator.yaml");
  no_time.latch->time_address = -1;
  EXPECT_THROW(DriveBackend(no_time, std::make_unique<ModbusTransport>("127.0.0.1", 1, 0.5), kPeriod,
                            steady_clock(), DriveTiming::kStepped),
               InputError);
}

// A client that never reads does not stall a stepped emulator either: the
// stepped client beside it runs its cycles, each one period of the plant.
TEST(DriveEmulator, AClientThatNeverReadsDoesNotStallTheSteppedClient) {
  LockStep ls;
  const int fd = flood_without_reading(ls.port);
  auto drives = ls.client();
  drives->configure();
  drives->activate();
  const std::uint32_t us0 = ls.latch_us();
  HardwareCommand hold;
  hold.mode = {JointMode::kPosition, JointMode::kPosition, JointMode::kPosition};
  hold.theta_m = drives->last_state().theta_m;
  for (int k = 1; k <= 20; ++k) {
    drives->read(k * kPeriod);
    drives->write(hold, k * kPeriod);
  }
  EXPECT_EQ(ls.latch_us() - us0, 20u * 4000u);
  EXPECT_EQ(ls.emu->error(), "");
  ::close(fd);
}

// Lock step is the twin backend over Modbus: the same commands (on the
// register map's count grid) give the readings of the twin backend in
// process cycle for cycle, within the register map's rounding (half a
// count; the torques: half a 0.01 N m step).
TEST(DriveEmulator, SteppedReadingsAreTheTwinBackendsForTheSameCommands) {
  LockStep ls;
  auto drives = ls.client();
  TwinBackend twin(twin_config_from_scenario(kSrc + "/tests/fixtures/twin_disc.yaml", kPeriod));
  drives->configure();
  twin.configure();
  drives->activate();  // one cycle: the power stages come on holding
  twin.activate();
  twin.read(kPeriod);
  Eigen::Vector3d c0;
  for (int i = 0; i < 3; ++i) c0[i] = theta_to_counts(ls.map.axes[i], drives->last_state().theta_m[i]);
  const double count = 2 * M_PI / static_cast<double>(ls.map.axes[0].counts_per_rev);
  double worst = 0.0, worst_torque = 0.0, moved = 0.0;
  for (int k = 0; k < 200; ++k) {
    const double t = (k + 2) * kPeriod;
    const HardwareState& a = drives->read(t);
    const HardwareState& b = twin.read(t);
    for (int i = 0; i < 3; ++i) {
      worst = std::max(worst, std::abs(wrap_pi(a.theta_m[i] - b.theta_m[i])));
      worst_torque = std::max(worst_torque, std::abs(a.torque[i] - b.torque[i]));
    }
    moved = std::max(moved, std::abs(wrap_pi(b.theta_m[1] - counts_to_theta(ls.map.axes[1], c0[1]))));
    // Joint 2 ramps by 2 counts a cycle for 100 cycles, then holds.
    HardwareCommand cmd;
    cmd.mode = {JointMode::kPosition, JointMode::kPosition, JointMode::kPosition};
    for (int i = 0; i < 3; ++i)
      cmd.theta_m[i] = counts_to_theta(ls.map.axes[i], static_cast<std::int64_t>(c0[i]) + (i == 1 ? 2 * std::min(k, 100) : 0));
    drives->write(cmd, t);
    twin.write(cmd, t);
  }
  std::printf("stepped emulator vs twin backend: readings %.3g counts, torques %.3g N m apart; joint 2 moved %.0f counts\n",
              worst / count, worst_torque, moved / count);
  EXPECT_GT(moved / count, 50.0);  // the robot moved (joint 2 against the two others: a servo fight)
  EXPECT_LE(worst, 0.5 * count + 1e-12);
  EXPECT_LE(worst_torque, 0.005 + 1e-9);
}

// A path sampled on the fly (hw/procedures/trajectory_session.cpp) through
// Modbus in lock step and through the twin backend in process, same hardware
// limits and twin: the same session time (the plan's, not the wall's), the
// same sample times, each sample's read times its cycle's, and readings
// within a count (the setpoints go to the drives in 17-bit counts).
TEST(DriveEmulator, ASessionOnTheFlyInLockStepTakesTheTwinBackendsTimeAndSamples) {
  test::TempDir dir("emu_lockstep_session");
  const std::string head = "rate_hz: 250\ncontroller: " + kSrc + "/models/gpm2002.yaml\n";
  test::write_text(dir / "twin.yaml", "backend: twin\n" + head + "twin: {scenario: " + kSrc +
                                          "/tests/fixtures/twin_disc.yaml}\n" + test::kSafetyYaml);
  LockStep ls;
  test::write_text(dir / "map.yaml", register_map_to_yaml(ls.map));
  test::write_text(dir / "modbus.yaml", "backend: modbus\n" + head + "modbus: {register_map: " +
                                            (dir / "map.yaml").string() + ", timing: stepped}\n" +
                                            test::kSafetyYaml);
  TrajectoryPlan plan;
  sim::WaypointLimits lim;
  lim.max_speed_mm_s = 40;
  lim.max_accel_mm_s2 = 200;
  lim.max_normal_mm_s2 = 200;
  const Robot robot;
  plan.path = sim::excitation_path(robot.home, {{236.5, 260}, {206.5, 240}, {226.5, 230}}, lim);
  plan.settle = {0.01, 0.0, 1.0};
  SessionResult r[2];
  for (const char* name : {"twin", "modbus"}) {
    auto hw = make_hardware(load_hardware_config((dir / (std::string(name) + ".yaml")).string()), ls.frozen);
    SampleLog log((dir / (std::string(name) + ".csv")).string(), false, SampleColumns::kOnTheFly);
    r[name[0] == 'm'] = run_trajectory_session(*hw, plan, log, nullptr);
  }
  const Samples a = read_samples_csv((dir / "twin.csv").string());
  const Samples b = read_samples_csv((dir / "modbus.csv").string());
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(r[1].taken, trajectory_sample_count(plan, kPeriod));
  EXPECT_DOUBLE_EQ(r[1].duration_s, r[0].duration_s);
  const double count = 2 * M_PI / 131072;
  double worst = 0.0;
  for (std::size_t j = 0; j < a.size(); ++j) {
    EXPECT_DOUBLE_EQ(b.t[j], a.t[j]) << j;
    EXPECT_EQ(b.t_read[j], Eigen::Vector3d::Constant(b.t[j])) << j;  // the latch of the sample's cycle
    for (int i = 0; i < 3; ++i) worst = std::max(worst, std::abs(wrap_pi(b.theta_m[j][i] - a.theta_m[j][i])));
  }
  std::printf("lock step session: %zu samples, %.3f s of robot time each, readings %.3f counts apart at most\n",
              a.size(), r[1].duration_s, worst / count);
  EXPECT_LE(worst, count + 1e-12);
  EXPECT_EQ(ls.frozen.now(), 0.0);
  EXPECT_EQ(ls.emu->error(), "");
}

}  // namespace
}  // namespace gpm::hw
