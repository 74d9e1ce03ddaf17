#include "render/png_writer.hpp"

#include <cstdio>
#include <cstring>

#include <fmt/format.h>
#include <png.h>

#include "models/errors.hpp"
#include "models/output_file.hpp"

namespace gpm::render {

void write_png_to(const OutputFile& out, const FrameImage& img) {
  png_image image;
  std::memset(&image, 0, sizeof(image));
  image.version = PNG_IMAGE_VERSION;
  image.width = static_cast<png_uint_32>(img.width);
  image.height = static_cast<png_uint_32>(img.height);
  image.format = PNG_FORMAT_RGB;
  const int ok =
      png_image_write_to_file(&image, out.write_path().c_str(), 0, img.rgb.data(), img.width * 3, nullptr);
  const std::string message = image.message;
  png_image_free(&image);
  if (!ok) throw InputError(fmt::format("{}: cannot write the PNG: {}", out.path(), message));
}

void write_png(const std::string& path, const FrameImage& img) {
  OutputFile out(path);  // models/output_file.hpp: staged, or in place for a device
  write_png_to(out, img);
  out.commit();
}

FrameImage read_png(const std::string& path) {
  png_image image;
  std::memset(&image, 0, sizeof(image));
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&image, path.c_str()))
    throw InputError(fmt::format("{}: cannot read the PNG: {}", path, image.message));
  image.format = PNG_FORMAT_RGB;
  FrameImage img;
  img.width = static_cast<int>(image.width);
  img.height = static_cast<int>(image.height);
  img.rgb.resize(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, img.rgb.data(), 0, nullptr)) {
    const std::string message = image.message;
    png_image_free(&image);
    throw InputError(fmt::format("{}: cannot read the PNG: {}", path, message));
  }
  return img;
}

}  // namespace gpm::render
