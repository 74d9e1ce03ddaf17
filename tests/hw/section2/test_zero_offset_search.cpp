// Tests of hw/procedures/zero_offset_search.cpp (paper section 2.4 on the twin, through
// the safety supervisor): the 9-point grid converges from three different
// initial estimates to the twin's actual offsets; the direct fit of E gets
// there with far fewer motions; encoder noise does not move the result much
// (eq. 28); a search that leaves the safe workspace stops and says where;
// points and dwell outside their documented range are refused.
#include "hw/procedures/zero_offset_search.hpp"

#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "models/errors.hpp"
#include "zero_test_util.hpp"

namespace gpm::hw {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

double err(const ZeroSearchResult& r) { return (r.offsets - test::kActualOffsets).cwiseAbs().maxCoeff(); }

void print(const char* what, const ZeroSearchResult& r) {
  std::printf("%s: ok %d offsets %.6f %.6f %.6f (initial %.6f %.6f %.6f) err %.2e rad E %.3e "
              "motions %d circles %d robot %.1f s wall %.1f s%s%s\n",
              what, r.ok, r.offsets[0], r.offsets[1], r.offsets[2], r.initial_offsets[0],
              r.initial_offsets[1], r.initial_offsets[2], err(r), r.E, r.motions, r.circles,
              r.robot_time_s, r.wall_time_s, r.ok ? "" : " error: ", r.error.c_str());
}

// Three starts a few mm from O (jogged with the uncalibrated controller).
const Vector2d kStarts[3] = {{219.5, 252.5}, {213.0, 247.5}, {217.5, 245.0}};

// Tolerance: the grid stops at d = 0.125 mm; an O error of 0.125 mm diagonal
// moves the offsets by |J| * 0.18 mm, about 1e-3 rad at most on this robot.
constexpr double kGridTol = 1.2e-3;

TEST(ZeroOffsetSearch, PointsAndDwellOutsideTheirDocumentedRangeAreRefused) {
  // Issue 36.8: gpm zero --points 1e9 --dwell 1e9 were accepted (models/bounds.hpp).
  const auto message = [](const ZeroSearchOptions& o) {
    try {
      validate_zero_search_options(o);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  ZeroSearchOptions o;
  EXPECT_EQ(message(o), "accepted");
  o.circle_points = 1000000000;
  EXPECT_EQ(message(o), "zero-offset search: interpolation points per circle must be a whole number from 6 to 3600 points");
  o = ZeroSearchOptions{};
  o.circle_dwell_s = 1e9;
  EXPECT_EQ(message(o), "zero-offset search: the dwell at each interpolation point must be a number from 0 to 60 s");
}

TEST(ZeroOffsetSearch, GridConvergesFromThreeStartsToTheActualOffsets) {
  const test::TempDir dir("zero_grid");
  const auto hw = test::write_twin_hardware(dir, test::kActualOffsets, 17, 0.0);
  std::vector<Vector3d> found;
  for (const Vector2d& s : kStarts) {
    const ZeroSearchResult r = test::run_on_twin(hw, test::fast_options(s));
    print("grid", r);
    ASSERT_TRUE(r.ok) << r.error;
    // The start really was off: its step-2 offsets are wrong by more than the result's.
    EXPECT_GT((r.initial_offsets - test::kActualOffsets).cwiseAbs().maxCoeff(), 5e-3);
    EXPECT_LT(err(r), kGridTol);
    EXPECT_EQ(r.d_final_mm, 0.125);
    found.push_back(r.offsets);
  }
  for (int i = 1; i < 3; ++i) EXPECT_LT((found[i] - found[0]).cwiseAbs().maxCoeff(), 2 * kGridTol);
}

TEST(ZeroOffsetSearch, DirectFitIsMoreAccurateWithFewerMotions) {
  const test::TempDir dir("zero_direct");
  const auto hw = test::write_twin_hardware(dir, test::kActualOffsets, 17, 0.0);
  ZeroSearchOptions o = test::fast_options(kStarts[0]);
  o.method = ZeroMethod::kDirect;
  o.circle_radius_mm = 40.0;  // a larger circle conditions the 3-offset fit better
  const ZeroSearchResult d = test::run_on_twin(hw, o);
  print("direct", d);
  ASSERT_TRUE(d.ok) << d.error;
  // Quantisation (17 bits, 4.8e-5 rad a count) limits it (measured 2.2e-4 rad
  // here); with ideal encoders the same run ends within 3e-6 rad.
  EXPECT_LT(err(d), kGridTol / 2);
  EXPECT_LE(d.circles, 4);
  EXPECT_LE(d.motions, 12);
}

TEST(ZeroOffsetSearch, RobustToEncoderNoise) {
  // 5e-5 rad of Gaussian reading noise (about 1 count of a 17-bit encoder):
  // eq. 28 says E only gains the noise variance, so the minimum stays put.
  // The step-2 readings at R enter the offsets directly: average them longer.
  const test::TempDir dir("zero_noise");
  const auto hw = test::write_twin_hardware(dir, test::kActualOffsets, 17, 5e-5);
  ZeroSearchOptions g = test::fast_options(kStarts[1]);
  g.settle_velocity_rad_s = 0.01;  // the noisy speed readings rarely drop below 0.002 rad/s
  g.average_s = 0.2;
  g.circle_points = 48;
  const ZeroSearchResult r = test::run_on_twin(hw, g);
  print("grid noise", r);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_LT(err(r), 1.5 * kGridTol);
  ZeroSearchOptions o = g;
  o.method = ZeroMethod::kDirect;
  const ZeroSearchResult d = test::run_on_twin(hw, o);
  print("direct noise", d);
  ASSERT_TRUE(d.ok) << d.error;
  EXPECT_LT(err(d), 1.5 * kGridTol);
  // Stop and go: readings averaged at each interpolation point.
  o.circle_dwell_s = 0.1;
  const ZeroSearchResult s = test::run_on_twin(hw, o);
  print("direct noise dwell", s);
  ASSERT_TRUE(s.ok) << s.error;
  EXPECT_LT(err(s), 1.5 * kGridTol);
  EXPECT_EQ(s.trace.back().circle.size(), static_cast<size_t>(o.circle_points));
  EXPECT_GT(s.robot_time_s, d.robot_time_s);
}

TEST(ZeroOffsetSearch, StopsAndReportsWhenTheSearchLeavesTheSafeWorkspace) {
  // Workspace disc of 45 - 5 mm: the 30 mm circle fits about the start but not
  // about every candidate of the d = 4 mm pattern.
  const test::TempDir dir("zero_leave");
  const auto hw = test::write_twin_hardware(dir, test::kActualOffsets, 17, 0.0, 45.0);
  const HardwareConfig cfg = load_hardware_config(hw.string());
  auto sup = make_hardware(cfg);
  std::vector<ZeroCandidate> sunk;
  ZeroSearchOptions o = test::fast_options(kStarts[2]);
  o.circle_radius_mm = 30.0;
  ZeroSearchResult r;
  bool stopped = false;
  try {
    r = run_zero_offset_search(*sup, o, [&](const ZeroCandidate& z) { sunk.push_back(z); });
  } catch (const ZeroSearchStopped& e) {  // the procedure convention: a stop throws
    stopped = true;
    r = e.partial();
    EXPECT_EQ(std::string(e.what()), r.error);
    EXPECT_FALSE(e.interrupted());
  }
  print("leave", r);
  ASSERT_TRUE(stopped);
  ASSERT_FALSE(r.ok);
  EXPECT_NE(r.error.find("search point"), std::string::npos) << r.error;
  EXPECT_NE(r.error.find("outside the safe workspace"), std::string::npos) << r.error;
  EXPECT_NE(r.error.find("beyond 40.000 mm"), std::string::npos) << r.error;
  EXPECT_EQ(r.error.find("estimate 0 "), std::string::npos) << r.error;  // a later candidate
  EXPECT_EQ(sup->state(), LifecycleState::kFinalized);
  // The evaluations made before the stop are kept, and were handed out as they came.
  ASSERT_GE(r.trace.size(), 1u);
  EXPECT_EQ(sunk.size(), r.trace.size());
  EXPECT_EQ(sup->rejected_count(), 0);  // stopped before commanding the bad point
}

}  // namespace
}  // namespace gpm::hw
