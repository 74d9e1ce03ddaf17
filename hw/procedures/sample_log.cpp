#include "hw/procedures/sample_log.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include <fmt/format.h>

#include "hw/hw_errors.hpp"
#include "models/bounds.hpp"
#include "models/errors.hpp"
#include "models/measured_data.hpp"
#include "models/robot_yaml.hpp"
#include "models/samples.hpp"
#include "models/yaml_util.hpp"

namespace gpm::hw {
namespace {

// The header lines (models/measured_data.hpp: how any output knows a sampling log).
const std::string kHeaderAtRest = std::string(kSamplingLogHeader) + "\n";
const std::string kHeaderOnTheFly = std::string(kSamplingLogHeader) + kSamplingLogOnTheFlyColumns + "\n";

const std::string& header_of(SampleColumns c) { return c == SampleColumns::kOnTheFly ? kHeaderOnTheFly : kHeaderAtRest; }

// ",a,b,c" of a triple, each number exact.
std::string triple_fields(const Eigen::Vector3d& v) {
  return fmt::format(",{},{},{}", format_exact(v[0]), format_exact(v[1]), format_exact(v[2]));
}

// text is empty or the beginning of a header (a session stopped before its first sample).
bool is_header_begun(const std::string& text) {
  return kHeaderAtRest.compare(0, text.size(), text) == 0 || kHeaderOnTheFly.compare(0, text.size(), text) == 0;
}

// text begins with a whole header line of either kind.
bool starts_with_header(const std::string& text) {
  return text.compare(0, kHeaderAtRest.size(), kHeaderAtRest) == 0 ||
         text.compare(0, kHeaderOnTheFly.size(), kHeaderOnTheFly) == 0;
}

// Writes text whole; a regular file is then flushed to disk (fsync), a device
// or FIFO written in place is not (it cannot be).
void write_all(int fd, const std::string& text, const std::string& path, bool sync) {
  size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw HardwareError(fmt::format("{}: write failed: {}", path, std::strerror(errno)));
    done += static_cast<size_t>(n);
  }
  if (sync && ::fsync(fd) != 0) throw HardwareError(fmt::format("{}: fsync failed: {}", path, std::strerror(errno)));
}

// Takes the exclusive lock of fd (one session appends to a file at a time).
void lock_or_refuse(int fd, const std::string& path) {
  if (::flock(fd, LOCK_EX | LOCK_NB) == 0) return;
  const int err = errno;
  ::close(fd);
  if (err == EWOULDBLOCK) {
    throw InputError(fmt::format("{}: another session is appending to this file (it is locked); "
                                 "wait for it to end",
                                 path));
  }
  throw InputError(fmt::format("{}: cannot lock: {}", path, std::strerror(err)));
}

}  // namespace

SampleLog::SampleLog(const std::string& path, bool resume, SampleColumns columns) : path_(path), columns_(columns) {
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) {
    open_in_place(st, resume);
    return;
  }
  fd_ = ::open(path.c_str(), O_RDWR | O_APPEND | O_CLOEXEC);
  if (fd_ < 0) {
    if (errno != ENOENT) throw InputError(fmt::format("{}: cannot open: {}", path, std::strerror(errno)));
    create_now();
    return;
  }
  lock_or_refuse(fd_, path);
  try {
    read_existing(resume);
  } catch (...) {  // refused: release the file and its lock
    ::close(fd_);
    fd_ = -1;
    throw;
  }
}

SampleLog::SampleLog(SampleColumns columns) : path_("the samples in memory"), in_memory_(true), columns_(columns) {}

void SampleLog::create_now() {
  // Created with its header before anything moves: a folder that cannot be
  // written (read-only, full, missing) is refused here, not after the first
  // motion; the file is removed again if no sample is recorded.
  const int fd = ::open(path_.c_str(), O_RDWR | O_APPEND | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) throw InputError(fmt::format("{}: cannot create: {}", path_, std::strerror(errno)));
  lock_or_refuse(fd, path_);  // closes fd when it throws
  fd_ = fd;
  created_ = true;
  try {
    write_all(fd_, header_of(columns_), path_, true);
  } catch (const HardwareError& e) {
    close_and_discard_if_empty();
    throw InputError(e.what());
  }
}

