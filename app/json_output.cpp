// JSON on stdout (app/json_output.hpp).
#include "app/json_output.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "models/yaml_util.hpp"

namespace gpm::cli {
namespace {

// The value of a plain (unquoted) YAML scalar, typed as YAML 1.2's core schema
// reads it (the toolkit writes only these forms).
Json plain_scalar(const std::string& s) {
  if (s == "true" || s == "True" || s == "TRUE") return true;
  if (s == "false" || s == "False" || s == "FALSE") return false;
  if (s.empty() || s == "~" || s == "null" || s == "Null" || s == "NULL") return nullptr;
  if (s == ".nan" || s == ".NaN" || s == ".NAN" || s == ".inf" || s == ".Inf" || s == ".INF" || s == "+.inf" ||
      s == "-.inf" || s == "-.Inf" || s == "-.INF")
    return nullptr;
  const char* begin = s.c_str();
  char* end = nullptr;
  errno = 0;
  const long long i = std::strtoll(begin, &end, 10);
  if (end != begin && *end == '\0' && errno == 0) return i;
  end = nullptr;
  const double x = std::strtod(begin, &end);
  if (end != begin && *end == '\0' && std::isfinite(x)) return x;
  return s;
}

}  // namespace

Json json_number(double x) { return std::isfinite(x) ? Json(x) : Json(nullptr); }

Json yaml_to_json(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Map: {
      Json out = Json::object();
      for (const auto& kv : node) out[kv.first.Scalar()] = yaml_to_json(kv.second);
      return out;
    }
    case YAML::NodeType::Sequence: {
      Json out = Json::array();
      for (const auto& item : node) out.push_back(yaml_to_json(item));
      return out;
    }
    case YAML::NodeType::Scalar:
      // yaml-cpp tags a quoted scalar "!" and a plain one "?".
      return node.Tag() == "!" ? Json(node.Scalar()) : plain_scalar(node.Scalar());
    case YAML::NodeType::Null:
    case YAML::NodeType::Undefined:
      break;
  }
  return nullptr;
}

Json yaml_text_to_json(const std::string& text, const std::string& file) {
  return yaml_to_json(load_yaml_string(text, file));
}

void print_json(const Json& doc) {
  // Invalid UTF-8 (never written by the toolkit) is replaced, not thrown.
  const std::string text = doc.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
  std::fwrite(text.data(), 1, text.size(), stdout);
  std::fflush(stdout);
}

}  // namespace gpm::cli
