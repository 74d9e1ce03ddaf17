#include "models/measured_data.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <optional>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fmt/format.h>

#include "models/errors.hpp"

namespace gpm {

namespace fs = std::filesystem;

namespace {

// What a marker says.
struct Marker {
  std::string kind, samples;
};

std::string marker_path(const std::string& dir) { return (fs::path(dir) / kMeasuredMarker).string(); }

std::string read_fd(int fd) {
  std::string text;
  char buf[4096];
  for (;;) {
    const ssize_t n = ::pread(fd, buf, sizeof buf, static_cast<off_t>(text.size()));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    text.append(buf, static_cast<size_t>(n));
  }
  return text;
}

Marker parse_marker(const std::string& text) {
  Marker m;
  size_t at = 0;
  while (at < text.size()) {
    size_t end = text.find('\n', at);
    if (end == std::string::npos) end = text.size();
    const std::string line = text.substr(at, end - at);
    if (line.rfind("kind: ", 0) == 0) m.kind = line.substr(6);
    if (line.rfind("samples: ", 0) == 0) m.samples = line.substr(9);
    at = end + 1;
  }
  if (m.kind.empty()) m.kind = "hardware";
  if (m.samples.empty()) m.samples = "samples.csv";
  return m;
}

// True while a session holds the marker's lock.
bool marker_locked(const std::string& dir) {
  const int fd = ::open(marker_path(dir).c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return false;
  const bool locked = ::flock(fd, LOCK_SH | LOCK_NB) != 0 && errno == EWOULDBLOCK;
  ::close(fd);
  return locked;
}

// The marker of dir, when it guards something: a session holds it, or its
// samples file exists. A marker left by a session killed before its first
// sample (no samples, no lock) guards nothing and is removed.
std::optional<Marker> read_marker(const std::string& dir) {
  const int fd = ::open(marker_path(dir).c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return std::nullopt;
  const Marker m = parse_marker(read_fd(fd));
  ::close(fd);
  std::error_code ec;
  if (!fs::exists(fs::path(dir) / m.samples, ec) && !marker_locked(dir)) {
    ::unlink(marker_path(dir).c_str());
    return std::nullopt;
  }
  return m;
}

bool same_folder(const std::string& a, const std::string& b) {
  struct stat sa {}, sb {};
  if (::stat(a.c_str(), &sa) != 0 || ::stat(b.c_str(), &sb) != 0) return false;
  return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}

bool owned_by(const std::string& dir, const MeasuredFolder* owner) {
  return owner != nullptr && same_folder(owner->dir(), dir);
}

std::string refusal(const std::string& dir, const Marker& m) {
  if (marker_locked(dir))
    return fmt::format("{}: a hardware session ({}) is recording into this folder now ({} is locked); choose another "
                       "output folder",
                       dir, m.kind, marker_path(dir));
  return fmt::format("{}: holds the measured samples of a {} session ({}; {}): only that session continues it "
                     "(--resume); choose another output folder",
                     dir, m.kind, marker_path(dir), m.samples);
}

}  // namespace

MeasuredFolder::MeasuredFolder(const std::string& dir, const std::string& kind, const std::string& samples_name)
    : dir_(dir), kind_(kind), samples_name_(samples_name) {
  if (dir.empty()) throw InputError("output folder name is empty");
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    throw InputError(fmt::format("{}: exists and is not a folder", dir));
  if (!fs::exists(dir, ec)) {
    fs::create_directories(dir, ec);
    if (ec) throw InputError(fmt::format("{}: cannot create the output folder: {}", dir, ec.message()));
    created_dir_ = true;
  }
  const std::string marker = marker_path(dir);
  try {
    fd_ = ::open(marker.c_str(), O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd_ >= 0) {
      created_marker_ = true;
    } else if (errno == EEXIST) {
      fd_ = ::open(marker.c_str(), O_RDWR | O_CLOEXEC);
    }
    if (fd_ < 0) throw InputError(fmt::format("{}: cannot write the marker {}: {}", dir, marker, std::strerror(errno)));
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
      if (errno == EWOULDBLOCK)
        throw InputError(fmt::format("{}: another hardware session is recording into this folder ({} is locked); "
                                     "wait for it to end",
                                     dir, marker));
      throw InputError(fmt::format("{}: cannot lock {}: {}", dir, marker, std::strerror(errno)));
    }
    if (!created_marker_) {
      const Marker m = parse_marker(read_fd(fd_));
      if (m.kind != kind_ || m.samples != samples_name_)
        throw InputError(fmt::format("{}: holds the measured samples of a {} session ({}; {}); a {} session does not "
                                     "continue it: choose another output folder",
                                     dir, m.kind, marker, m.samples, kind_));
    } else {
      if (fs::exists(samples_path(), ec))
        throw InputError(fmt::format("{}: exists but no hardware session recorded it into this folder (no {}): "
                                     "measured samples are never mixed with others; choose another output folder",
                                     samples_path(), marker));
      const std::string text = fmt::format(
          "# gpm: this folder holds measured samples ({}); only a {} session with --resume continues it\n"
          "kind: {}\nsamples: {}\n",
          samples_name_, kind_, kind_, samples_name_);
      if (::write(fd_, text.data(), text.size()) != static_cast<ssize_t>(text.size()) || ::fsync(fd_) != 0)
        throw InputError(fmt::format("{}: cannot write the marker {}: {}", dir, marker, std::strerror(errno)));
    }
  } catch (...) {
    if (created_marker_) ::unlink(marker.c_str());
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
    if (created_dir_) ::rmdir(dir.c_str());
    throw;
  }
}

MeasuredFolder::~MeasuredFolder() {
  std::error_code ec;
  if (created_marker_ && !fs::exists(samples_path(), ec)) ::unlink(marker_path(dir_).c_str());
  if (fd_ >= 0) ::close(fd_);
  if (created_dir_) ::rmdir(dir_.c_str());  // only when empty
}

std::string MeasuredFolder::samples_path() const { return (fs::path(dir_) / samples_name_).string(); }

void refuse_measured_folder(const std::string& dir, const MeasuredFolder* owner) {
  if (dir.empty() || owned_by(dir, owner)) return;
  if (const std::optional<Marker> m = read_marker(dir)) throw InputError(refusal(dir, *m));
}

bool is_sampling_log(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return false;
  struct stat st {};
  char buf[512] = {};
  ssize_t n = 0;
  if (::fstat(fd, &st) == 0 && S_ISREG(st.st_mode)) n = ::pread(fd, buf, sizeof buf, 0);
  ::close(fd);
  const std::string head(buf, n > 0 ? static_cast<size_t>(n) : 0);
  const size_t eol = head.find('\n');
  if (eol == std::string::npos || static_cast<size_t>(st.st_size) <= eol + 1) return false;  // no row after it
  std::string line = head.substr(0, eol);
  if (!line.empty() && line.back() == '\r') line.pop_back();
  const std::string at_rest = kSamplingLogHeader;
  return line == at_rest || line == at_rest + kSamplingLogOnTheFlyColumns;
}

void refuse_measured_file(const std::string& path, const MeasuredFolder* owner, bool sampling_session) {
  std::error_code ec;
  fs::path p = fs::weakly_canonical(fs::path(path), ec);
  if (ec) p = fs::path(path);
  const std::string dir = p.parent_path().empty() ? std::string(".") : p.parent_path().string();
  if (owned_by(dir, owner)) return;
  const std::optional<Marker> m = read_marker(dir);
  if (m && p.filename().string() == m->samples)
    throw InputError(fmt::format("{}: is the measured samples file of {} ({} session, {}): it is never replaced, "
                                 "and only that session continues it (--resume); choose another output",
                                 path, dir, m->kind, marker_path(dir)));
  if (!sampling_session && is_sampling_log(p.string()))
    throw InputError(fmt::format("{}: holds measured samples (a hardware sampling log: first line {}): it is never "
                                 "replaced, only gpm sample --resume continues it; choose another output",
                                 path, kSamplingLogHeader));
}

}  // namespace gpm
