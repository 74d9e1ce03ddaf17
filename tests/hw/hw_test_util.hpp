// Helpers shared by the hw tests: example safety limits, a recording backend
// that follows its commands exactly, temporary files.
#pragma once

#include <filesystem>
#include <memory>
#include <stdexcept>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "hw/clock.hpp"
#include "hw/hw_errors.hpp"
#include "hw/robot_hardware.hpp"
#include "hw/safety_limits.hpp"
#include "models/yaml_util.hpp"

namespace gpm::hw::test {

inline const std::string kSafetyYaml = R"(safety:
  joint_min: [0.3, 2.4, 4.0]
  joint_max: [1.9, 3.8, 5.7]
  max_velocity: [1.0, 1.0, 1.0]
  max_acceleration: [5.0, 5.0, 5.0]
  workspace_centre: [216.5, 250]
  workspace_radius: 90
  workspace_margin: 5
  reach_margin: 2
  min_transmission: 0.15
  min_direct: 0.15
  max_inconsistency: 0.05
  watchdog_hold: 0.1
  watchdog_disable: 0.5
  comms_timeout: 0.1
)";

// The example limits above.
inline SafetyLimits example_limits() {
  const YAML::Node n = load_yaml_string(kSafetyYaml, "test");
  return safety_limits_from_yaml(n["safety"], "test", "safety");
}

// A backend whose readings equal its last position command; records every command.
class RecordingBackend final : public RobotHardware {
 public:
  explicit RecordingBackend(const Eigen::Vector3d& start, double period = 0.004)
      : position_(start), period_(period) {}
  std::vector<HardwareCommand>* record = nullptr;  // where commands go (outlives this)
  bool fail_reads = false;
  bool frozen = false;  // readings never change: drives that do not move
  bool wall_clock = false;  // report real (not simulated) time
  double read_delay_s = 0.0;  // each read takes this long on clock
  ManualClock* clock = nullptr;
  // Reports torques (reads so far) x (1, 2, 3) N m, and each joint's reading
  // taken read_offset_s after the cycle's time (drives polled in turn).
  bool count_torque = false;
  Eigen::Vector3d read_offset_s = Eigen::Vector3d::Zero();

  double period_s() const override { return period_; }
  bool simulated_time() const override { return !wall_clock; }
  std::string describe() const override { return "recording"; }

 protected:
  void on_configure(HardwareState& s) override { s.theta_m = position_; }
  void on_activate(const HardwareState&) override { enabled_ = true; }
  void on_deactivate() override { enabled_ = false; }
  void on_shutdown() noexcept override { enabled_ = false; }
  void on_error() noexcept override { enabled_ = false; }
  void on_read(double t, HardwareState& s) override {
    if (fail_reads) throw HardwareError("recording: read failed");
    if (read_delay_s > 0 && clock) clock->advance(read_delay_s);
    s.time_s = t;
    s.theta_m = position_;
    for (auto& d : s.drive) d.enabled = enabled_;
    ++reads_;
    s.torque_reported = count_torque;
    if (count_torque) s.torque = static_cast<double>(reads_) * Eigen::Vector3d(1, 2, 3);
    s.read_time_s = Eigen::Vector3d::Constant(t) + read_offset_s;
  }
  void on_write(const HardwareCommand& c, double) override {
    if (record) record->push_back(c);
    for (int i = 0; i < 3; ++i)
      if (c.mode[i] == JointMode::kPosition && !frozen) position_[i] = c.theta_m[i];
  }

 private:
  Eigen::Vector3d position_;
  double period_;
  bool enabled_ = false;
  long reads_ = 0;
};

// A fresh empty temporary folder for one test, removed with everything in it
// when the object goes out of scope (tests leave no files behind, and a
// rerun in the same build starts from nothing).
class TempDir {
 public:
  explicit TempDir(const std::string& name) {
    std::string pattern = (std::filesystem::temp_directory_path() / ("gpm_hw_" + name + "_XXXXXX")).string();
    if (!::mkdtemp(pattern.data())) throw std::runtime_error("cannot create a temporary folder " + pattern);
    path_ = pattern;
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  operator const std::filesystem::path&() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

inline void write_text(const std::filesystem::path& p, const std::string& text) {
  std::ofstream(p) << text;
}

inline std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

}  // namespace gpm::hw::test
