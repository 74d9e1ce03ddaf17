// Sample backend plugin (hw/plugin/gpm_backend_plugin.h): a simulated motion
// card in the manner of a lab's multi-axis card (one call reads every encoder,
// stamped by the card's own clock, as a Googol card's GT_GetEncPos with its
// clock). The "card" is the MuJoCo twin of gpm (TwinBackend) in simulated
// time; its clock runs from its own origin (clock_offset_s at the twin's
// t = 0). C++ inside; only gpm_backend_plugin_entry is exported, and no
// exception leaves a table function.
//
// Configuration (plugin.config of the hardware file, a map or a YAML file):
//   scenario: ../scenarios/simulate_disc.yaml   # the twin: actual robot, servo, encoders
//   clock_offset_s: 1000.0                      # optional: the card clock at power on (s)
//   report_torque: true                         # optional: the card reports drive torques
//   poll_in_turn_s: 0.0                         # optional: a card without a latch, reading its
//                                               # axes one after another this far apart (s;
//                                               # its lagged readings are of error-free encoders)
//   stamp_each_axis: true                       # optional: false, the card stamps the three
//                                               # readings with one time (it does not know better)
#include <cstring>
#include <exception>
#include <filesystem>
#include <memory>
#include <string>

#include "hw/backends/twin_backend.hpp"
#include "hw/hardware_config.hpp"
#include "hw/hw_errors.hpp"
#include "hw/plugin/gpm_backend_plugin.h"
#include "sim/encoder_model.hpp"
#include "models/errors.hpp"
#include "models/yaml_util.hpp"

// One card: the twin behind it and the card's settings.
struct gpm_backend {
  std::unique_ptr<gpm::hw::TwinBackend> twin;
  double clock_offset_s = 0.0;
  bool report_torque = true;
  double poll_in_turn_s = 0.0;
  bool stamp_each_axis = true;
  gpm::sim::EncoderModel encoder;  // the twin's, to quantise a reading taken off the twin's instant
  gpm::Geometry actual;            // the twin's actual robot (its encoder offsets)
  std::string error;
};

