// Backend `plugin`: a controller gpm does not know, driven through a shared
// library that implements the C plugin ABI of hw/plugin/gpm_backend_plugin.h
// (a motion card, an EtherCAT master, a vendor SDK). The library is loaded
// and its ABI and API versions checked when the backend is made; every
// call's code, reading and time is checked here, so a failing plugin gives a
// HardwareError with its own message, not a crash of gpm. make_hardware puts
// it behind the SafetySupervisor like every backend.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "hw/plugin/gpm_backend_plugin.h"
#include "hw/robot_hardware.hpp"

namespace gpm::hw {

// Settings of the plugin backend (constant): the hardware file's plugin section.
struct PluginBackendConfig {
  std::string library;                     // absolute path of the shared library
  std::optional<std::string> config_path;  // plugin.config naming a file (absolute)
  std::optional<std::string> config_text;  // plugin.config given as a map (YAML flow text)
  std::string base_dir;                    // folder of relative paths in the configuration
  std::string source;                      // where the section is ("hw.yaml"), for messages
  double period_s = 0.004;                 // read/write cycle period
};

class PluginBackend final : public RobotHardware {
 public:
  // Loads config.library, checks its versions and creates an instance from
  // the configuration (nothing is connected before configure()). Throws
  // InputError for a library that cannot be loaded, has no entry, is of
  // another ABI or API major version (one line naming the file and both
  // versions), or refuses its configuration (GPM_BACKEND_E_CONFIG);
  // HardwareError for a library that breaks the contract (no table, a null
  // function) or fails to create.
  explicit PluginBackend(PluginBackendConfig config);
  ~PluginBackend() override;

  // The plugin's name (its table's name).
  const std::string& name() const { return name_; }

  double period_s() const override { return config_.period_s; }
  bool simulated_time() const override;
  std::string describe() const override;

 protected:
  void on_configure(HardwareState& initial) override;
  void on_activate(const HardwareState& current) override;
  void on_deactivate() override;
  void on_shutdown() noexcept override;
  void on_error() noexcept override;
  void on_reset() override;
  void on_read(double time_s, HardwareState& state) override;
  void on_write(const HardwareCommand& command, double time_s) override;

 private:
  void create();
  void destroy() noexcept;
  std::string plugin_error(const gpm_backend* instance) const;
  // The code of the table call f (what: its name); HardwareError if an exception escapes it.
  template <class F> int call(const char* what, F&& f) const;
  // Calls f; HardwareError with the plugin's last_error unless it returns GPM_BACKEND_OK.
  template <class F> void check(const char* what, F&& f) const;
  // Calls f, ignoring any failure (disabling, shutting down).
  template <class F> static void quietly(F&& f) noexcept;
  void convert(const gpm_backend_state& in, double host_time_s, HardwareState& out);

  PluginBackendConfig config_;
  const gpm_backend_api* api_ = nullptr;  // the plugin's table (the library is never unloaded)
  std::string name_;
  gpm_backend* instance_ = nullptr;
  bool active_ = false;
  bool have_previous_ = false;
  HardwareState previous_;  // last converted reading (velocity by differences)
  gpm_backend_state last_raw_{};  // last reading as the plugin gave it (activate holds there)
};

}  // namespace gpm::hw
