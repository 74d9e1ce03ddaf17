// Strict reading of YAML scalars and maps, with errors that name the file,
// the line and the key path (docs/ARCHITECTURE.md: one clear line, exit 2).
#pragma once

#include <array>
#include <functional>
#include <initializer_list>
#include <string>
#include <string_view>

#include <yaml-cpp/yaml.h>

namespace gpm {

// "FILE:LINE: KEYPATH: " prefix for an error about node.
std::string yaml_where(const std::string& file, const YAML::Node& node, std::string_view keypath);

// Loads a YAML file; throws InputError for a missing file, a syntax error or a
// key that appears twice in one map (every YAML the toolkit reads comes here).
YAML::Node load_yaml_file(const std::string& file);

// Parses YAML text (file names the source in errors); same checks as above.
YAML::Node load_yaml_string(const std::string& text, const std::string& file);

// A finite number at node; throws InputError for non-numeric or non-finite.
double yaml_number(const YAML::Node& node, const std::string& file, std::string_view keypath);

// A number > 0.
double yaml_positive(const YAML::Node& node, const std::string& file, std::string_view keypath);

// An integer (no fractional part) at node, in [lo, hi].
long long yaml_integer(const YAML::Node& node, const std::string& file, std::string_view keypath,
                       long long lo, long long hi);

// A boolean (true/false).
bool yaml_bool(const YAML::Node& node, const std::string& file, std::string_view keypath);

// A string scalar.
std::string yaml_string(const YAML::Node& node, const std::string& file, std::string_view keypath);

// True when s is valid UTF-8 without control characters (printable text).
bool is_printable_utf8(std::string_view s);

// A printable single-line text scalar (valid UTF-8, no control characters).
std::string yaml_text(const YAML::Node& node, const std::string& file, std::string_view keypath);

// Requires node to be a map whose keys are all in allowed; an unknown key is
// reported with the nearest allowed name.
void yaml_check_keys(const YAML::Node& node, const std::string& file, std::string_view keypath,
                     std::initializer_list<std::string_view> allowed);

// Three values from a number or a list of three at keypath: each element is
// read by element(element node, its key path: keypath or keypath[i]); a number
// gives number_gives(that value) (by default the value three times). A list
// of another length is an error "expected LIST_EXPECTED, got a list of N".
std::array<double, 3> yaml_number_or_three(
    const YAML::Node& node, const std::string& file, const std::string& keypath, std::string_view list_expected,
    const std::function<double(const YAML::Node&, const std::string&)>& element,
    const std::function<std::array<double, 3>(double)>& number_gives = [](double x) {
      return std::array<double, 3>{x, x, x};
    });

// Shortest decimal text that reads back to exactly x (lossless round trip).
std::string format_exact(double x);

}  // namespace gpm
