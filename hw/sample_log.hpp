// Samples file written as they are taken: each sample is one line appended
// and flushed to disk (fsync) at once, so a crash or a lost connection loses
// nothing already measured; a session can resume, skipping recorded samples.
// Columns: sample,theta_m1,theta_m2,theta_m3,target_x,target_y (DESIGN.md
// samples contract; target_* are the commanded poses, not true positions).
#pragma once

#include <set>
#include <string>

#include <Eigen/Core>

namespace gpm::hw {

class SampleLog {
 public:
  // Opens path for appending. Without resume an existing file is refused
  // (InputError: never overwrite measurements); with resume its complete rows
  // are kept (a torn last line from a crash is dropped) and their ids skipped.
  SampleLog(const std::string& path, bool resume);
  ~SampleLog();
  SampleLog(const SampleLog&) = delete;
  SampleLog& operator=(const SampleLog&) = delete;

  // True when sample id is already in the file.
  bool has(long id) const { return ids_.count(id) > 0; }
  // Number of samples in the file.
  size_t size() const { return ids_.size(); }
  // Appends one sample and flushes it to disk; throws HardwareError if it cannot.
  void append(long id, const Eigen::Vector3d& theta_m, const Eigen::Vector2d& target);
  // Closes the file; removes it if this log created it and it holds no sample.
  void close_and_discard_if_empty();
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  int fd_ = -1;
  bool created_ = false;
  std::set<long> ids_;
};

}  // namespace gpm::hw
