#include "models/yaml_util.hpp"

#include <charconv>
#include <cmath>
#include <map>
#include <sstream>
#include <vector>

#include <fmt/format.h>
#include <yaml-cpp/eventhandler.h>

#include "models/bounds.hpp"
#include "models/errors.hpp"
#include "models/output_file.hpp"
#include "models/parameters.hpp"

namespace gpm {

std::string yaml_where(const std::string& file, const YAML::Node& node, std::string_view keypath) {
  const YAML::Mark mark = node.Mark();
  std::string out = file;
  if (!mark.is_null()) out += fmt::format(":{}", mark.line + 1);
  out += ": ";
  if (!keypath.empty()) out += fmt::format("{}: ", keypath);
  return out;
}

namespace {

// Streams the parser's events and refuses a map key that appears twice in the
// same map (issue 14.5: yaml-cpp keeps both entries and which one a reader sees
// differs by reader). Event-based, so aliases are not expanded: linear in the text.
class DuplicateKeyCheck final : public YAML::EventHandler {
 public:
  explicit DuplicateKeyCheck(const std::string& file) : file_(file) {}

  void OnDocumentStart(const YAML::Mark&) override { stack_.clear(); }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& mark, YAML::anchor_t) override { node(mark, "null", true); }
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t) override { node(mark, "*alias", false); }
  void OnScalar(const YAML::Mark& mark, const std::string&, YAML::anchor_t,
                const std::string& value) override {
    node(mark, value, true);
  }
  void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {
    open(mark, false);
  }
  void OnSequenceEnd() override { close(); }
  void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {
    open(mark, true);
  }
  void OnMapEnd() override { close(); }

 private:
  struct Frame {
    bool is_map = false;
    bool expect_key = true;  // maps: the next node is a key
    std::string key;         // maps: the key of the value being read
    long index = 0;          // sequences: the index of the item being read
    std::map<std::string, int> lines;  // maps: scalar key -> line (1-based)
  };

  // Dotted key path of the node being read (sequence items as [i]).
  std::string path() const {
    std::string out;
    for (const Frame& f : stack_) {
      if (f.is_map) {
        if (f.expect_key) break;  // inside a (complex) key: stop here
        out += out.empty() ? f.key : "." + f.key;
      } else {
        out += fmt::format("[{}]", f.index);
      }
    }
    return out;
  }

  // A scalar, null or alias node at mark (text is the key when it is a key).
  void node(const YAML::Mark& mark, const std::string& text, bool keyable) {
    if (!stack_.empty() && stack_.back().is_map && stack_.back().expect_key) {
      Frame& m = stack_.back();
      const int line = mark.line + 1;
      if (keyable) {
        const auto [it, inserted] = m.lines.emplace(text, line);
        if (!inserted) {
          const std::string prefix = path();
          const std::string where = prefix.empty() ? text : prefix + "." + text;
          throw InputError(fmt::format(
              "{}:{}: {}: duplicate key (first at line {}, again at line {}); a key may appear "
              "once in a map: keep one of the two",
              file_, line, where, it->second, line));
        }
      }
      m.key = keyable ? text : "*alias";
    }
    done();
  }

  void open(const YAML::Mark&, bool is_map) {
    if (!stack_.empty() && stack_.back().is_map && stack_.back().expect_key) {
      stack_.back().key = "?";  // a complex (collection) key
    }
    Frame f;
    f.is_map = is_map;
    stack_.push_back(std::move(f));
  }

  void close() {
    if (!stack_.empty()) stack_.pop_back();
    done();
  }

  // The node just read in the top frame is complete.
  void done() {
    if (stack_.empty()) return;
    Frame& f = stack_.back();
    if (f.is_map) {
      f.expect_key = !f.expect_key;
    } else {
      ++f.index;
    }
  }

  const std::string& file_;
  std::vector<Frame> stack_;
};

}  // namespace

YAML::Node load_yaml_string(const std::string& text, const std::string& file) {
  try {
    {
      std::istringstream in(text);
      YAML::Parser parser(in);
      DuplicateKeyCheck check(file);
      parser.HandleNextDocument(check);
    }
    return YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw InputError(fmt::format("{}:{}:{}: YAML syntax error: {}", file, e.mark.line + 1,
                                 e.mark.column + 1, e.msg));
  }
}

YAML::Node load_yaml_file(const std::string& file) {
  note_input(file);  // models/output_file.hpp: never also an output of the command
  return load_yaml_string(read_input_file(file, limits::kMaxYamlBytes), file);
}

double yaml_number(const YAML::Node& node, const std::string& file, std::string_view keypath) {
  if (!node.IsDefined() || node.IsNull()) {
    throw InputError(yaml_where(file, node, keypath) + "missing value (expected a number)");
  }
  if (!node.IsScalar()) {
    throw InputError(yaml_where(file, node, keypath) + "expected a number, got a list or map");
  }
  std::string_view s = node.Scalar();
  const std::string text(s);
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  double v = 0.0;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  const bool yaml_special = text == ".nan" || text == ".NaN" || text == ".inf" || text == "-.inf" ||
                            text == "+.inf" || text == ".Inf" || text == "-.Inf";
  if (yaml_special || (ec == std::errc() && ptr == s.data() + s.size() && !std::isfinite(v))) {
    throw InputError(yaml_where(file, node, keypath) +
                     fmt::format("value must be a finite number, got '{}'", text));
  }
  if (ec != std::errc() || ptr != s.data() + s.size() || s.empty()) {
    throw InputError(yaml_where(file, node, keypath) +
                     fmt::format("'{}' is not a number", text));
  }
  return v;
}

