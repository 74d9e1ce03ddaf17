// MuJoCo plumbing shared by the twin: error handlers, loading a model from
// MJCF text (through a virtual file system, no temporary files), and owning
// pointers for mjModel and mjData.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>

#include "models/errors.hpp"

#include <mujoco/mujoco.h>

namespace gpm::sim {

// A failure inside the physics engine (a MuJoCo error, or a diverged step).
class SimError : public Error {
 public:
  explicit SimError(const std::string& what) : Error(what) {}
};

struct ModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct DataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};
using ModelPtr = std::unique_ptr<mjModel, ModelDeleter>;
using DataPtr = std::unique_ptr<mjData, DataDeleter>;

// Installs MuJoCo error and warning handlers (idempotent): errors throw
// SimError instead of waiting on stdin and writing MUJOCO_LOG.TXT.
void install_mujoco_handlers();

// Compiles MJCF text; throws SimError with MuJoCo's message on failure.
ModelPtr load_model_from_xml(const std::string& xml);

// Id of a named object of the given type; throws SimError if missing.
int require_id(const mjModel* m, mjtObj type, const char* name);

}  // namespace gpm::sim
