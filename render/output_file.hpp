// Output files written all or nothing: a temporary name in the destination's
// folder, renamed over the destination at the end, removed on failure.
#pragma once

#include <string>

namespace gpm::render {

// Temporary name next to path: "<folder>/.<name>.tmp<pid>".
std::string temporary_name_for(const std::string& path);

// Checks that path can be written: not a folder, its folder exists and a file
// can be created there (one is created and removed). Throws InputError naming
// path and the reason.
void check_output_file(const std::string& path);

// Renames tmp to path; throws InputError naming path (tmp is removed).
void commit_output_file(const std::string& tmp, const std::string& path);

}  // namespace gpm::render
