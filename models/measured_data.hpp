// The measured-data guard (docs/CLI.md, "Output files"): measured samples cannot be
// taken again, so a folder a hardware session records into is never written
// by anything else.
// - A hardware session that records into an output folder (gpm run
//   --hardware: DIR/samples.csv) holds a MeasuredFolder for its whole life:
//   the marker DIR/.gpm-measured (the session's kind and its samples file) is
//   written before anything moves and locked (flock) until the session's
//   command ends; it stays once samples were recorded.
// - Such a folder is refused as the output folder of any other command
//   (OutputFolder, check_output_folder), its samples file is never replaced
//   (OutputFile) nor appended by another session (gpm sample); only a session
//   of the same kind, with --resume, continues it, and never two at once.
// - A hardware sampling log (gpm sample -o FILE, wherever FILE lies) is
//   known by its first line (kSamplingLogHeader): once it holds a row it is
//   never replaced by an output of any command (OutputFile, OutputFolder,
//   check_output_folder); only a sampling session appends to it (hw::SampleLog:
//   with --resume, one at a time).
// Every refusal is one InputError line naming the folder or file.
#pragma once

#include <string>

namespace gpm {

// The marker's file name inside a folder holding measured samples.
inline constexpr const char* kMeasuredMarker = ".gpm-measured";
// The first line of a hardware sampling log (hw/procedures/sample_log.hpp);
// a log of samples taken on the fly continues it with
// kSamplingLogOnTheFlyColumns.
inline constexpr const char* kSamplingLogHeader = "sample,theta_m1,theta_m2,theta_m3,target_x,target_y";
inline constexpr const char* kSamplingLogOnTheFlyColumns =
    ",tau1,tau2,tau3,tau_last1,tau_last2,tau_last3,tau_between1,tau_between2,tau_between3,t_read1,t_read2,t_read3,t";

class MeasuredFolder {
 public:
  // Opens dir (created when missing) for a hardware session of kind (e.g.
  // "gpm run --hardware") that appends its samples to dir/samples_name: writes
  // the marker and locks it. Throws InputError when dir is not a folder,
  // another session holds the lock, the marker names another kind, or
  // dir/samples_name exists without a marker (samples no session of this
  // folder recorded, e.g. a simulation's).
  MeasuredFolder(const std::string& dir, const std::string& kind, const std::string& samples_name);
  // Releases the lock. When no samples file exists (nothing was recorded),
  // removes the marker written here, and dir when it was created here and is empty.
  ~MeasuredFolder();
  MeasuredFolder(const MeasuredFolder&) = delete;
  MeasuredFolder& operator=(const MeasuredFolder&) = delete;

  const std::string& dir() const { return dir_; }
  // dir/samples_name: where the session appends its samples.
  std::string samples_path() const;

 private:
  std::string dir_, kind_, samples_name_;
  int fd_ = -1;
  bool created_dir_ = false, created_marker_ = false;
};

// A marker with neither samples nor a session holding it (a session killed
// before its first sample) guards nothing: the checks below remove it.
// Throws InputError when dir holds measured samples (its marker) and owner is
// not the session holding dir: "DIR: holds the measured samples of a gpm run
// --hardware session (DIR/.gpm-measured); ..." or, while that session runs,
// "DIR: a hardware session is recording into this folder now ...".
void refuse_measured_folder(const std::string& dir, const MeasuredFolder* owner = nullptr);

// True when path (links followed) is a regular file whose first line is
// kSamplingLogHeader (alone or continued by kSamplingLogOnTheFlyColumns) and
// which holds more than that line: measured samples.
bool is_sampling_log(const std::string& path);

// Throws InputError when path is the samples file named by the marker of its
// folder (links followed) and owner is not that folder's session, or, unless
// sampling_session (the caller appends to a log by hw::SampleLog's rules), when
// path is a sampling log holding samples (is_sampling_log) and owner does not
// hold its folder.
void refuse_measured_file(const std::string& path, const MeasuredFolder* owner = nullptr,
                          bool sampling_session = false);

}  // namespace gpm
