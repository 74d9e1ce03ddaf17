#include "hw/backends/plugin_backend.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <filesystem>

#include <dlfcn.h>
#include <fmt/format.h>

#include "hw/hw_errors.hpp"
#include "hw/plugin/gpm_backend_plugin.h"
#include "models/errors.hpp"
#include "models/kinematics.hpp"

namespace gpm::hw {
namespace {

// The layout of ABI version 1 on a 64-bit host: a change of the header that
// moves a field must bump GPM_BACKEND_ABI_VERSION (and these numbers).
static_assert(GPM_BACKEND_ABI_VERSION == 1u);
static_assert(sizeof(void*) != 8 || sizeof(gpm_backend_api) == 96);
static_assert(sizeof(gpm_backend_state) == 168 && offsetof(gpm_backend_state, time_s) == 16 &&
              offsetof(gpm_backend_state, read_time_s) == 24 && offsetof(gpm_backend_state, theta_m) == 48 &&
              offsetof(gpm_backend_state, drive) == 120);
static_assert(sizeof(gpm_backend_command) == 40 && offsetof(gpm_backend_command, theta_m) == 16);
static_assert(sizeof(void*) != 8 || sizeof(gpm_backend_create_args) == 40);

// Bytes of a table that holds every function of API 1.0 (up to last_error).
constexpr std::size_t kTableSize = offsetof(gpm_backend_api, last_error) + sizeof(void*);

// Readings older than this (s) before the plugin's time of the reading are refused.
constexpr double kMaxReadAge = 1.0;

// Text of s on one line: control characters as spaces, at most 300 characters.
std::string one_line(const char* s) {
  if (!s) return "(no message)";
  std::string out;
  for (const char* p = s; *p && out.size() < 300; ++p) out += (static_cast<unsigned char>(*p) < 0x20) ? ' ' : *p;
  return out.empty() ? "(no message)" : out;
}

// Name of a return code of the ABI.
std::string code_name(int code) {
  switch (code) {
    case GPM_BACKEND_E_FAILED: return "failed";
    case GPM_BACKEND_E_CONFIG: return "bad configuration";
    case GPM_BACKEND_E_COMMS: return "no answer from the controller";
    case GPM_BACKEND_E_DRIVE_FAULT: return "drive fault";
    case GPM_BACKEND_E_STATE: return "not allowed in the plugin's state";
    case GPM_BACKEND_E_ARGUMENT: return "argument refused";
    default: return "unknown code";
  }
}

// The first null function of t (nullptr when every one is there).
const char* missing_function(const gpm_backend_api& t) {
  if (!t.create) return "create";
  if (!t.destroy) return "destroy";
  if (!t.configure) return "configure";
  if (!t.activate) return "activate";
  if (!t.deactivate) return "deactivate";
  if (!t.read) return "read";
  if (!t.write) return "write";
  if (!t.emergency_stop) return "emergency_stop";
  if (!t.last_error) return "last_error";
  return nullptr;
}

// Throws unless t is a complete table of this host's ABI and API major version.
void check_table(const gpm_backend_api* t, const std::string& file) {
  if (!t) {
    throw HardwareError(fmt::format("{}: backend plugin gave no table for ABI version {} (its entry returned NULL: "
                                    "it cannot serve this ABI, or failed to start)",
                                    file, GPM_BACKEND_ABI_VERSION));
  }
  if (t->abi_version != GPM_BACKEND_ABI_VERSION) {
    throw InputError(fmt::format("{}: backend plugin of ABI version {}, this gpm has ABI version {}: rebuild it "
                                 "against this gpm's hw/plugin/gpm_backend_plugin.h",
                                 file, t->abi_version, GPM_BACKEND_ABI_VERSION));
  }
  const unsigned major = t->api_version >> 16, minor = t->api_version & 0xffffu;
  if (major != GPM_BACKEND_API_VERSION_MAJOR) {
    throw InputError(fmt::format("{}: backend plugin of API version {}.{}, this gpm has API version {}.{} (the "
                                 "major versions must match): rebuild it against this gpm's "
                                 "hw/plugin/gpm_backend_plugin.h",
                                 file, major, minor, GPM_BACKEND_API_VERSION_MAJOR, GPM_BACKEND_API_VERSION_MINOR));
  }
  if (t->struct_size < kTableSize) {
    throw InputError(fmt::format("{}: backend plugin table of {} bytes, ABI version {} needs at least {}", file,
                                 t->struct_size, GPM_BACKEND_ABI_VERSION, kTableSize));
  }
  if (const char* f = missing_function(*t)) {
    throw HardwareError(fmt::format("{}: backend plugin has no function '{}' (a null pointer in its table)", file, f));
  }
}

// Loads file (kept loaded for the life of the process) and returns its checked table.
const gpm_backend_api* load_table(const std::string& file) {
  void* lib = ::dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL | RTLD_NODELETE);
  if (!lib) throw InputError(fmt::format("{}: cannot load the backend plugin: {}", file, one_line(::dlerror())));
  void* sym = ::dlsym(lib, GPM_BACKEND_PLUGIN_ENTRY_NAME);
  if (!sym) {
    ::dlclose(lib);
    throw InputError(fmt::format("{}: not a gpm backend plugin: it exports no function {} "
                                 "(hw/plugin/gpm_backend_plugin.h)",
                                 file, GPM_BACKEND_PLUGIN_ENTRY_NAME));
  }
  const auto entry = reinterpret_cast<gpm_backend_plugin_entry_fn>(sym);
  const gpm_backend_api* t = nullptr;
  try {
    t = entry(GPM_BACKEND_ABI_VERSION);
  } catch (...) {
    throw HardwareError(fmt::format("{}: {} let an exception escape", file, GPM_BACKEND_PLUGIN_ENTRY_NAME));
  }
  check_table(t, file);
  return t;
}

}  // namespace

