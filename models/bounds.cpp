// Documented ranges of user numbers and input file sizes (models/bounds.hpp).
#include "models/bounds.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>

#include <fmt/format.h>

#include "models/errors.hpp"
#include "models/yaml_util.hpp"

namespace gpm {
namespace {

// What a file that is not a regular one is, for messages.
const char* file_kind(mode_t mode) {
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "a special file";
}

// A limit as a reader writes it: 2000, 1e10, 9007199254740992, 1e-12.
std::string limit_text(double x) {
  if (x == std::floor(x) && std::abs(x) < 1e16) {
    std::string g = fmt::format("{:g}", x);  // 1e+10 -> 1e10, as one types it
    if (const auto e = g.find("e+"); e != std::string::npos) {
      std::size_t d = e + 2;
      while (d + 1 < g.size() && g[d] == '0') ++d;
      g = g.substr(0, e + 1) + g.substr(d);
    }
    if (std::abs(x) >= 1e6 && std::stod(g) == x) return g;
    return fmt::format("{:.0f}", x);
  }
  return fmt::format("{}", x);
}

[[noreturn]] void refuse(const Bound& b, std::string_view where, std::string_view text) {
  throw InputError(fmt::format("{}: must be {}, got '{}'", where, describe(b), text));
}

}  // namespace

std::string describe(const Bound& b) {
  std::string out = fmt::format("{} from {} to {}", b.whole ? "a whole number" : "a number", limit_text(b.lo),
                                limit_text(b.hi));
  if (*b.unit) out += fmt::format(" {}", b.unit);
  return out;
}

bool within(double v, const Bound& b) {
  return std::isfinite(v) && v >= b.lo && v <= b.hi && (!b.whole || v == std::floor(v));
}

double check_bound(double v, const Bound& b, std::string_view where, std::string_view text) {
  if (!within(v, b)) refuse(b, where, text.empty() ? fmt::format("{}", v) : std::string(text));
  return v;
}

double parse_bounded(std::string_view text, const Bound& b, std::string_view where) {
  std::string_view s = text;
  while (!s.empty() && s.front() == ' ') s.remove_prefix(1);
  while (!s.empty() && s.back() == ' ') s.remove_suffix(1);
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  double v = 0.0;
  const auto [p, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || ec != std::errc() || p != s.data() + s.size()) refuse(b, where, text);
  return check_bound(v, b, where, text);
}

double yaml_within(const YAML::Node& node, const std::string& file, std::string_view keypath, const Bound& b) {
  const double v = yaml_number(node, file, keypath);
  if (!within(v, b)) {
    throw InputError(yaml_where(file, node, keypath) + fmt::format("must be {}, got {}", describe(b), node.Scalar()));
  }
  return v;
}

std::vector<std::string> split_unique_list(std::string_view list, std::string_view where) {
  std::vector<std::string> items;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = list.find(',', start);
    std::string_view item = list.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start);
    while (!item.empty() && item.front() == ' ') item.remove_prefix(1);
    while (!item.empty() && item.back() == ' ') item.remove_suffix(1);
    for (std::size_t k = 0; k < items.size(); ++k) {
      if (!item.empty() && items[k] == item) {
        throw InputError(fmt::format("{}: '{}' is given twice (items {} and {}); give each once", where, item, k + 1,
                                     items.size() + 1));
      }
    }
    items.emplace_back(item);
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return items;
}

std::string read_input_file(const std::string& path, std::size_t max_bytes) {
  // Opened without blocking: a FIFO with no writer would wait forever in
  // open(2); it is refused below, as is every other non-regular file.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) throw InputError(fmt::format("{}: cannot open file (does it exist and is it readable?)", path));
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    if (S_ISDIR(st.st_mode)) throw InputError(fmt::format("{}: is a folder, not a file", path));
    throw InputError(fmt::format("{}: is {}, not a regular file (inputs are read from files); give the file itself",
                                 path, file_kind(st.st_mode)));
  }
  // Read in chunks up to one byte past the limit: a file that grows while it
  // is read is refused without being held in memory.
  std::string text;
  char chunk[65536];
  while (text.size() <= max_bytes) {
    const ssize_t n = ::read(fd, chunk, sizeof chunk);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int err = errno;
      ::close(fd);
      throw InputError(fmt::format("{}: cannot read: {}", path, std::strerror(err)));
    }
    if (n == 0) break;
    text.append(chunk, static_cast<std::size_t>(n));
  }
  ::close(fd);
  if (text.size() > max_bytes) {
    throw InputError(fmt::format("{}: larger than {} MiB, the limit for this kind of file (is it the right file?)",
                                 path, max_bytes >> 20));
  }
  return text;
}

}  // namespace gpm
