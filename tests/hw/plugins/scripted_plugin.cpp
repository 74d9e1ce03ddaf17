// A backend plugin for tests/hw/test_plugin_backend.cpp: ideal drives (each
// position joint reads exactly its last command) whose failures are scripted
// by the configuration, and, by compile definitions, tables that break the
// contract: GPM_TEST_PLUGIN_ABI / GPM_TEST_PLUGIN_API (other versions),
// GPM_TEST_PLUGIN_NULL_TABLE, GPM_TEST_PLUGIN_NULL_READ, GPM_TEST_PLUGIN_NO_ENTRY.
//
// Configuration (a map): start: [q1, q2, q3] (rad, the readings at configure);
// fail: create|configure|activate|read|write with code: C (default 1) at the
// call number after: N (default 0: the first); nan_after: N (reads from the
// N-th on give a NaN on axis 2); stale_after: N (axis 3 read 5 s before the
// reading's time); throw_read: N (the N-th read lets a C++ exception escape,
// which the ABI forbids).
#include <cmath>
#include <exception>
#include <stdexcept>
#include <string>

#include <yaml-cpp/yaml.h>

#include "hw/plugin/gpm_backend_plugin.h"

#ifndef GPM_TEST_PLUGIN_ABI
#define GPM_TEST_PLUGIN_ABI GPM_BACKEND_ABI_VERSION
#endif
#ifndef GPM_TEST_PLUGIN_API
#define GPM_TEST_PLUGIN_API GPM_BACKEND_API_VERSION
#endif

struct gpm_backend {
  double q[3] = {0, 0, 0};
  bool enabled[3] = {false, false, false};
  std::string fail;
  int code = GPM_BACKEND_E_FAILED;
  long after = 0, nan_after = -1, stale_after = -1, throw_read = -1;
  long reads = 0, writes = 0;
  std::string error;
};

namespace {

thread_local std::string create_error;
long g_emergency_stops = 0;
long g_live = 0;

// A scripted failure of call number n of call: its code, with a message.
int32_t scripted(gpm_backend* b, const char* call, long n) {
  if (b->fail != call || n != b->after) return GPM_BACKEND_OK;
  b->error = std::string("scripted failure of ") + call + " (card timeout on axis 2)";
  return b->code;
}

int32_t t_create(const gpm_backend_create_args* a, gpm_backend** out) {
  *out = nullptr;
  try {
    const YAML::Node c = a->config_text ? YAML::Load(a->config_text) : YAML::Node();
    auto* b = new gpm_backend;
    if (c["start"]) for (int i = 0; i < 3; ++i) b->q[i] = c["start"][i].as<double>();
    if (c["fail"]) b->fail = c["fail"].as<std::string>();
    if (c["code"]) b->code = c["code"].as<int>();
    if (c["after"]) b->after = c["after"].as<long>();
    if (c["nan_after"]) b->nan_after = c["nan_after"].as<long>();
    if (c["stale_after"]) b->stale_after = c["stale_after"].as<long>();
    if (c["throw_read"]) b->throw_read = c["throw_read"].as<long>();
    if (b->fail == "create") {
      create_error = "key 'fail': scripted refusal of the configuration";
      const int code = b->code;
      delete b;
      return code;
    }
    *out = b;
    ++g_live;
    return GPM_BACKEND_OK;
  } catch (const std::exception& e) {
    create_error = e.what();
    return GPM_BACKEND_E_CONFIG;
  }
}

void t_destroy(gpm_backend* b) {
  --g_live;
  delete b;
}

void fill(const gpm_backend* b, double t, gpm_backend_state* s) {
  s->time_s = t;
  for (int i = 0; i < 3; ++i) {
    s->read_time_s[i] = t;
    s->theta_m[i] = b->q[i];
    s->drive[i].enabled = b->enabled[i];
    s->drive[i].status_word = b->enabled[i] ? 0x27 : 0x40;
  }
  if (b->nan_after >= 0 && b->reads >= b->nan_after) s->theta_m[1] = std::nan("");
  if (b->stale_after >= 0 && b->reads >= b->stale_after) s->read_time_s[2] = t - 5.0;
}

int32_t t_configure(gpm_backend* b, gpm_backend_state* s) {
  if (const int32_t c = scripted(b, "configure", 0)) return c;
  fill(b, 0.0, s);
  return GPM_BACKEND_OK;
}

int32_t t_activate(gpm_backend* b, const gpm_backend_state*) {
  if (const int32_t c = scripted(b, "activate", 0)) return c;
  for (bool& e : b->enabled) e = true;
  return GPM_BACKEND_OK;
}

int32_t t_deactivate(gpm_backend* b) {
  for (bool& e : b->enabled) e = false;
  return GPM_BACKEND_OK;
}

[[maybe_unused]] int32_t t_read(gpm_backend* b, double t, gpm_backend_state* s) {
  if (const int32_t c = scripted(b, "read", b->reads)) return c;
  if (b->reads == b->throw_read) throw std::runtime_error("scripted exception");
  fill(b, t, s);
  ++b->reads;
  return GPM_BACKEND_OK;
}

int32_t t_write(gpm_backend* b, double, const gpm_backend_command* c) {
  if (const int32_t code = scripted(b, "write", b->writes++)) return code;
  for (int i = 0; i < 3; ++i) {
    b->enabled[i] = c->mode[i] == GPM_BACKEND_POSITION;
    if (b->enabled[i]) b->q[i] = c->theta_m[i];
  }
  return GPM_BACKEND_OK;
}

int32_t t_emergency_stop(gpm_backend* b) {
  ++g_emergency_stops;
  for (bool& e : b->enabled) e = false;
  return GPM_BACKEND_OK;
}

const char* t_last_error(const gpm_backend* b) { return b ? b->error.c_str() : create_error.c_str(); }

const gpm_backend_api kTable = {
    GPM_TEST_PLUGIN_ABI, sizeof(gpm_backend_api), GPM_TEST_PLUGIN_API, GPM_BACKEND_FLAG_SIMULATED_TIME,
    "scripted",          t_create,                t_destroy,           t_configure,
    t_activate,          t_deactivate,
#ifdef GPM_TEST_PLUGIN_NULL_READ
    nullptr,
#else
    t_read,
#endif
    t_write,             t_emergency_stop,        t_last_error,
};

}  // namespace

#ifndef GPM_TEST_PLUGIN_NO_ENTRY
extern "C" GPM_BACKEND_EXPORT const gpm_backend_api* gpm_backend_plugin_entry(uint32_t) {
#ifdef GPM_TEST_PLUGIN_NULL_TABLE
  return nullptr;
#else
  return &kTable;
#endif
}
#endif

// For the tests: emergency stops so far, and instances alive.
extern "C" GPM_BACKEND_EXPORT long gpm_test_plugin_emergency_stops() { return g_emergency_stops; }
extern "C" GPM_BACKEND_EXPORT long gpm_test_plugin_live() { return g_live; }
