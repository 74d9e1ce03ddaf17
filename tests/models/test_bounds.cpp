// Tests of models/bounds.cpp: the documented ranges of user numbers (issue 36.1,
// 36.8, 36.12) and the bounded reading of input files.
#include "models/bounds.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>

#include <gtest/gtest.h>

#include "models/errors.hpp"

namespace gpm {
namespace {

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(Bounds, DescribeNamesTheRangeAsAReaderWritesIt) {
  EXPECT_EQ(describe(limits::kEvaluations), "a whole number from 1 to 1e10 evaluations");
  EXPECT_EQ(describe(limits::kEncoderSigma), "a number from 1e-12 to 1 rad");
  EXPECT_EQ(describe(limits::kSeed), "a whole number from 0 to 9007199254740992");
  EXPECT_EQ(describe(limits::kStudyPoses), "a whole number from 12 to 2000 poses");
}

TEST(Bounds, WithinChecksRangeWholenessAndFiniteness) {
  EXPECT_TRUE(within(1, limits::kEvaluations));
  EXPECT_TRUE(within(1e10, limits::kEvaluations));
  EXPECT_FALSE(within(1e19, limits::kEvaluations));
  EXPECT_FALSE(within(0, limits::kEvaluations));
  EXPECT_FALSE(within(2.5, limits::kEvaluations));
  EXPECT_FALSE(within(std::nan(""), limits::kEncoderSigma));
  EXPECT_FALSE(within(1e-300, limits::kEncoderSigma));
  EXPECT_TRUE(within(1e-5, limits::kEncoderSigma));
}

TEST(Bounds, ParseBoundedNamesWhereValueAndRange) {
  EXPECT_EQ(parse_bounded("1e6", limits::kEvaluations, "--budget"), 1e6);
  EXPECT_EQ(parse_bounded("+7", limits::kEvaluations, "--budget"), 7);
  EXPECT_EQ(error_of([] { parse_bounded("1e19", limits::kEvaluations, "--budget"); }),
            "--budget: must be a whole number from 1 to 1e10 evaluations, got '1e19'");
  EXPECT_EQ(error_of([] { parse_bounded("", limits::kSeed, "--seed"); }),
            "--seed: must be a whole number from 0 to 9007199254740992, got ''");
  EXPECT_EQ(error_of([] { parse_bounded("-1", limits::kSeed, "--seed"); }),
            "--seed: must be a whole number from 0 to 9007199254740992, got '-1'");
  EXPECT_NE(error_of([] { parse_bounded("12abc", limits::kSamples, "--n"); }), "");
  EXPECT_NE(error_of([] { parse_bounded("nan", limits::kEncoderSigma, "--sigma"); }), "");
  EXPECT_NE(error_of([] { parse_bounded("inf", limits::kEvaluations, "--budget"); }), "");
}

TEST(Bounds, YamlWithinNamesFileLineAndKey) {
  const YAML::Node n = YAML::Load("budget: 1e12");
  EXPECT_EQ(error_of([&] { yaml_within(n["budget"], "s.yaml", "calibration.budget", limits::kEvaluations); }),
            "s.yaml:1: calibration.budget: must be a whole number from 1 to 1e10 evaluations, got 1e12");
}

TEST(Bounds, ReadInputFileRefusesDevicesFifosAndOversizedInput) {
  EXPECT_NE(error_of([] { read_input_file("/dev/zero", 1024); }).find("/dev/zero: is a character device"),
            std::string::npos);
  EXPECT_NE(error_of([] { read_input_file("/dev/null", 1024); }).find("/dev/null: is a character device"),
            std::string::npos);
  EXPECT_NE(error_of([] { read_input_file("/", 1024); }).find("/: is a folder"), std::string::npos);
  EXPECT_NE(error_of([] { read_input_file("/nonexistent/x.yaml", 1024); }).find("cannot open"), std::string::npos);
  // A FIFO nobody writes: refused at once (open(2) without O_NONBLOCK waits for a writer forever).
  const std::string fifo = (std::filesystem::temp_directory_path() / ("gpm_bounds_fifo" + std::to_string(::getpid()))).string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string fifo_error = error_of([&] { read_input_file(fifo, 1024); });
  std::filesystem::remove(fifo);
  EXPECT_NE(fifo_error.find(": is a FIFO (named pipe), not a regular file"), std::string::npos) << fifo_error;
  // One byte over the limit is refused, the limit itself is read.
  const std::string big = (std::filesystem::temp_directory_path() / ("gpm_bounds_big" + std::to_string(::getpid()))).string();
  { std::ofstream(big) << std::string(1024, 'x'); }
  EXPECT_EQ(read_input_file(big, 1024).size(), 1024u);
  const std::string over = error_of([&] { read_input_file(big, 1023); });
  std::filesystem::remove(big);
  EXPECT_NE(over.find("larger than"), std::string::npos) << over;
}

}  // namespace
}  // namespace gpm
