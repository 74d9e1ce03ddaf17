#include "models/samples.hpp"

#include <charconv>
#include <cmath>
#include <sstream>
#include <unordered_map>

#include <fmt/format.h>

#include "models/bounds.hpp"
#include "models/errors.hpp"
#include "models/output_file.hpp"
#include "models/robot_yaml.hpp"
#include "models/yaml_util.hpp"

namespace gpm {
namespace {

std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : line) {
    if (c == ',') {
      out.push_back(cur);
      cur.clear();
    } else if (c != '\r') {
      cur += c;
    }
  }
  out.push_back(cur);
  for (auto& f : out) {
    size_t a = f.find_first_not_of(" \t");
    size_t b = f.find_last_not_of(" \t");
    f = a == std::string::npos ? std::string() : f.substr(a, b - a + 1);
  }
  return out;
}

// The header row of a samples CSV: its column names, its line number and the file's name.
struct Header {
  std::vector<std::string> names;
  int line = 0;
  std::string file;

  // The column named name, or -1.
  int find(const std::string& name) const {
    for (size_t i = 0; i < names.size(); ++i)
      if (names[i] == name) return static_cast<int>(i);
    return -1;
  }
};

// The header: the first non-empty line of in (line_no counts the lines
// read). Throws InputError for an empty file or a column named twice.
Header read_header(std::istream& in, int& line_no, const std::string& file) {
  Header h;
  h.file = file;
  std::string line;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.find_first_not_of(" \t\r") != std::string::npos) {
      h.names = split_csv_line(line);
      break;
    }
  }
  if (h.names.empty()) {
    throw InputError(fmt::format("{}: empty file (expected a header row "
                                 "sample,theta_m1,theta_m2,theta_m3[,x,y])", file));
  }
  h.line = line_no;
  // A column named twice is refused (issue 36.5): which of the two a reader
  // takes would otherwise decide the data silently.
  for (size_t i = 0; i < h.names.size(); ++i) {
    for (size_t k = 0; k < i; ++k) {
      if (!h.names[i].empty() && h.names[i] == h.names[k]) {
        throw InputError(fmt::format("{}:{}: column '{}' appears twice in the header (fields {} and {}); a column "
                                     "may appear once: keep one of the two",
                                     file, h.line, h.names[i], k + 1, i + 1));
      }
    }
  }
  return h;
}

// The optional triples of drive torques and read times, by column prefix (the three columns or none).
constexpr int kNumTriples = 4;
constexpr const char* kTriples[kNumTriples] = {"tau", "tau_last", "tau_between", "t_read"};

// Where each known column stands in the header (-1: absent); a torque
// triple's first column is -1 when the triple is absent.
struct Columns {
  int id = -1, x = -1, y = -1, time = -1;
  int theta[3] = {-1, -1, -1};
  int triple[kNumTriples][3] = {};
};

// The known columns of h. Throws InputError for a missing theta_m column, x
// without y (or y without x), or a torque triple with one or two of its columns.
Columns find_columns(const Header& h) {
  Columns c;
  c.id = h.find("sample");
  for (int k = 0; k < 3; ++k) c.theta[k] = h.find(fmt::format("theta_m{}", k + 1));
  c.x = h.find("x");
  c.y = h.find("y");
  for (int k = 0; k < 3; ++k) {
    if (c.theta[k] < 0) {
      throw InputError(fmt::format("{}:{}: missing column 'theta_m{}' (the header must name "
                                   "theta_m1,theta_m2,theta_m3; sample, x, y are optional)",
                                   h.file, h.line, k + 1));
    }
  }
  if ((c.x < 0) != (c.y < 0)) {
    throw InputError(fmt::format("{}:{}: column '{}' without '{}' (give both x and y, or neither)",
                                 h.file, h.line, c.x < 0 ? "y" : "x", c.x < 0 ? "x" : "y"));
  }
  for (int q = 0; q < kNumTriples; ++q) {
    const char* name = kTriples[q];
    int found = 0;
    for (int k = 0; k < 3; ++k) found += (c.triple[q][k] = h.find(fmt::format("{}{}", name, k + 1))) >= 0;
    for (int k = 0; found > 0 && found < 3 && k < 3; ++k)
      if (c.triple[q][k] < 0)
        throw InputError(fmt::format("{}:{}: column '{}{}' missing (give {}1,{}2,{}3 all three, or none)", h.file,
                                     h.line, name, k + 1, name, name, name));
  }
  c.time = h.find("t");
  return c;
}

// The number in field col of row f (line ln). Throws InputError naming the
// column for a missing field, text that is not a number, or a non-finite value.
double field_number(const Header& h, const std::vector<std::string>& f, int col, int ln) {
  const std::string& name = h.names[static_cast<size_t>(col)];
  if (col >= static_cast<int>(f.size())) {
    throw InputError(fmt::format("{}:{}: column '{}' is missing on this row ({} fields, header has {})",
                                 h.file, ln, name, f.size(), h.names.size()));
  }
  const std::string& t = f[static_cast<size_t>(col)];
  std::string_view sv = t;
  if (!sv.empty() && sv.front() == '+') sv.remove_prefix(1);
  double v = 0.0;
  const auto [p, ec] = std::from_chars(sv.data(), sv.data() + sv.size(), v);
  if (ec != std::errc() || p != sv.data() + sv.size() || sv.empty())
    throw InputError(fmt::format("{}:{}: column '{}': '{}' is not a number", h.file, ln, name, t));
  if (!std::isfinite(v))
    throw InputError(fmt::format("{}:{}: column '{}': value must be finite, got '{}'", h.file, ln, name, t));
  return v;
}

