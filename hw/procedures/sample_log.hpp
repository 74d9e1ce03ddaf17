// Samples file written as they are taken: each sample is one line appended
// and flushed to disk (fsync) at once, so a crash or a lost connection loses
// nothing already measured; a session can resume, skipping recorded samples.
// Columns: sample,theta_m1,theta_m2,theta_m3,target_x,target_y (docs/ARCHITECTURE.md
// samples contract; target_* are the commanded poses, not true positions).
#pragma once

#include <map>
#include <set>
#include <string>

#include <Eigen/Core>

struct stat;

namespace gpm::hw {

class SampleLog {
 public:
  // One recorded row (for checking a resumed plan).
  struct Recorded {
    Eigen::Vector3d theta_m = Eigen::Vector3d::Zero();
    bool has_target = false;
    Eigen::Vector2d target = Eigen::Vector2d::Zero();
  };

  // Opens path for appending and holds an exclusive lock (flock) on it while
  // open: a second log on the same file is refused (InputError). An existing
  // file is read (at most limits::kMaxCsvBytes) and left as it is unless it is
  // a sampling log (first line kSamplingLogHeader, models/measured_data.hpp):
  // an empty file or a header alone is started again; without resume a log
  // holding rows is refused (InputError: never overwrite them). With resume
  // its complete rows are kept (a torn last line from a crash is dropped once
  // the rest is read) and their ids skipped; an id found twice is refused. A file that does not
  // exist is created with its header at once (InputError when it cannot be:
  // refused before anything moves) and removed again when the log is closed
  // or destroyed without a sample, so a session that records nothing leaves
  // no file. An existing device or FIFO is written in place (the
  // output policy): the header at once (a refusal here, before anything
  // moves), no lock, no fsync, no resume; a folder or socket is refused.
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
  // Closes the file; removes it if this log created it and it holds no
  // sample (the destructor does the same).
  void close_and_discard_if_empty();
  const std::string& path() const { return path_; }
  // The rows of the file by id: those found when it was opened and those
  // appended since.
  const std::map<long, Recorded>& recorded() const { return recorded_; }

 private:
  // Reads the rows of the file open on fd_ (locked), see the constructor.
  void read_existing(bool resume);
  // Creates the file with its header and locks it (see the constructor).
  void create_now();
  // Opens the device or FIFO st describes for writing in place.
  void open_in_place(const struct stat& st, bool resume);

  std::string path_;
  int fd_ = -1;
  bool created_ = false;
  bool closed_ = false;
  bool in_place_ = false;  // a device or FIFO
  std::set<long> ids_;
  std::map<long, Recorded> recorded_;
};

}  // namespace gpm::hw