PluginBackend::PluginBackend(PluginBackendConfig config) : config_(std::move(config)) {
  api_ = load_table(config_.library);
  name_ = api_->name && *api_->name ? one_line(api_->name) : std::filesystem::path(config_.library).stem().string();
  create();
}

PluginBackend::~PluginBackend() { on_shutdown(); }

bool PluginBackend::simulated_time() const { return (api_->flags & GPM_BACKEND_FLAG_SIMULATED_TIME) != 0; }

std::string PluginBackend::describe() const { return fmt::format("plugin {} ({})", name_, config_.library); }

std::string PluginBackend::plugin_error(const gpm_backend* instance) const {
  try {
    return one_line(api_->last_error(instance));
  } catch (...) {
    return "(last_error let an exception escape)";
  }
}

template <class F>
int PluginBackend::call(const char* what, F&& f) const {
  try {
    return f();
  } catch (...) {
    // Not allowed by the ABI; caught where the unwinding reaches here.
    throw HardwareError(fmt::format("plugin {}: {} let an exception escape (the plugin ABI allows none: catch "
                                    "everything inside)",
                                    name_, what));
  }
}

template <class F>
void PluginBackend::check(const char* what, F&& f) const {
  const int code = call(what, f);
  if (code == GPM_BACKEND_OK) return;
  throw HardwareError(fmt::format("plugin {}: {} failed ({}, code {}): {}", name_, what, code_name(code), code,
                                  plugin_error(instance_)));
}

template <class F>
void PluginBackend::quietly(F&& f) noexcept {
  try {
    f();
  } catch (...) {  // best effort: on the way to a stop or out
  }
}

void PluginBackend::create() {
  gpm_backend_create_args a{};
  a.struct_size = sizeof a;
  a.config_path = config_.config_path ? config_.config_path->c_str() : nullptr;
  a.config_text = config_.config_text ? config_.config_text->c_str() : nullptr;
  a.base_dir = config_.base_dir.c_str();
  a.period_s = config_.period_s;
  gpm_backend* out = nullptr;
  const int code = call("create", [&] { return api_->create(&a, &out); });
  if (code == GPM_BACKEND_E_CONFIG) {
    throw InputError(fmt::format("{}: plugin.config: backend plugin {} refused its configuration: {}", config_.source,
                                 name_, plugin_error(nullptr)));
  }
  if (code != GPM_BACKEND_OK) {
    throw HardwareError(fmt::format("plugin {}: create failed ({}, code {}): {}", name_, code_name(code), code,
                                    plugin_error(nullptr)));
  }
  if (!out) throw HardwareError(fmt::format("plugin {}: create returned success and no instance", name_));
  instance_ = out;
  active_ = false;
  have_previous_ = false;
}