double yaml_positive(const YAML::Node& node, const std::string& file, std::string_view keypath) {
  const double v = yaml_number(node, file, keypath);
  if (!(v > 0.0)) {
    throw InputError(yaml_where(file, node, keypath) + fmt::format("must be positive, got {}", v));
  }
  return v;
}

long long yaml_integer(const YAML::Node& node, const std::string& file, std::string_view keypath,
                       long long lo, long long hi) {
  const double v = yaml_number(node, file, keypath);
  if (v != std::floor(v) || v < static_cast<double>(lo) || v > static_cast<double>(hi)) {
    throw InputError(yaml_where(file, node, keypath) +
                     fmt::format("must be a whole number from {} to {}, got {}", lo, hi, node.Scalar()));
  }
  return static_cast<long long>(v);
}

bool yaml_bool(const YAML::Node& node, const std::string& file, std::string_view keypath) {
  if (node.IsScalar()) {
    const std::string& s = node.Scalar();
    if (s == "true" || s == "True" || s == "yes" || s == "on") return true;
    if (s == "false" || s == "False" || s == "no" || s == "off") return false;
  }
  throw InputError(yaml_where(file, node, keypath) + "expected true or false");
}

std::string yaml_string(const YAML::Node& node, const std::string& file, std::string_view keypath) {
  if (!node.IsDefined() || !node.IsScalar()) {
    throw InputError(yaml_where(file, node, keypath) + "expected a text value");
  }
  return node.Scalar();
}

bool is_printable_utf8(std::string_view s) {
  size_t i = 0;
  while (i < s.size()) {
    const auto c = static_cast<unsigned char>(s[i]);
    if (c < 0x80) {
      if (c < 0x20 || c == 0x7f) return false;
      ++i;
      continue;
    }
    int extra = 0;
    unsigned int cp = 0;
    if ((c & 0xe0) == 0xc0) extra = 1, cp = c & 0x1f;
    else if ((c & 0xf0) == 0xe0) extra = 2, cp = c & 0x0f;
    else if ((c & 0xf8) == 0xf0) extra = 3, cp = c & 0x07;
    else return false;
    if (i + static_cast<size_t>(extra) >= s.size()) return false;
    for (int k = 1; k <= extra; ++k) {
      const auto d = static_cast<unsigned char>(s[i + static_cast<size_t>(k)]);
      if ((d & 0xc0) != 0x80) return false;
      cp = (cp << 6) | (d & 0x3f);
    }
    // Overlong forms, surrogates, beyond U+10FFFF and C1 controls are not text.
    const unsigned int min_cp[] = {0, 0x80, 0x800, 0x10000};
    if (cp < min_cp[extra] || (cp >= 0xd800 && cp <= 0xdfff) || cp > 0x10ffff || (cp >= 0x80 && cp < 0xa0)) return false;
    i += static_cast<size_t>(extra) + 1;
  }
  return true;
}

std::string yaml_text(const YAML::Node& node, const std::string& file, std::string_view keypath) {
  const std::string s = yaml_string(node, file, keypath);
  if (!is_printable_utf8(s)) {
    throw InputError(yaml_where(file, node, keypath) +
                     "must be printable single-line UTF-8 text (no control characters)");
  }
  return s;
}

std::array<double, 3> yaml_number_or_three(
    const YAML::Node& node, const std::string& file, const std::string& keypath, std::string_view list_expected,
    const std::function<double(const YAML::Node&, const std::string&)>& element,
    const std::function<std::array<double, 3>(double)>& number_gives) {
  if (!node.IsSequence()) return number_gives(element(node, keypath));
  if (node.size() != 3)
    throw InputError(yaml_where(file, node, keypath) +
                     fmt::format("expected {}, got a list of {}", list_expected, node.size()));
  std::array<double, 3> out{};
  for (std::size_t i = 0; i < 3; ++i) out[i] = element(node[i], fmt::format("{}[{}]", keypath, i));
  return out;
}

void yaml_check_keys(const YAML::Node& node, const std::string& file, std::string_view keypath,
                     std::initializer_list<std::string_view> allowed) {
  if (!node.IsMap()) {
    throw InputError(yaml_where(file, node, keypath) + "expected a map of keys");
  }
  for (const auto& kv : node) {
    const std::string key = kv.first.Scalar();
    bool ok = false;
    std::string_view best;
    int best_d = 1 << 30;
    std::string valid;
    for (std::string_view a : allowed) {
      if (a == key) ok = true;
      const int d = edit_distance(key, a);
      if (d < best_d) best_d = d, best = a;
      if (!valid.empty()) valid += ", ";
      valid += a;
    }
    if (!ok) {
      const std::string path = keypath.empty() ? key : fmt::format("{}.{}", keypath, key);
      throw InputError(yaml_where(file, kv.first, path) +
                       fmt::format("unknown key (did you mean {}?); valid keys: {}", best, valid));
    }
  }
}

std::string format_exact(double x) { return fmt::format("{}", x); }

}  // namespace gpm
