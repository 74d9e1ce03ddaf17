// Tests of models/yaml_util.cpp: strict numbers, key checks, exact formatting.
#include "models/yaml_util.hpp"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "models/errors.hpp"

namespace gpm {
namespace {

std::string error_of(auto&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(YamlUtil, NumbersStrict) {
  const YAML::Node n = load_yaml_string("a: 1.5\nb: abc\nc: .nan\nd: +2\ne: 1e400\n", "f.yaml");
  EXPECT_EQ(yaml_number(n["a"], "f.yaml", "a"), 1.5);
  EXPECT_EQ(yaml_number(n["d"], "f.yaml", "d"), 2.0);
  EXPECT_EQ(error_of([&] { yaml_number(n["b"], "f.yaml", "b"); }), "f.yaml:2: b: 'abc' is not a number");
  EXPECT_NE(error_of([&] { yaml_number(n["c"], "f.yaml", "c"); }).find("finite"), std::string::npos);
  EXPECT_NE(error_of([&] { yaml_number(n["e"], "f.yaml", "e"); }).find("e:"), std::string::npos);
}

TEST(YamlUtil, UnknownKeySuggestsNearest) {
  const YAML::Node n = load_yaml_string("nmae: x\n", "r.yaml");
  EXPECT_EQ(error_of([&] { yaml_check_keys(n, "r.yaml", "", {"name", "geometry"}); }),
            "r.yaml:1: nmae: unknown key (did you mean name?); valid keys: name, geometry");
}

TEST(YamlUtil, SyntaxErrorNamesLine) {
  EXPECT_NE(error_of([] { load_yaml_string("a: [1, 2\nb: 3\n", "s.yaml"); }).find("s.yaml:"),
            std::string::npos);
  EXPECT_NE(error_of([] { load_yaml_file("/nonexistent/x.yaml"); }).find("cannot open"),
            std::string::npos);
}

TEST(YamlUtil, DuplicateKeysRefusedWithBothLines) {
  // A second, tighter safety block appended to a file (issue 14.5).
  EXPECT_EQ(error_of([] {
              load_yaml_string("name: a\nsafety:\n  max_velocity: 2\nother: 1\nsafety:\n  max_velocity: 1\n",
                               "hw.yaml");
            }),
            "hw.yaml:5: safety: duplicate key (first at line 2, again at line 5); a key may appear "
            "once in a map: keep one of the two");
  // Nested, the key path names the map; in a list item, the index.
  EXPECT_EQ(error_of([] { load_yaml_string("geometry:\n  xa1: 0\n  ya1: 1\n  xa1: 2\n", "r.yaml"); }),
            "r.yaml:4: geometry.xa1: duplicate key (first at line 2, again at line 4); a key may "
            "appear once in a map: keep one of the two");
  EXPECT_NE(error_of([] { load_yaml_string("poses:\n  - {x: 1, y: 2}\n  - {x: 1, x: 2}\n", "p.yaml"); })
                .find("p.yaml:3: poses[1].x: duplicate key (first at line 3"),
            std::string::npos);
  // The same key in different maps, in sequences, under aliases: all fine.
  const YAML::Node n = load_yaml_string(
      "a: &A {x: 1, y: 2}\nb: *A\nc:\n  x: 1\n  d: {x: 3}\nl: [{x: 1}, {x: 2}]\n", "ok.yaml");
  EXPECT_EQ(n["c"]["d"]["x"].as<int>(), 3);
  EXPECT_EQ(n["b"]["y"].as<int>(), 2);
  // A map used as a key does not confuse the path of the keys after it.
  EXPECT_NE(error_of([] { load_yaml_string("? {k: 1}\n: v\nz: 1\nz: 2\n", "c.yaml"); }).find("c.yaml:4: z:"),
            std::string::npos);
}

TEST(YamlUtil, FormatExactRoundTripsRandomDoubles) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1e3, 1e3);
  for (int k = 0; k < 20000; ++k) {
    const double x = u(rng) * std::pow(10.0, static_cast<int>(rng() % 20) - 10);
    const YAML::Node n = load_yaml_string("v: " + format_exact(x), "t");
    EXPECT_EQ(yaml_number(n["v"], "t", "v"), x);
  }
}

TEST(YamlUtil, PrintableUtf8) {
  EXPECT_TRUE(is_printable_utf8("GPM2002 #3: caf\xc3\xa9 \xe2\x82\xac"));
  EXPECT_FALSE(is_printable_utf8("a\x10" "b"));       // control character (found by fuzzing)
  EXPECT_FALSE(is_printable_utf8("\xff\xff"));        // not UTF-8
  EXPECT_FALSE(is_printable_utf8("\xc0\xaf"));        // overlong
  EXPECT_FALSE(is_printable_utf8("\xe2\x82"));        // truncated
  EXPECT_FALSE(is_printable_utf8("\xed\xa0\x80"));   // surrogate
  const YAML::Node n = load_yaml_string("name: \"x\\ty\"\n", "t");
  EXPECT_NE(error_of([&] { yaml_text(n["name"], "t", "name"); }).find("printable"), std::string::npos);
}

TEST(YamlUtil, IntegersAndBools) {
  const YAML::Node n = load_yaml_string("i: 17\nf: 1.5\nb: true\n", "t");
  EXPECT_EQ(yaml_integer(n["i"], "t", "i", 1, 32), 17);
  EXPECT_NE(error_of([&] { yaml_integer(n["f"], "t", "f", 1, 32); }).find("whole number"), std::string::npos);
  EXPECT_TRUE(yaml_bool(n["b"], "t", "b"));
}

}  // namespace
}  // namespace gpm
