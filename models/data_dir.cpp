// Data folders (models/data_dir.hpp). GPM_DATA_ROOT (the source tree) is
// defined for this file only, so that no other object depends on where the
// source tree lies.
#include "models/data_dir.hpp"

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <system_error>

namespace gpm {
namespace {

namespace fs = std::filesystem;

// A data root is a folder with the nominal robot file in its models/.
bool is_data_root(const fs::path& root) {
  std::error_code ec;
  return fs::is_regular_file(root / "models" / "gpm2002.yaml", ec);
}

// Path of the file mapped at address addr (the executable or shared object
// holding it), from /proc/self/maps; empty when unknown.
fs::path mapped_file(const void* addr) {
  const auto a = reinterpret_cast<std::uintptr_t>(addr);
  std::ifstream maps("/proc/self/maps");
  for (std::string line; std::getline(maps, line);) {
    // "start-end perms offset dev inode   path"
    std::istringstream in(line);
    std::string range, perms, offset, dev, inode, path;
    if (!(in >> range >> perms >> offset >> dev >> inode)) continue;
    const auto dash = range.find('-');
    if (dash == std::string::npos) continue;
    const std::uintptr_t lo = std::stoull(range.substr(0, dash), nullptr, 16);
    const std::uintptr_t hi = std::stoull(range.substr(dash + 1), nullptr, 16);
    if (a < lo || a >= hi) continue;
    std::getline(in >> std::ws, path);
    return path.empty() || path[0] != '/' ? fs::path() : fs::path(path);
  }
  return {};
}

// PREFIX/share/gpm of the installed binary (executable, library or Python
// module) that holds this code, or empty when it is not installed.
std::string installed_root() {
  const fs::path object = mapped_file(reinterpret_cast<const void*>(&installed_root));
  if (object.empty()) return {};
  // PREFIX/bin/ or PREFIX/lib/ (one level below PREFIX), PREFIX/lib/python3/dist-packages/ (three).
  fs::path dir = object.parent_path();
  for (int up = 1; up <= 3; ++up) {
    dir = dir.parent_path();
    if (up == 2) continue;
    const fs::path root = dir / "share" / "gpm";
    if (is_data_root(root)) return root.string();
  }
  return {};
}

}  // namespace

std::string data_root() {
  const char* env = std::getenv("GPM_DATA_DIR");
  if (env && *env) return env;
  static const std::string installed = installed_root();
  if (!installed.empty()) return installed;
  return GPM_DATA_ROOT;
}

std::string models_dir() { return data_root() + "/models"; }

std::string scenarios_dir() { return data_root() + "/scenarios"; }

}  // namespace gpm
