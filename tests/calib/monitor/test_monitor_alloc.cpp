// Tests of calib/monitor/monitor.cpp: monitor_step() allocates nothing per
// cycle. This binary replaces the global operator new (and wraps malloc,
// calloc and realloc at link time, which catches Eigen's own allocator) with
// counting versions and runs 10,000 cycles after a warm-up, through an
// offset jump, its alarm and its explanation.
#include <atomic>
#include <cstdlib>
#include <new>
#include <vector>

#include <gtest/gtest.h>

#include "calib/monitor/monitor.hpp"
#include "tests/calib/monitor/circle_stream.hpp"

namespace {
std::atomic<long> g_allocations{0};
}  // namespace

void* operator new(std::size_t n) {
  ++g_allocations;
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t n) { return operator new(n); }
void* operator new(std::size_t n, std::align_val_t a) {
  ++g_allocations;
  if (void* p = std::aligned_alloc(static_cast<std::size_t>(a), (n + static_cast<std::size_t>(a) - 1) / static_cast<std::size_t>(a) * static_cast<std::size_t>(a))) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t n, std::align_val_t a) { return operator new(n, a); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }

extern "C" {
void* __real_malloc(std::size_t);
void* __real_calloc(std::size_t, std::size_t);
void* __real_realloc(void*, std::size_t);
void* __wrap_malloc(std::size_t n) { ++g_allocations; return __real_malloc(n); }
void* __wrap_calloc(std::size_t n, std::size_t m) { ++g_allocations; return __real_calloc(n, m); }
void* __wrap_realloc(void* p, std::size_t n) { ++g_allocations; return __real_realloc(p, n); }
}

namespace gpm::calib::monitor {
namespace {

TEST(MonitorAlloc, TenThousandCyclesAllocateNothing) {
  const MonitorModel m = make_monitor_model(MonitorSettings{});
  MonitorData* d = new MonitorData(make_monitor_data(m));
  testing::CircleStream cs;
  const Geometry base = m.settings.geometry;
  // Readings first (the stream is not under test): warm-up 0..5 s, then
  // 10,000 cycles from 5 s (the end of the learning phase at 8 s among
  // them) with a jump of dth2 at 11 s.
  ASSERT_EQ(m.settings.learning_s, 8.0);
  const int warm = 5000, counted = 10000;
  std::vector<Eigen::Vector3d> readings(warm + counted);
  for (int c = 0; c < warm + counted; ++c) {
    Geometry g = base;
    if (c >= 11000) g[kDth2] += 1e-4;
    readings[static_cast<size_t>(c)] = cs.readings(g, c / 1000.0);
  }
  for (int c = 0; c < warm; ++c) monitor_step(m, *d, c / 1000.0, readings[static_cast<size_t>(c)]);
  long alarms = 0, explained = 0, accepted = 0;
  const long before = g_allocations.load();
  for (int c = warm; c < warm + counted; ++c) {
    const StepResult r = monitor_step(m, *d, c / 1000.0, readings[static_cast<size_t>(c)]);
    alarms += r.alarm;
    explained += r.explained;
    accepted += r.accepted;
  }
  const long during = g_allocations.load() - before;
  EXPECT_EQ(during, 0);
  // The counted cycles did the expensive paths too.
  EXPECT_GT(accepted, 1000);
  EXPECT_GE(alarms, 1);
  EXPECT_GE(explained, 1);
  // The counter works: an allocation outside the loop is seen.
  const long mark = g_allocations.load();
  std::vector<double>* v = new std::vector<double>(100);
  EXPECT_GE(g_allocations.load() - mark, 2);
  delete v;
  const long mark2 = g_allocations.load();
  void* volatile p = std::malloc(64);  // as Eigen's aligned_malloc does (volatile: not elided)
  EXPECT_EQ(g_allocations.load() - mark2, 1);
  std::free(p);
  delete d;
}

// The same with the reading model of a real drive (motion corrections,
// cyclic-error and clearance coordinates, forward kinematics per sample).
TEST(MonitorAlloc, ReadingModelAllocatesNothing) {
  MonitorSettings s;
  s.reading.skew_s = {0.0, 5e-5, 1e-4};
  s.reading.compliance_rad_per_Nm = {1e-4, 1e-4, 1e-4};
  s.reading.load.coulomb_Nm = {0.3, 0.3, 0.3};
  s.reading.cyclic_rad = {2e-5, 2e-5, 2e-5};
  s.reading.clearance_mm = {0.01, 0.01, 0.01};
  const MonitorModel m = make_monitor_model(s);
  MonitorData* d = new MonitorData(make_monitor_data(m));
  testing::CircleStream cs;
  const int n = 6000;
  std::vector<Eigen::Vector3d> readings(n);
  for (int c = 0; c < n; ++c) readings[static_cast<size_t>(c)] = cs.readings(s.geometry, c / 1000.0);
  const Eigen::Vector3d omega(0.3, -0.3, 0.3), tau(0.0, 1.0, -1.0);
  for (int c = 0; c < 2000; ++c) monitor_step(m, *d, c / 1000.0, readings[static_cast<size_t>(c)], omega, tau);
  long accepted = 0;
  const long before = g_allocations.load();
  for (int c = 2000; c < n; ++c)
    accepted += monitor_step(m, *d, c / 1000.0, readings[static_cast<size_t>(c)], omega, tau).accepted;
  EXPECT_EQ(g_allocations.load() - before, 0);
  EXPECT_GT(accepted, 300);
  delete d;
}

}  // namespace
}  // namespace gpm::calib::monitor
