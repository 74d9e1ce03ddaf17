// The output policy of every file the toolkit writes (docs/CLI.md,
// "Output files"), in one place:
// - a regular file (or a new one) is staged as a hidden temporary in the same
//   folder and renamed over the target when complete: all or nothing;
// - an existing device or FIFO (e.g. /dev/null) is written in place, never
//   replaced; a folder or a socket is refused;
// - a symbolic link is followed: its target is replaced, the link stays;
// - an output that is also an input of the command (same device and inode)
//   is refused, whichever the command meets first: the command line tracks
//   every file a command reads (note_input, called by the readers) and every
//   file it will write (declare_output, check_output_folder);
// - a folder holding measured samples is written only by its hardware
//   session (models/measured_data.hpp);
// - temporaries are removed on every exit path: destructors on errors, and
//   on SIGINT/SIGTERM/SIGHUP the handler of install_output_signal_cleanup().
// Every refusal is an InputError naming the path.
#pragma once

#include <string>
#include <vector>

namespace gpm {

class MeasuredFolder;

// One output file being written.
class OutputFile {
 public:
  // Prepares writing path: resolves symbolic links, refuses a folder, a
  // socket, a missing folder, any of inputs or of the inputs tracked
  // (same file), a measured samples file (refuse_measured_file), and creates
  // the temporary (so an unwritable folder fails here, before any work).
  explicit OutputFile(const std::string& path, const std::vector<std::string>& inputs = {});
  // Removes the temporary unless committed.
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;
  OutputFile(OutputFile&& other) noexcept;
  OutputFile& operator=(OutputFile&&) = delete;

  // Where the writer writes: the temporary, or the target itself when the
  // target is a device or FIFO.
  const std::string& write_path() const { return write_path_; }
  // The path as given (for messages).
  const std::string& path() const { return path_; }
  // The file that is replaced or written (symbolic links resolved).
  const std::string& target() const { return target_; }
  // True when the target is written in place (device, FIFO).
  bool in_place() const { return in_place_; }
  // Renames the temporary over the target (nothing to do in place); throws
  // InputError naming the path (the temporary is removed).
  void commit();
  // Removes the temporary (nothing in place); safe to call twice.
  void discard() noexcept;

 private:
  std::string path_, target_, write_path_;
  bool in_place_ = false;
  bool done_ = false;
};

// Writes text to path by the policy; throws InputError naming the path
// ("disk full?" when the write fails, the system's reason otherwise).
void write_output_file(const std::string& path, const std::string& text,
                       const std::vector<std::string>& inputs = {});

// Throws InputError "OUTPUT: is also an input of this command (INPUT)" when
// output names an existing file that is one of inputs (device and inode).
void refuse_output_equal_to_input(const std::string& output, const std::vector<std::string>& inputs);

// ---- every input against every output of one command (file identity) ------
// While tracking is on (the gpm command line turns it on for its command),
// every file a reader opens (load_yaml_file, read_samples_csv: the files a
// scenario or a hardware file names too) is noted, every output path is
// declared, and an output that is the same regular file as an input (device
// and inode, links followed) throws InputError "OUTPUT: is also an input of
// this command (INPUT); choose another output", whichever of the two came
// first: a command that declares its outputs before it reads is refused
// before it parses anything. Off (the default, e.g. in the Python module):
// nothing is kept.
void track_command_files(bool on);
// Notes an input the command reads (before reading it); throws as above.
void note_input(const std::string& path);
// Declares an output the command will write; throws as above.
void declare_output(const std::string& path);

// Checks an output folder before any work: refuses a path that exists and
// is not a folder and a folder holding measured samples unless owner is its
// session (models/measured_data.hpp), and declares dir/NAME for each of names
// (the files the command writes there). Creates nothing.
void check_output_folder(const std::string& dir, const std::vector<std::string>& names,
                         const MeasuredFolder* owner = nullptr);

// A folder of outputs written all or nothing: files are staged in a hidden
// folder inside dir and moved into place by commit(), each by the policy of
// OutputFile (a file of dir that is a symlink or a device is followed or
// written in place). Other files of dir are kept. A folder created here is
// removed again when nothing was committed. A folder holding measured
// samples is refused (at construction and again at commit) unless owner is
// its hardware session.
class OutputFolder {
 public:
  // Creates dir when missing; throws InputError when it is not a folder,
  // cannot be written or holds another session's measured samples.
  explicit OutputFolder(const std::string& dir, const std::vector<std::string>& inputs = {},
                        const MeasuredFolder* owner = nullptr);
  // Removes the staging folder, and dir when it was created here and nothing
  // was committed.
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  // Stages file `name` (a plain name, no folder) with text.
  void add(const std::string& name, const std::string& text);
  // Path of a staged file `name` for writers that need a path; the caller
  // writes it completely before commit().
  std::string staged_path(const std::string& name);
  // Moves every staged file into dir; throws InputError naming the file.
  void commit();
  // Drops every staged file but those named in keep (commit() then moves
  // only these: what a command that could not write all its files keeps).
  void keep_only(const std::vector<std::string>& keep);
  // The folder.
  const std::string& dir() const { return dir_; }

 private:
  std::string dir_, target_, stage_;  // as given, links resolved, the staging folder
  std::vector<std::string> inputs_, names_;
  const MeasuredFolder* owner_ = nullptr;
  bool created_ = false, committed_ = false;
};

// Temporary name next to path: "<folder>/.<name>.tmp<pid>".
std::string temporary_name_for(const std::string& path);

// Checks that path can be written by the policy (as OutputFile does, the
// temporary created and removed again); throws InputError naming path.
void check_output_file(const std::string& path, const std::vector<std::string>& inputs = {});

// Renames tmp to path; throws InputError naming path (tmp is removed).
void commit_output_file(const std::string& tmp, const std::string& path);

// Registers a temporary (file or folder) for removal by the signal handler;
// unregister it once it is renamed or removed. At most 64 at once (more are
// still removed by destructors, not by the handler).
void register_temporary(const std::string& path);
void unregister_temporary(const std::string& path);

// Removes every registered temporary (files, then folders); async-signal-safe,
// for signal handlers of other commands (e.g. one that stops drives first).
void remove_registered_temporaries() noexcept;

// Installs handlers for SIGINT, SIGTERM and SIGHUP that remove the registered
// temporaries, print "gpm: interrupted" and exit 130. A command that installs
// its own handlers later replaces these (and should call
// remove_registered_temporaries()).
void install_output_signal_cleanup();

}  // namespace gpm
