#include "render/output_file.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <unistd.h>

#include <fmt/format.h>

#include "models/errors.hpp"

namespace gpm::render {

namespace fs = std::filesystem;

std::string temporary_name_for(const std::string& path) {
  const fs::path p(path);
  const fs::path tmp = p.parent_path() / fmt::format(".{}.tmp{}", p.filename().string(), static_cast<long>(::getpid()));
  return tmp.string();
}

void check_output_file(const std::string& path) {
  if (path.empty()) throw InputError("output file name is empty");
  std::error_code ec;
  const fs::path p(path);
  if (fs::is_directory(p, ec)) throw InputError(fmt::format("{}: is a folder, not a file name", path));
  const fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
  if (!fs::is_directory(dir, ec))
    throw InputError(fmt::format("{}: cannot write: folder {} does not exist", path, dir.string()));
  const std::string tmp = temporary_name_for(path);
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) throw InputError(fmt::format("{}: cannot write: {}", path, std::strerror(errno)));
  std::fclose(f);
  std::remove(tmp.c_str());
}

void commit_output_file(const std::string& tmp, const std::string& path) {
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw InputError(fmt::format("{}: cannot write: {}", path, ec.message()));
  }
}

}  // namespace gpm::render