// Strict reader (issue 14.4): throws InputError unless row f (line ln) has
// exactly the header's field count, so a decimal comma (`1,5`) or a missing
// field never shifts the columns.
void check_field_count(const Header& h, const std::vector<std::string>& f, int ln) {
  if (f.size() == h.names.size()) return;
  const std::string why = f.size() > h.names.size()
                              ? std::string("a decimal comma or an extra field?")
                              : fmt::format("column '{}' is missing on this row", h.names[f.size()]);
  throw InputError(fmt::format("{}:{}: expected {} fields as in the header (line {}), found {} ({})", h.file, ln,
                               h.names.size(), h.line, f.size(), why));
}

// Appends row f (line ln) to s: readings, x,y, torques, time (increasing)
// and sample id (a whole number; its index when the file has none).
void append_row(const Header& h, const Columns& c, const std::vector<std::string>& f, int ln, Samples& s) {
  const auto number = [&](int col) { return field_number(h, f, col, ln); };
  Eigen::Vector3d t;
  for (int k = 0; k < 3; ++k) t[k] = number(c.theta[k]);
  s.theta_m.push_back(t);
  if (s.has_xy) s.xy.emplace_back(number(c.x), number(c.y));
  std::vector<Eigen::Vector3d>* triples[kNumTriples] = {&s.tau, &s.tau_last, &s.tau_between, &s.t_read};
  for (int q = 0; q < kNumTriples; ++q)
    if (c.triple[q][0] >= 0)
      triples[q]->emplace_back(number(c.triple[q][0]), number(c.triple[q][1]), number(c.triple[q][2]));
  if (c.time >= 0) {
    const double t_s = number(c.time);
    if (!s.t.empty() && !(t_s > s.t.back()))
      throw InputError(fmt::format("{}:{}: column 't': {} s does not follow {} s of the row before (the times of "
                                   "the readings must increase)",
                                   h.file, ln, f[static_cast<size_t>(c.time)], format_exact(s.t.back())));
    s.t.push_back(t_s);
  }
  if (c.id < 0) {
    s.id.push_back(static_cast<long>(s.theta_m.size() - 1));
    return;
  }
  const double id = number(c.id);
  if (id != std::floor(id) || std::abs(id) > 9.0e15) {
    throw InputError(fmt::format("{}:{}: column 'sample': '{}' is not a whole number of at "
                                 "most 16 digits",
                                 h.file, ln, f[static_cast<size_t>(c.id)]));
  }
  s.id.push_back(static_cast<long>(id));
}

}  // namespace

Samples parse_samples_csv(const std::string& text, const std::string& file) {
  std::istringstream in(text);
  int line_no = 0;
  const Header header = read_header(in, line_no, file);
  const Columns columns = find_columns(header);
  Samples s;
  s.has_xy = columns.x >= 0;
  std::unordered_map<long, int> line_of_id;  // each sample is recorded once
  std::string line;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const auto f = split_csv_line(line);
    check_field_count(header, f, line_no);
    append_row(header, columns, f, line_no, s);
    const auto [it, fresh] = line_of_id.emplace(s.id.back(), line_no);
    if (!fresh) {
      throw InputError(fmt::format("{}:{}: sample {} appears twice (first at line {}): each sample is one row; the "
                                   "file was edited or joined from others",
                                   file, line_no, s.id.back(), it->second));
    }
  }
  return s;
}

Samples read_samples_csv(const std::string& path) {
  note_input(path);  // models/output_file.hpp: never also an output of the command
  return parse_samples_csv(read_input_file(path, limits::kMaxCsvBytes), path);
}

std::string samples_to_csv(const Samples& s) {
  const std::pair<const char*, const std::vector<Eigen::Vector3d>*> triples[kNumTriples] = {
      {"tau", &s.tau}, {"tau_last", &s.tau_last}, {"tau_between", &s.tau_between}, {"t_read", &s.t_read}};
  std::string out = s.has_xy ? "sample,theta_m1,theta_m2,theta_m3,x,y" : "sample,theta_m1,theta_m2,theta_m3";
  for (const auto& [name, v] : triples)
    if (!v->empty()) out += fmt::format(",{}1,{}2,{}3", name, name, name);
  out += s.t.empty() ? "\n" : ",t\n";
  for (size_t j = 0; j < s.size(); ++j) {
    const long id = j < s.id.size() ? s.id[j] : static_cast<long>(j);
    out += fmt::format("{},{},{},{}", id, format_exact(s.theta_m[j][0]),
                       format_exact(s.theta_m[j][1]), format_exact(s.theta_m[j][2]));
    if (s.has_xy) out += fmt::format(",{},{}", format_exact(s.xy[j][0]), format_exact(s.xy[j][1]));
    for (const auto& [name, v] : triples)
      if (!v->empty())
        out += fmt::format(",{},{},{}", format_exact((*v)[j][0]), format_exact((*v)[j][1]), format_exact((*v)[j][2]));
    if (!s.t.empty()) out += fmt::format(",{}", format_exact(s.t[j]));
    out += '\n';
  }
  return out;
}

void write_samples_csv(const Samples& s, const std::string& path) {
  write_file_atomic(path, samples_to_csv(s));
}

}  // namespace gpm
