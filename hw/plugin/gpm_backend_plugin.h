/* gpm backend plugin ABI: how a controller that gpm does not know (a motion
 * card, an EtherCAT or CANopen master, a vendor SDK) drives the GPM2002 through
 * gpm's hardware layer, without changing gpm.
 *
 * Plain C99, this header only: a plugin includes it, is built as a shared
 * library (any compiler, any build system, C or C++ inside) and exports ONE
 * function, gpm_backend_plugin_entry, that returns a table of plain C function
 * pointers. The hardware file names the library:
 *
 *     backend: plugin
 *     plugin: {library: libmycard.so, config: mycard.yaml}
 *
 * gpm (the host) loads it with dlopen, checks the versions below, and puts it
 * behind its safety supervisor like every backend: the plugin never sees a
 * command that breaks the hardware file's limits, and the host disables the
 * drives (emergency_stop) on any failure.
 *
 * Rules of the contract
 *  - Every function but destroy and last_error returns an int32_t code:
 *    GPM_BACKEND_OK (0) or one of GPM_BACKEND_E_*. On a nonzero code the
 *    host reads last_error() for one line of text and stops the robot. No
 *    C++ exception, longjmp or signal may cross a table function: catch
 *    everything inside.
 *  - Units: radians, radians per second, newton metres, seconds. Joint
 *    positions are ENCODER READINGS theta_m of the three base joints, angles
 *    counter-clockwise from +X (joint i: theta_a = theta_m + dth_i, with the
 *    robot file's zero offsets); convert the card's counts and directions.
 *  - Axis i of every array is joint i + 1 of the robot (A1, A2, A3).
 *  - The host calls one instance from one thread at a time, in this order:
 *    create, configure, then read/write cycles (activate, deactivate between
 *    them), destroy. read is called every cycle (period_s of create) while
 *    configured; write only while active. Several instances may live in one
 *    process (tests create more than one).
 *  - Pointers the host passes are valid only during the call.
 *  - The library stays loaded until the process ends (it is never unloaded).
 *
 * Versions
 *  - GPM_BACKEND_ABI_VERSION: the binary layout of this header's structs and
 *    function signatures. The host refuses a table whose abi_version differs
 *    from its own, with one line naming the library and both versions.
 *  - GPM_BACKEND_API_VERSION (major.minor): the meaning of the calls. The
 *    major must equal the host's; a minor adds fields or functions at the END
 *    of the table only (struct_size tells the host which ones a plugin has).
 *
 * A worked example: hw/README.md, "Writing a backend plugin for your
 * controller"; a complete one: hw/plugin/examples/motion_card_plugin.cpp.
 */
#ifndef GPM_BACKEND_PLUGIN_H
#define GPM_BACKEND_PLUGIN_H

#include <stdint.h>

/* Binary layout version (exact match required). */
#define GPM_BACKEND_ABI_VERSION 1u
/* Contract version major.minor, and both in one number (major << 16 | minor). */
#define GPM_BACKEND_API_VERSION_MAJOR 1u
#define GPM_BACKEND_API_VERSION_MINOR 0u
#define GPM_BACKEND_API_VERSION ((GPM_BACKEND_API_VERSION_MAJOR << 16) | GPM_BACKEND_API_VERSION_MINOR)

/* The one exported symbol, and its name for dlsym. */
#define GPM_BACKEND_PLUGIN_ENTRY_NAME "gpm_backend_plugin_entry"

/* Number of axes (joints) of the GPM2002. */
#define GPM_BACKEND_AXES 3

/* Marks the entry function exported (build the rest with hidden visibility). */
#if defined(_WIN32)
#define GPM_BACKEND_EXPORT __declspec(dllexport)
#elif defined(__GNUC__)
#define GPM_BACKEND_EXPORT __attribute__((visibility("default")))
#else
#define GPM_BACKEND_EXPORT
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* Return codes of the table functions. The host turns every nonzero code
 * into a hardware error (drives disabled, samples kept, exit 1), except
 * GPM_BACKEND_E_CONFIG from create: bad input, nothing moved, exit 2. */
enum gpm_backend_code {
  GPM_BACKEND_OK = 0,
  GPM_BACKEND_E_FAILED = 1,       /* any other failure */
  GPM_BACKEND_E_CONFIG = 2,       /* the configuration is invalid (say which key in last_error) */
  GPM_BACKEND_E_COMMS = 3,        /* the controller does not answer: connection lost, timeout */
  GPM_BACKEND_E_DRIVE_FAULT = 4,  /* a drive or the card reports a fault */
  GPM_BACKEND_E_STATE = 5,        /* a call not allowed in the plugin's current state */
  GPM_BACKEND_E_ARGUMENT = 6      /* an argument the plugin cannot accept */
};

/* What a joint's drive is asked to do (gpm_backend_command.mode). */
enum gpm_backend_joint_mode {
  GPM_BACKEND_TORQUE_OFF = 0,  /* drive disabled: no torque, the encoder is still read */
  GPM_BACKEND_POSITION = 1     /* drive closes its position loop on theta_m */
};

/* Bits of gpm_backend_api.flags. */
enum gpm_backend_flag {
  /* Time is simulated: read(host_time_s) advances the plant to host_time_s
   * and the host runs its cycles as fast as it can (a simulator). Without
   * it the host paces its cycles on the wall clock (real drives). */
  GPM_BACKEND_FLAG_SIMULATED_TIME = 1u
};

/* Opaque instance of a backend, owned by the plugin. */
typedef struct gpm_backend gpm_backend;

