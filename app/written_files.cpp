// Every file a command wrote (app/written_files.hpp).
#include "app/written_files.hpp"

#include <algorithm>
#include <chrono>

#include <fmt/format.h>

namespace gpm::cli {
namespace fs = std::filesystem;
namespace {
fs::file_time_type g_start = fs::file_time_type::clock::now();
}

void mark_command_start() {
  // 20 ms early: the kernel stamps files with its coarse clock (a tick behind).
  g_start = fs::file_time_type::clock::now() - std::chrono::milliseconds(20);
}

std::vector<std::string> files_written_since(const std::string& dir, fs::file_time_type since) {
  std::vector<std::string> out;
  std::error_code ec;
  fs::recursive_directory_iterator it(dir, ec), end;
  for (; !ec && it != end; it.increment(ec)) {
    const fs::path& p = it->path();
    if (p.filename().string().starts_with(".")) {
      if (it->is_directory(ec)) it.disable_recursion_pending();
      continue;
    }
    std::error_code fe;
    if (!it->is_regular_file(fe) || fe) continue;
    const fs::file_time_type t = fs::last_write_time(p, fe);
    if (!fe && t >= since) out.push_back((fs::path(dir) / fs::relative(p, dir, fe)).string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

void print_written(const std::string& dir, int width, const std::string& label) {
  for (const std::string& f : files_written_since(dir, g_start)) fmt::print("{:<{}}{}\n", label, width, f);
}

}  // namespace gpm::cli
