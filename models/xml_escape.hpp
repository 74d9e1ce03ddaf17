// XML text: the one escaping function of the project (MJCF, SVG, HTML reports).
#pragma once

#include <string>

namespace gpm {

// Escapes &, <, > and " for XML text and attribute values.
inline std::string xml_escape(const std::string& s) {
  std::string out;
  out.reserve(s.size());
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

}  // namespace gpm
