// Tests of hw/backends/register_map.cpp: parsing, clear errors, count conversions.
#include <gtest/gtest.h>

#include "hw/backends/register_map.hpp"
#include "hw_test_util.hpp"
#include "models/errors.hpp"

namespace gpm::hw {
namespace {

const std::string kSrc = GPM_SOURCE_DIR;

std::string error_of(const std::string& text) {
  try {
    parse_register_map(text, "map.yaml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(RegisterMap, ExamplesLoadAndRoundTrip) {
  const RegisterMap m = load_register_map(kSrc + "/hw/examples/register_map_emulator.yaml");
  EXPECT_EQ(m.host, "127.0.0.1");
  EXPECT_EQ(m.axes[2].unit_id, 3);
  EXPECT_EQ(m.axes[0].actual_position, 12);
  EXPECT_EQ(m.axes[1].fault.bit, 3);
  ASSERT_TRUE(m.latch.has_value());
  EXPECT_EQ(m.latch->address, 30);
  EXPECT_EQ(m.axes[2].latched_position, 18);
  EXPECT_EQ(m.axes[2].latch_id, 20);
  EXPECT_EQ(m.latch->time_address, 32);
  EXPECT_EQ(parse_register_map(register_map_to_yaml(m), "x"), m);
  EXPECT_NO_THROW(load_register_map(kSrc + "/hw/examples/register_map_example_drive.yaml"));
}

TEST(RegisterMap, RefusesHostNamesAndBadKeys) {
  std::string t = test::read_text(kSrc + "/hw/examples/register_map_emulator.yaml");
  std::string bad = t;
  bad.replace(bad.find("127.0.0.1"), 9, "drives.local");
  EXPECT_NE(error_of(bad).find("connection.host: 'drives.local' is not an IPv4 address"),
            std::string::npos)
      << error_of(bad);
  bad = t;
  bad.replace(bad.find("sign: 1"), 7, "sign: 0");
  EXPECT_NE(error_of(bad).find("axes[0].sign"), std::string::npos) << error_of(bad);
  bad = t;
  bad.replace(bad.find("position_command: 2 "), 20, "position_command: 11");
  EXPECT_NE(error_of(bad).find("overlap"), std::string::npos) << error_of(bad);
  bad = t;
  bad.replace(bad.find("    counts_per_rev: 131072\n"), 27, "");
  EXPECT_NE(error_of(bad).find("missing key 'counts_per_rev'"), std::string::npos) << error_of(bad);
}

TEST(RegisterMap, CountsConversions) {
  AxisRegisters a;
  a.counts_per_rev = 131072;
  a.sign = -1;
  a.offset_counts = 1000;
  for (double th : {0.0, 1.0, 3.0, 4.8, 6.2}) {
    const std::int32_t c = theta_to_counts(a, th);
    EXPECT_NEAR(counts_to_theta(a, c), th, 2 * M_PI / 131072 / 2 + 1e-12);
  }
  for (WordOrder o : {WordOrder::kHighFirst, WordOrder::kLowFirst}) {
    for (std::int32_t v : {0, 1, -1, 123456789, -2147483647 - 1}) {
      const auto r = split32(v, o);
      EXPECT_EQ(join32(r.data(), o), v);
    }
  }
  EXPECT_EQ(split32(0x12345678, WordOrder::kHighFirst)[0], 0x1234);
  EXPECT_EQ(split32(0x12345678, WordOrder::kLowFirst)[0], 0x5678);
}

// Addresses that are not one drive, and axes that would share registers, are
// refused (all were once accepted).
TEST(RegisterMap, BroadcastAddressesAndSharedRegistersAreRefused) {
  const std::string text = test::read_text(kSrc + "/hw/examples/register_map_emulator.yaml");
  auto replaced = [&](const std::string& from, const std::string& to, size_t nth = 0) {
    std::string t = text;
    size_t a = t.find(from);
    for (size_t k = 0; k < nth; ++k) a = t.find(from, a + 1);
    return t.replace(a, from.size(), to);
  };
  EXPECT_EQ(error_of(text), "");
  for (const char* host : {"0.0.0.0", "255.255.255.255", "224.0.0.1", "239.1.2.3"}) {
    const std::string e = error_of(replaced("host: 127.0.0.1", std::string("host: ") + host));
    EXPECT_NE(e.find("not one machine"), std::string::npos) << host << ": " << e;
  }
  EXPECT_EQ(error_of(replaced("host: 127.0.0.1", "host: 192.168.10.11")), "");
  const std::string unit0 = error_of(replaced("unit_id: 2", "unit_id: 0"));
  EXPECT_NE(unit0.find("broadcast"), std::string::npos) << unit0;
  // Axis 2 on unit 1 with the same registers as axis 1.
  const std::string shared = error_of(replaced("unit_id: 2", "unit_id: 1"));
  EXPECT_NE(shared.find("shares unit_id 1 and register"), std::string::npos) << shared;
  EXPECT_NE(shared.find("axes[0]"), std::string::npos) << shared;
}

// A latch needs its trigger and, on every axis, the latched position and its
// id; a trigger register already used on that unit is refused.
TEST(RegisterMap, LatchNeedsAllItsPartsAndItsOwnRegister) {
  const std::string text = test::read_text(kSrc + "/hw/examples/register_map_emulator.yaml");
  std::string no_trigger = text;
  const size_t at = no_trigger.find("latch: {unit_id: 1, register: 30");
  no_trigger.erase(at, no_trigger.find('\n', at) - at);
  EXPECT_NE(error_of(no_trigger).find("latch"), std::string::npos) << error_of(no_trigger);
  std::string one_axis_missing = text;
  one_axis_missing.erase(one_axis_missing.rfind("    latch_id: 20"), 16);
  EXPECT_NE(error_of(one_axis_missing).find("axes[2]"), std::string::npos) << error_of(one_axis_missing);
  std::string taken = text;
  taken.replace(taken.find("register: 30, time"), 12, "register: 12");
  EXPECT_NE(error_of(taken).find("latch.register"), std::string::npos) << error_of(taken);
  EXPECT_EQ(error_of(text), "");
}

// The latch's time (two registers on the latch's unit) is optional; registers
// of an axis on that unit, or of the trigger itself, are refused.
TEST(RegisterMap, LatchTimeIsOptionalAndHasItsOwnRegisters) {
  const std::string text = test::read_text(kSrc + "/hw/examples/register_map_emulator.yaml");
  auto with_latch = [&](const std::string& latch) {
    std::string t = text;
    const size_t at = t.find("latch: {unit_id: 1, register: 30");
    return t.replace(at, t.find('\n', at) - at, latch);
  };
  const RegisterMap no_time = parse_register_map(with_latch("latch: {unit_id: 1, register: 30}"), "map.yaml");
  EXPECT_EQ(no_time.latch->time_address, -1);
  EXPECT_EQ(parse_register_map(register_map_to_yaml(no_time), "x"), no_time);
  const RegisterMap unit2 = parse_register_map(with_latch("latch: {unit_id: 2, register: 30, time: 40}"), "map.yaml");
  EXPECT_EQ(unit2.latch->time_address, 40);
  EXPECT_EQ(parse_register_map(register_map_to_yaml(unit2), "x"), unit2);
  for (const char* bad : {"latch: {unit_id: 1, register: 30, time: 29}",   // overlaps the trigger
                          "latch: {unit_id: 1, register: 30, time: 30}",
                          "latch: {unit_id: 1, register: 30, time: 11}",   // axis 1's fault code and position
                          "latch: {unit_id: 1, register: 30, time: 20}"}) {  // axis 1's latch id
    const std::string e = error_of(with_latch(bad));
    EXPECT_NE(e.find("latch.time"), std::string::npos) << bad << ": " << e;
  }
  EXPECT_NE(error_of(with_latch("latch: {unit_id: 1, register: 30, time: -1}")).find("latch.time"),
            std::string::npos);
}

}  // namespace
}  // namespace gpm::hw
