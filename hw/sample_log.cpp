#include "hw/sample_log.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "hw/hw_errors.hpp"
#include "models/errors.hpp"
#include "models/robot_yaml.hpp"
#include "models/samples.hpp"
#include "models/yaml_util.hpp"

namespace gpm::hw {
namespace {

constexpr const char* kHeader = "sample,theta_m1,theta_m2,theta_m3,target_x,target_y\n";

void write_all(int fd, const std::string& text, const std::string& path) {
  size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw HardwareError(fmt::format("{}: write failed: {}", path, std::strerror(errno)));
    done += static_cast<size_t>(n);
  }
  if (::fsync(fd) != 0) throw HardwareError(fmt::format("{}: fsync failed: {}", path, std::strerror(errno)));
}

}  // namespace

SampleLog::SampleLog(const std::string& path, bool resume) : path_(path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const bool exists = fs::exists(path, ec);
  if (exists && !resume) {
    throw InputError(fmt::format("{}: file exists (it may hold measurements): pass --resume to "
                                 "continue it, or choose another output file",
                                 path));
  }
  if (exists) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    std::string text = ss.str();
    if (!text.empty() && text.back() != '\n') {
      // A torn last line (crash while writing): drop it, keep the rest.
      text.erase(text.rfind('\n') == std::string::npos ? 0 : text.rfind('\n') + 1);
      write_file_atomic(path, text);
    }
    if (text.empty()) {
      write_file_atomic(path, kHeader);
    } else {
      const Samples s = parse_samples_csv(text, path);
      ids_.insert(s.id.begin(), s.id.end());
    }
  }
  fd_ = ::open(path.c_str(), O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) {
    throw InputError(fmt::format("{}: cannot open for writing: {}", path, std::strerror(errno)));
  }
  if (!exists) {
    created_ = true;
    write_all(fd_, kHeader, path);
  }
}

SampleLog::~SampleLog() {
  if (fd_ >= 0) ::close(fd_);
}

void SampleLog::append(long id, const Eigen::Vector3d& q, const Eigen::Vector2d& target) {
  if (fd_ < 0) throw HardwareError(fmt::format("{}: sample log is closed", path_));
  write_all(fd_,
            fmt::format("{},{},{},{},{},{}\n", id, format_exact(q[0]), format_exact(q[1]),
                        format_exact(q[2]), format_exact(target.x()), format_exact(target.y())),
            path_);
  ids_.insert(id);
}

void SampleLog::close_and_discard_if_empty() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  if (created_ && ids_.empty()) {
    std::error_code ec;
    std::filesystem::remove(path_, ec);
  }
}

}  // namespace gpm::hw
