// Every file a command wrote, printed at its end (issue 35.5): the files of
// an output folder whose modification time is not older than the command's
// start, so that a folder's older files (kept by the output policy) are not
// listed and nothing is listed that was not written.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace gpm::cli {

// Records now as the command's start (app/cli_main.cpp, before parsing).
void mark_command_start();

// The regular files under dir (sub-folders too; hidden ones left out)
// modified at or after since, as dir/NAME, sorted.
std::vector<std::string> files_written_since(const std::string& dir, std::filesystem::file_time_type since);

// Prints "LABEL DIR/NAME" on stdout for each file under dir written since the
// command's start, label padded to width.
void print_written(const std::string& dir, int width = 11, const std::string& label = "wrote");

}  // namespace gpm::cli
