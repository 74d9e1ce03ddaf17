// Data folders (models/data_dir.hpp). GPM_DATA_ROOT is defined for this file
// only, so that no other object depends on where the source tree lies.
#include "models/data_dir.hpp"

#include <cstdlib>

namespace gpm {
namespace {
std::string data_root() {
  const char* env = std::getenv("GPM_DATA_DIR");
  if (env && *env) return env;
  return GPM_DATA_ROOT;
}
}  // namespace

std::string models_dir() { return data_root() + "/models"; }

std::string scenarios_dir() { return data_root() + "/scenarios"; }

}  // namespace gpm
