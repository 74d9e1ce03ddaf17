// Tests of models/measured_data.cpp, the measured-data guard: a hardware
// session marks and locks its folder; no other writer (OutputFolder,
// OutputFile) touches it; only a session of the same kind continues it, one
// at a time; a session that records nothing leaves nothing behind.
#include "models/measured_data.hpp"

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <unistd.h>

#include <gtest/gtest.h>

#include "models/errors.hpp"
#include "models/output_file.hpp"
#include "temp_files.hpp"

namespace gpm {
namespace {

namespace fs = std::filesystem;

using test::put;
using test::slurp;
using test::TempDir;

// The InputError message of f (empty when it does not throw one).
template <class F>
std::string refusal(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return {};
}

constexpr const char* kKind = "gpm run --hardware";

TEST(MeasuredFolder, NothingRecordedLeavesNothing) {
  const TempDir d("nothing");
  {
    const MeasuredFolder m(d / "run", kKind, "samples.csv");
    EXPECT_TRUE(fs::exists(d / "run/.gpm-measured"));
    EXPECT_EQ(m.samples_path(), d / "run/samples.csv");
  }
  EXPECT_FALSE(fs::exists(d / "run"));  // made here, removed again
  {
    const MeasuredFolder m(d.path.string(), kKind, "samples.csv");
  }
  EXPECT_TRUE(fs::is_empty(d.path));  // an existing folder stays, without the marker
}

TEST(MeasuredFolder, OnlyItsSessionWritesTheFolder) {
  const TempDir d("guard");
  const std::string dir = d / "run";
  {
    const MeasuredFolder m(dir, kKind, "samples.csv");
    put(m.samples_path(), "sample,theta_m1,theta_m2,theta_m3,target_x,target_y\n0,1,3,5,216.5,250\n");
    // While the session runs: its lock refuses every other writer and session.
    EXPECT_NE(refusal([&] { OutputFolder out(dir); }).find("is recording into this folder now"), std::string::npos);
    EXPECT_NE(refusal([&] { MeasuredFolder again(dir, kKind, "samples.csv"); }).find("another hardware session"),
              std::string::npos);
    // The session itself writes its outputs.
    OutputFolder out(dir, {}, &m);
    out.add("summary.json", "{}");
    out.commit();
  }
  EXPECT_TRUE(fs::exists(dir + "/.gpm-measured"));  // samples were recorded: the marker stays
  const std::string held = refusal([&] { OutputFolder out(dir); });
  EXPECT_NE(held.find("holds the measured samples of a gpm run --hardware session"), std::string::npos) << held;
  EXPECT_EQ(held.find('\n'), std::string::npos);
  EXPECT_NE(refusal([&] { check_output_folder(dir, {"samples.csv"}); }).find("holds the measured samples"),
            std::string::npos);
  EXPECT_NE(refusal([&] { write_output_file(dir + "/samples.csv", "replaced"); }).find("is the measured samples file"),
            std::string::npos);
  EXPECT_NE(refusal([&] { refuse_measured_file(dir + "/./samples.csv"); }), "");
  EXPECT_EQ(refusal([&] { refuse_measured_file(dir + "/notes.txt"); }), "");  // other files are not measured
  EXPECT_EQ(slurp(dir + "/samples.csv"), "sample,theta_m1,theta_m2,theta_m3,target_x,target_y\n0,1,3,5,216.5,250\n");
  // The same kind of session continues it (a --resume); another kind does not.
  EXPECT_NO_THROW(MeasuredFolder(dir, kKind, "samples.csv"));
  EXPECT_NE(refusal([&] { MeasuredFolder other(dir, "gpm zero", "samples.csv"); }).find("does not continue it"),
            std::string::npos);
  EXPECT_TRUE(fs::exists(dir + "/samples.csv"));
}

TEST(MeasuredFolder, AMarkerThatGuardsNothingIsRemoved) {
  const TempDir d("stale");
  put(d / ".gpm-measured", "kind: gpm run --hardware\nsamples: samples.csv\n");  // a session killed before sampling
  EXPECT_NO_THROW(check_output_folder(d.path.string(), {"samples.csv"}));
  EXPECT_FALSE(fs::exists(d / ".gpm-measured"));
}

TEST(MeasuredFolder, SamplesNoSessionRecordedAreNotContinued) {
  const TempDir d("unmarked");
  put(d / "samples.csv", "sample,theta_m1,theta_m2,theta_m3,x,y\n0,1,3,5,216.5,250\n");  // e.g. gpm simulate's
  const std::string why = refusal([&] { MeasuredFolder m(d.path.string(), kKind, "samples.csv"); });
  EXPECT_NE(why.find("no hardware session recorded it"), std::string::npos) << why;
  EXPECT_FALSE(fs::exists(d / ".gpm-measured"));
  put(d / "file", "x");
  EXPECT_NE(refusal([&] { MeasuredFolder m(d / "file", kKind, "samples.csv"); }).find("is not a folder"),
            std::string::npos);
}

// A sampling log (gpm sample -o FILE, anywhere) is known by its first line:
// once it holds a row no output replaces it (a file, a folder's file, before
// any work), only a sampling session continues it; a header alone, another
// CSV and a link to a log are told apart.
TEST(SamplingLog, NoOutputReplacesALogHoldingSamples) {
  const TempDir d("log");
  const std::string log = d / "samples.csv", text = std::string(kSamplingLogHeader) + "\n0,1,3,5,216.5,250\n";
  put(log, text);
  EXPECT_TRUE(is_sampling_log(log));
  const std::string why = refusal([&] { write_output_file(log, "x"); });
  EXPECT_NE(why.find("holds measured samples (a hardware sampling log"), std::string::npos) << why;
  EXPECT_NE(refusal([&] { check_output_folder(d.path.string(), {"samples.csv", "summary.json"}); }), "");
  EXPECT_NE(refusal([&] { OutputFolder f(d.path.string()); f.add("samples.csv", "x"); }), "");
  fs::create_symlink(log, d / "link.csv");
  EXPECT_NE(refusal([&] { write_output_file(d / "link.csv", "x"); }), "");
  EXPECT_EQ(refusal([&] { refuse_measured_file(log, nullptr, /*sampling_session=*/true); }), "");
  EXPECT_EQ(slurp(log), text);
  // Not measured: the header alone, a simulation's samples, a folder.
  put(d / "header.csv", std::string(kSamplingLogHeader) + "\n");
  put(d / "sim.csv", "sample,theta_m1,theta_m2,theta_m3,x,y\n0,1,3,5,216.5,250\n");
  EXPECT_FALSE(is_sampling_log(d / "header.csv"));
  EXPECT_FALSE(is_sampling_log(d / "sim.csv"));
  EXPECT_FALSE(is_sampling_log(d.path.string()));
  EXPECT_NO_THROW(write_output_file(d / "header.csv", "x"));
  EXPECT_NO_THROW(write_output_file(d / "sim.csv", "x"));
}

// A log of samples taken on the fly (its header continued by the torque and
// time columns) is measured data as well; a header with other columns is not.
TEST(SamplingLog, ALogOfSamplesOnTheFlyIsMeasuredDataToo) {
  const TempDir d("log_fly");
  const std::string head = std::string(kSamplingLogHeader) + kSamplingLogOnTheFlyColumns;
  const std::string log = d / "fly.csv", text = head + "\n0,1,3,5,216.5,250,0,0,0,0,0,0,0,0,0,0,0,0,0\n";
  put(log, text);
  EXPECT_TRUE(is_sampling_log(log));
  EXPECT_NE(refusal([&] { write_output_file(log, "x"); }), "");
  EXPECT_EQ(slurp(log), text);
  put(d / "other.csv", std::string(kSamplingLogHeader) + ",extra\n0,1,3,5,216.5,250,7\n");
  EXPECT_FALSE(is_sampling_log(d / "other.csv"));
  put(d / "fly_header.csv", head + "\n");
  EXPECT_FALSE(is_sampling_log(d / "fly_header.csv"));
}

}  // namespace
}  // namespace gpm