void SampleLog::open_in_place(const struct stat& st, bool resume) {
  if (S_ISDIR(st.st_mode)) throw InputError(fmt::format("{}: is a folder, not a samples file", path_));
  if (S_ISSOCK(st.st_mode)) throw InputError(fmt::format("{}: is a socket, not a samples file", path_));
  // A device or FIFO (the output policy, models/output_file.hpp): written in
  // place, never read back, locked, truncated nor fsynced; the header is
  // written now, so one that cannot be written is refused before anything moves.
  if (resume) {
    throw InputError(fmt::format("{}: is a device or FIFO: there are no recorded samples to resume; "
                                 "give the samples file",
                                 path_));
  }
  // A FIFO nobody reads fails at once (ENXIO) instead of blocking.
  fd_ = ::open(path_.c_str(), O_WRONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd_ < 0) {
    const int err = errno;
    throw InputError(fmt::format("{}: cannot write: {}", path_,
                                 err == ENXIO ? "no process reads this FIFO" : std::strerror(err)));
  }
  const int flags = ::fcntl(fd_, F_GETFL);
  if (flags >= 0) ::fcntl(fd_, F_SETFL, flags & ~O_NONBLOCK);
  in_place_ = true;
  try {
    write_all(fd_, header_of(columns_), path_, false);
  } catch (const HardwareError& e) {
    ::close(fd_);
    fd_ = -1;
    throw InputError(e.what());
  }
}

namespace {

// The whole file open on fd, at most limits::kMaxCsvBytes (as every samples
// reader, models/bounds.hpp); throws InputError naming path otherwise.
std::string read_bounded(int fd, const std::string& path) {
  std::string text;
  char buf[65536];
  while (text.size() <= limits::kMaxCsvBytes) {
    const ssize_t n = ::pread(fd, buf, sizeof buf, static_cast<off_t>(text.size()));
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw InputError(fmt::format("{}: cannot read: {}", path, std::strerror(errno)));
    if (n == 0) break;
    text.append(buf, static_cast<size_t>(n));
  }
  if (text.size() > limits::kMaxCsvBytes)
    throw InputError(fmt::format("{}: larger than {} MiB, the limit of a samples file (is it the right file?)", path,
                                 limits::kMaxCsvBytes >> 20));
  return text;
}

// Whether the file (its whole text) holds a log's rows to read: false for an
// empty or header-only file (a session stopped before its first sample), which
// is started again with header; throws InputError for a file that is not a
// samples log, or a log when resume is off. Nothing is changed in another file.
bool holds_rows_to_resume(int fd, const std::string& text, const std::string& header, bool resume,
                          const std::string& path) {
  if (is_header_begun(text)) {
    if (text == header) return false;
    if (::ftruncate(fd, 0) != 0) throw InputError(fmt::format("{}: cannot start it again: {}", path, std::strerror(errno)));
    write_all(fd, header, path, true);
    return false;
  }
  if (!starts_with_header(text)) {
    throw InputError(fmt::format("{}: exists and is not a samples log (its first line is not {}): it is left as it "
                                 "is; choose another output file",
                                 path, kSamplingLogHeader));
  }
  if (!resume) {
    throw InputError(fmt::format("{}: file exists (it may hold measurements): pass --resume to "
                                 "continue it, or choose another output file",
                                 path));
  }
  return true;
}

// Whether the samples were taken on the fly (times and torques in every row);
// throws InputError when that is not how this session samples (columns).
bool on_the_fly_as_planned(const Samples& s, SampleColumns columns, const std::string& path) {
  const bool on_the_fly = s.t.size() == s.size() && s.tau_last.size() == s.size() && s.tau_between.size() == s.size();
  if (s.size() > 0 && on_the_fly != (columns == SampleColumns::kOnTheFly)) {
    throw InputError(fmt::format("{}: its samples were taken {} and this session samples {}: the file was recorded "
                                 "with another plan; choose another output file",
                                 path, on_the_fly ? "on the fly" : "at rest",
                                 columns == SampleColumns::kOnTheFly ? "on the fly" : "at rest"));
  }
  return on_the_fly;
}

// The commanded targets (target_x, target_y: not read by the samples parser,
// which takes true positions x, y) of the first n rows of the log text, in file
// order; none where the columns are missing; throws InputError naming the line
// of one that is not a number.
std::vector<std::optional<Eigen::Vector2d>> commanded_targets(const std::string& text, size_t n,
                                                              const std::string& path) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::vector<std::string> f;
    std::stringstream ls(line);
    std::string cell;
    while (std::getline(ls, cell, ',')) f.push_back(cell);
    if (!f.empty()) rows.push_back(f);
  }
  int cx = -1, cy = -1;
  for (size_t k = 0; !rows.empty() && k < rows[0].size(); ++k) {
    if (rows[0][k] == "target_x") cx = static_cast<int>(k);
    if (rows[0][k] == "target_y") cy = static_cast<int>(k);
  }
  std::vector<std::optional<Eigen::Vector2d>> targets(n);
  for (size_t j = 0; j < n; ++j) {
    if (cx < 0 || cy < 0 || j + 1 >= rows.size() || static_cast<int>(rows[j + 1].size()) <= std::max(cx, cy)) continue;
    try {
      targets[j] = Eigen::Vector2d(std::stod(rows[j + 1][static_cast<size_t>(cx)]),
                                   std::stod(rows[j + 1][static_cast<size_t>(cy)]));
    } catch (const std::exception&) {
      throw InputError(fmt::format("{}: line {}: target_x, target_y are not numbers", path, j + 2));
    }
  }
  return targets;
}