void PluginBackend::destroy() noexcept {
  if (instance_) quietly([&] { api_->destroy(instance_); });
  instance_ = nullptr;
  active_ = false;
}

void PluginBackend::convert(const gpm_backend_state& in, double t, HardwareState& s) {
  if (!std::isfinite(in.time_s)) {
    throw HardwareError(fmt::format("plugin {}: the time of the reading is not a finite number ({})", name_, in.time_s));
  }
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(in.theta_m[i])) {
      throw HardwareError(fmt::format("plugin {}: axis {} reading is not a finite number ({})", name_, i + 1,
                                      in.theta_m[i]));
    }
    const double age = in.time_s - in.read_time_s[i];
    if (!(age >= -1e-6 && age <= kMaxReadAge)) {
      throw HardwareError(fmt::format("plugin {}: axis {} was read at {} s on the plugin's clock, the reading's time "
                                      "is {} s (valid: at most that time and no more than {} s before it)",
                                      name_, i + 1, in.read_time_s[i], in.time_s, kMaxReadAge));
    }
    if ((in.velocity_reported && !std::isfinite(in.velocity[i])) || (in.torque_reported && !std::isfinite(in.torque[i]))) {
      throw HardwareError(fmt::format("plugin {}: axis {} velocity or torque is not a finite number ({}, {})", name_,
                                      i + 1, in.velocity[i], in.torque[i]));
    }
    // The plugin's clock is its own: only how long before the reading's
    // time each axis was read carries over to the host's time t.
    s.read_time_s[i] = t - std::max(age, 0.0);
    s.theta_m[i] = in.theta_m[i];
    s.torque[i] = in.torque_reported ? in.torque[i] : 0.0;
    const double dt = s.read_time_s[i] - previous_.read_time_s[i];
    s.velocity[i] = in.velocity_reported ? in.velocity[i]
                    : have_previous_ && dt > 0 ? wrap_pi(in.theta_m[i] - previous_.theta_m[i]) / dt
                                                : 0.0;
    s.drive[i].enabled = in.drive[i].enabled != 0;
    s.drive[i].fault = in.drive[i].fault != 0;
    s.drive[i].status_word = in.drive[i].status_word;
    s.drive[i].fault_code = in.drive[i].fault_code;
  }
  s.time_s = t;
  s.torque_reported = in.torque_reported != 0;
  previous_ = s;
  have_previous_ = true;
}

void PluginBackend::on_configure(HardwareState& initial) {
  if (!instance_) create();
  gpm_backend_state st{};
  st.struct_size = sizeof st;
  check("configure", [&] { return api_->configure(instance_, &st); });
  have_previous_ = false;
  convert(st, initial.time_s, initial);
  last_raw_ = st;
}

void PluginBackend::on_activate(const HardwareState&) {
  check("activate", [&] { return api_->activate(instance_, &last_raw_); });
  active_ = true;
}

void PluginBackend::on_deactivate() {
  active_ = false;
  check("deactivate", [&] { return api_->deactivate(instance_); });
}

void PluginBackend::on_shutdown() noexcept {
  if (instance_ && active_) quietly([&] { api_->deactivate(instance_); });
  destroy();
}

void PluginBackend::on_error() noexcept {
  if (instance_) quietly([&] { api_->emergency_stop(instance_); });
  active_ = false;
}

void PluginBackend::on_reset() {
  destroy();
  create();
}

void PluginBackend::on_read(double time_s, HardwareState& s) {
  gpm_backend_state st{};
  st.struct_size = sizeof st;
  check("read", [&] { return api_->read(instance_, time_s, &st); });
  convert(st, time_s, s);
  last_raw_ = st;
}

void PluginBackend::on_write(const HardwareCommand& cmd, double time_s) {
  gpm_backend_command c{};
  c.struct_size = sizeof c;
  for (int i = 0; i < 3; ++i) {
    c.mode[i] = cmd.mode[i] == JointMode::kPosition ? GPM_BACKEND_POSITION : GPM_BACKEND_TORQUE_OFF;
    c.theta_m[i] = cmd.theta_m[i];
  }
  check("write", [&] { return api_->write(instance_, time_s, &c); });
}

}  // namespace gpm::hw
