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
// Every refusal is one InputError line naming the folder.
#pragma once

#include <string>

namespace gpm {

// The marker's file name inside a folder holding measured samples.
inline constexpr const char* kMeasuredMarker = ".gpm-measured";

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

// Throws InputError when path is the samples file named by the marker of its
// folder (links followed) and owner is not that folder's session.
void refuse_measured_file(const std::string& path, const MeasuredFolder* owner = nullptr);

}  // namespace gpm