namespace {

using gpm::hw::HardwareState;

// The message of the last failed create (last_error(NULL)), per thread.
thread_local std::string create_error;

// Runs f, turning every exception into a code and b's (or create's) message.
template <class F>
int32_t guarded(gpm_backend* b, F&& f) {
  std::string& error = b ? b->error : create_error;
  try {
    f();
    return GPM_BACKEND_OK;
  } catch (const gpm::InputError& e) {
    error = e.what();
    return GPM_BACKEND_E_CONFIG;
  } catch (const gpm::hw::LifecycleError& e) {
    error = e.what();
    return GPM_BACKEND_E_STATE;
  } catch (const std::exception& e) {
    error = e.what();
    return GPM_BACKEND_E_FAILED;
  } catch (...) {
    error = "unknown failure";
    return GPM_BACKEND_E_FAILED;
  }
}

// The card's configuration from the create arguments.
YAML::Node load_config(const gpm_backend_create_args& a) {
  if (a.config_path) return gpm::load_yaml_file(a.config_path);
  if (a.config_text) return gpm::load_yaml_string(a.config_text, "plugin.config");
  throw gpm::InputError("motion card: no configuration (give plugin.config: {scenario: FILE})");
}

// The card's one read: every encoder at one instant, on the card's clock;
// polled in turn, axis i lag_i = (2 - i) poll_in_turn_s before the last: its
// reading that of an encoder without errors but its counts at that time (the
// twin's true link angle less its offset, to first order in the speed,
// quantised), stamped with that time unless the card stamps one time for all.
void get_encoders(const gpm_backend& b, const HardwareState& twin, gpm_backend_state& s) {
  const gpm::sim::TwinSnapshot& truth = b.twin->snapshot();
  s.time_s = b.clock_offset_s + twin.time_s;
  s.velocity_reported = 1;
  s.torque_reported = b.report_torque ? 1 : 0;
  for (int i = 0; i < GPM_BACKEND_AXES; ++i) {
    const double lag = (GPM_BACKEND_AXES - 1 - i) * b.poll_in_turn_s;
    s.read_time_s[i] = b.stamp_each_axis ? s.time_s - lag : s.time_s;
    s.theta_m[i] = lag > 0.0 ? gpm::sim::quantise_reading(b.encoder, truth.theta_a[i] - truth.velocity[i] * lag -
                                                                         b.actual.dth_(i))
                             : twin.theta_m[i];
    s.velocity[i] = twin.velocity[i];
    s.torque[i] = b.report_torque ? twin.torque[i] : 0.0;
    s.drive[i].enabled = twin.drive[i].enabled ? 1 : 0;
    s.drive[i].fault = twin.drive[i].fault ? 1 : 0;
    s.drive[i].status_word = twin.drive[i].status_word;
    s.drive[i].fault_code = twin.drive[i].fault_code;
  }
}

int32_t card_create(const gpm_backend_create_args* a, gpm_backend** out) {
  *out = nullptr;
  return guarded(nullptr, [&] {
    const YAML::Node c = load_config(*a);
    const std::string where = a->config_path ? a->config_path : "plugin.config";
    gpm::yaml_check_keys(c, where, "", {"scenario", "clock_offset_s", "report_torque", "poll_in_turn_s", "stamp_each_axis"});
    if (!c["scenario"]) throw gpm::InputError(where + ": missing key 'scenario' (the twin behind the card)");
    std::filesystem::path scenario = gpm::yaml_string(c["scenario"], where, "scenario");
    if (scenario.is_relative()) scenario = std::filesystem::path(a->base_dir) / scenario;
    auto b = std::make_unique<gpm_backend>();
    if (c["clock_offset_s"]) b->clock_offset_s = gpm::yaml_number(c["clock_offset_s"], where, "clock_offset_s");
    if (c["report_torque"]) b->report_torque = gpm::yaml_bool(c["report_torque"], where, "report_torque");
    if (c["poll_in_turn_s"]) b->poll_in_turn_s = gpm::yaml_number(c["poll_in_turn_s"], where, "poll_in_turn_s");
    if (!(b->poll_in_turn_s >= 0.0 && b->poll_in_turn_s <= 0.01)) {
      throw gpm::InputError(where + ": poll_in_turn_s must be from 0 to 0.01 s (the time between two axes' reads)");
    }
    if (c["stamp_each_axis"]) b->stamp_each_axis = gpm::yaml_bool(c["stamp_each_axis"], where, "stamp_each_axis");
    const gpm::hw::TwinBackendConfig twin =
        gpm::hw::twin_config_from_scenario(scenario.lexically_normal().string(), a->period_s);
    b->encoder = twin.twin.encoder;
    b->actual = twin.actual.geometry;
    b->twin = std::make_unique<gpm::hw::TwinBackend>(twin);
    *out = b.release();
  });
}

void card_destroy(gpm_backend* b) {
  if (!b) return;
  if (b->twin) b->twin->shutdown();
  delete b;
}

int32_t card_configure(gpm_backend* b, gpm_backend_state* initial) {
  return guarded(b, [&] {
    b->twin->configure();
    get_encoders(*b, b->twin->last_state(), *initial);
  });
}

int32_t card_activate(gpm_backend* b, const gpm_backend_state*) {
  return guarded(b, [&] { b->twin->activate(); });
}

int32_t card_deactivate(gpm_backend* b) {
  return guarded(b, [&] { b->twin->deactivate(); });
}

int32_t card_read(gpm_backend* b, double host_time_s, gpm_backend_state* s) {
  return guarded(b, [&] { get_encoders(*b, b->twin->read(host_time_s), *s); });
}

int32_t card_write(gpm_backend* b, double host_time_s, const gpm_backend_command* c) {
  return guarded(b, [&] {
    gpm::hw::HardwareCommand cmd;
    for (int i = 0; i < GPM_BACKEND_AXES; ++i) {
      if (c->mode[i] != GPM_BACKEND_POSITION && c->mode[i] != GPM_BACKEND_TORQUE_OFF) {
        throw gpm::hw::HardwareError("motion card: axis " + std::to_string(i + 1) + ": unknown mode " +
                                     std::to_string(c->mode[i]));
      }
      cmd.mode[i] = c->mode[i] == GPM_BACKEND_POSITION ? gpm::hw::JointMode::kPosition
                                                        : gpm::hw::JointMode::kTorqueOff;
      cmd.theta_m[i] = c->theta_m[i];
    }
    b->twin->write(cmd, host_time_s);
  });
}

int32_t card_emergency_stop(gpm_backend* b) {
  return guarded(b, [&] { b->twin->emergency_stop("host request"); });
}

const char* card_last_error(const gpm_backend* b) { return b ? b->error.c_str() : create_error.c_str(); }

const gpm_backend_api kTable = {
    GPM_BACKEND_ABI_VERSION,
    sizeof(gpm_backend_api),
    GPM_BACKEND_API_VERSION,
    GPM_BACKEND_FLAG_SIMULATED_TIME,
    "motion-card-sim",
    card_create,
    card_destroy,
    card_configure,
    card_activate,
    card_deactivate,
    card_read,
    card_write,
    card_emergency_stop,
    card_last_error,
};

}  // namespace

extern "C" GPM_BACKEND_EXPORT const gpm_backend_api* gpm_backend_plugin_entry(uint32_t) { return &kTable; }
