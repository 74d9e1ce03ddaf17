// JSON on stdout for `--json` (gpm kin, gpm calibrate, gpm design): one
// document, written with nlohmann::json. A file the command writes as YAML is
// turned into JSON from its own text, so that the document and the file carry
// the same content (docs/FORMATS.md, JSON output).
#pragma once

#include <string>

#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

namespace gpm::cli {

// Key order as written (the YAML files' order, the text output's order).
using Json = nlohmann::ordered_json;

// A number, or null when it is not finite (JSON has no NaN or infinity).
Json json_number(double x);

// The JSON value of a YAML node: maps -> objects (file order), sequences ->
// arrays; a quoted scalar -> string; a plain scalar -> true/false, null (~,
// null, empty, .nan, .inf), an integer, a number, or else a string.
Json yaml_to_json(const YAML::Node& node);

// The JSON value of YAML text (file names the source in errors; the text is
// one the command has just written, so an error here is a bug).
Json yaml_text_to_json(const std::string& text, const std::string& file);

// Prints doc on stdout as one JSON document (two-space indent, newline).
void print_json(const Json& doc);

}  // namespace gpm::cli
