/* A backend plugin written against gpm's installed header alone, in C99:
 * ideal drives, each position joint reading exactly its last command, in
 * simulated time; no velocity or torque reported (the host differentiates
 * the readings). Its configuration file holds the three readings at power
 * on (rad), e.g. "1.1111 3.1107 4.8249". */
#include <stdio.h>
#include <stdlib.h>

#include <hw/plugin/gpm_backend_plugin.h>

struct gpm_backend {
  double q[GPM_BACKEND_AXES];
  int enabled[GPM_BACKEND_AXES];
  char error[256];
};

static char create_error[256];

static int32_t ideal_create(const struct gpm_backend_create_args* a, gpm_backend** out) {
  FILE* f;
  gpm_backend* b;
  *out = NULL;
  if (!a->config_path) {
    snprintf(create_error, sizeof create_error, "give plugin.config: a file with the three start readings");
    return GPM_BACKEND_E_CONFIG;
  }
  b = calloc(1, sizeof *b);
  if (!b) return GPM_BACKEND_E_FAILED;
  f = fopen(a->config_path, "r");
  if (!f || fscanf(f, "%lf %lf %lf", &b->q[0], &b->q[1], &b->q[2]) != 3) {
    snprintf(create_error, sizeof create_error, "%s: expected three numbers (rad)", a->config_path);
    if (f) fclose(f);
    free(b);
    return GPM_BACKEND_E_CONFIG;
  }
  fclose(f);
  *out = b;
  return GPM_BACKEND_OK;
}

static void ideal_destroy(gpm_backend* b) { free(b); }

static int32_t ideal_read(gpm_backend* b, double host_time_s, struct gpm_backend_state* s) {
  int i;
  s->time_s = host_time_s;
  for (i = 0; i < GPM_BACKEND_AXES; ++i) {
    s->read_time_s[i] = host_time_s;
    s->theta_m[i] = b->q[i];
    s->drive[i].enabled = (uint32_t)b->enabled[i];
  }
  return GPM_BACKEND_OK;
}

static int32_t ideal_configure(gpm_backend* b, struct gpm_backend_state* initial) {
  return ideal_read(b, 0.0, initial);
}

static int32_t ideal_activate(gpm_backend* b, const struct gpm_backend_state* current) {
  int i;
  (void)current;
  for (i = 0; i < GPM_BACKEND_AXES; ++i) b->enabled[i] = 1;
  return GPM_BACKEND_OK;
}

static int32_t ideal_deactivate(gpm_backend* b) {
  int i;
  for (i = 0; i < GPM_BACKEND_AXES; ++i) b->enabled[i] = 0;
  return GPM_BACKEND_OK;
}

static int32_t ideal_write(gpm_backend* b, double host_time_s, const struct gpm_backend_command* c) {
  int i;
  (void)host_time_s;
  for (i = 0; i < GPM_BACKEND_AXES; ++i) {
    if (c->mode[i] != GPM_BACKEND_POSITION && c->mode[i] != GPM_BACKEND_TORQUE_OFF) {
      snprintf(b->error, sizeof b->error, "axis %d: unknown mode %u", i + 1, (unsigned)c->mode[i]);
      return GPM_BACKEND_E_ARGUMENT;
    }
    b->enabled[i] = c->mode[i] == GPM_BACKEND_POSITION;
    if (b->enabled[i]) b->q[i] = c->theta_m[i];
  }
  return GPM_BACKEND_OK;
}

static int32_t ideal_emergency_stop(gpm_backend* b) { return ideal_deactivate(b); }

static const char* ideal_last_error(const gpm_backend* b) { return b ? b->error : create_error; }

static const struct gpm_backend_api table = {
  GPM_BACKEND_ABI_VERSION, sizeof(struct gpm_backend_api), GPM_BACKEND_API_VERSION,
  GPM_BACKEND_FLAG_SIMULATED_TIME, "ideal-drives",
  ideal_create, ideal_destroy, ideal_configure, ideal_activate, ideal_deactivate,
  ideal_read, ideal_write, ideal_emergency_stop, ideal_last_error
};

GPM_BACKEND_EXPORT const struct gpm_backend_api* gpm_backend_plugin_entry(uint32_t host_abi_version) {
  (void)host_abi_version;
  return &table;
}