/* Arguments of create (read them during the call only). */
struct gpm_backend_create_args {
  uint32_t struct_size;     /* sizeof(struct gpm_backend_create_args) of the host */
  uint32_t reserved;        /* 0 */
  const char* config_path;  /* plugin.config when it is a file name: an absolute path, any format
                               the plugin reads; NULL otherwise */
  const char* config_text;  /* plugin.config when it is a map: that map as one line of YAML flow
                               text ({key: value, ...}); NULL otherwise */
  const char* base_dir;     /* folder that relative paths in the configuration are taken from
                               (the config file's folder, or the hardware file's); never NULL */
  double period_s;          /* the host's read/write cycle period (s) */
};

/* One drive's status as it reports it. */
struct gpm_backend_drive_status {
  uint32_t enabled;      /* nonzero: power stage on, following commands */
  uint32_t fault;        /* nonzero: the drive reports a fault (the host stops the robot) */
  uint16_t status_word;  /* raw status word (for messages; 0 if none) */
  uint16_t fault_code;   /* drive-specific fault code (0 = none) */
  uint32_t reserved;     /* 0 */
};

/* The state of the three joints, filled by configure and read. The host
 * zeroes it and sets struct_size before each call. */
struct gpm_backend_state {
  uint32_t struct_size;        /* sizeof(struct gpm_backend_state) of the host: write no further */
  uint32_t torque_reported;    /* nonzero: torque[] is measured (else leave it 0) */
  uint32_t velocity_reported;  /* nonzero: velocity[] is measured (else the host differentiates
                                  theta_m over read_time_s) */
  uint32_t reserved;           /* 0 */
  double time_s;               /* the plugin's clock at this reading (s; any origin, monotonic) */
  double read_time_s[GPM_BACKEND_AXES];  /* when each axis' position was captured, on the same
                                  clock: all equal for a card that latches its encoders in one
                                  call, each reply's time for drives polled one after another;
                                  at most time_s and no older than 1 s */
  double theta_m[GPM_BACKEND_AXES];      /* encoder readings (rad); must be finite */
  double velocity[GPM_BACKEND_AXES];     /* joint velocities (rad/s) */
  double torque[GPM_BACKEND_AXES];       /* joint torques (N m) */
  struct gpm_backend_drive_status drive[GPM_BACKEND_AXES];
};

/* A command for the three joints (write). */
struct gpm_backend_command {
  uint32_t struct_size;                  /* sizeof(struct gpm_backend_command) of the host */
  uint32_t mode[GPM_BACKEND_AXES];       /* enum gpm_backend_joint_mode, per joint */
  double theta_m[GPM_BACKEND_AXES];      /* position targets (rad, encoder space); for a
                                            torque-off joint its last reading */
};

/* The table the plugin returns. All function pointers are required. */
struct gpm_backend_api {
  uint32_t abi_version;  /* GPM_BACKEND_ABI_VERSION the plugin was built with */
  uint32_t struct_size;  /* sizeof(struct gpm_backend_api) the plugin was built with */
  uint32_t api_version;  /* GPM_BACKEND_API_VERSION the plugin was built with */
  uint32_t flags;        /* GPM_BACKEND_FLAG_* */
  const char* name;      /* short name for messages ("googol-gts"); static storage */

  /* A new instance from args: parse and check the configuration, allocate.
   * Do not touch the hardware yet (the host may create an instance to check
   * a hardware file and never configure it). On success set *out and return
   * GPM_BACKEND_OK; on failure return a code, leave *out NULL, and make
   * last_error(NULL) describe it. */
  int32_t (*create)(const struct gpm_backend_create_args* args, gpm_backend** out);
  /* Disables the drives if needed, disconnects and frees the instance. */
  void (*destroy)(gpm_backend* b);
  /* Connect and check the controller and drives, drives left disabled; fill
   * initial with a first reading. */
  int32_t (*configure)(gpm_backend* b, struct gpm_backend_state* initial);
  /* Enable the drives (all three; per-joint modes follow with write), each
   * holding its position of current (the host's last reading). */
  int32_t (*activate)(gpm_backend* b, const struct gpm_backend_state* current);
  /* Disable the drives (no torque); the encoders stay readable. */
  int32_t (*deactivate)(gpm_backend* b);
  /* Read the state of this cycle. host_time_s is the host's time of the
   * cycle (a simulated-time plugin advances its plant to it). */
  int32_t (*read)(gpm_backend* b, double host_time_s, struct gpm_backend_state* state);
  /* Send one command; the host has checked it against its safety limits. */
  int32_t (*write)(gpm_backend* b, double host_time_s, const struct gpm_backend_command* command);
  /* Disable every drive at once, best effort, from any state: called on any
   * failure and on a stop request. Must return quickly and never block; the
   * host stops the robot whatever it returns. */
  int32_t (*emergency_stop)(gpm_backend* b);
  /* One line of text about the last failure of b (of the last failed create
   * when b is NULL); never NULL; valid until the next call on b. */
  const char* (*last_error)(const gpm_backend* b);
};

/* The entry the plugin exports: its table (static storage, valid while the
 * library is loaded). host_abi_version is the host's GPM_BACKEND_ABI_VERSION:
 * return your table whatever it is (the host refuses a mismatch and names
 * both versions), or NULL when the plugin cannot start at all. */
GPM_BACKEND_EXPORT const struct gpm_backend_api* gpm_backend_plugin_entry(uint32_t host_abi_version);

/* Type of the entry, for the host's dlsym. */
typedef const struct gpm_backend_api* (*gpm_backend_plugin_entry_fn)(uint32_t host_abi_version);

#ifdef __cplusplus
}
#endif

#endif /* GPM_BACKEND_PLUGIN_H */
