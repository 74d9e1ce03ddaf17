// PNG files of rendered frames (libpng), written all or nothing.
#pragma once

#include <string>

#include "models/output_file.hpp"
#include "render/frame_image.hpp"

namespace gpm::render {

// Writes img as an 8-bit RGB PNG at path by the output policy
// (models/output_file.hpp): a temporary file in the same folder, then
// renamed. Throws InputError naming path if it cannot be written (nothing is
// left behind).
void write_png(const std::string& path, const FrameImage& img);

// Writes img as a PNG to out.write_path(); the caller commits out.
void write_png_to(const OutputFile& out, const FrameImage& img);

// Reads an 8-bit RGB PNG (for tests and tools); throws InputError naming path.
FrameImage read_png(const std::string& path);

}  // namespace gpm::render
