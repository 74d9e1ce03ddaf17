#include "models/samples.hpp"

#include <charconv>
#include <cmath>
#include <sstream>

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

}  // namespace

Samples parse_samples_csv(const std::string& text, const std::string& file) {
  std::istringstream in(text);
  std::string line;
  int line_no = 0;
  // Header: first non-empty line.
  std::vector<std::string> header;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.find_first_not_of(" \t\r") != std::string::npos) {
      header = split_csv_line(line);
      break;
    }
  }
  if (header.empty()) {
    throw InputError(fmt::format("{}: empty file (expected a header row "
                                 "sample,theta_m1,theta_m2,theta_m3[,x,y])", file));
  }
  const int header_line = line_no;
  // A column named twice is refused (issue 36.5): which of the two a reader
  // takes would otherwise decide the data silently.
  for (size_t i = 0; i < header.size(); ++i) {
    for (size_t k = 0; k < i; ++k) {
      if (!header[i].empty() && header[i] == header[k]) {
        throw InputError(fmt::format("{}:{}: column '{}' appears twice in the header (fields {} and {}); a column "
                                     "may appear once: keep one of the two",
                                     file, header_line, header[i], k + 1, i + 1));
      }
    }
  }
  auto find = [&](const char* name) -> int {
    for (size_t i = 0; i < header.size(); ++i)
      if (header[i] == name) return static_cast<int>(i);
    return -1;
  };
  const int c_id = find("sample");
  const int c_t[3] = {find("theta_m1"), find("theta_m2"), find("theta_m3")};
  const int c_x = find("x"), c_y = find("y");
  for (int k = 0; k < 3; ++k) {
    if (c_t[k] < 0) {
      throw InputError(fmt::format("{}:{}: missing column 'theta_m{}' (the header must name "
                                   "theta_m1,theta_m2,theta_m3; sample, x, y are optional)",
                                   file, header_line, k + 1));
    }
  }
  if ((c_x < 0) != (c_y < 0)) {
    throw InputError(fmt::format("{}:{}: column '{}' without '{}' (give both x and y, or neither)",
                                 file, header_line, c_x < 0 ? "y" : "x", c_x < 0 ? "x" : "y"));
  }
  // Optional triples of drive torques: the three columns or none.
  struct Triple {
    const char* name;
    int col[3];
    std::vector<Eigen::Vector3d>* out;
  };
  Samples s;
  Triple triples[3] = {{"tau", {}, &s.tau}, {"tau_last", {}, &s.tau_last}, {"tau_between", {}, &s.tau_between}};
  for (Triple& tr : triples) {
    int found = 0;
    for (int k = 0; k < 3; ++k) found += (tr.col[k] = find(fmt::format("{}{}", tr.name, k + 1).c_str())) >= 0;
    for (int k = 0; found > 0 && found < 3 && k < 3; ++k)
      if (tr.col[k] < 0)
        throw InputError(fmt::format("{}:{}: column '{}{}' missing (give {}1,{}2,{}3 all three, or none)", file,
                                     header_line, tr.name, k + 1, tr.name, tr.name, tr.name));
    if (found == 0) tr.out = nullptr;
  }
  const int c_time = find("t");
  s.has_xy = c_x >= 0;
  auto number = [&](const std::vector<std::string>& f, int col, int ln) {
    if (col >= static_cast<int>(f.size())) {
      throw InputError(fmt::format("{}:{}: column '{}' is missing on this row ({} fields, header has {})",
                                   file, ln, header[static_cast<size_t>(col)], f.size(), header.size()));
    }
    const std::string& t = f[static_cast<size_t>(col)];
    std::string_view sv = t;
    if (!sv.empty() && sv.front() == '+') sv.remove_prefix(1);
    double v = 0.0;
    const auto [p, ec] = std::from_chars(sv.data(), sv.data() + sv.size(), v);
    if (ec != std::errc() || p != sv.data() + sv.size() || sv.empty()) {
      throw InputError(fmt::format("{}:{}: column '{}': '{}' is not a number", file, ln,
                                   header[static_cast<size_t>(col)], t));
    }
    if (!std::isfinite(v)) {
      throw InputError(fmt::format("{}:{}: column '{}': value must be finite, got '{}'", file, ln,
                                   header[static_cast<size_t>(col)], t));
    }
    return v;
  };
  while (std::getline(in, line)) {
    ++line_no;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const auto f = split_csv_line(line);
    // Strict reader (issue 14.4): every row has exactly the header's field count,
    // so a decimal comma (`1,5`) or a missing field never shifts the columns.
    if (f.size() != header.size()) {
      const std::string why =
          f.size() > header.size()
              ? std::string("a decimal comma or an extra field?")
              : fmt::format("column '{}' is missing on this row", header[f.size()]);
      throw InputError(fmt::format("{}:{}: expected {} fields as in the header (line {}), found {} ({})",
                                   file, line_no, header.size(), header_line, f.size(), why));
    }
    Eigen::Vector3d t;
    for (int k = 0; k < 3; ++k) t[k] = number(f, c_t[k], line_no);
    s.theta_m.push_back(t);
    if (s.has_xy) s.xy.emplace_back(number(f, c_x, line_no), number(f, c_y, line_no));
    for (const Triple& tr : triples)
      if (tr.out) tr.out->emplace_back(number(f, tr.col[0], line_no), number(f, tr.col[1], line_no), number(f, tr.col[2], line_no));
    if (c_time >= 0) {
      const double t_s = number(f, c_time, line_no);
      if (!s.t.empty() && !(t_s > s.t.back()))
        throw InputError(fmt::format("{}:{}: column 't': {} s does not follow {} s of the row before (the times of "
                                     "the readings must increase)",
                                     file, line_no, f[static_cast<size_t>(c_time)], format_exact(s.t.back())));
      s.t.push_back(t_s);
    }
    if (c_id >= 0) {
      const double id = number(f, c_id, line_no);
      if (id != std::floor(id) || std::abs(id) > 9.0e15) {
        throw InputError(fmt::format("{}:{}: column 'sample': '{}' is not a whole number of at "
                                     "most 16 digits",
                                     file, line_no, f[static_cast<size_t>(c_id)]));
      }
      s.id.push_back(static_cast<long>(id));
    } else {
      s.id.push_back(static_cast<long>(s.theta_m.size() - 1));
    }
  }
  return s;
}

Samples read_samples_csv(const std::string& path) {
  note_input(path);  // models/output_file.hpp: never also an output of the command
  return parse_samples_csv(read_input_file(path, limits::kMaxCsvBytes), path);
}

std::string samples_to_csv(const Samples& s) {
  const std::pair<const char*, const std::vector<Eigen::Vector3d>*> triples[3] = {
      {"tau", &s.tau}, {"tau_last", &s.tau_last}, {"tau_between", &s.tau_between}};
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