// Sample j's motion as a log of samples on the fly recorded it.
SampleMotion motion_of(const Samples& s, size_t j) {
  SampleMotion m;
  m.t_s = s.t[j];
  m.tau = s.tau.size() == s.size() ? s.tau[j] : s.tau_last[j];
  m.tau_last = s.tau_last[j];
  m.tau_between = s.tau_between[j];
  m.t_read = s.t_read.size() == s.size() ? s.t_read[j] : Eigen::Vector3d::Constant(s.t[j]);
  return m;
}

}  // namespace

void SampleLog::read_existing(bool resume) {
  std::string text = read_bounded(fd_, path_);
  if (!holds_rows_to_resume(fd_, text, header_of(columns_), resume, path_)) return;
  // A torn last line (crash while writing) is dropped once the rest is read.
  const size_t read = text.size(), kept = text.rfind('\n') + 1;
  text.resize(kept);
  const Samples s = parse_samples_csv(text, path_);
  const bool on_the_fly = on_the_fly_as_planned(s, columns_, path_);
  const std::vector<std::optional<Eigen::Vector2d>> targets = commanded_targets(text, s.size(), path_);
  for (size_t j = 0; j < s.size(); ++j) {
    ids_.insert(s.id[j]);  // each id once: parse_samples_csv refuses an id twice
    Recorded r;
    r.theta_m = s.theta_m[j];
    if (targets[j]) r.target = *targets[j], r.has_target = true;
    if (on_the_fly) r.motion = motion_of(s, j);
    recorded_[s.id[j]] = r;
  }
  if (kept != read && ::ftruncate(fd_, static_cast<off_t>(kept)) != 0)
    throw InputError(fmt::format("{}: cannot drop the torn last line: {}", path_, std::strerror(errno)));
}

SampleLog::~SampleLog() {
  if (!closed_) close_and_discard_if_empty();
}

void SampleLog::write_row(const std::string& row, bool sync) {
  if (closed_) throw HardwareError(fmt::format("{}: sample log is closed", path_));
  if (in_memory_) return;
  if (fd_ < 0) throw HardwareError(fmt::format("{}: sample log is not open", path_));
  write_all(fd_, row, path_, sync && !in_place_);
}

void SampleLog::append(long id, const Eigen::Vector3d& q, const Eigen::Vector2d& target) {
  if (columns_ != SampleColumns::kAtRest)
    throw HardwareError(fmt::format("{}: a log of samples on the fly takes their torques and times", path_));
  write_row(fmt::format("{},{},{},{},{},{}\n", id, format_exact(q[0]), format_exact(q[1]), format_exact(q[2]),
                        format_exact(target.x()), format_exact(target.y())),
            true);
  ids_.insert(id);
  recorded_[id] = Recorded{q, true, target, std::nullopt};
}

void SampleLog::append(long id, const Eigen::Vector3d& q, const Eigen::Vector2d& target, const SampleMotion& m) {
  if (columns_ != SampleColumns::kOnTheFly)
    throw HardwareError(fmt::format("{}: a log of samples at rest has no torque or time columns", path_));
  write_row(fmt::format("{},{},{},{},{},{}{}{}{}{},{}\n", id, format_exact(q[0]), format_exact(q[1]),
                        format_exact(q[2]), format_exact(target.x()), format_exact(target.y()), triple_fields(m.tau),
                        triple_fields(m.tau_last), triple_fields(m.tau_between), triple_fields(m.t_read),
                        format_exact(m.t_s)),
            false);
  ids_.insert(id);
  recorded_[id] = Recorded{q, true, target, m};
}

void SampleLog::sync() {
  if (fd_ >= 0 && !in_place_ && ::fsync(fd_) != 0)
    throw HardwareError(fmt::format("{}: fsync failed: {}", path_, std::strerror(errno)));
}

void SampleLog::close_and_discard_if_empty() {
  closed_ = true;
  if (created_ && ids_.empty()) {
    std::error_code ec;
    std::filesystem::remove(path_, ec);
  } else if (fd_ >= 0 && !in_place_) {
    (void)::fsync(fd_);  // what was appended reaches the disk
  }
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

}  // namespace gpm::hw
