#include "models/output_file.hpp"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <optional>
#include <utility>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fmt/format.h>

#include "models/errors.hpp"
#include "models/measured_data.hpp"

namespace gpm {

namespace fs = std::filesystem;

namespace {

// ---- registry of temporaries, read by the signal handler -------------------

constexpr int kSlots = 64;
constexpr size_t kPathMax = 4096;
struct Slot {
  std::atomic<int> state{0};  // 0 free, 1 being changed, 2 holds a path
  char path[kPathMax];
};
Slot g_slots[kSlots];

std::string absolute(const std::string& p) {
  std::error_code ec;
  const fs::path a = fs::absolute(p, ec);
  return ec ? p : a.string();
}

std::string reason(int err) { return std::strerror(err); }

// Follows symbolic links (relative targets from the link's folder).
fs::path resolve_links(const fs::path& p, const std::string& given) {
  fs::path cur = p;
  for (int depth = 0; depth < 40; ++depth) {
    std::error_code ec;
    if (!fs::is_symlink(cur, ec)) return cur;
    const fs::path t = fs::read_symlink(cur, ec);
    if (ec) throw InputError(fmt::format("{}: cannot read the link: {}", given, ec.message()));
    cur = t.is_absolute() ? t : cur.parent_path() / t;
  }
  throw InputError(fmt::format("{}: too many levels of symbolic links", given));
}

// Same file: device and inode of two existing paths (links followed).
bool same_file(const std::string& a, const std::string& b) {
  struct stat sa {}, sb {};
  if (::stat(a.c_str(), &sa) != 0 || ::stat(b.c_str(), &sb) != 0) return false;
  return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
}

// ---- the files of one command (inputs and outputs), by identity ------------

using Identity = std::pair<dev_t, ino_t>;

// Device and inode of an existing regular file (links followed): only a
// regular file is replaced by an output (a device or FIFO is written in place).
std::optional<Identity> regular_identity(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) return std::nullopt;
  return Identity{st.st_dev, st.st_ino};
}

struct CommandFiles {
  std::mutex mutex;
  bool on = false;
  std::vector<std::pair<std::string, Identity>> inputs;  // as read
  std::vector<std::string> outputs;                      // as declared
};

CommandFiles& command_files() {
  static CommandFiles files;
  return files;
}

std::string input_output_refusal(const std::string& output, const std::string& input) {
  return fmt::format("{}: is also an input of this command ({}); choose another output", output, input);
}

void write_text(const std::string& file, const std::string& text, const std::string& given) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  if (!out) throw InputError(fmt::format("{}: cannot write: {}", given, reason(errno)));
  out << text;
  out.flush();
  if (!out) throw InputError(fmt::format("{}: write failed (disk full?)", given));
}

extern "C" void on_signal(int) {
  remove_registered_temporaries();
  static const char msg[] = "gpm: interrupted\n";
  [[maybe_unused]] const ssize_t n = ::write(STDERR_FILENO, msg, sizeof msg - 1);
  ::_exit(130);
}

}  // namespace

void register_temporary(const std::string& path) {
  const std::string a = absolute(path);
  if (a.size() >= kPathMax) return;
  for (Slot& s : g_slots) {
    int expected = 0;
    if (s.state.compare_exchange_strong(expected, 1)) {
      std::memcpy(s.path, a.c_str(), a.size() + 1);
      s.state.store(2);
      return;
    }
  }
}

void unregister_temporary(const std::string& path) {
  const std::string a = absolute(path);
  for (Slot& s : g_slots) {
    if (s.state.load() == 2 && a == s.path) {
      int expected = 2;
      if (s.state.compare_exchange_strong(expected, 1)) {
        s.state.store(0);
        return;
      }
    }
  }
}

void remove_registered_temporaries() noexcept {
  for (Slot& s : g_slots)
    if (s.state.load() == 2) ::unlink(s.path);
  // Folders last, inner ones (registered later) first; twice for nesting.
  for (int pass = 0; pass < 2; ++pass)
    for (int k = kSlots - 1; k >= 0; --k)
      if (g_slots[k].state.load() == 2) ::rmdir(g_slots[k].path);
}

void install_output_signal_cleanup() {
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) ::sigaction(sig, &sa, nullptr);
}

// ---- single files -----------------------------------------------------------

std::string temporary_name_for(const std::string& path) {
  const fs::path p(path);
  const fs::path tmp =
      p.parent_path() / fmt::format(".{}.tmp{}", p.filename().string(), static_cast<long>(::getpid()));
  return tmp.string();
}

