// Encoder samples (docs/FORMATS.md, file contracts): CSV with a header row, columns
// found by name, others ignored: sample,theta_m1,theta_m2,theta_m3[,x,y] with
// readings in rad and, where known (simulation), the true end-effector in mm;
// optional: t (s, when each reading was taken, increasing), the drive torques
// tau1..3, tau_last1..3, tau_between1..3 (N m) and t_read1..3 (s, when each
// joint's reading was taken, where the drives are read one after another;
// each triple all or none).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace gpm {

struct Samples {
  std::vector<long> id;                    // the `sample` column (or 0..n-1)
  std::vector<Eigen::Vector3d> theta_m;    // encoder readings (rad)
  std::vector<Eigen::Vector2d> xy;         // true end-effector (mm), if has_xy
  bool has_xy = false;
  std::vector<double> t;                   // `t`: time of each reading (s), empty if the file has none
  // Drive torques (N m), each empty if the file has none: the sample's (tau1..3),
  // the drive period's just before the reading (tau_last1..3) and the mean over the
  // periods since the sample before (tau_between1..3; sim/sampling.hpp SampleRecord).
  std::vector<Eigen::Vector3d> tau, tau_last, tau_between;
  // `t_read1..3`: when each joint's reading was taken (s; t is the sample's
  // instant), empty if the file has none.
  std::vector<Eigen::Vector3d> t_read;

  size_t size() const { return theta_m.size(); }
};

// Reads a samples CSV; throws InputError naming the file, line and column for
// missing columns, non-numeric or non-finite values, and rows whose field count
// differs from the header's (strict reader).
Samples read_samples_csv(const std::string& path);

// Parses samples CSV text; file names the source in errors.
Samples parse_samples_csv(const std::string& text, const std::string& file);

// CSV text of samples (header and rows), numbers written exactly.
std::string samples_to_csv(const Samples& s);

// Writes samples atomically.
void write_samples_csv(const Samples& s, const std::string& path);

}  // namespace gpm
