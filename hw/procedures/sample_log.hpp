// Samples file written as they are taken: each sample is one line appended
// and flushed to disk (fsync) at once, so a crash or a lost connection loses
// nothing already measured; a session can resume, skipping recorded samples.
// Columns: sample,theta_m1,theta_m2,theta_m3,target_x,target_y (docs/FORMATS.md
// samples contract; target_* are the commanded poses, not true positions);
// samples taken on the fly add the drive torques tau1..3, tau_last1..3,
// tau_between1..3, each joint's read time t_read1..3 and the sample's time t.
#pragma once

#include <map>
#include <optional>
#include <set>
#include <string>

#include <Eigen/Core>

struct stat;

namespace gpm::hw {

// Which columns a samples file has.
enum class SampleColumns { kAtRest, kOnTheFly };

// What the drives report of a sample taken on the fly (sim/sampling.hpp
// SampleRecord has the same on the twin).
struct SampleMotion {
  double t_s = 0.0;                                       // the sample's instant (s, the cycle's time)
  Eigen::Vector3d t_read = Eigen::Vector3d::Zero();       // when each joint's reading was taken (s)
  Eigen::Vector3d tau = Eigen::Vector3d::Zero();          // drive torque read with the readings (N m)
  Eigen::Vector3d tau_last = Eigen::Vector3d::Zero();     // the cycle's before (N m)
  Eigen::Vector3d tau_between = Eigen::Vector3d::Zero();  // mean over the cycles since the sample before (N m)
};

class SampleLog {
 public:
  // One recorded row (for checking a resumed plan, and for the calibration).
  struct Recorded {
    Eigen::Vector3d theta_m = Eigen::Vector3d::Zero();
    bool has_target = false;
    Eigen::Vector2d target = Eigen::Vector2d::Zero();
    std::optional<SampleMotion> motion;  // on the fly
  };

  // Opens path for appending and holds an exclusive lock (flock) on it while
  // open: a second log on the same file is refused (InputError). An existing
  // file is read (at most limits::kMaxCsvBytes) and left as it is unless it is
  // a sampling log (first line kSamplingLogHeader, models/measured_data.hpp):
  // an empty file or a header alone is started again; without resume a log
  // holding rows is refused (InputError: never overwrite them). With resume
  // its complete rows are kept (a torn last line from a crash is dropped once
  // the rest is read) and their ids skipped; an id found twice is refused (parse_samples_csv). A file that does not
  // exist is created with its header at once (InputError when it cannot be:
  // refused before anything moves) and removed again when the log is closed
  // or destroyed without a sample, so a session that records nothing leaves
  // no file. An existing device or FIFO is written in place (the
  // output policy): the header at once (a refusal here, before anything
  // moves), no lock, no fsync, no resume; a folder or socket is refused.
  // columns: the file's columns; a resumed file with other columns is refused.
  SampleLog(const std::string& path, bool resume, SampleColumns columns = SampleColumns::kAtRest);
  // A log in memory (the in-process twin of gpm run: its caller writes the
  // samples with the twin's truth): rows are recorded, nothing is written.
  explicit SampleLog(SampleColumns columns);
  ~SampleLog();
  SampleLog(const SampleLog&) = delete;
  SampleLog& operator=(const SampleLog&) = delete;

  // True when sample id is already in the file.
  bool has(long id) const { return ids_.count(id) > 0; }
  // Number of samples in the file.
  size_t size() const { return ids_.size(); }
  // Appends one sample at rest and flushes it to disk; throws HardwareError if it cannot.
  void append(long id, const Eigen::Vector3d& theta_m, const Eigen::Vector2d& target);
  // Appends one sample taken on the fly (a log of SampleColumns::kOnTheFly):
  // written at once (a crash of the process loses nothing), flushed to disk
  // by sync(), which a loop at the drive rate calls every few samples.
  void append(long id, const Eigen::Vector3d& theta_m, const Eigen::Vector2d& target, const SampleMotion& motion);
  // Flushes what was appended to disk (fsync; nothing for a device or FIFO).
  void sync();
  // Flushes and closes the file; removes it if this log created it and it
  // holds no sample (the destructor does the same).
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
  // Writes one row to the open file; sync: fsync it.
  void write_row(const std::string& row, bool sync);

  std::string path_;
  int fd_ = -1;
  bool created_ = false;
  bool closed_ = false;
  bool in_place_ = false;  // a device or FIFO
  bool in_memory_ = false;  // nothing written (SampleLog(SampleColumns))
  SampleColumns columns_ = SampleColumns::kAtRest;
  std::set<long> ids_;
  std::map<long, Recorded> recorded_;
};

}  // namespace gpm::hw