void refuse_output_equal_to_input(const std::string& output, const std::vector<std::string>& inputs) {
  for (const std::string& in : inputs) {
    if (!in.empty() && same_file(output, in))
      throw InputError(fmt::format("{}: is also an input of this command ({}); choose another output", output, in));
  }
}

void track_command_files(bool on) {
  CommandFiles& c = command_files();
  const std::lock_guard<std::mutex> lock(c.mutex);
  c.on = on;
  c.inputs.clear();
  c.outputs.clear();
}

void note_input(const std::string& path) {
  CommandFiles& c = command_files();
  const std::lock_guard<std::mutex> lock(c.mutex);
  if (!c.on) return;
  const std::optional<Identity> id = regular_identity(path);
  if (!id) return;  // missing (the reader says so) or not a regular file
  for (const std::string& out : c.outputs)
    if (regular_identity(out) == id) throw InputError(input_output_refusal(out, path));
  for (const auto& [p, known] : c.inputs)
    if (known == *id) return;
  c.inputs.emplace_back(path, *id);
}

void declare_output(const std::string& path) {
  CommandFiles& c = command_files();
  const std::lock_guard<std::mutex> lock(c.mutex);
  if (!c.on || path.empty()) return;
  if (const std::optional<Identity> id = regular_identity(path))
    for (const auto& [in, known] : c.inputs)
      if (known == *id) throw InputError(input_output_refusal(path, in));
  for (const std::string& out : c.outputs)
    if (out == path) return;
  c.outputs.push_back(path);
}

void check_output_folder(const std::string& dir, const std::vector<std::string>& names, const MeasuredFolder* owner) {
  if (dir.empty()) throw InputError("output folder name is empty");
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    throw InputError(fmt::format("{}: exists and is not a folder", dir));
  refuse_measured_folder(dir, owner);
  for (const std::string& n : names) {
    declare_output((fs::path(dir) / n).string());
    refuse_measured_file((fs::path(dir) / n).string(), owner);  // e.g. a gpm sample log named DIR/samples.csv
  }
}

OutputFile::OutputFile(const std::string& path, const std::vector<std::string>& inputs) : path_(path) {
  if (path.empty()) throw InputError("output file name is empty");
  refuse_output_equal_to_input(path, inputs);
  declare_output(path);
  const fs::path target = resolve_links(fs::path(path), path);
  target_ = target.string();
  struct stat st {};
  if (::stat(target_.c_str(), &st) == 0) {
    if (S_ISDIR(st.st_mode)) throw InputError(fmt::format("{}: is a folder, not a file name", path));
    if (S_ISSOCK(st.st_mode)) throw InputError(fmt::format("{}: is a socket, not a file", path));
    if (!S_ISREG(st.st_mode)) {  // device or FIFO: written in place, never replaced
      in_place_ = true;
      write_path_ = target_;
      return;
    }
  }
  refuse_measured_file(target_);
  const fs::path dir = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    throw InputError(fmt::format("{}: cannot write: folder {} does not exist", path, dir.string()));
  write_path_ = temporary_name_for(target_);
  // Keep an existing file's permissions; new files get 0666 less the umask.
  const mode_t mode = ::stat(target_.c_str(), &st) == 0 ? (st.st_mode & 07777) : 0666;
  register_temporary(write_path_);
  const int fd = ::open(write_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, mode);
  if (fd < 0) {
    const int err = errno;
    unregister_temporary(write_path_);
    throw InputError(fmt::format("{}: cannot write: {}", path, reason(err)));
  }
  if (mode != 0666 && ::fchmod(fd, mode) != 0) {
    // the staged file keeps the default permissions
  }
  ::close(fd);
}

OutputFile::OutputFile(OutputFile&& o) noexcept
    : path_(std::move(o.path_)), target_(std::move(o.target_)), write_path_(std::move(o.write_path_)),
      in_place_(o.in_place_), done_(o.done_) {
  o.done_ = true;
}

OutputFile::~OutputFile() { discard(); }

void OutputFile::discard() noexcept {
  if (done_) return;
  done_ = true;
  if (in_place_) return;
  ::unlink(write_path_.c_str());
  unregister_temporary(write_path_);
}

void OutputFile::commit() {
  if (done_) return;
  if (in_place_) {
    done_ = true;
    return;
  }
  if (::rename(write_path_.c_str(), target_.c_str()) != 0) {
    const int err = errno;
    discard();
    throw InputError(fmt::format("{}: cannot write: {}", path_, reason(err)));
  }
  done_ = true;
  unregister_temporary(write_path_);
}

