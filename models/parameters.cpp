#include "models/parameters.hpp"

#include <algorithm>
#include <cctype>

#include <fmt/format.h>

#include "models/errors.hpp"

namespace gpm {
namespace {

constexpr std::array<std::string_view, kNumParams> kNames = {
    "xa1", "ya1", "xa2", "ya2", "xa3", "ya3", "la1", "la2",
    "la3", "lb1", "lb2", "lb3", "dth1", "dth2", "dth3"};

}  // namespace

std::string_view param_name(int i) { return kNames.at(static_cast<size_t>(i)); }

std::optional<int> param_index(std::string_view name) {
  for (int i = 0; i < kNumParams; ++i) {
    if (kNames[static_cast<size_t>(i)] == name) return i;
  }
  return std::nullopt;
}

int edit_distance(std::string_view a, std::string_view b) {
  std::vector<int> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = static_cast<int>(j);
  for (size_t i = 1; i <= a.size(); ++i) {
    int diag = row[0];
    row[0] = static_cast<int>(i);
    for (size_t j = 1; j <= b.size(); ++j) {
      const int up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] != b[j - 1] ? 1 : 0)});
      diag = up;
    }
  }
  return row[b.size()];
}

std::string nearest_param_name(std::string_view name_in) {
  std::string lower(name_in);
  for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const std::string_view name = lower;
  int best = 0;
  int best_d = edit_distance(name, kNames[0]);
  for (int i = 1; i < kNumParams; ++i) {
    const int d = edit_distance(name, kNames[static_cast<size_t>(i)]);
    if (d < best_d) best = i, best_d = d;
  }
  return std::string(kNames[static_cast<size_t>(best)]);
}

bool is_length(int i) { return i >= kLa1 && i <= kLb3; }
bool is_offset(int i) { return i >= kDth1 && i <= kDth3; }

Geometry Geometry::gpm2002_nominal() {
  Geometry g;
  g[kXa1] = 0.0;   g[kYa1] = 250.0;
  g[kXa2] = 433.0; g[kYa2] = 0.0;
  g[kXa3] = 433.0; g[kYa3] = 500.0;
  for (int i = 0; i < kNumChains; ++i) {
    g[la(i)] = 244.0;
    g[lb(i)] = 244.0;
    g[dth(i)] = 0.0;
  }
  return g;
}

FreeMask parse_param_list(std::string_view list, std::string_view what) {
  FreeMask mask;
  size_t start = 0;
  int position = 0;
  while (start <= list.size()) {
    size_t end = list.find(',', start);
    if (end == std::string_view::npos) end = list.size();
    std::string_view item = list.substr(start, end - start);
    while (!item.empty() && item.front() == ' ') item.remove_prefix(1);
    while (!item.empty() && item.back() == ' ') item.remove_suffix(1);
    if (!item.empty()) {
      const auto idx = param_index(item);
      if (!idx) {
        throw InputError(fmt::format(
            "{}[{}]: unknown parameter '{}' (did you mean {}?); valid: xa1 ya1 xa2 ya2 xa3 "
            "ya3 la1 la2 la3 lb1 lb2 lb3 dth1 dth2 dth3",
            what, position, item, nearest_param_name(item)));
      }
      if (mask.test(static_cast<size_t>(*idx))) {
        throw InputError(fmt::format("{}[{}]: '{}' is given twice; give each parameter once", what, position, item));
      }
      mask.set(static_cast<size_t>(*idx));
    }
    ++position;
    if (end == list.size()) break;
    start = end + 1;
  }
  return mask;
}

std::string format_param_list(const FreeMask& mask) {
  std::string out;
  for (int i = 0; i < kNumParams; ++i) {
    if (!mask.test(static_cast<size_t>(i))) continue;
    if (!out.empty()) out += ',';
    out += param_name(i);
  }
  return out;
}

FreeMask default_free_mask() {
  FreeMask m;
  m.set();
  for (int i : {kXa1, kYa1, kXa2, kYa2}) m.reset(static_cast<size_t>(i));
  return m;
}

}  // namespace gpm
