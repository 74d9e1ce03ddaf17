#include "sim/mujoco_util.hpp"

#include <cstring>
#include <mutex>

#include <fmt/format.h>

namespace gpm::sim {
namespace {

void throw_on_error(const char* msg) { throw SimError(fmt::format("MuJoCo error: {}", msg)); }

// Warnings also land in mjData::warning counters, which the twin checks.
void ignore_warning(const char*) {}

}  // namespace

void install_mujoco_handlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    mju_user_error = throw_on_error;
    mju_user_warning = ignore_warning;
  });
}

ModelPtr load_model_from_xml(const std::string& xml) {
  install_mujoco_handlers();
  // mjVFS holds 2000 file names of 1000 bytes: keep it off the stack.
  auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());
  const char* name = "model.xml";
  if (mj_makeEmptyFileVFS(vfs.get(), name, static_cast<int>(xml.size())) != 0) {
    throw SimError("MuJoCo: cannot create the in-memory model file");
  }
  const int idx = mj_findFileVFS(vfs.get(), name);
  std::memcpy(vfs->filedata[idx], xml.data(), xml.size());
  char error[1000] = "";
  mjModel* m = nullptr;
  {
    // The XML parser keeps global state: one compilation at a time (runs in
    // parallel threads, e.g. gpm study effects, each compile their twin).
    static std::mutex parser;
    const std::lock_guard lock(parser);
    m = mj_loadXML(name, vfs.get(), error, sizeof(error));
  }
  mj_deleteVFS(vfs.get());
  if (!m) throw SimError(fmt::format("MuJoCo cannot compile the model: {}", error));
  return ModelPtr(m);
}

int require_id(const mjModel* m, mjtObj type, const char* name) {
  const int id = mj_name2id(m, type, name);
  if (id < 0) throw SimError(fmt::format("model has no {} named '{}'", mju_type2Str(type), name));
  return id;
}

}  // namespace gpm::sim