void write_output_file(const std::string& path, const std::string& text, const std::vector<std::string>& inputs) {
  OutputFile out(path, inputs);
  write_text(out.write_path(), text, path);
  out.commit();
}

void check_output_file(const std::string& path, const std::vector<std::string>& inputs) {
  OutputFile probe(path, inputs);
  probe.discard();
}

void commit_output_file(const std::string& tmp, const std::string& path) {
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    unregister_temporary(tmp);
    throw InputError(fmt::format("{}: cannot write: {}", path, reason(err)));
  }
  unregister_temporary(tmp);
}

// ---- folders ----------------------------------------------------------------

OutputFolder::OutputFolder(const std::string& dir, const std::vector<std::string>& inputs,
                           const MeasuredFolder* owner)
    : dir_(dir), inputs_(inputs), owner_(owner) {
  if (dir.empty()) throw InputError("output folder name is empty");
  const fs::path target = resolve_links(fs::path(dir), dir);
  target_ = target.string();
  std::error_code ec;
  if (fs::exists(target, ec) && !fs::is_directory(target, ec))
    throw InputError(fmt::format("{}: exists and is not a folder", dir));
  refuse_measured_folder(target_, owner_);
  if (!fs::exists(target, ec)) {
    // Creates the missing folders; only the last one is removed again.
    fs::create_directories(target, ec);
    if (ec) throw InputError(fmt::format("{}: cannot create the output folder: {}", dir, ec.message()));
    created_ = true;
    register_temporary(target.string());
  }
  stage_ = (target / fmt::format(".gpm-output.tmp{}", static_cast<long>(::getpid()))).string();
  register_temporary(stage_);
  if (::mkdir(stage_.c_str(), 0777) != 0 && errno != EEXIST) {
    const int err = errno;
    unregister_temporary(stage_);
    if (created_) {
      ::rmdir(target.c_str());
      unregister_temporary(target.string());
    }
    throw InputError(fmt::format("{}: cannot write in the output folder: {}", dir, reason(err)));
  }
}

OutputFolder::~OutputFolder() {
  std::error_code ec;
  for (const std::string& n : names_) {
    const std::string p = (fs::path(stage_) / n).string();
    ::unlink(p.c_str());
    unregister_temporary(p);
  }
  fs::remove_all(stage_, ec);
  unregister_temporary(stage_);
  if (created_) {
    if (!committed_) ::rmdir(target_.c_str());  // only when empty
    unregister_temporary(target_);
  }
}

std::string OutputFolder::staged_path(const std::string& name) {
  if (name.empty() || name.find('/') != std::string::npos)
    throw InputError(fmt::format("{}: '{}' is not a plain file name", dir_, name));
  const std::string p = (fs::path(stage_) / name).string();
  for (const std::string& n : names_)
    if (n == name) return p;
  declare_output((fs::path(dir_) / name).string());  // against the inputs tracked, before it is written
  refuse_measured_file((fs::path(target_) / name).string(), owner_);  // a sampling log there is never replaced
  names_.push_back(name);
  register_temporary(p);
  return p;
}

void OutputFolder::add(const std::string& name, const std::string& text) {
  write_text(staged_path(name), text, (fs::path(dir_) / name).string());
}

void OutputFolder::commit() {
  refuse_measured_folder(target_, owner_);  // a hardware session may have begun meanwhile
  // Every file is checked before any is moved: a refusal leaves dir as it was.
  std::vector<OutputFile> targets;
  targets.reserve(names_.size());
  for (const std::string& n : names_) targets.emplace_back((fs::path(dir_) / n).string(), inputs_);
  for (size_t k = 0; k < names_.size(); ++k) {
    const std::string staged = (fs::path(stage_) / names_[k]).string();
    OutputFile& t = targets[k];
    if (t.in_place()) {
      std::ifstream in(staged, std::ios::binary);
      std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      write_text(t.write_path(), text, t.path());
      t.commit();
    } else {
      const std::string target = t.target();
      t.discard();
      commit_output_file(staged, target);
    }
  }
  names_.clear();
  committed_ = true;
}

void OutputFolder::keep_only(const std::vector<std::string>& keep) {
  std::vector<std::string> kept;
  for (const std::string& n : names_) {
    if (std::find(keep.begin(), keep.end(), n) != keep.end()) {
      kept.push_back(n);
      continue;
    }
    const std::string p = (fs::path(stage_) / n).string();
    ::unlink(p.c_str());
    unregister_temporary(p);
  }
  names_ = kept;
}

}  // namespace gpm
